// @ts-check
// The page's one state (issue 17): the mesh shown (its picture, stats and
// exports belong together) and the file being loaded, each with its own
// client Session. A new file replaces the shown mesh only when its lines are
// ready, so the page never mixes two meshes: while it loads, the previous
// mesh stays in view, dimmed and labelled; Cancel drops the new file and the
// page is the previous mesh's again, header, picture, stats and exports.
// Every view (dom.js, the exports) reads the phase and texts from here.

/**
 * @typedef {import('../client/client.js').Session} Session
 * @typedef {import('../client/client.js').Result} Result
 * @typedef {{session: Session, name: string, src?: string, vertices?: number, triangles?: number, loadMs?: number,
 *            notes: string[], result?: Result, options?: object, stale?: boolean}} MeshState
 *   src: the link it was opened by (#src=); options: the pipeline options that made `result` (the panel returns to them on cancel);
 *   stale: the worker's lines may no longer be `result`'s (a cancelled or failed run, a worker restart)
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
  if (loading) return loading.triangles === undefined ? `${loading.name}: reading…` : `${loading.name}: ${count(loading.triangles)}, computing its lines…`;
  if (shown) return `${shown.name}: ${count(shown.triangles ?? shown.result?.stats.triangles)}`;
  return '';
}

/** The label over the picture while it shows the previous mesh, or ''. @param {PageState} state */
export function viewLabelOf({ shown, loading }) {
  return shown && loading ? `Previous mesh: ${shown.name} (shown until ${loading.name} is ready)` : '';
}

/**
 * What the exports save, or the sentence saying why there is nothing.
 * @param {PageState} state
 * @returns {{shown: MeshState} | {refusal: string}}
 */
export function exportSource({ shown }) {
  if (!shown?.result) return { refusal: 'Nothing to export yet: open a mesh and wait for its lines.' };
  if (shown.session.busy) return { refusal: `Nothing to export yet: wait for the new lines of ${shown.name} (or Cancel).` };
  return { shown };
}
