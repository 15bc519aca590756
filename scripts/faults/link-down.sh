#!/usr/bin/env bash
# Fault (issue 14): the drone-edge link goes down mid-flight. The drone and the edge run in network namespaces of
# their own (scripts/two-hosts.sh, realtime replay, needs root); the link is cut AT_S seconds into the run for FOR_S
# seconds. The same flight runs undisturbed first. For both it ends with: the poses out of the camera frames and the
# largest gap between poses, the outage in seconds of the flight, the first registration accepted after it, the
# registrations accepted, and the ATE in W (from the declared alignment on) against the ground truth.
# Usage: bash scripts/faults/link-down.sh [DATASET] [AT_S] [FOR_S]
#   DATASET: a simulated dataset with ground truth (default: runs/fault-link-flight, simulated once from
#            deploy/scenarios/edge-faults.yaml: tiny's city, 100 s); AT_S, FOR_S: default 45 and 30
set -euo pipefail
die() { echo "link-down: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=${TWINSLAM_BUILD_DIR:-$root/build}/bin
[[ -x $bin/twinslam ]] || die "$bin/twinslam not built (bash scripts/test.sh builds it)"
dataset=${1:-$root/runs/fault-link-flight}
at=${2:-45}; for_s=${3:-30}
if [[ -z ${1:-} && ! -d $dataset/mav0 ]]; then
  "$bin/twinslam" sim --scenario "$root/deploy/scenarios/edge-faults.yaml" --out "$dataset" --features --quiet
fi
[[ -d $dataset/mav0 ]] || die "$dataset: not a dataset (no mav0/)"
features=()
[[ -f $dataset/mav0/cam0/features.csv ]] && features=(--features)

seconds_of_day() { awk -F'[:.]' '{ printf "%.3f", $1 * 3600 + $2 * 60 + $3 + ("0." $4) }' <<< "$1"; }
# One line per run: what the drone flew and what the edge gave it.
report() {  # NAME OUT LOG
  local run=$2/run start t0 down up
  start=$(seconds_of_day "$(grep -m1 'replay starts' "$run/logs/ingest.log" | cut -d' ' -f1)")
  t0=$(grep -m1 -o 'sensor stamp [0-9]*' "$run/logs/ingest.log" | grep -o '[0-9]*$')
  down=$(grep -o 'link down at [0-9:.]*' "$3" | grep -o '[0-9:.]*$' || true)
  up=$(grep -o 'link up at [0-9:.]*' "$3" | grep -o '[0-9:.]*$' || true)
  local outage="none" after=0
  if [[ -n $down && -n $up ]]; then
    down=$(awk -v a="$(seconds_of_day "$down")" -v s="$start" 'BEGIN { printf "%.1f", a - s }')
    up=$(awk -v a="$(seconds_of_day "$up")" -v s="$start" 'BEGIN { printf "%.1f", a - s }')
    outage="$down-$up s"; after=$up
  fi
  local poses frames gap first accepted ate
  poses=$(grep -vc '^#' "$run/trajectory.tum")
  frames=$(($(wc -l < "$dataset/mav0/cam0/data.csv") - 1))
  gap=$(awk '!/^#/ { if (n++) { d = $1 - p; if (d > g) g = d } p = $1 } END { printf "%.2f", g }' "$run/trajectory.tum")
  first=$(awk -F, -v t0="$t0" -v after="$after" 'NR > 1 && $2 == 1 { t = ($1 - t0) / 1e9; if (t > after) { printf "%.1f s", t; exit } }' "$run/registrations.csv")
  accepted=$(awk -F, 'NR > 1 && $2 == 1 { n++ } END { print n + 0 }' "$run/registrations.csv")
  ate=$("$bin/twinslam" eval --gt "$dataset" --est "$run" --align none --json | grep -o '"ate_pos_rmse_m": *[0-9.e-]*' | grep -o '[0-9.e-]*$')
  printf "%-12s poses %s/%s, largest gap %s s | outage %s | first accepted registration after it %s | accepted %s | ATE in W %.3f m\n" \
    "$1" "$poses" "$frames" "$gap" "$outage" "${first:-none}" "$accepted" "$ate"
}

out=$root/runs/fault-link
rm -rf "$out"; mkdir -p "$out"
bash "$root/scripts/two-hosts.sh" "$dataset" "$out/undisturbed" --realtime "${features[@]}" > "$out/undisturbed.log" 2>&1 ||
  die "the undisturbed run failed ($out/undisturbed.log)"
status=0
bash "$root/scripts/two-hosts.sh" "$dataset" "$out/link-down" --link-down "$at" "$for_s" --realtime "${features[@]}" \
  > "$out/link-down.log" 2>&1 || status=$?
echo "fault: the drone-edge link down ${at} s into the run for ${for_s} s (run exit $status; $out)"
report undisturbed "$out/undisturbed" "$out/undisturbed.log"
report link-down "$out/link-down" "$out/link-down.log"
exit "$status"
