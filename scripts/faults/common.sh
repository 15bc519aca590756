# Sourced by the fault scripts (link-down.sh, loss-delay.sh, restart-estimator.sh): their flight, their undisturbed
# two-host run, and one line per run (OUT/run) saying what the drone flew and what the edge gave it. Needs $root (the
# repository), $bin (the executables) and a die function.

# fault_flight [DATASET]: sets $dataset (default runs/fault-link-flight, simulated once from
# deploy/scenarios/edge-faults.yaml: tiny's city, 100 s) and $features (--features when it has feature tracks).
fault_flight() {
  dataset=${1:-$root/runs/fault-link-flight}
  if [[ -z ${1:-} && ! -d $dataset/mav0 ]]; then
    "$bin/twinslam" sim --scenario "$root/deploy/scenarios/edge-faults.yaml" --out "$dataset" --features --quiet
  fi
  [[ -d $dataset/mav0 ]] || die "$dataset: not a dataset (no mav0/)"
  features=()
  if [[ -f $dataset/mav0/cam0/features.csv ]]; then features=(--features); fi
}

# two_hosts NAME OUT [OPTIONS...]: a realtime two-host run of $dataset into OUT/NAME (log OUT/NAME.log).
two_hosts() {
  local name=$1 out=$2
  shift 2
  bash "$root/scripts/two-hosts.sh" "$dataset" "$out/$name" "$@" --realtime "${features[@]}" > "$out/$name.log" 2>&1
}
seconds_of_day() { awk -F'[:.]' '{ printf "%.3f", $1 * 3600 + $2 * 60 + $3 + ("0." $4) }' <<< "$1"; }

# report NAME OUT LOG: the poses out of the camera frames and the largest gap between them, the outage (from LOG's
# "link down/up at" or "fault begins/ends at" lines, if any) in seconds of the flight, the first registration
# accepted after it, the registrations accepted and fused (on their own keyframe / re-attached), their latency, the
# ATE in W, and with an outage the registration service's resident memory at its start, its peak during it and at
# the end.
report() {
  local run=$2/run start t0 down up
  start=$(seconds_of_day "$(grep -m1 'replay starts' "$run/logs/ingest.log" | cut -d' ' -f1)")
  t0=$(grep -m1 -o 'sensor stamp [0-9]*' "$run/logs/ingest.log" | grep -o '[0-9]*$')
  # The fault's start and end in LOG: two-hosts.sh's "link down/up at T", a fault script's "fault begins/ends at T".
  down=$(grep -o -E '(link down|fault begins) at [0-9:.]*' "$3" | grep -o '[0-9:.]*$' || true)
  up=$(grep -o -E '(link up|fault ends) at [0-9:.]*' "$3" | grep -o '[0-9:.]*$' || true)
  local outage="none" after=0 memory=""
  if [[ -n $down && -n $up ]]; then
    # The registration service's memory while the drone is unreachable (two-hosts.sh samples it once a second).
    memory=$(awk -F, -v d="$(seconds_of_day "$down")" -v u="$(seconds_of_day "$up")" '
      $2 == "twinslam-registration" { if ($1 <= d) at = $4; if ($1 >= d && $1 <= u && $4 > peak) peak = $4; last = $4 }
      END { if (at != "") printf " | registration RSS %.0f MB at the fault, %.0f MB peak during it, %.0f MB at the end", at, peak, last }' \
      "$2/edge-memory.csv" 2>/dev/null || true)
    down=$(awk -v a="$(seconds_of_day "$down")" -v s="$start" 'BEGIN { printf "%.1f", a - s }')
    up=$(awk -v a="$(seconds_of_day "$up")" -v s="$start" 'BEGIN { printf "%.1f", a - s }')
    outage="$down-$up s"; after=$up
  fi
  local poses frames gap first accepted ate fused
  poses=$(grep -vc '^#' "$run/trajectory.tum")
  frames=$(($(wc -l < "$dataset/mav0/cam0/data.csv") - 1))
  gap=$(awk '!/^#/ { if (n++) { d = $1 - p; if (d > g) g = d } p = $1 } END { printf "%.2f", g }' "$run/trajectory.tum")
  first=$(awk -F, -v t0="$t0" -v after="$after" 'NR > 1 && $2 == 1 { t = ($1 - t0) / 1e9; if (t > after) { printf "%.1f s", t; exit } }' "$run/registrations.csv")
  accepted=$(awk -F, 'NR > 1 && $2 == 1 { n++ } END { print n + 0 }' "$run/registrations.csv")
  fused=$(python3 -c 'import json, sys
d = json.load(open(sys.argv[1])); e = d["counters"].get("estimator", {}); l = d.get("registration_latency_ms", {})
print("fused %d (re-attached %d, unknown keyframe %d), latency median %.0f ms p99 %.0f ms" % (e.get("registrations_fused", 0),
      e.get("registrations_reattached", 0), e.get("registrations_unknown_keyframe", 0), l.get("median", 0), l.get("p99", 0)))' "$run/run.json")
  ate=$("$bin/twinslam" eval --gt "$dataset" --est "$run" --align none --json | grep -o '"ate_pos_rmse_m": *[0-9.e-]*' | grep -o '[0-9.e-]*$')
  printf "%-12s poses %s/%s, largest gap %s s | outage %s | first accepted registration after it %s | accepted %s, %s | ATE in W %.3f m%s\n" \
    "$1" "$poses" "$frames" "$gap" "$outage" "${first:-none}" "$accepted" "$fused" "$ate" "$memory"
}
