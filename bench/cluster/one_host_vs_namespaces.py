#!/usr/bin/env python3
"""The demo on one host against the same demo on three network namespaces, side by side, each
with and without mpi_yield_when_idle: scenes/demo.yaml, 4 zone ranks, one gateway, 32 players for
20 s, through deploy/cluster.sh with deploy/clusters/local.cluster (everything on loopback,
shared memory between ranks) and deploy/clusters/netns3.cluster (ranks 0-1 on h1, 2-3 on h2 over
Open MPI's TCP, the gateway and players on h3: every zone-gateway and gateway-player packet
crosses a veth pair and a bridge). Needs root (namespaces).

Reported per run: zone tick p50 (median over ranks) and p99 (worst rank), the handoff latency
(border crossing to the first input applied at the new owner, pooled over ranks) at p50/p99,
migrations and avatar handoffs, and the mean bytes/s per client in and out.

Usage: bench/cluster/one_host_vs_namespaces.py [BUILD_DIR] [SECONDS]
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
SECONDS = sys.argv[2] if len(sys.argv) > 2 else "20"
PREFIX = f"zsb{os.getpid()}"


def percentile(values, q):
    if not values:
        return float("nan")
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q / 100 * (len(s) - 1))))]


def run(cluster, run_dir, yield_mode):
    env = {**os.environ, "ZONESIM_BIN": str(BUILD / "bin"), "ZONESIM_NETNS": PREFIX,
           "ZONESIM_DEMO_SECONDS": SECONDS, "ZONESIM_CLUSTER_SECONDS": SECONDS,
           "ZONESIM_DEMO_TRUTH_EVERY": "0", "ZONESIM_CLUSTER_TRUTH_EVERY": "0",
           "ZONESIM_DEMO_YIELD": yield_mode, "ZONESIM_CLUSTER_YIELD": yield_mode,
           "ZONESIM_CLUSTER_SCENE": "scenes/demo.yaml", "ZONESIM_DEMO_SCENE": "scenes/demo.yaml"}
    with open(run_dir.parent / f"{run_dir.name}.log", "w") as log:
        subprocess.run([ROOT / "deploy/cluster.sh", ROOT / "deploy/clusters" / cluster, run_dir],
                       env=env, stdout=log, stderr=subprocess.STDOUT, check=True)
    zones = [json.loads(p.read_text()) for p in run_dir.glob("zone_*_summary.json")]
    report = json.loads((run_dir / "report.json").read_text())
    latency = [ms for z in zones for ms in z.get("handoff_latency_ms", [])]
    t = report["totals"]
    return {
        "tick_p50": statistics.median(z["tick_ms_p50"] for z in zones),
        "tick_p99": max(z["tick_ms_p99"] for z in zones),
        "handoff_p50": percentile(latency, 50), "handoff_p99": percentile(latency, 99),
        "migrations": t["migrations"], "handoffs": t["avatar_handoffs"],
        "in": t["bytes_in_per_s_mean"], "out": t["bytes_out_per_s_mean"],
    }


def main():
    rows = []
    with tempfile.TemporaryDirectory(prefix="zs_bench_hosts_") as tmp:
        subprocess.run([ROOT / "deploy/netns.sh", "up", PREFIX, "3"], check=True)
        try:
            for cluster, label in (("local.cluster", "one host (loopback, shared memory)"),
                                   ("netns3.cluster", "3 namespaces (TCP, veth + bridge)")):
                for yield_mode in ("off", "on"):
                    rows.append((label, yield_mode, run(cluster, Path(tmp) / f"{cluster}-{yield_mode}", yield_mode)))
        finally:
            subprocess.run([ROOT / "deploy/netns.sh", "down", PREFIX])
    print(f"| cluster | yield | tick p50 / p99 ms | handoff p50 / p99 ms | migrations | avatar handoffs "
          f"| per client in / out B/s |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for label, y, r in rows:
        print(f"| {label} | {y} | {r['tick_p50']:.2f} / {r['tick_p99']:.1f} | {r['handoff_p50']:.0f} / "
              f"{r['handoff_p99']:.0f} | {r['migrations']} | {r['handoffs']} | {r['in']:.0f} / {r['out']:.0f} |")


if __name__ == "__main__":
    main()
