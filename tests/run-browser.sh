#!/usr/bin/env bash
# The web app (web/dist) in headless Debian Chromium through playwright-core.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f web/dist/index.html ]; then
  echo "run-browser: web/dist is missing; run web/build.sh" >&2
  exit 1
fi
node --test --test-concurrency=1 tests/browser/*.test.mjs
