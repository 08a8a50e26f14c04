// Messages between the page and the pipeline worker. Only plain objects and
// typed arrays travel; the worker never posts a view of the WASM heap.
//
// page → worker
//   {type: 'init', cancelFlag?: Int32Array over a SharedArrayBuffer}
//   {type: 'open', job, files: [{name, bytes: ArrayBuffer}], dracoPath, options}
//       decode the dropped files (web/src/io), then as 'load'
//   {type: 'load', job, name, positions: Float64Array, indices: Uint32Array, options}
//       repair (weld) the soup, build a Pipeline, run it with `options`
//   {type: 'options', job, options}   set_options + run: only dirty stages re-run
//   {type: 'fields', job}             per-vertex curvature/extremality, per-triangle regularity
//   {type: 'export', job, request, format: 'obj'|'json'}   the CLI's text of the current lines
// worker → page
//   {type: 'ready'}
//   {type: 'progress', job, stage, fraction}
//   {type: 'loaded', job, name, vertices, triangles, notes, report, milliseconds (repair), readMs?}
//   {type: 'result', job, ran: [stage], stats, lines, milliseconds, surface?}
//       surface {positions: Float64Array, indices: Uint32Array} when pre-smoothing ran
//   {type: 'fields', job, fields}
//   {type: 'export', job, request, format, text}
//   {type: 'cancelled', job}
//   {type: 'error', job, request?, message, kind, named}   named: the message already names the file;
//       request: the failed export's
//
// Cancel: the page sets cancelFlag[0] = 1; the worker's progress callback
// sees it and the pipeline stops (staying valid up to its last finished
// stage). Without cross-origin isolation there is no shared memory: the page
// then terminates the worker and starts a new one.

/** Pipeline stages in order (core stage_name()). */
export const STAGES = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing', 'tracing', 'singular', 'polylines', 'fairing', 'filter'];

/** UI parameter names → Session.setOptions keys (see wasm/session.h). */
export const OPTION_KEYS = [
  'presmoothSteps',
  'smoothingSteps',
  'smoothingTimeStep',
  'hausdorffBound',
  'threshold',
  'boundaryRings',
  'vertexWeights',
];

/** Transferable buffers of a message payload (every typed array in it). */
export function transferables(value, out = []) {
  if (ArrayBuffer.isView(value)) {
    if (!out.includes(value.buffer)) out.push(value.buffer);
  } else if (value && typeof value === 'object') {
    for (const v of Object.values(value)) transferables(v, out);
  }
  return out;
}
