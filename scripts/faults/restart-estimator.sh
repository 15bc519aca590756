#!/usr/bin/env bash
# Fault (issue 14): the drone's estimator is killed (SIGKILL) mid-flight and restarted by `twinslam run --restart
# estimator` (realtime replay: in lockstep ingest would wait for the dead estimator). The new estimator starts from
# nothing: it initializes in flight, aligns to W from GNSS again, and registration and tiles must serve it again (the
# same vehicle_id). The same flight runs undisturbed first. For both it ends with common.sh's report line (the
# fault: from the kill to the new process; the largest gap between poses; the first registration accepted after it;
# ATE in W over the poses in W: run.json out_of_world_ns lists the stretch the new estimator spent in its own L) and
# the restarts.
# Usage: bash scripts/faults/restart-estimator.sh [DATASET] [AT_S]
#   DATASET: a simulated dataset with ground truth (default: runs/fault-link-flight, simulated once from
#            deploy/scenarios/edge-faults.yaml: tiny's city, 100 s); AT_S: seconds into the replay (default 45)
set -euo pipefail
die() { echo "restart-estimator: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=${TWINSLAM_BUILD_DIR:-$root/build}/bin
[[ -x $bin/twinslam ]] || die "$bin/twinslam not built (bash scripts/test.sh builds it)"
at=${2:-45}
[[ $at =~ ^[0-9]+([.][0-9]+)?$ ]] || die "AT_S: seconds, not '$at'"
source "$root/scripts/faults/common.sh"
fault_flight "${1:-}"
now() { date +%T.%N | cut -c1-12; }

out=$root/runs/fault-estimator
rm -rf "$out"; mkdir -p "$out/undisturbed" "$out/restarted"
"$bin/twinslam" run "$dataset" --mode vio-twin --realtime "${features[@]}" --no-progress --out "$out/undisturbed/run" \
  > "$out/undisturbed.log" 2>&1 || die "the undisturbed run failed ($out/undisturbed.log)"

"$bin/twinslam" run "$dataset" --mode vio-twin --realtime "${features[@]}" --no-progress --out "$out/restarted/run" \
  --restart estimator,tiles,registration > "$out/restarted.log" 2>&1 &
run_pid=$!
# The replay starts when ingest says so; the kill falls AT_S seconds later.
for _ in $(seq 1 600); do
  grep -qs 'replay starts' "$out/restarted/run/logs/ingest.log" && break
  sleep 0.1
done
if ! grep -qs 'replay starts' "$out/restarted/run/logs/ingest.log"; then
  wait "$run_pid" || true
  die "the replay never started"
fi
sleep "$at"
pid=$(pgrep -P "$run_pid" -f twinslam-estimator || true)
[[ -n $pid ]] || { wait "$run_pid" || true; die "no estimator to kill ${at} s into the replay"; }
kill -9 "$pid"
# The fault's times in a file of their own (the run writes restarted.log at its own offset).
echo "restart-estimator: fault begins at $(now): estimator pid $pid killed" > "$out/fault.log"
new=""
for _ in $(seq 1 300); do
  new=$(pgrep -P "$run_pid" -f twinslam-estimator || true)
  [[ -n $new && $new != "$pid" ]] && break
  sleep 0.05
done
echo "restart-estimator: fault ends at $(now): estimator back as pid ${new:-none}" >> "$out/fault.log"
status=0
wait "$run_pid" || status=$?
echo "fault: the estimator killed ${at} s into the replay and restarted (run exit $status; $out)"
report undisturbed "$out/undisturbed" "$out/undisturbed.log"
report restarted "$out/restarted" "$out/fault.log"
python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
since_first = lambda t: (t - d["aligned_from_stamp_ns"]) / 1e9 + d["aligned_after_s"]
print("restarted: status %s, restarts %s, out of W after the alignment %s" % (d["status"],
      [(r["service"], r["ended"], round(r["at_s"], 1)) for r in d["restarts"]],
      ["%.1f-%.1f s" % (since_first(a), since_first(b)) for a, b in d["out_of_world_ns"]]))' \
  "$out/restarted/run/run.json"
exit "$status"
