#!/usr/bin/env bash
# A private Docker engine for the demo (no engine runs on these machines out of the box; ../shared/NOTES-dependencies.md
# "Containers"): its images, containers and socket live in one folder, and it touches nothing else of the host.
#
#   source docker/engine.sh start [DIR]   start dockerd (DIR: $TWINSLAM_DOCKER_DIR, else /var/tmp/twinslam-docker),
#                                         export DOCKER_HOST; the folder keeps the images for the next demo
#   bash docker/engine.sh stop [DIR]      stop it: containers, networks and the daemon; checks that the host's
#                                         iptables rules and IPv4 forwarding are as before it started
#
# The daemon runs with --iptables=false --ip-forward=false: containers on one bridge network reach each other at layer
# 2 without any host rule, and image builds use the host's network (docker build --network host), so the engine adds
# no iptables chain and leaves forwarding alone. Needs root and the Debian packages docker.io, docker-compose.
set -euo pipefail
engine_die() { echo "engine.sh: $*" >&2; exit 2; }
engine_dir=$(realpath -m "${2:-${TWINSLAM_DOCKER_DIR:-/var/tmp/twinslam-docker}}")
engine_sock=unix://$engine_dir/docker.sock

engine_start() {
  command -v dockerd > /dev/null || engine_die "dockerd not found: apt-get install docker.io docker-compose"
  command -v docker-compose > /dev/null || engine_die "docker-compose not found: apt-get install docker-compose"
  [[ $(id -u) -eq 0 ]] || engine_die "the engine needs root (a rootless engine is not set up here)"
  mkdir -p "$engine_dir/data" "$engine_dir/exec"
  export DOCKER_HOST=$engine_sock
  if docker version > /dev/null 2>&1; then return 0; fi  # already running from this folder
  iptables-save 2> /dev/null | grep -v '^#' | sed 's/\[[0-9]*:[0-9]*\]//' > "$engine_dir/iptables.before" || true
  cat /proc/sys/net/ipv4/ip_forward > "$engine_dir/ip_forward.before"
  dockerd --data-root "$engine_dir/data" --exec-root "$engine_dir/exec" -H "$engine_sock" \
    --pidfile "$engine_dir/dockerd.pid" --iptables=false --ip-forward=false --ip-masq=false \
    > "$engine_dir/dockerd.log" 2>&1 &
  for _ in $(seq 100); do
    docker version > /dev/null 2>&1 && return 0
    sleep 0.2
  done
  engine_die "dockerd did not start in 20 s: $engine_dir/dockerd.log"
}

engine_stop() {
  export DOCKER_HOST=$engine_sock
  [[ -f $engine_dir/dockerd.pid ]] || return 0
  local pid; pid=$(cat "$engine_dir/dockerd.pid")
  if docker version > /dev/null 2>&1; then
    local ids; ids=$(docker ps -aq)
    [[ -z $ids ]] || docker rm -f $ids > /dev/null
    docker network prune -f > /dev/null
  fi
  kill "$pid" 2> /dev/null || true
  for _ in $(seq 150); do kill -0 "$pid" 2> /dev/null || break; sleep 0.2; done
  kill -0 "$pid" 2> /dev/null && engine_die "dockerd ($pid) did not stop in 30 s"
  rm -f "$engine_dir/dockerd.pid"
  # What the host looks like again: the same iptables rules and forwarding as before the engine.
  if [[ -f $engine_dir/iptables.before ]]; then
    iptables-save 2> /dev/null | grep -v '^#' | sed 's/\[[0-9]*:[0-9]*\]//' > "$engine_dir/iptables.after" || true
    diff -q "$engine_dir/iptables.before" "$engine_dir/iptables.after" > /dev/null ||
      engine_die "the host's iptables rules changed while the engine ran: diff $engine_dir/iptables.{before,after}"
  fi
  if [[ -f $engine_dir/ip_forward.before ]]; then
    [[ $(cat /proc/sys/net/ipv4/ip_forward) == $(cat "$engine_dir/ip_forward.before") ]] ||
      engine_die "net.ipv4.ip_forward changed while the engine ran"
  fi
  echo "engine.sh: engine stopped; no container, network, iptables rule or forwarding setting left behind" >&2
}

case "${1:-}" in
  start) engine_start ;;
  stop) engine_stop ;;
  *) engine_die "usage: engine.sh start|stop [DIR]" ;;
esac
