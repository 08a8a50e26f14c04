/* global Module, navigator, require */
// The threaded build only (crestline-mt), after pre.js: how many threads the
// pipeline uses. Module.threadCount may be given to the factory; otherwise
// the cores the browser (or node) reports, at most 8. The pthread pool
// (PTHREAD_POOL_SIZE=Module.pthreadPoolSize) starts with the module, and once
// the runtime is up the core is told to use exactly that many
// (Module.setThreads; Module.threads() reports it).
if (!(Module['threadCount'] >= 1)) {
  var cores = typeof navigator == 'object' && navigator.hardwareConcurrency;
  if (!cores && typeof process == 'object' && typeof require == 'function') cores = require('os').cpus().length;
  Module['threadCount'] = Math.max(1, Math.min(cores || 1, 8));
}
Module['threadCount'] = Math.floor(Module['threadCount']);
// At least one pooled worker: with none, 3.1.6's glue never finishes starting.
Module['pthreadPoolSize'] = Math.max(1, Module['threadCount'] - 1);
var crestlineRuntimeInitialized = Module['onRuntimeInitialized'];
Module['onRuntimeInitialized'] = function () {
  Module['setThreads'](Module['threadCount']);
  if (crestlineRuntimeInitialized) crestlineRuntimeInitialized();
};
