#!/usr/bin/env bash
# Fault (issue 14): an edge service is killed with SIGKILL mid-flight. `twinslam run` restarts it with back-off and
# lists the restart in run.json; the estimator flies on meanwhile. Ends with the run's status, its restarts and the
# ATE in W (from the declared alignment on) against the ground truth.
# Usage: bash scripts/faults/kill-edge-service.sh registration|tiles [DATASET] [AFTER_S]
#   DATASET: a simulated dataset with ground truth (default: runs/fault-tiny, simulated once from the `tiny` scenario)
#   AFTER_S: seconds after the service started before it is killed (default 5)
set -euo pipefail
usage="usage: kill-edge-service.sh registration|tiles [DATASET] [AFTER_S]"
service=${1:-}
case "$service" in
  registration|tiles) ;;
  *) echo "kill-edge-service: the service must be registration or tiles, not '${service}' ($usage)" >&2; exit 2 ;;
esac
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
twinslam=${TWINSLAM_BUILD_DIR:-$root/build}/bin/twinslam
[[ -x $twinslam ]] || { echo "kill-edge-service: $twinslam not built (bash scripts/test.sh builds it)" >&2; exit 2; }
dataset=${2:-$root/runs/fault-tiny}
after=${3:-5}
if [[ -z ${2:-} && ! -d $dataset/mav0 ]]; then
  "$twinslam" sim --scenario tiny --out "$dataset" --features --quiet
fi
[[ -d $dataset/mav0 ]] || { echo "kill-edge-service: $dataset: not a dataset (no mav0/)" >&2; exit 2; }
features=()
[[ -f $dataset/mav0/cam0/features.csv ]] && features=(--features)
out=$root/runs/fault-kill-$service
rm -rf "$out" "$out.log"
"$twinslam" run "$dataset" --mode vio-twin "${features[@]}" --out "$out" > "$out.log" 2>&1 &
run_pid=$!
pid=""
for _ in $(seq 1 600); do
  pid=$(pgrep -P "$run_pid" -f "twinslam-$service" || true)
  [[ -n $pid ]] && break
  sleep 0.1
done
if [[ -z $pid ]]; then
  echo "kill-edge-service: twinslam-$service never started (see $out/logs)" >&2
  wait "$run_pid" || true
  exit 1
fi
sleep "$after"
if kill -9 "$pid" 2>/dev/null; then
  echo "fault: killed twinslam-$service (pid $pid) ${after} s after it started"
else
  echo "fault: twinslam-$service (pid $pid) had already ended; nothing killed" >&2
fi
status=0
wait "$run_pid" || status=$?
echo "run $out: exit $status"
# run.json: the status and the restarts (one object per restart).
tr -d '\n' < "$out/run.json" | grep -o '"restarts": *\[[^]]*\]' | tr -s ' ' || echo '"restarts": none recorded'
grep -o '"status": *"[a-z]*"' "$out/run.json"
"$twinslam" eval --gt "$dataset" --est "$out"
exit "$status"
