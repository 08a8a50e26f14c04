#!/usr/bin/env bash
# Installs whatever is missing on a Debian bookworm machine (as root): the
# Debian packages the build and tests need, and the npm packages of
# package-lock.json. Fast when everything is already there.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libtinygltf-dev nlohmann-json3-dev libfast-float-dev libfmt-dev
  libcli11-dev libdraco-dev libmeshoptimizer-dev catch2
  emscripten nodejs chromium
  clang clang-format clang-tidy libclang-rt-14-dev python3
)
missing=()
# Node.js may come from elsewhere (e.g. a nodesource build that bundles npm,
# which conflicts with Debian's npm package): only ask Debian for npm if the
# command is missing.
command -v npm >/dev/null 2>&1 || packages+=(npm)
for p in "${packages[@]}"; do
  # A nodejs that ships its own npm (e.g. NodeSource) conflicts with Debian's npm.
  if [ "$p" = npm ] && command -v npm >/dev/null; then continue; fi
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# npm packages: reinstall only when the lock file changed since the last install.
if [ ! -f node_modules/.package-lock.json ] || ! cmp -s package-lock.json node_modules/.crestline-lock; then
  echo "setup: installing npm packages"
  npm ci --no-audit --no-fund --loglevel=error
  cp package-lock.json node_modules/.crestline-lock
fi
