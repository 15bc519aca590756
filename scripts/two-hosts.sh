#!/usr/bin/env bash
# Two hosts on one machine (issue 14 item 3): the drone (ingest, tracking, estimator and the run's recorder) and the
# edge (tiles, registration) each in a network namespace of its own, joined by a veth link; DDS over UDP only (no
# shared memory between the "hosts"), discovery through initial peers or a Fast DDS discovery server on the edge.
# Needs root (ip netns). Everything it adds (namespaces, link, discovery server) is removed on exit.
#
#   bash scripts/two-hosts.sh DATASET OUT [--discovery peers|server] [--link-down AT_S FOR_S]
#                             [--netem LOSS_PCT DELAY_MS] [TWINSLAM RUN OPTIONS...]
#
# --link-down: the link goes down AT_S seconds after the run starts, for FOR_S seconds (`ip link set down` on both
# ends). --netem: every packet crossing the link, either way, is lost with LOSS_PCT % probability or delayed by
# DELAY_MS; the kernel here has no netem qdisc, so the link runs through a third namespace that routes it through
# twinslam-netem (a userspace netem between two TUN devices; its counts are printed at the end).
# OUT/run is the `twinslam run DATASET --mode vio-twin` folder (run.json lists edge_netns), OUT/qos.xml the profiles
# both sides used, OUT/edge-memory.csv the edge processes' resident memory once a second. With `--secure` among the
# run options the link runs under DDS-Security. Prints the bytes that crossed the link and the run's line.
# TWINSLAM_BIN: the executables' folder.
set -euo pipefail
die() { echo "two-hosts.sh: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[[ $# -ge 2 ]] || die "usage: two-hosts.sh DATASET OUT [--discovery peers|server] [--link-down AT_S FOR_S] [--netem LOSS_PCT DELAY_MS] [TWINSLAM RUN OPTIONS...]"
dataset=$(realpath "$1"); out=$(realpath -m "$2"); shift 2
discovery=peers; down_at=; down_for=; loss=; delay=
number='^[0-9]+([.][0-9]+)?$'
while [[ $# -gt 0 ]]; do
  case "$1" in
    --discovery) discovery=${2:-}; shift 2 || die "--discovery needs peers or server" ;;
    --link-down)
      down_at=${2:-}; down_for=${3:-}; shift 3 || die "--link-down needs AT_S FOR_S"
      [[ $down_at =~ $number && $down_for =~ $number ]] || die "--link-down: AT_S FOR_S in seconds" ;;
    --netem)
      loss=${2:-}; delay=${3:-}; shift 3 || die "--netem needs LOSS_PCT DELAY_MS"
      [[ $loss =~ $number && $delay =~ $number ]] || die "--netem: LOSS_PCT DELAY_MS are numbers" ;;
    *) break ;;
  esac
done
[[ $discovery == peers || $discovery == server ]] || die "--discovery: peers or server, not '$discovery'"
mkdir -p "$out"
bin=${TWINSLAM_BIN:-$root/build/bin}
[[ -x $bin/twinslam ]] || die "$bin/twinslam not found (build first, or set TWINSLAM_BIN)"
[[ $(id -u) -eq 0 ]] || die "needs root for network namespaces (ip netns)"
command -v ip >/dev/null || die "the ip command (iproute2) is missing"

# Names and addresses unique to this process: parallel runs (tests) never meet.
tag=$(( $$ % 200 + 20 ))
drone=tw-drone-$$; edge=tw-edge-$$; middle=tw-link-$$
drone_ip=10.213.$tag.1; edge_ip=10.213.$tag.129
server_pid=; fault_pid=; netem_pid=; memory_pid=
cleanup() {
  for p in $server_pid $fault_pid $netem_pid $memory_pid; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  for ns in "$drone" "$edge" "$middle"; do ip netns del "$ns" 2>/dev/null || true; done
}
trap cleanup EXIT
ip netns add "$drone" || die "cannot create network namespaces (ip netns add failed)"
ip netns add "$edge"
for ns in "$drone" "$edge"; do ip -n "$ns" link set lo up; done
if [[ -z $loss ]]; then
  # One veth link, one /24: drone and edge are neighbours.
  ip link add "vd$$" type veth peer name "ve$$"
  ip link set "vd$$" netns "$drone"
  ip link set "ve$$" netns "$edge"
  ip -n "$drone" addr add "$drone_ip/24" dev "vd$$"
  ip -n "$edge" addr add "$edge_ip/24" dev "ve$$"
else
  # Drone (lower /25) and edge (upper /25) each reach a router namespace; policy routing there sends what comes from
  # either side into a TUN device of twinslam-netem, which impairs it and writes it into the other side's TUN device,
  # from where the router forwards it on.
  [[ -x $bin/twinslam-netem ]] || die "$bin/twinslam-netem not built"
  ip netns add "$middle"
  ip -n "$middle" link set lo up
  ip link add "vd$$" type veth peer name "ld$$"
  ip link add "ve$$" type veth peer name "le$$"
  ip link set "vd$$" netns "$drone"; ip link set "ld$$" netns "$middle"
  ip link set "ve$$" netns "$edge"; ip link set "le$$" netns "$middle"
  ip -n "$drone" addr add "$drone_ip/25" dev "vd$$"
  ip -n "$edge" addr add "$edge_ip/25" dev "ve$$"
  ip -n "$middle" addr add "10.213.$tag.126/25" dev "ld$$"
  ip -n "$middle" addr add "10.213.$tag.254/25" dev "le$$"
  ip netns exec "$middle" sysctl -qw net.ipv4.ip_forward=1 net.ipv4.conf.all.rp_filter=0 net.ipv4.conf.default.rp_filter=0
  for t in "td$$" "te$$"; do ip -n "$middle" tuntap add dev "$t" mode tun; done
  for d in "ld$$" "le$$" "td$$" "te$$"; do
    ip netns exec "$middle" sysctl -qw "net.ipv4.conf.$d.rp_filter=0"; ip -n "$middle" link set "$d" up
  done
  ip -n "$middle" rule add iif "ld$$" table 100; ip -n "$middle" route add default dev "td$$" table 100
  ip -n "$middle" rule add iif "le$$" table 101; ip -n "$middle" route add default dev "te$$" table 101
  ip netns exec "$middle" "$bin/twinslam-netem" --a "td$$" --b "te$$" --loss "$loss" --delay "$delay" \
    > "$out/netem.log" 2>&1 &
  netem_pid=$!
fi
ip -n "$drone" link set "vd$$" up
ip -n "$edge" link set "ve$$" up
if [[ -n $loss ]]; then
  ip -n "$drone" route add default via "10.213.$tag.126"
  ip -n "$edge" route add default via "10.213.$tag.254"
fi

# The profiles: the project's file with its default participant (twinslam.local, every process uses it) on UDP only
# and discovering through the link.
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
  /<transport_id>twinslam_udp(_secure)?<\/transport_id>/ && !secure { print "      <maxInitialPeersRange>16</maxInitialPeersRange>" }
' "$root/deploy/qos/twinslam.xml" > "$out/qos.xml"

if [[ $discovery == server ]]; then
  command -v fastdds >/dev/null || die "fastdds (fastdds-tools) is missing for --discovery server"
  ip netns exec "$edge" fastdds discovery -i 0 -l "$edge_ip" -p 11811 > "$out/discovery-server.log" 2>&1 &
  server_pid=$!
  sleep 1
fi

echo "two-hosts.sh: drone $drone ($drone_ip), edge $edge ($edge_ip), discovery: $discovery${loss:+, link: $loss % loss and $delay ms delay each way (twinslam-netem in $middle)}"
# With --netem the router's ends go down: downing the drone's or edge's own end would delete its default route via
# the router, which `link set up` does not bring back.
if [[ -z $loss ]]; then
  link() { ip -n "$drone" link set "vd$$" "$1" && ip -n "$edge" link set "ve$$" "$1"; }
else
  link() { ip -n "$middle" link set "ld$$" "$1" && ip -n "$middle" link set "le$$" "$1"; }
fi
if [[ -n $down_at ]]; then
  ( sleep "$down_at"; link down; echo "two-hosts.sh: link down at $(date +%T.%N | cut -c1-12)"
    sleep "$down_for"; link up; echo "two-hosts.sh: link up at $(date +%T.%N | cut -c1-12)" ) &
  fault_pid=$!
fi
# The edge's memory, once a second (OUT/edge-memory.csv: local time of day in seconds, the clock of the logs and of
# the link down/up lines; process, pid, RSS in MB): registration must not grow while the drone is unreachable.
(
  echo "time_of_day_s,process,pid,rss_mb"
  while sleep 1; do
    IFS=: read -r h m sec < <(date +%H:%M:%S)
    t=$(( 10#$h * 3600 + 10#$m * 60 + 10#$sec ))
    for p in $(ip netns pids "$edge" 2>/dev/null); do
      name=$(tr '\0' '\n' < "/proc/$p/cmdline" 2>/dev/null | head -n1) || continue
      rss=$(awk '/^VmRSS:/ { printf "%.1f", $2 / 1024 }' "/proc/$p/status" 2>/dev/null) || continue
      [[ -n $rss ]] && echo "$t,${name##*/},$p,$rss"
    done
  done
) > "$out/edge-memory.csv" &
memory_pid=$!
rc=0
ip netns exec "$drone" env TWINSLAM_QOS_FILE="$out/qos.xml" "$bin/twinslam" run "$dataset" --mode vio-twin \
  --out "$out/run" --edge-netns "$edge" --domain 0 --no-progress "$@" || rc=$?
if [[ -n $fault_pid ]]; then wait "$fault_pid" 2>/dev/null || true; fault_pid=; fi
kill "$memory_pid" 2>/dev/null || true; wait "$memory_pid" 2>/dev/null || true; memory_pid=
awk -F, 'NR > 1 && $2 ~ /^twinslam-/ { if (!($2 in first)) first[$2] = $4; last[$2] = $4; if ($4 > peak[$2]) peak[$2] = $4 }
  END { for (n in peak) printf "two-hosts.sh: %s RSS %.0f MB at its first sample, %.0f MB peak, %.0f MB at the end\n", n, first[n], peak[n], last[n] }' \
  "$out/edge-memory.csv" | sort
bytes() { ip -n "$1" -s -j link show "$2" | sed -n 's/.*"rx":{"bytes":\([0-9]*\).*"tx":{"bytes":\([0-9]*\).*/\1 \2/p'; }
read -r rx tx < <(bytes "$drone" "vd$$")
echo "two-hosts.sh: the link carried $tx bytes drone -> edge and $rx bytes edge -> drone"
if [[ -n $netem_pid ]]; then
  kill "$netem_pid"; wait "$netem_pid" 2>/dev/null || true; netem_pid=
  sed -n 's/^twinslam-netem: /two-hosts.sh: netem /p' "$out/netem.log"
fi
exit $rc
