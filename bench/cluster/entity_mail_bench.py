#!/usr/bin/env python3
"""What messages between entities cost a tick (issue 15: hits, kills, gifts and pickups across
zones, zone_node/cluster/entity_mail.h).

scenes/skirmish.yaml (1,600 NPCs, 400 of them brawling where four zones meet; 15 unique items)
runs 600 ticks (--no-dds) on 1, 2 and 4 ranks with its interactions, and again with them off
(the same scene with `interactions: {enabled: false}`), in one run of this script. Reported per
rank count, on the slowest rank: mean tick time with and without (the ratio), the two stages
the interactions add (ai.interactions: choosing targets and posting; migrate.mail: the three
delivery rounds), and what went between ranks: messages per tick applied, of them across a
border, forwarded after a migrating target, and mail bytes per tick.

Usage: bench/cluster/entity_mail_bench.py [BUILD_DIR]
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
SCENE = ROOT / "scenes/skirmish.yaml"
TICKS = 600


def run(scene, ranks, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    metrics = out / f"metrics_{scene.stem}_{ranks}"
    subprocess.run(["mpirun", "--oversubscribe", "-np", str(ranks), str(BUILD / "bin/zone_node"),
                    "--scene", str(scene), "--ticks", str(TICKS), "--no-dds", "--metrics",
                    str(metrics)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return [json.loads(p.read_text()) for p in metrics.glob("zone_*_summary.json")]


def slowest(summaries, key):
    return max(s[key] for s in summaries)


def main():
    with tempfile.TemporaryDirectory(prefix="zs_mail_") as tmp:
        out = Path(tmp)
        off = out / "skirmish_off.yaml"
        text = SCENE.read_text()
        off.write_text(text.replace("interactions:\n", "interactions:\n  enabled: false\n", 1))
        rows = []
        for ranks in (1, 2, 4):
            print(f"running {ranks} rank(s), interactions on and off...", file=sys.stderr,
                  flush=True)
            rows.append((ranks, run(SCENE, ranks, out), run(off, ranks, out)))
    print(f"scenes/skirmish.yaml, {TICKS} ticks, --no-dds; ms are per tick, slowest rank\n")
    print("| ranks | tick ms on | tick ms off | on / off | ai.interactions ms | migrate.mail ms "
          "| messages applied / tick | across a border / tick | forwarded / tick "
          "| mail bytes / tick | hits | kills | pickups (contested) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for ranks, on, off_ in rows:
        total = lambda k: sum(s.get(k, 0) for s in on)
        t_on = slowest(on, "tick_ms_p50")
        t_off = slowest(off_, "tick_ms_p50")
        print(f"| {ranks} | {t_on:.3f} | {t_off:.3f} | {t_on / t_off:.2f} "
              f"| {slowest(on, 'ai.interactions_ms_mean'):.3f} "
              f"| {slowest(on, 'migrate.mail_ms_mean'):.3f} "
              f"| {total('mail_applied') / TICKS:.1f} | {total('mail_cross_zone') / TICKS:.2f} "
              f"| {total('mail_forwarded') / TICKS:.3f} | {total('mail_bytes') / TICKS:.0f} "
              f"| {total('hits')} | {total('kills')} "
              f"| {total('pickups')} ({total('pickups_contested')}) |")


if __name__ == "__main__":
    main()
