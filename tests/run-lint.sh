#!/usr/bin/env bash
# JavaScript checks: the type check of the worker protocol and the client
# (JSDoc types, files marked // @ts-check; web/tsconfig.json).
set -euo pipefail
cd "$(dirname "$0")/.."
npx --no-install tsc -p web
echo "lint: tsc -p web passed"
