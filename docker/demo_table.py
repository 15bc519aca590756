#!/usr/bin/env python3
"""The container demo's accuracy table (docker/demo.sh): one row per run of OUT (containers, native), markdown.

Usage: demo_table.py OUT DATASET RUN...   (OUT/RUN/run/{run.json,trajectory.tum,registrations.csv}, OUT/RUN/eval.json)
"""
import csv
import json
import sys


def row(out, dataset, name):
    run = f"{out}/{name}/run"
    info = json.load(open(f"{run}/run.json"))
    ate = json.load(open(f"{out}/{name}/eval.json"))["ate_pos_rmse_m"]
    stamps = [float(l.split()[0]) for l in open(f"{run}/trajectory.tum") if l.strip() and not l.startswith("#")]
    gap = max((b - a for a, b in zip(stamps, stamps[1:])), default=0.0)
    with open(f"{run}/registrations.csv") as f:
        regs = list(csv.reader(f))[1:]
    accepted = sum(1 for r in regs if len(r) > 1 and r[1] == "1")
    fused = info.get("counters", {}).get("estimator", {}).get("registrations_fused", 0)
    lat = info.get("registration_latency_ms", {})
    frames = sum(1 for _ in open(f"{dataset}/mav0/cam0/data.csv")) - 1
    return name, info.get("status"), len(stamps), frames, gap, len(regs), accepted, fused, lat, ate


def main():
    out, dataset, names = sys.argv[1], sys.argv[2], sys.argv[3:]
    rows = [row(out, dataset, n) for n in names]
    print("| run | status | poses / frames | largest gap [s] | registrations: answered / accepted / fused "
          "| latency median / p99 [ms] | ATE in W [m] |")
    print("|---|---|---|---|---|---|---|")
    for name, status, poses, frames, gap, regs, acc, fused, lat, ate in rows:
        print(f"| {name} | {status} | {poses} / {frames} | {gap:.2f} | {regs} / {acc} / {fused} "
              f"| {lat.get('median', 0):.0f} / {lat.get('p99', 0):.0f} | {ate:.3f} |")
    ates = dict((r[0], r[-1]) for r in rows)
    if "containers" in ates and "native" in ates and ates["native"] > 0:
        print(f"\ncontainers / native ATE: {ates['containers'] / ates['native']:.2f}")


if __name__ == "__main__":
    main()
