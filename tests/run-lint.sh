#!/usr/bin/env bash
# JavaScript checks: ESLint's recommended rules over web/, wasm/, tests/,
# bench/ and scripts/ (eslint.config.js), and the type check of the worker
# protocol, the client and the package's .d.ts (JSDoc types in files marked
# // @ts-check; web/tsconfig.json), and the README example against the .d.ts.
set -euo pipefail
cd "$(dirname "$0")/.."
npx --no-install eslint --max-warnings 0 .
echo "lint: eslint passed"
npx --no-install tsc -p web
echo "lint: tsc -p web passed"
node tests/check-readme-types.mjs
