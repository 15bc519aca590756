#!/usr/bin/env bash
# Two hosts on one machine (issue 14 item 3): the drone (ingest, tracking, estimator and the run's recorder) and the
# edge (tiles, registration) each in a network namespace of its own, joined by a veth link; DDS over UDP only (no
# shared memory between the "hosts"), discovery through initial peers or a Fast DDS discovery server on the edge.
# Needs root (ip netns). Everything it adds (namespaces, link, discovery server) is removed on exit.
#
#   bash scripts/two-hosts.sh DATASET OUT [--discovery peers|server] [--link-down AT_S FOR_S] [TWINSLAM RUN OPTIONS...]
#
# --link-down: the link goes down AT_S seconds after the run starts, for FOR_S seconds (`ip link set down` on both
# ends; the kernel here has no netem, so delay and loss are not offered).
# OUT/run is the `twinslam run DATASET --mode vio-twin` folder (run.json lists edge_netns), OUT/qos.xml the profiles
# both sides used. With `--secure` among the run options the link runs under DDS-Security. Prints the bytes that crossed the link and the run's line. TWINSLAM_BIN: the executables' folder.
set -euo pipefail
die() { echo "two-hosts.sh: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[[ $# -ge 2 ]] || die "usage: two-hosts.sh DATASET OUT [--discovery peers|server] [TWINSLAM RUN OPTIONS...]"
dataset=$(realpath "$1"); out=$(realpath -m "$2"); shift 2
discovery=peers
if [[ "${1:-}" == "--discovery" ]]; then discovery=${2:-}; shift 2 || die "--discovery needs peers or server"; fi
[[ $discovery == peers || $discovery == server ]] || die "--discovery: peers or server, not '$discovery'"
down_at=; down_for=
if [[ "${1:-}" == "--link-down" ]]; then
  down_at=${2:-}; down_for=${3:-}; shift 3 || die "--link-down needs AT_S FOR_S"
  [[ $down_at =~ ^[0-9]+([.][0-9]+)?$ && $down_for =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--link-down: AT_S FOR_S in seconds"
fi
bin=${TWINSLAM_BIN:-$root/build/bin}
[[ -x $bin/twinslam ]] || die "$bin/twinslam not found (build first, or set TWINSLAM_BIN)"
[[ $(id -u) -eq 0 ]] || die "needs root for network namespaces (ip netns)"
command -v ip >/dev/null || die "the ip command (iproute2) is missing"

# Names and addresses unique to this process: parallel runs (tests) never meet.
tag=$(( $$ % 200 + 20 ))
drone=tw-drone-$$; edge=tw-edge-$$
drone_ip=10.213.$tag.1; edge_ip=10.213.$tag.2
server_pid=; fault_pid=
cleanup() {
  for p in $server_pid $fault_pid; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  ip netns del "$drone" 2>/dev/null || true
  ip netns del "$edge" 2>/dev/null || true
}
trap cleanup EXIT
ip netns add "$drone" || die "cannot create network namespaces (ip netns add failed)"
ip netns add "$edge"
ip link add "vd$$" type veth peer name "ve$$"
ip link set "vd$$" netns "$drone"
ip link set "ve$$" netns "$edge"
ip -n "$drone" addr add "$drone_ip/24" dev "vd$$"
ip -n "$edge" addr add "$edge_ip/24" dev "ve$$"
for ns in "$drone" "$edge"; do ip -n "$ns" link set lo up; done
ip -n "$drone" link set "vd$$" up
ip -n "$edge" link set "ve$$" up

# The profiles: the project's file with its default participant (twinslam.local, every process uses it) on UDP only
# and discovering through the link.
mkdir -p "$out"
locator() { echo "<locator><udpv4><address>$1</address>${2:+<port>$2</port>}</udpv4></locator>"; }
if [[ $discovery == peers ]]; then
  find_peers="<initialPeersList>$(locator "$drone_ip")$(locator "$edge_ip")</initialPeersList>"
  protocol=""
else
  find_peers=""
  protocol="<discoveryProtocol>CLIENT</discoveryProtocol><discoveryServersList><RemoteServer prefix=\"44.53.00.5f.45.50.52.4f.53.49.4d.41\"><metatrafficUnicastLocatorList>$(locator "$edge_ip" 11811)</metatrafficUnicastLocatorList></RemoteServer></discoveryServersList>"
fi
participant="  <participant profile_name=\"twinslam.local\" is_default_profile=\"true\"><rtps>
    <useBuiltinTransports>false</useBuiltinTransports>
    <userTransports><transport_id>twinslam_udp</transport_id></userTransports>
    <builtin>$find_peers<discovery_config>$protocol<leaseDuration><sec>5</sec></leaseDuration><leaseAnnouncement><sec>1</sec></leaseAnnouncement></discovery_config></builtin>
  </rtps></participant>"
# The secured profiles (run --secure) keep their DDS-Security properties and discover the same way, on UDP only.
# Every process of a side has its own participant id: initial peers must reach more than Fast DDS's default 4.
PARTICIPANT=$participant BUILTIN="<builtin>$find_peers<discovery_config>$protocol<leaseDuration><sec>5</sec></leaseDuration><leaseAnnouncement><sec>1</sec></leaseAnnouncement></discovery_config></builtin>" awk '
  /<participant profile_name="twinslam.local"/ { print ENVIRON["PARTICIPANT"]; skip = 1 }
  skip && /<\/participant>/ { skip = 0; next }
  skip { next }
  /<participant profile_name="twinslam.secure\./ { secure = 1 }
  secure && /<\/participant>/ { secure = 0 }
  secure && /<transport_id>twinslam_shm<\/transport_id>/ { next }
  secure && /<builtin>/ { print ENVIRON["BUILTIN"]; in_builtin = 1 }
  in_builtin { if (/<\/builtin>/) in_builtin = 0; next }
  { print }
  /<transport_id>twinslam_udp<\/transport_id>/ && !secure { print "      <maxInitialPeersRange>16</maxInitialPeersRange>" }
' "$root/deploy/qos/twinslam.xml" > "$out/qos.xml"

if [[ $discovery == server ]]; then
  command -v fastdds >/dev/null || die "fastdds (fastdds-tools) is missing for --discovery server"
  ip netns exec "$edge" fastdds discovery -i 0 -l "$edge_ip" -p 11811 > "$out/discovery-server.log" 2>&1 &
  server_pid=$!
  sleep 1
fi

echo "two-hosts.sh: drone $drone ($drone_ip), edge $edge ($edge_ip), discovery: $discovery"
link() { ip -n "$drone" link set "vd$$" "$1" && ip -n "$edge" link set "ve$$" "$1"; }
if [[ -n $down_at ]]; then
  ( sleep "$down_at"; link down; echo "two-hosts.sh: link down at $(date +%T.%N | cut -c1-12)"
    sleep "$down_for"; link up; echo "two-hosts.sh: link up at $(date +%T.%N | cut -c1-12)" ) &
  fault_pid=$!
fi
rc=0
ip netns exec "$drone" env TWINSLAM_QOS_FILE="$out/qos.xml" "$bin/twinslam" run "$dataset" --mode vio-twin \
  --out "$out/run" --edge-netns "$edge" --domain 0 --no-progress "$@" || rc=$?
if [[ -n $fault_pid ]]; then wait "$fault_pid" 2>/dev/null || true; fault_pid=; fi
bytes() { ip -n "$1" -s -j link show "$2" | sed -n 's/.*"rx":{"bytes":\([0-9]*\).*"tx":{"bytes":\([0-9]*\).*/\1 \2/p'; }
read -r rx tx < <(bytes "$drone" "vd$$")
echo "two-hosts.sh: the link carried $tx bytes drone -> edge and $rx bytes edge -> drone"
exit $rc
