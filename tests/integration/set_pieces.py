"""Static and kinematic set pieces on more than one zone (scenes/set_pieces.yaml): every zone
places the ramp, the moving platform and the turntable itself, so a box that slides down the
ramp across the border and a box the platform carries across it end where they do on one
rank. Not bit for bit: a zone rebuilds its engine world when a body migrates in or out, which
costs that step its warm start, so the two runs differ by the solver's unconverged remainder."""
import json
import tempfile
from pathlib import Path

import harness as h

TICKS = 360  # 6 s: the slider crosses x = 20 at about 1.4 s, the platform's rider at about 4 s
TOLERANCE_M = 1e-3

with tempfile.TemporaryDirectory(prefix="zs_setpieces_") as tmp:
    out = Path(tmp)
    ends, migrated = {}, {}
    for ranks in (1, 2):
        dump = out / f"{ranks}.jsonl"
        metrics = out / f"metrics_{ranks}"
        h.run(h.mpirun(ranks, h.bin_dir() / "zone_node", "--scene",
                       h.SOURCE_DIR / "scenes/set_pieces.yaml", "--ticks", TICKS, "--no-dds",
                       "--dump-state", dump, "--metrics", metrics),
              out / f"{ranks}.log", h.base_env(), timeout=300)
        rows = [json.loads(line) for line in dump.read_text().splitlines()]
        ends[ranks] = {r["id"]: r["pos"] for r in rows}
        migrated[ranks] = sum(json.loads(p.read_text()).get("migrated_out", 0)
                              for p in metrics.glob("zone_*_summary.json"))
    h.check(len(ends[1]) == 5 and ends[1].keys() == ends[2].keys(),
            f"the 5 dynamic bodies are in both dumps, the 3 set pieces in neither ({len(ends[1])})")
    h.check(migrated[2] >= 2, f"on 2 ranks {migrated[2]} bodies crossed the border")
    worst = max(max(abs(a - b) for a, b in zip(ends[1][i], ends[2][i])) for i in ends[1])
    h.check(worst < TOLERANCE_M, f"2 ranks end within {worst:.2e} m of 1 rank (< {TOLERANCE_M})")
    slider = min(p[0] for p in ends[2].values())
    # The rider is the box near z = 30 (the platform's line); the turned box lies at x = 30.
    rider = [p[0] for p in ends[2].values() if abs(p[2] - 30) < 0.5 and p[0] < 26]
    h.check(slider < 14.4, f"the slider went down the ramp and off its foot, to x = {slider:.2f}")
    h.check(len(rider) == 1 and abs(rider[0] - (16 + TICKS / 60)) < 0.2,
            f"the platform carried its rider to x = {rider} (platform at {16 + TICKS / 60:.1f})")
print("set pieces passed")
