// @ts-check
// The page's one state (issue 17): the mesh shown (its picture, stats and
// exports belong together) and the file being loaded, each with its own
// client Session. A new file replaces the shown mesh as soon as its surface
// is repaired ('loaded', long before its lines), so the page never mixes two
// meshes: while it is read, the previous mesh stays in view, dimmed and
// labelled, and Cancel drops the new file (the page is the previous mesh's
// again, header, picture, stats and exports); once the new surface is shown,
// its lines are pending and Cancel keeps it without lines (or, during a
// recompute, with the lines it had).
// Every view (dom.js, the exports) reads the phase and texts from here.

/**
 * @typedef {import('../client/client.js').Session} Session
 * @typedef {import('../client/client.js').Result} Result
 * @typedef {{session: Session, name: string, src?: string, vertices?: number, triangles?: number, loadMs?: number,
 *            notes: string[], result?: Result, options?: object, stale?: boolean, surface?: object | null}} MeshState
 *   src: the link it was opened by (#src=); options: the pipeline options that made `result` (the panel returns to them on cancel);
 *   stale: the worker's lines may no longer be `result`'s (a cancelled or failed run, a worker restart);
 *   surface: the surface drawn when it was loaded, until the first result (no result: no lines yet)
 * @typedef {{shown: MeshState | null, loading: (MeshState & {restore: object | null}) | null,
 *            error: string | null, notes: string[], progress: {stage: string, fraction: number} | null}} PageState
 *   restore: the panel's pipeline options to return to if the load is cancelled
 * @typedef {'empty' | 'loading' | 'computing' | 'ready' | 'error'} Phase
 */

/** @returns {PageState} */
export const emptyState = () => ({ shown: null, loading: null, error: null, notes: [], progress: null });

/**
 * loading: a new file is read or computed; computing: the shown mesh re-runs
 * (a changed parameter); error: the last action failed (the shown mesh, if
 * any, is still whole); ready: the shown mesh has its lines; empty: nothing.
 * @param {PageState} state
 * @returns {Phase}
 */
export function phaseOf(state) {
  if (state.loading) return 'loading';
  if (state.shown?.session.busy) return 'computing';
  if (state.error) return 'error';
  return state.shown ? 'ready' : 'empty';
}

const count = (/** @type {number | undefined} */ n) => (n === undefined ? '' : `${n.toLocaleString('en-US')} triangles`);

/** The header: what the page is about now. @param {PageState} state */
export function headerOf({ shown, loading }) {
  if (loading) return `${loading.name}: reading…`;
  if (!shown) return '';
  const header = `${shown.name}: ${count(shown.triangles ?? shown.result?.stats.triangles)}`;
  if (shown.result) return header;
  return `${header}, ${shown.session.busy ? 'computing its lines…' : 'lines not computed'}`;
}

/** The label over the picture while it shows the previous mesh, or ''. @param {PageState} state */
export function viewLabelOf({ shown, loading }) {
  return shown && loading ? `Previous mesh: ${shown.name} (shown until ${loading.name} is read)` : '';
}

/** The counts of a mesh without lines yet (the stats line), or ''. @param {MeshState} shown */
export function countsOf(shown) {
  if (shown.vertices === undefined) return '';
  const lines = shown.session.busy ? 'lines: computing…' : 'lines: not computed (cancelled; change a setting to compute them)';
  return [
    shown.name,
    `${shown.vertices.toLocaleString('en-US')} vertices, ${count(shown.triangles)}`,
    lines,
    shown.loadMs === undefined ? '' : `read and repair ${shown.loadMs.toFixed(0)} ms`,
  ]
    .filter(Boolean)
    .join('\n');
}

/**
 * What the exports save, or the sentence saying why there is nothing.
 * @param {PageState} state
 * @returns {{shown: MeshState} | {refusal: string}}
 */
export function exportSource({ shown }) {
  if (!shown) return { refusal: 'Nothing to export yet: open a mesh and wait for its lines.' };
  if (shown.session.busy) return { refusal: `Nothing to export yet: wait for the ${shown.result ? 'new ' : ''}lines of ${shown.name} (or Cancel).` };
  if (!shown.result) return { refusal: `Nothing to export yet: the lines of ${shown.name} are not computed (cancelled); change a setting to compute them.` };
  return { shown };
}
