#!/usr/bin/env bash
# One-step set-up on Debian 12: installs the missing Debian packages (idempotent: a few seconds when all are there),
# configures and builds twinslam in Release with -j2 into build/ (TWINSLAM_BUILD_DIR). Extra arguments go to the
# cmake configure step (scripts/test.sh --sanitize passes the sanitizer build's options).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${TWINSLAM_BUILD_DIR:-$root/build}

missing=()
while read -r pkg; do
  [[ -z "$pkg" || "$pkg" == \#* ]] && continue
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done < "$root/scripts/packages.txt"
if (( ${#missing[@]} )); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
  sudo=""; [[ $(id -u) -eq 0 ]] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# npm packages, installed exactly as package-lock.json says (npm ci), rerun only when node_modules is missing or older
# than the lock file (npm rewrites node_modules/.package-lock.json on every install):
#   services/bridge/web  three.js and esbuild: the web view, bundled at build time (services/bridge/web.cmake)
#   tests/node           the official MCAP reader (@mcap/core), Foxglove's OMG IDL decoder and WebSocket client, and
#                        playwright-core (the web view in Debian's chromium): the Node checks of the test suite
for node_dir in "$root/services/bridge/web" "$root/tests/node"; do
  installed=$node_dir/node_modules/.package-lock.json
  [[ -f "$installed" && ! "$node_dir/package-lock.json" -nt "$installed" ]] && continue
  if command -v npm >/dev/null; then
    echo "setup: npm ci in ${node_dir#$root/}" >&2
    (cd "$node_dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  else
    echo "setup: npm not found: ${node_dir#$root/} is not installed (the web view and the Node checks need it)" >&2
  fi
done

[[ -n "${TWINSLAM_SETUP_PACKAGES_ONLY:-}" ]] && exit 0
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# Two jobs: a 2-core, 24 GB machine; translation units with PCL (later) need ~2 GB each.
cmake --build "$build" -j2
