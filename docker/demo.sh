#!/usr/bin/env bash
# The drone + edge demo in containers (issue 14): builds the image, runs the edge (tiles, registration) and the drone
# (ingest, tracking, estimator) as separate compose projects joined only by the link network, flies the dataset in
# mode vio-twin in real time, prints the accuracy table and tears everything down (containers, networks, the engine).
#
#   bash docker/demo.sh [DATASET] [--features] [--out OUT] [--no-reference] [--keep-engine] [--swap SERVICE@SECONDS]
#
# DATASET: default runs/city-loops (the main job's default city; simulated once, in a container, when missing).
# --features: the dataset's ideal feature tracks instead of images (the drone then runs no tracking container).
# OUT (default runs/docker-demo): containers/run (the containers' run: trajectory, registrations, run.json, logs/ of
# every container), twin-store, native/run (the same flight without containers, when this checkout is built:
# build/bin or TWINSLAM_BIN; --no-reference skips it), table.md. Needs root (the engine; docker/engine.sh).
# --swap SERVICE@SECONDS: SECONDS into the flight the edge's SERVICE (tiles or registration) is upgraded in place, as
# an operator would: its container is stopped and replaced by one from another image tag (the same build, tagged
# twinslam:swapped) while the drone flies on; the demo then prints, for both runs, the largest gap between poses, the
# swap's start and end (the new container's first heartbeat) and the first registration accepted after it
# (scripts/faults/common.sh). The swap's times: OUT/containers/swap.log.
set -euo pipefail
die() { echo "demo.sh: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dataset=""; out=$root/runs/docker-demo; features=""; reference=1; keep_engine=0; swap=""; swap_after=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --features) features=--features; shift ;;
    --out) [[ $# -ge 2 ]] || die "--out needs a folder"; out=$2; shift 2 ;;
    --no-reference) reference=0; shift ;;
    --keep-engine) keep_engine=1; shift ;;
    --swap)
      [[ $# -ge 2 && $2 =~ ^([a-z]+)@([0-9]+([.][0-9]+)?)$ ]] || die "--swap needs SERVICE@SECONDS, e.g. registration@60"
      swap=${BASH_REMATCH[1]}; swap_after=${BASH_REMATCH[2]}; shift 2
      case "$swap" in
        tiles|registration) ;;
        estimator|tracking|ingest) die "--swap $swap: only the edge's services are swapped in flight (a new estimator" \
          "resumes from its checkpoint, which the drone's containers do not share yet; ingest is the run itself)" ;;
        *) die "--swap $swap: not a service of the demo (tiles or registration)" ;;
      esac ;;
    -*) die "unknown option $1 (usage: demo.sh [DATASET] [--features] [--out OUT] [--no-reference] [--keep-engine]" \
          "[--swap SERVICE@SECONDS])" ;;
    *) [[ -z $dataset ]] || die "one dataset only"; dataset=$1; shift ;;
  esac
done
out=$(realpath -m "$out")
bin=${TWINSLAM_BIN:-$root/build/bin}
image=${TWINSLAM_IMAGE:-twinslam:latest}
export TWINSLAM_IMAGE=$image

# --- the engine, the base image and twinslam's image --------------------------------------------------------------
source "$root/docker/engine.sh" start
cleanup() {
  if declare -F cleanup_projects > /dev/null; then cleanup_projects; fi
  [[ $keep_engine -eq 1 ]] || bash "$root/docker/engine.sh" stop
}
trap cleanup EXIT
bash "$root/docker/base-image.sh"
echo "demo.sh: building $image (the first build compiles the services: ~20 min on 2 cores)" >&2
mkdir -p "$out"
docker build --network host -f "$root/docker/Dockerfile" -t "$image" "$root" > "$out/image-build.log" 2>&1 ||
  die "the image did not build: $out/image-build.log"
in_container() {  # run a twinslam command in a throw-away container as the caller, with DIR mounted at the same path
  local dir=$1; shift
  docker run --rm --network none --user "$(id -u):$(id -g)" -v "$dir:$dir" -w "$dir" "$image" "$@"
}

# --- the flight and its twin ----------------------------------------------------------------------------------------
if [[ -z $dataset ]]; then
  dataset=$root/runs/city-loops
  if [[ ! -d $dataset/mav0 ]]; then
    echo "demo.sh: simulating the default city (city-loops) into $dataset, once (~4 min)" >&2
    mkdir -p "$root/runs"
    in_container "$root/runs" twinslam sim --scenario city-loops --out "$dataset" --features --quiet
  fi
fi
dataset=$(realpath "$dataset")
[[ -f $dataset/dataset.yaml ]] || die "$dataset: not a dataset (no dataset.yaml)"
[[ -z $features || -f $dataset/mav0/cam0/features.csv ]] || die "--features: $dataset has no mav0/cam0/features.csv"
origin=$(sed -n 's/^origin: *{lat: *\([^,]*\), *lon: *\([^,]*\), *alt: *\([^}]*\)}.*/\1,\2,\3/p' "$dataset/dataset.yaml")
[[ -n $origin ]] || die "$dataset/dataset.yaml: no origin {lat, lon, alt}"
twin=$(sed -n 's/^ *path: *"\{0,1\}\([^"]*\)"\{0,1\}.*/\1/p' "$dataset/dataset.yaml" | head -1)
[[ -n $twin && -f $dataset/$twin ]] || die "$dataset/dataset.yaml names no twin file that exists"
rm -rf "$out/twin-store" "$out/containers" "$out/native"
mkdir -p "$out/containers/run/logs"
docker run --rm --network none --user "$(id -u):$(id -g)" -v "$dataset:/data:ro" -v "$out:/out" "$image" \
  twinslam twin build "/data/$twin" --origin "$origin" --out /out/twin-store > "$out/twin-build.log" 2>&1 ||
  die "the twin store did not build: $out/twin-build.log"
chown -R 10001 "$out/containers"  # the containers' user writes the run

# --- edge, then drone ----------------------------------------------------------------------------------------------
export TWINSLAM_DOMAIN=${TWINSLAM_DOMAIN:-0} TWINSLAM_DATASET=$dataset TWINSLAM_OUT=$out/containers
export TWINSLAM_ORIGIN=$origin TWINSLAM_TWIN_STORE=$out/twin-store TWINSLAM_FEATURES=$features
drone_services=(ingest tracking estimator)
if [[ -n $features ]]; then drone_services=(ingest estimator); export TWINSLAM_EXTERNAL=estimator,tiles,registration; fi
cleanup_projects() {
  docker-compose -p twinslam-drone -f "$root/docker/compose.drone.yml" down -t 5 > /dev/null 2>&1 || true
  docker-compose -p twinslam-edge -f "$root/docker/compose.edge.yml" down -t 5 > /dev/null 2>&1 || true
  docker network rm twinslam-link > /dev/null 2>&1 || true
}
# swap_edge_service SERVICE AFTER_S DIR: AFTER_S seconds after the flight's replay starts, stop SERVICE's container
# (its log kept in DIR/run/logs/container-SERVICE-before-swap.log) and start one from the image tagged
# twinslam:swapped; "fault begins/ends at" lines (the end: the new container's first heartbeat) for report().
swap_edge_service() {
  local service=$1 after=$2 dir=$3 edge=(docker-compose -p twinslam-edge -f "$root/docker/compose.edge.yml")
  for _ in $(seq 1200); do
    grep -q 'replay starts' "$dir/run/logs/ingest.log" 2> /dev/null && break
    kill -0 "$drone_pid" 2> /dev/null || return 0  # the drone ended before its replay began: its log says why
    sleep 0.1
  done
  sleep "$after"
  kill -0 "$drone_pid" 2> /dev/null || { echo "swap: the flight ended before ${after} s"; return 0; }
  echo "fault begins at $(date +%H:%M:%S.%N | cut -c1-12): stopping $service"
  "${edge[@]}" stop -t 10 "$service" > /dev/null 2>&1 || true
  "${edge[@]}" logs --no-color "$service" > "$dir/run/logs/container-$service-before-swap.log" 2>&1 || true
  docker tag "$image" twinslam:swapped
  TWINSLAM_IMAGE=twinslam:swapped "${edge[@]}" up -d --no-deps "$service" > /dev/null 2>&1 ||
    { echo "swap: $service did not start from twinslam:swapped"; return 0; }
  for _ in $(seq 60); do
    if "${edge[@]}" exec -T "$service" twinslam-healthcheck > /dev/null 2>&1; then
      echo "fault ends at $(date +%H:%M:%S.%N | cut -c1-12): $service serving again from twinslam:swapped"
      return 0
    fi
  done
  echo "swap: no heartbeat from the new $service within 3 min"
}
cleanup_projects  # a demo interrupted before left them behind
docker network create twinslam-link > /dev/null
docker-compose -p twinslam-edge -f "$root/docker/compose.edge.yml" up -d 2> "$out/containers/edge-up.log" ||
  die "the edge did not start: $out/containers/edge-up.log"
echo "demo.sh: edge up (tiles, registration); the drone flies $dataset in real time" >&2
status=0
docker-compose -p twinslam-drone -f "$root/docker/compose.drone.yml" up --exit-code-from ingest \
  --abort-on-container-exit "${drone_services[@]}" > "$out/containers/drone-up.log" 2>&1 &
drone_pid=$!
if [[ -n $swap ]]; then swap_edge_service "$swap" "$swap_after" "$out/containers" > "$out/containers/swap.log"; fi
wait "$drone_pid" || status=$?
# Stopped before their logs are read: registration says whom it served when it stops.
docker-compose -p twinslam-edge -f "$root/docker/compose.edge.yml" stop -t 10 > /dev/null 2>&1 || true
for p in drone edge; do
  for s in $(docker-compose -p "twinslam-$p" -f "$root/docker/compose.$p.yml" ps --services 2> /dev/null); do
    docker-compose -p "twinslam-$p" -f "$root/docker/compose.$p.yml" logs --no-color "$s" \
      > "$out/containers/run/logs/container-$s.log" 2>&1 || true
  done
done
chown -R "$(id -u):$(id -g)" "$out/containers"
[[ $status -eq 0 ]] || die "the drone's run ended with exit $status: $out/containers/drone-up.log"
# The edge goes before the reference flies: its registration would answer the reference's local maps too.
cleanup_projects

# --- the same flight without containers, then the table --------------------------------------------------------------
if [[ $reference -eq 1 && -x $bin/twinslam ]]; then
  echo "demo.sh: the same flight without containers ($bin)" >&2
  # On a private domain of its own (TWINSLAM_DOMAIN is the containers').
  env -u TWINSLAM_DOMAIN "$bin/twinslam" run "$dataset" --mode vio-twin --realtime --no-progress $features \
    --out "$out/native/run" > "$out/native.log" 2>&1 || die "the run without containers failed: $out/native.log"
elif [[ $reference -eq 1 ]]; then
  echo "demo.sh: $bin/twinslam not built: no run without containers to compare with" >&2
fi
rows=()
for r in containers native; do
  [[ -f $out/$r/run/run.json ]] || continue
  docker run --rm --network none --user "$(id -u):$(id -g)" -v "$dataset:$dataset:ro" -v "$out:$out" "$image" \
    twinslam eval --gt "$dataset" --est "$out/$r/run" --align none --json > "$out/$r/eval.json"
  rows+=("$r")
done
python3 "$root/docker/demo_table.py" "$out" "$dataset" "${rows[@]}" | tee "$out/table.md"
if [[ -n $swap ]]; then  # the swap's lines, in the fault scripts' shape (scripts/faults/common.sh)
  if [[ ! -x $bin/twinslam ]]; then  # report() evaluates with $bin/twinslam: the image's, then
    bin=$out/bin; mkdir -p "$bin"
    printf '#!/bin/sh\nexec docker run --rm --network none -v "%s:%s:ro" -v "%s:%s" "%s" twinslam "$@"\n' \
      "$dataset" "$dataset" "$out" "$out" "$image" > "$bin/twinslam"
    chmod +x "$bin/twinslam"
  fi
  source "$root/scripts/faults/common.sh"
  [[ -d $out/native/run ]] && report "without containers, not swapped" "$out/native" /dev/null | tee -a "$out/table.md"
  report "containers, $swap swapped" "$out/containers" "$out/containers/swap.log" | tee -a "$out/table.md"
fi
