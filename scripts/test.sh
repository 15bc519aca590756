#!/usr/bin/env bash
# The whole test suite: set-up (packages, configure, build) then ctest. Called by .ci/run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${TWINSLAM_BUILD_DIR:-$root/build}
bash "$root/scripts/setup.sh"
cd "$build"
ctest -j2 --output-on-failure --timeout 600 "$@"
