#!/usr/bin/env bash
# Fails when a tracked C++ file differs from what clang-format (.clang-format)
# would make of it, or a JavaScript file under web/src, wasm/, tests/ or bench/
# from what Prettier (.prettierrc.json) would make of it
# (the lock file's version; fetched by npx where node_modules lacks it).
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
mapfile -t files < <(git ls-files '*.cpp' '*.h' | grep -v '^web/')
if clang-format --dry-run --Werror "${files[@]}" 2>/dev/null; then
  echo "format: ${#files[@]} files as clang-format writes them"
else
  clang-format --dry-run "${files[@]}" 2>&1 | grep -o '^[^:]*:[0-9]*' | sort -u | head -20
  echo "format: run clang-format -i on the files above" >&2
  status=1
fi
js=("web/src/**/*.js" "wasm/*.mjs" "tests/**/*.mjs" "bench/*.mjs")
prettier=(npx --no-install prettier)
if [ ! -x node_modules/.bin/prettier ]; then
  # A work tree sharing another's node_modules: the lock file's Prettier from the npm registry.
  version=$(node -p "require('./package-lock.json').packages['node_modules/prettier'].version")
  prettier=(npx --yes "prettier@$version")
fi
if "${prettier[@]}" --check --log-level warn "${js[@]}"; then
  echo "format: JavaScript as Prettier writes it"
else
  echo "format: run npx prettier --write on the files above" >&2
  status=1
fi
exit $status
