#!/usr/bin/env bash
# The main job: set-up, simulate the default city flight (city-loops, once), run the service pipeline on it and
# print what it produced; once the estimator publishes poses, also the accuracy against ground truth.
# Usage: bash scripts/demo.sh [DATASET]   (an existing dataset folder, e.g. ../shared/data/euroc-v1-01-micro)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${TWINSLAM_BUILD_DIR:-$root/build}
bash "$root/scripts/setup.sh"
twinslam="$build/bin/twinslam"
dataset=${1:-$root/runs/city-loops}
if [[ ! -f "$dataset/dataset.yaml" && ! -d "$dataset/mav0" ]]; then
  "$twinslam" sim --scenario city-loops --out "$dataset" --features --preview
fi
"$twinslam" run "$dataset" --mode vio --out "$root/runs/demo"
if [[ -f "$root/runs/demo/trajectory.tum" ]]; then
  "$twinslam" eval --gt "$dataset" --est "$root/runs/demo" --align posyaw
fi
echo "run record: $root/runs/demo/run.json (service logs in $root/runs/demo/logs/)"
