#!/usr/bin/env python3
"""What recording costs the demo (issue 16: at most 5% on the zone tick p99).

deploy/demo.sh (4 zone ranks, a gateway and a fleet of players on scenes/demo.yaml, in real
time) runs PAIRS times without and with the recording (ZONESIM_DEMO_RECORD no / yes,
alternating, so drift on a shared machine hits both alike). Per run: the zone tick p50 and p99
of the slowest rank, the gateway tick mean and max, and the recording's size. Then the ratio
of the medians, with / without.

Usage: bench/cluster/recorder_overhead.py [PAIRS [SECONDS [PLAYERS]]]  (defaults 3, 20, 32)
       with ZONESIM_BIN=build/bin (the programs already built)
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PAIRS = int(sys.argv[1]) if len(sys.argv) > 1 else 3
SECONDS = sys.argv[2] if len(sys.argv) > 2 else "20"
PLAYERS = sys.argv[3] if len(sys.argv) > 3 else "32"


def demo(record, tmp, n):
    run = Path(tmp) / f"run_{record}_{n}"
    env = dict(os.environ, ZONESIM_BIN=os.environ.get("ZONESIM_BIN", str(ROOT / "build/bin")),
               ZONESIM_DEMO_RECORD=record, ZONESIM_DEMO_SECONDS=SECONDS,
               ZONESIM_DEMO_PLAYERS=PLAYERS)
    subprocess.run(["bash", str(ROOT / "deploy/demo.sh"), str(run)], env=env, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    zones = [json.loads(p.read_text()) for p in run.glob("zone_*_summary.json")]
    gateway = json.loads((run / "gateway_summary.json").read_text())
    size = sum(p.stat().st_size for p in (run / "record").glob("*.zsrec")) if record == "yes" else 0
    return {"p50": max(z["tick_ms_p50"] for z in zones), "p99": max(z["tick_ms_p99"] for z in zones),
            "gw_mean": gateway["tick_ms_mean"], "gw_max": gateway["tick_ms_max"],
            "mb": size / 1e6}


def main():
    rows = {"no": [], "yes": []}
    with tempfile.TemporaryDirectory(prefix="zs_recbench_") as tmp:
        for n in range(PAIRS):
            for record in ("no", "yes"):
                print(f"pair {n + 1}/{PAIRS}: record = {record} ...", file=sys.stderr, flush=True)
                rows[record].append(demo(record, tmp, n))
    print(f"deploy/demo.sh, {SECONDS} s, {PLAYERS} players, {PAIRS} runs each (alternating)\n")
    print("| record | run | zone tick p50 ms | zone tick p99 ms | gateway tick mean ms | gateway tick max ms | recording MB |")
    print("|---|---|---|---|---|---|---|")
    for record in ("no", "yes"):
        for n, r in enumerate(rows[record]):
            print(f"| {record} | {n + 1} | {r['p50']:.3f} | {r['p99']:.3f} | {r['gw_mean']:.3f} "
                  f"| {r['gw_max']:.2f} | {r['mb']:.1f} |")
    med = {k: {f: statistics.median(r[f] for r in rows[k]) for f in ("p50", "p99", "gw_mean")}
           for k in rows}
    print(f"\nmedians, with / without: zone tick p50 {med['yes']['p50'] / med['no']['p50']:.3f}, "
          f"p99 {med['yes']['p99'] / med['no']['p99']:.3f}; gateway tick mean "
          f"{med['yes']['gw_mean'] / med['no']['gw_mean']:.3f}")


if __name__ == "__main__":
    main()
