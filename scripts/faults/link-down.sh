#!/usr/bin/env bash
# Fault (issue 14): the drone-edge link goes down mid-flight. The drone and the edge run in network namespaces of
# their own (scripts/two-hosts.sh, realtime replay, needs root); the link is cut AT_S seconds into the run for FOR_S
# seconds. The same flight runs undisturbed first. For both it ends with: the poses out of the camera frames and the
# largest gap between poses, the outage in seconds of the flight, the first registration accepted after it, the
# registrations accepted and fused, and the ATE in W (from the declared alignment on) against the ground truth.
# Usage: bash scripts/faults/link-down.sh [DATASET] [AT_S] [FOR_S]
#   DATASET: a simulated dataset with ground truth (default: runs/fault-link-flight, simulated once from
#            deploy/scenarios/edge-faults.yaml: tiny's city, 100 s); AT_S, FOR_S: default 45 and 30
set -euo pipefail
die() { echo "link-down: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=${TWINSLAM_BUILD_DIR:-$root/build}/bin
[[ -x $bin/twinslam ]] || die "$bin/twinslam not built (bash scripts/test.sh builds it)"
at=${2:-45}; for_s=${3:-30}
source "$root/scripts/faults/common.sh"
fault_flight "${1:-}"

out=$root/runs/fault-link
rm -rf "$out"; mkdir -p "$out"
two_hosts undisturbed "$out" || die "the undisturbed run failed ($out/undisturbed.log)"
status=0
two_hosts link-down "$out" --link-down "$at" "$for_s" || status=$?
echo "fault: the drone-edge link down ${at} s into the run for ${for_s} s (run exit $status; $out)"
report undisturbed "$out/undisturbed" "$out/undisturbed.log"
report link-down "$out/link-down" "$out/link-down.log"
exit "$status"
