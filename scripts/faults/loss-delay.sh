#!/usr/bin/env bash
# Fault (issue 14): a poor drone-edge link, LOSS_PCT % of the packets lost and DELAY_MS added each way for the whole
# flight. The drone and the edge run in network namespaces of their own (scripts/two-hosts.sh --netem: the kernel here
# has no netem qdisc, so the link runs through twinslam-netem; realtime replay, needs root). The same flight runs
# undisturbed first. For both it ends with the report line of common.sh (poses and their largest gap, registrations
# accepted and fused on their own keyframe, latency, ATE in W); for the impaired run also the packets each direction
# lost.
# Usage: bash scripts/faults/loss-delay.sh [DATASET] [LOSS_PCT] [DELAY_MS]
#   DATASET: a simulated dataset with ground truth (default: runs/fault-link-flight, simulated once from
#            deploy/scenarios/edge-faults.yaml: tiny's city, 100 s); LOSS_PCT, DELAY_MS: default 10 and 100
set -euo pipefail
die() { echo "loss-delay: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=${TWINSLAM_BUILD_DIR:-$root/build}/bin
[[ -x $bin/twinslam && -x $bin/twinslam-netem ]] ||
  die "$bin/twinslam or twinslam-netem not built (bash scripts/test.sh builds them)"
loss=${2:-10}; delay=${3:-100}
source "$root/scripts/faults/common.sh"
fault_flight "${1:-}"

out=$root/runs/fault-loss
rm -rf "$out"; mkdir -p "$out"
two_hosts undisturbed "$out" || die "the undisturbed run failed ($out/undisturbed.log)"
status=0
two_hosts impaired "$out" --netem "$loss" "$delay" || status=$?
echo "fault: ${loss} % loss and ${delay} ms delay each way on the drone-edge link for the whole flight" \
  "(run exit $status; $out)"
grep -o 'netem td[0-9]* -> te[0-9]* .*\|netem te[0-9]* -> td[0-9]* .*' "$out/impaired.log" |
  sed -e 's/^netem td[0-9]* -> te[0-9]*/drone -> edge:/' -e 's/^netem te[0-9]* -> td[0-9]*/edge -> drone:/'
report undisturbed "$out/undisturbed" "$out/undisturbed.log"
report impaired "$out/impaired" "$out/impaired.log"
exit "$status"
