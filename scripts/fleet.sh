#!/usr/bin/env bash
# A fleet on one edge (issue 14 item 6): one tiles service and one registration service serve every vehicle, each
# vehicle's own processes (ingest, tracking, estimator, its run's recorder) talk in a DDS partition named after it, so
# no vehicle's sensors reach another's estimator; the edge's processes are in partitions "edge,*" (they read every
# vehicle and each other). With --split two registration instances share the fleet, each in the partitions of half of
# the vehicles plus "edge": DDS itself routes each vehicle's LocalMaps to its instance only.
#
#   bash scripts/fleet.sh OUT DATASET... [--split] [--max] [-- TWINSLAM RUN OPTIONS...]
#
# The datasets must share one twin (the edge serves one store, built into OUT/twin-store). Dataset K flies as vehicle
# uavK (`twinslam run DATASET --mode vio-twin --realtime --shared-edge --vehicle uavK`, OUT/uavK); all start at once.
# --max: lockstep replay instead of realtime (each vehicle waits for the shared edge's answer to each LocalMap).
# OUT/edge/*.log the edge's logs (each registration instance ends with the vehicles it served), OUT/edge-usage.csv the
# edge processes' CPU time and resident memory once a second. Prints a line per vehicle (registrations accepted and
# fused, latency from LocalMap to Registration, ATE in W) and the edge's CPU and memory. TWINSLAM_BIN: executables.
set -euo pipefail
die() { echo "fleet.sh: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[[ $# -ge 2 ]] || die "usage: fleet.sh OUT DATASET... [--split] [--max] [-- TWINSLAM RUN OPTIONS...]"
out=$(realpath -m "$1"); shift
datasets=(); split=0; run_options=(); replay=--realtime
while [[ $# -gt 0 ]]; do
  case "$1" in
    --split) split=1; shift ;;
    --max) replay=--max; shift ;;
    --) shift; run_options=("$@"); break ;;
    *) [[ -f $1/dataset.yaml ]] || die "$1: not a dataset (no dataset.yaml)"; datasets+=("$(realpath "$1")"); shift ;;
  esac
done
n=${#datasets[@]}
[[ $n -ge 1 ]] || die "no dataset given"
[[ $split -eq 0 || $n -ge 2 ]] || die "--split needs at least two vehicles"
bin=${TWINSLAM_BIN:-$root/build/bin}
[[ -x $bin/twinslam ]] || die "$bin/twinslam not found (build first, or set TWINSLAM_BIN)"

# One twin for the whole fleet: the first dataset's, every other must be the same files.
twin0=$(sed -n 's/^ *path: *"\{0,1\}\([^"]*\)"\{0,1\}.*/\1/p' "${datasets[0]}/dataset.yaml" | head -1)
[[ -n $twin0 ]] || die "${datasets[0]}/dataset.yaml names no twin path"
sum0=$(cd "${datasets[0]}" && md5sum "$twin0" | cut -d' ' -f1)
for d in "${datasets[@]}"; do
  [[ $(cd "$d" && md5sum "$twin0" 2>/dev/null | cut -d' ' -f1) == "$sum0" ]] ||
    die "$d: its twin ($twin0) is not ${datasets[0]}'s: a fleet shares one edge and one twin"
done
origin=$(sed -n 's/^origin: *{lat: *\([^,]*\), *lon: *\([^,]*\), *alt: *\([^}]*\)}.*/\1,\2,\3/p' "${datasets[0]}/dataset.yaml")
[[ -n $origin ]] || die "${datasets[0]}/dataset.yaml: no origin {lat, lon, alt}"

rm -rf "$out"; mkdir -p "$out/edge"
"$bin/twinslam" twin build "${datasets[0]}/$twin0" --origin "$origin" --out "$out/twin-store" > "$out/edge/twin-build.log" 2>&1

export TWINSLAM_DOMAIN=${TWINSLAM_DOMAIN:-$(( $$ % 40 + 60 ))}  # runs' private domains are 100..199
edge_pids=(); sampler=
cleanup() {
  [[ -n $sampler ]] && { kill "$sampler" 2>/dev/null || true; }
  for p in "${edge_pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${edge_pids[@]}"; do wait "$p" 2>/dev/null || true; done
}
trap cleanup EXIT
start_edge() {  # NAME PARTITIONS EXEC ARGS...
  local name=$1 partition=$2 exe=$3; shift 3
  "$bin/$exe" "$replay" --vehicle "" --partition "$partition" "$@" > "$out/edge/$name.log" 2>&1 &
  edge_pids+=($!)
  echo "$name $!" >> "$out/edge/pids"
}
start_edge tiles "edge,*" twinslam-tiles --twin "$out/twin-store"
vehicles=(); for ((k = 0; k < n; k++)); do vehicles+=("uav$k"); done
if [[ $split -eq 1 ]]; then
  half_a=$(printf '%s,' "${vehicles[@]:0:$(( (n + 1) / 2 ))}"); half_b=$(printf '%s,' "${vehicles[@]:$(( (n + 1) / 2 ))}")
  start_edge registration-a "${half_a}edge" twinslam-registration
  start_edge registration-b "${half_b}edge" twinslam-registration
else
  start_edge registration "edge,*" twinslam-registration
fi

# The edge's CPU time (user + system, s) and resident memory once a second.
echo "t_s,process,pid,cpu_s,rss_mb" > "$out/edge-usage.csv"
tick=$(getconf CLK_TCK)
( while true; do
    while read -r name pid; do
      [[ -r /proc/$pid/stat ]] || continue
      awk -v t="$(date +%s.%N)" -v n="$name" -v p="$pid" -v hz="$tick" \
        '{ printf "%.2f,%s,%s,%.2f,", t, n, p, ($14 + $15) / hz }' "/proc/$pid/stat"
      awk '/^VmRSS/ { printf "%.1f\n", $2 / 1024 }' "/proc/$pid/status"
    done < "$out/edge/pids"
    sleep 1
  done >> "$out/edge-usage.csv" ) &
sampler=$!

run_pids=()
for ((k = 0; k < n; k++)); do
  "$bin/twinslam" run "${datasets[$k]}" --mode vio-twin "$replay" --shared-edge --vehicle "${vehicles[$k]}" \
    --out "$out/${vehicles[$k]}" --no-progress "${run_options[@]}" > "$out/${vehicles[$k]}.log" 2>&1 &
  run_pids+=($!)
done
failed=0
for ((k = 0; k < n; k++)); do wait "${run_pids[$k]}" || { echo "fleet.sh: ${vehicles[$k]} failed: $out/${vehicles[$k]}.log" >&2; failed=1; }; done
cleanup; trap - EXIT; sampler=; edge_pids=()

python3 "$root/scripts/fleet_report.py" "$out" "$bin/twinslam" "${datasets[@]}"
exit $failed
