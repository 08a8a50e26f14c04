// The widget's pipeline worker: one WASM module shared by the sessions of
// every <crestline-viewer> assigned to this worker (see pool.js), one Engine
// (Session + Pipeline) per viewer. Messages carry the viewer's `id`:
//
// page → worker
//   {type: 'open', id, job, url (absolute), options}   fetch, decode (web/src/io), then as 'load'
//   {type: 'load', id, job, name, positions, indices, options}
//   {type: 'options', id, job, options}      only the dirty stages re-run
//   {type: 'export', id, request, format: 'obj'|'json'}
//   {type: 'dispose', id}
// worker → page
//   {type: 'progress', id, job, stage, fraction}   stage 'fetch', 'decode', then the pipeline's
//   {type: 'loaded', id, job, vertices, triangles, notes}
//   {type: 'result', id, job, ran, stats, lines, surface?}
//   {type: 'reload', id, job}   this worker lost the viewer's mesh (after an abort): open it again
//   {type: 'export', id, request, text}
//   {type: 'error', id, job | request, message, kind, named}   named: the message names the file
import createCrestline from '../../../wasm/dist/crestline.js';
import wasmUrl from '../../../wasm/dist/crestline.wasm?url';
import { DRACOLoader } from 'three/examples/jsm/loaders/DRACOLoader.js';
import { loadMeshFiles } from '../io/load-files.js';
import { MeshError } from '../io/mesh-error.js';
import { Engine, createEngine } from '../worker/engine.js';
import { transferables } from '../worker/protocol.js';
import { fetchMesh } from './fetch-mesh.js';

let first = null; // the module's creation; its Engine serves the first viewer
const engines = new Map();
const latest = new Map(); // viewer id → its newest job: an older 'open' stops after each await
let dracoLoader = null; // its decoder files sit beside this worker's bundle

const post = (message) => self.postMessage(message, transferables(message));

async function engineFor(id) {
  if (engines.has(id)) return engines.get(id);
  first ??= createEngine(createCrestline, { wasmUrl });
  const shared = await first;
  const engine = [...engines.values()].includes(shared) ? new Engine(shared.module) : shared;
  engines.set(id, engine);
  return engine;
}

function run(engine, { id, job, options }, sendSurface) {
  let last = '';
  const progress = (stage, fraction) => {
    if (stage !== last || fraction === 1) self.postMessage({ type: 'progress', id, job, stage, fraction });
    last = stage;
    return true;
  };
  const result = engine.run(options, progress);
  const surface = sendSurface || result.ran.includes('presmooth') ? engine.surface() : undefined;
  post({ type: 'result', id, job, ran: result.ran, stats: result.stats, lines: result.lines, surface });
}

function load(engine, message, soup) {
  const { id, job } = message;
  const loaded = engine.load(soup);
  post({ type: 'loaded', id, job, vertices: loaded.vertices, triangles: loaded.triangles, notes: loaded.notes });
  run(engine, message, true);
}

/** Fetches and decodes off the page's thread; returns null when a newer job replaced this one. */
async function open({ id, job, url }) {
  const current = () => latest.get(id) === job;
  const files = await fetchMesh(url, (fraction) => self.postMessage({ type: 'progress', id, job, stage: 'fetch', fraction }));
  if (!current()) return null;
  self.postMessage({ type: 'progress', id, job, stage: 'decode', fraction: 0 });
  dracoLoader ??= new DRACOLoader();
  const soup = await loadMeshFiles(files, { dracoLoader });
  return current() ? soup : null;
}

async function handle(message) {
  const { id, job } = message;
  if (message.type === 'dispose') {
    engines.get(id)?.dispose();
    engines.delete(id);
    latest.delete(id);
    return;
  }
  if (job !== undefined) latest.set(id, job);
  const engine = await engineFor(id);
  switch (message.type) {
    case 'open': {
      const soup = await open(message);
      if (soup) load(engine, message, soup);
      break;
    }
    case 'load':
      load(engine, message, message);
      break;
    case 'options':
      // After a WebAssembly abort reset this worker, the viewer must send its mesh again.
      if (!engine.session) post({ type: 'reload', id, job });
      else run(engine, message, false);
      break;
    case 'export': {
      post({ type: 'export', id, request: message.request, text: engine.exportText(message.format) });
      break;
    }
  }
}

if (typeof WorkerGlobalScope !== 'undefined' && self instanceof WorkerGlobalScope) {
  self.onmessage = async ({ data }) => {
    try {
      await handle(data);
    } catch (error) {
      // An abort leaves the module unusable: every session of this worker starts over.
      if (error instanceof WebAssembly.RuntimeError) {
        engines.clear();
        first = null;
      }
      const message = error instanceof WebAssembly.RuntimeError
        ? `The computation failed inside WebAssembly (${error.message}).`
        : error.message;
      post({ type: 'error', id: data.id, job: data.job, request: data.request, message, kind: error.kind ?? 'internal', named: error instanceof MeshError });
    }
  };
}
