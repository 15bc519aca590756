#!/usr/bin/env bash
# The fleet benchmark (issue 14 item 6): N vehicles on one edge, realtime, for N in SIZES (default 1 5 10), and the
# largest fleet once more with two registration instances (scripts/fleet.sh --split). Vehicle K flies once around its
# own block of the 600 m city of city-loops, along the streets at 16-19 m, 80 s, ideal feature tracks; the vehicles
# are spread over the city and share its twin. Each vehicle also flies alone on the same kind of edge: its single-
# vehicle run, the reference of its ATE in the fleets.
#
#   bash scripts/fleet-bench.sh OUT [SIZES...] [--max]
#
# --max: every run (alone and in fleets) in lockstep instead of realtime: each estimator takes every frame whatever
# the CPU, and waits for the shared edge's answer to each LocalMap. On a machine with fewer cores than the fleet's
# processes need in realtime this stands in for each vehicle flying its own computer: the vehicles' ATE then shows what
# sharing the edge costs them, and the latency what the edge's queue adds (not realtime latency).
#
# OUT/data/uavK the datasets (kept and reused), OUT/single/uavK, OUT/fleet-N, OUT/fleet-N-split the fleet.sh folders.
# Prints a table: per fleet, registration latency median / p99, the edge's CPU and peak memory, the worst ratio of a
# vehicle's ATE in W to its single-vehicle run and how many vehicles stay within 1.2x; for the split fleet the
# vehicles each instance served. Takes about 20 minutes with the default sizes (--max: 15).
set -euo pipefail
die() { echo "fleet-bench.sh: $*" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[[ $# -ge 1 ]] || die "usage: fleet-bench.sh OUT [SIZES...] [--max]"
out=$(realpath -m "$1"); shift
replay=(); args=()
for a in "$@"; do
  if [[ $a == --max ]]; then replay=(--max); else args+=("$a"); fi
done
sizes=("${args[@]:-1 5 10}"); sizes=(${sizes[*]})
largest=0
for s in "${sizes[@]}"; do
  [[ $s =~ ^[0-9]+$ && $s -ge 1 && $s -le 10 ]] || die "a fleet size is 1..10, not '$s'"
  (( s > largest )) && largest=$s
done
bin=${TWINSLAM_BIN:-$root/build/bin}
export TWINSLAM_BIN=$bin
mkdir -p "$out/data"

# Block (i, j) of the 9 x 9 city (centre (i - 4, j - 4) x 60 m) that vehicle K circles, clear of the tower.
blocks=("1 1" "3 1" "5 1" "7 1" "7 3" "1 5" "2 7" "4 7" "6 7" "5 5")
datasets=()
for ((k = 0; k < largest; k++)); do
  read -r i j <<< "${blocks[$k]}"
  cx=$(( (i - 4) * 60 )); cy=$(( (j - 4) * 60 ))
  d=$out/data/uav$k
  datasets+=("$d")
  [[ -f $d/dataset.yaml ]] && continue
  cat > "$out/data/uav$k.yaml" <<EOF
# Vehicle $k of the fleet benchmark: once around the block at ($cx, $cy) along its streets.
name: fleet-uav$k
base: city-loops
trajectory: {type: waypoints, duration_s: 80, speed_mps: 3, waypoints: [[$((cx - 30)), $((cy - 30)), 16], [$((cx + 30)), $((cy - 30)), 19], [$((cx + 30)), $((cy + 30)), 16], [$((cx - 30)), $((cy + 30)), 19], [$((cx - 30)), $((cy - 25)), 16]]}
EOF
  "$bin/twinslam" sim --scenario "$out/data/uav$k.yaml" --out "$d" --features --no-images --quiet  # ideal tracks: no images
done

for ((k = 0; k < largest; k++)); do
  echo "fleet-bench.sh: uav$k alone"
  bash "$root/scripts/fleet.sh" "$out/single/uav$k" "${datasets[$k]}" "${replay[@]}" -- --features > "$out/single-uav$k.txt" ||
    echo "fleet-bench.sh: uav$k failed alone ($out/single-uav$k.txt)"
done
for s in "${sizes[@]}"; do
  echo "fleet-bench.sh: a fleet of $s"
  bash "$root/scripts/fleet.sh" "$out/fleet-$s" "${datasets[@]:0:$s}" "${replay[@]}" -- --features > "$out/fleet-$s.txt" ||
    echo "fleet-bench.sh: a vehicle's run failed in the fleet of $s ($out/fleet-$s.txt)"
done
if (( largest >= 2 )); then
  echo "fleet-bench.sh: a fleet of $largest, two registration instances"
  bash "$root/scripts/fleet.sh" "$out/fleet-$largest-split" "${datasets[@]}" --split "${replay[@]}" -- --features \
    > "$out/fleet-$largest-split.txt" || echo "fleet-bench.sh: a vehicle's run failed in the split fleet"
fi

python3 - "$out" "$largest" "${sizes[@]}" <<'EOF'
import json, sys
from pathlib import Path
out, largest, sizes = Path(sys.argv[1]), int(sys.argv[2]), [int(s) for s in sys.argv[3:]]
alone = {}
for k in range(largest):
    alone[f"uav{k}"] = json.loads((out / "single" / f"uav{k}" / "fleet.json").read_text())["vehicles"][0]["ate_w_m"]
print("| vehicles | registration instances | runs ok | latency median [ms] | latency p99 [ms] | edge CPU [% of a core] "
      "| edge peak RSS [MB] | worst ATE / alone | within 1.2x |")
print("|---|---|---|---|---|---|---|---|---|")
runs = [(s, f"fleet-{s}", 1) for s in sizes] + ([(largest, f"fleet-{largest}-split", 2)] if largest >= 2 else [])
for n, name, instances in runs:
    f = json.loads((out / name / "fleet.json").read_text())
    cpu = sum(u["cpu_pct"] for u in f["edge"].values())
    rss = sum(u["peak_rss_mb"] for u in f["edge"].values())
    ratios = [v["ate_w_m"] / alone[v["vehicle"]] if v["ate_w_m"] and alone[v["vehicle"]] else float("inf")
              for v in f["vehicles"]]
    within = sum(r <= 1.2 for r in ratios)
    ok = sum(v["status"] == "ok" for v in f["vehicles"])
    print(f"| {n} | {instances} | {ok}/{n} | {f['latency_median_ms']:.0f} | {f['latency_p99_ms']:.0f} | {cpu:.0f} | {rss:.0f} "
          f"| {max(ratios):.2f} | {within}/{n} |")
    if instances == 2:
        for inst, counts in f["served"].items():
            print(f"{inst} served " + ", ".join(f"{v} ({c})" for v, c in sorted(counts.items())))
print("alone, ATE in W [m]: " + ", ".join(f"{v} {a:.3f}" if a else f"{v} never in W" for v, a in alone.items()))
EOF
