#!/usr/bin/env python3
"""The report of scripts/fleet.sh: a line per vehicle, the fleet's registration latency, the edge's CPU and memory,
and which vehicles each registration instance served.

    python3 scripts/fleet_report.py OUT TWINSLAM DATASET...

OUT/uavK is vehicle K's run (dataset K), OUT/edge-usage.csv the edge's samples, OUT/edge/registration*.log the
instances' logs. Writes OUT/fleet.json with the same numbers.
"""
import csv
import json
import re
import subprocess
import sys
from pathlib import Path


def quantile(values, q):
    v = sorted(values)
    return v[min(len(v) - 1, int(q * len(v)))] if v else float("nan")


def vehicle(out, twinslam, k, dataset):
    run = out / f"uav{k}"
    info = json.loads((run / "run.json").read_text())
    latencies, accepted = [], 0
    with open(run / "registrations.csv") as f:
        for row in csv.DictReader(f):
            accepted += row["accepted"] == "1"
            if row["pipeline_latency_ms"]:
                latencies.append(float(row["pipeline_latency_ms"]))
    ev = subprocess.run([twinslam, "eval", "--gt", dataset, "--est", str(run), "--align", "none", "--json"],
                        capture_output=True, text=True)
    ate = json.loads(ev.stdout)["ate_pos_rmse_m"] if ev.returncode == 0 else None
    estimator = info.get("counters", {}).get("estimator", {})
    return {"vehicle": f"uav{k}", "status": info["status"], "registrations": len(latencies), "accepted": accepted,
            "fused": estimator.get("registrations_fused", 0), "latencies_ms": latencies, "ate_w_m": ate}


def edge_usage(path):
    first, last, peak = {}, {}, {}
    with open(path) as f:
        for row in csv.DictReader(f):
            name, t, cpu, rss = row["process"], float(row["t_s"]), float(row["cpu_s"]), float(row["rss_mb"])
            first.setdefault(name, (t, cpu))
            last[name] = (t, cpu)
            peak[name] = max(peak.get(name, 0.0), rss)
    usage = {}
    for name in first:
        (t0, c0), (t1, c1) = first[name], last[name]
        usage[name] = {"cpu_pct": 100.0 * (c1 - c0) / (t1 - t0) if t1 > t0 else 0.0, "peak_rss_mb": peak[name]}
    return usage


def served(out):
    by_instance = {}
    for log in sorted((out / "edge").glob("registration*.log")):
        counts = re.findall(r"served vehicle '([^']*)': (\d+) local maps", log.read_text(errors="replace"))
        by_instance[log.stem] = {v: int(c) for v, c in counts}
    return by_instance


def main():
    out, twinslam, datasets = Path(sys.argv[1]), sys.argv[2], sys.argv[3:]
    vehicles = [vehicle(out, twinslam, k, d) for k, d in enumerate(datasets)]
    for v in vehicles:
        ate = "never in W" if v["ate_w_m"] is None else f"{v['ate_w_m']:.3f} m"
        print(f"{v['vehicle']}: {v['status']}, registrations {v['registrations']} (accepted {v['accepted']}, fused "
              f"{v['fused']}), latency median {quantile(v['latencies_ms'], 0.5):.0f} ms p99 "
              f"{quantile(v['latencies_ms'], 0.99):.0f} ms, ATE in W {ate}")
    pooled = [x for v in vehicles for x in v["latencies_ms"]]
    print(f"fleet of {len(vehicles)}: registration latency (LocalMap published -> Registration received) median "
          f"{quantile(pooled, 0.5):.0f} ms, p99 {quantile(pooled, 0.99):.0f} ms over {len(pooled)} registrations")
    usage = edge_usage(out / "edge-usage.csv")
    for name, u in usage.items():
        print(f"edge {name}: CPU {u['cpu_pct']:.0f} % of a core, peak RSS {u['peak_rss_mb']:.0f} MB")
    instances = served(out)
    for name, counts in instances.items():
        print(f"{name} served: " + (", ".join(f"{v} ({c} local maps)" for v, c in sorted(counts.items())) or "nobody"))
    summary = {"vehicles": [{k: v for k, v in x.items() if k != "latencies_ms"} |
                            {"latency_median_ms": quantile(x["latencies_ms"], 0.5),
                             "latency_p99_ms": quantile(x["latencies_ms"], 0.99)} for x in vehicles],
               "latency_median_ms": quantile(pooled, 0.5), "latency_p99_ms": quantile(pooled, 0.99),
               "edge": usage, "served": instances}
    (out / "fleet.json").write_text(json.dumps(summary, indent=2) + "\n")


if __name__ == "__main__":
    main()
