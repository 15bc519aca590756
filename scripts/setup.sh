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

# The official MCAP reader (@mcap/core) and Foxglove's OMG IDL decoder (@foxglove/omgidl-*), in tests/node, check
# that Foxglove can read our MCAP files (McapNode.OfficialReaderReadsTheSampleFile, McapRecording.*). npm ci installs exactly package-lock.json; rerun only when
# node_modules is missing or older than the lock file (npm rewrites node_modules/.package-lock.json on every install).
node_dir=$root/tests/node
installed=$node_dir/node_modules/.package-lock.json
if [[ ! -f "$installed" || "$node_dir/package-lock.json" -nt "$installed" ]]; then
  if command -v npm >/dev/null; then
    echo "setup: npm ci in tests/node" >&2
    (cd "$node_dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  else
    echo "setup: npm not found: the MCAP official-reader test will fail" >&2
  fi
fi

[[ -n "${TWINSLAM_SETUP_PACKAGES_ONLY:-}" ]] && exit 0
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# Two jobs: a 2-core, 24 GB machine; translation units with PCL (later) need ~2 GB each.
cmake --build "$build" -j2
