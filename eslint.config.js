// ESLint (flat config) over the JavaScript of web/, wasm/, tests/ and bench/:
// the recommended rules, which catch bugs (undefined names, unused
// variables, unreachable code, …); no style rules. Run by tests/run-lint.sh.
import js from '@eslint/js';
import globals from 'globals';

export default [
  { ignores: ['**/dist/**', 'build*/**', 'node_modules/**', 'test-results/**', 'out/**', 'fuzz/**', 'web/types/**'] },
  js.configs.recommended,
  {
    rules: {
      'no-unused-vars': ['error', { argsIgnorePattern: '^_', varsIgnorePattern: '^_', caughtErrors: 'none' }],
      // Errors here carry one sentence for the user; the original is not shown.
      'preserve-caught-error': 'off',
    },
  },
  // The page, the widget and the worker.
  { files: ['web/src/**/*.js'], languageOptions: { globals: { ...globals.browser, ...globals.worker } } },
  // Node: configs, the CLI on WASM, node tests, benchmarks, the node worker.
  {
    files: ['web/*.config.js', 'wasm/*.mjs', 'tests/**/*.mjs', 'bench/*.mjs', 'scripts/*.mjs', 'eslint.config.js', 'web/src/client/node.js', 'web/src/worker/node-worker.js', 'web/src/index.node.js'],
    languageOptions: { globals: globals.node },
  },
  // Browser tests and the browser benchmark: functions passed to page.evaluate run in the page.
  { files: ['tests/browser/**/*.mjs', 'bench/browser.mjs'], languageOptions: { globals: { ...globals.node, ...globals.browser } } },
  // Emscripten's --pre-js runs inside the module factory.
  { files: ['wasm/pre.js'], languageOptions: { sourceType: 'script', globals: { Module: 'writable' } } },
];
