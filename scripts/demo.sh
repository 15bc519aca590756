#!/usr/bin/env bash
# The main job: set-up, then run the service pipeline on a dataset and print what it produced.
# Until the simulator and estimator land this replays the real EuRoC excerpt through all services (lockstep) and
# prints the message counts; later it simulates the default city and prints the accuracy table.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${TWINSLAM_BUILD_DIR:-$root/build}
bash "$root/scripts/setup.sh"
dataset=${1:-$root/../shared/data/euroc-v1-01-micro}
"$build/bin/twinslam" run "$dataset" --mode vio --out "$root/runs/demo"
echo "run record: $root/runs/demo/run.json (service logs in $root/runs/demo/logs/)"
