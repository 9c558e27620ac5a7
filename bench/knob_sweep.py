#!/usr/bin/python3
"""Work-precision of one scene key: the scene run on a local cluster with players once per
value, each run measured as bench/tune.py measures it (error shown to players against the
zones' truth, download per player, tick time), printed as a table, written as CSV and plotted.

    /usr/bin/python3 bench/knob_sweep.py scenes/demo.yaml clients.downlink_kbps 0,10,20,40,80 \
        --csv sweep.csv --plot sweep.png

Values are numbers or names as the scene file writes them; each run is an overlay of the scene
(docs/scene-format.md, "Overlay files") setting only that key.
"""
import argparse
import csv
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from tuning import knobs, measure  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "deploy"))
import truth_error  # noqa: E402

NEAR = "0-25 m"  # truth_error's first band: what a player sees closest


def value_of(text):
    try:
        return int(text)
    except ValueError:
        try:
            return float(text)
        except ValueError:
            return text


def near_p99(run):
    _, bands, _ = truth_error.join(run)
    return measure.percentile(bands[NEAR], 99) if bands.get(NEAR) else float("nan")


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene", type=Path)
    p.add_argument("key", help="the dotted scene key, e.g. clients.downlink_kbps")
    p.add_argument("values", help="comma-separated values")
    p.add_argument("--seconds", type=float, default=20, help="players' time per run (default 20)")
    p.add_argument("--players", type=int, default=32)
    p.add_argument("--truth-every", type=int, default=16)
    p.add_argument("--repeats", type=int, default=1, help="runs per value (alternating)")
    p.add_argument("--work", type=Path, default=Path("/tmp/knob_sweep"))
    p.add_argument("--csv", type=Path)
    p.add_argument("--plot", type=Path)
    p.add_argument("--bin", type=Path, default=ROOT / "build" / "bin")
    a = p.parse_args(argv)
    if not a.scene.is_file():
        p.error(f"scene {a.scene}: no such file")
    values = [value_of(v.strip()) for v in a.values.split(",") if v.strip()]
    if not values:
        p.error("no values")
    scene = knobs.merged_scene(a.scene)
    ranks = measure.ranks_of(scene)
    rows = []
    for r in range(a.repeats):
        for v in values:
            folder = (a.work / f"{a.key}={v}-{r}").resolve()
            folder.mkdir(parents=True, exist_ok=True)
            overlay = folder / "scene.yaml"
            overlay.write_text(knobs.overlay_text(a.scene.resolve(), {a.key: v}, [f"knob_sweep: {a.key} = {v}"]))
            started = time.monotonic()
            try:
                f = measure.run_once(overlay, folder, ranks, a.seconds, a.players, a.truth_every, a.bin)
            except measure.RunError as e:
                sys.exit(f"knob_sweep.py: {e}")
            f["near_error_p99"] = near_p99(folder / "run")
            rows.append({"value": v, "repeat": r, **f})
            print(f"{a.key} = {v!s:<8} error p99 {f['shown_error_p99']:.3f} m (0-25 m {f['near_error_p99']:.3f})  "
                  f"{f['kbps_per_client']:.1f} kbit/s  tick p99 {f['tick_ms_p99']:.2f} ms  "
                  f"({time.monotonic() - started:.0f} s)", flush=True)
    print(f"\n| {a.key} | run | kbit/s per player | shown error p99 m | 0-25 m p99 m | tick p99 ms | samples |")
    print("|---|---|---|---|---|---|---|")
    for row in rows:
        print(f"| {row['value']} | {row['repeat'] + 1} | {row['kbps_per_client']:.1f} | {row['shown_error_p99']:.3f} | "
              f"{row['near_error_p99']:.3f} | {row['tick_ms_p99']:.2f} | {row['samples']} |")
    if a.csv:
        with open(a.csv, "w", newline="") as out:
            w = csv.DictWriter(out, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    if a.plot:
        from tuning import sweep_plot
        sweep_plot.plot(rows, f"{a.scene.name}: {a.key}", a.plot)

if __name__ == "__main__":
    main(sys.argv[1:])
