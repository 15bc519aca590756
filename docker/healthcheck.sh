#!/usr/bin/env bash
# The image's health check: healthy while this container's service (TWINSLAM_SERVICE, e.g. registration; the compose
# files set it) sends its DDS heartbeat in TWINSLAM_DOMAIN. Listens 3 s (heartbeats come twice a second) and exits
# cleanly: a listener killed mid-way would leave its shared-memory segments in the container's /dev/shm.
set -uo pipefail
service=${TWINSLAM_SERVICE:?TWINSLAM_SERVICE names the container\'s service}
heard=$(twinslam echo heartbeat --count 0 --timeout 3 2> /dev/null)
grep -q "\"service\":\"$service\"" <<< "$heard" && exit 0
echo "no heartbeat from '$service' in domain ${TWINSLAM_DOMAIN:-0} for 3 s" >&2
exit 1
