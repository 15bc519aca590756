#!/usr/bin/env bash
# Fault (issue 14): a poor drone-edge link, LOSS_PCT % of the packets lost and DELAY_MS added each way for the whole
# flight. The drone and the edge run in network namespaces of their own (scripts/two-hosts.sh --netem: the kernel here
# has no netem qdisc, so the link runs through twinslam-netem; realtime replay, needs root). The same flight runs
# undisturbed first. For both it ends with the line of report.sh (poses and their largest gap, registrations accepted
# and fused on their own keyframe, latency, ATE in W); for the impaired run also the packets each direction lost.
# Usage: bash scripts/faults/loss-delay.sh [DATASET] [LOSS_PCT] [DELAY_MS]
#   DATASET: a simulated dataset with ground truth (default: runs/fault-link-flight, simulated once from
#            deploy/scenarios/edge-faults.yaml: tiny's city, 100 s); LOSS_PCT, DELAY_MS: default 10 and 100
set -euo pipefail
die() { echo "loss-delay: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=${TWINSLAM_BUILD_DIR:-$root/build}/bin
[[ -x $bin/twinslam && -x $bin/twinslam-netem ]] || die "$bin/twinslam or twinslam-netem not built (bash scripts/test.sh builds them)"
dataset=${1:-$root/runs/fault-link-flight}
loss=${2:-10}; delay=${3:-100}
if [[ -z ${1:-} && ! -d $dataset/mav0 ]]; then
  "$bin/twinslam" sim --scenario "$root/deploy/scenarios/edge-faults.yaml" --out "$dataset" --features --quiet
fi
[[ -d $dataset/mav0 ]] || die "$dataset: not a dataset (no mav0/)"
features=()
[[ -f $dataset/mav0/cam0/features.csv ]] && features=(--features)

source "$root/scripts/faults/report.sh"

out=$root/runs/fault-loss
rm -rf "$out"; mkdir -p "$out"
bash "$root/scripts/two-hosts.sh" "$dataset" "$out/undisturbed" --realtime "${features[@]}" > "$out/undisturbed.log" 2>&1 ||
  die "the undisturbed run failed ($out/undisturbed.log)"
status=0
bash "$root/scripts/two-hosts.sh" "$dataset" "$out/impaired" --netem "$loss" "$delay" --realtime "${features[@]}" \
  > "$out/impaired.log" 2>&1 || status=$?
echo "fault: ${loss} % loss and ${delay} ms delay each way on the drone-edge link for the whole flight (run exit $status; $out)"
grep -o 'netem td[0-9]* -> te[0-9]* .*\|netem te[0-9]* -> td[0-9]* .*' "$out/impaired.log" |
  sed -e 's/^netem td[0-9]* -> te[0-9]*/drone -> edge:/' -e 's/^netem te[0-9]* -> td[0-9]*/edge -> drone:/'
report undisturbed "$out/undisturbed" "$out/undisturbed.log"
report impaired "$out/impaired" "$out/impaired.log"
exit "$status"
