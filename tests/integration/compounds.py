"""Compound bodies on one and two zones (scenes/compounds.yaml), each against its analytic
result: the table rests on its legs with its centre of mass 0.78793 m up; the gallows tips
about its foot's edge onto its arm's tip, turned atan(1 / 3.604); the sled slides on its
runners across the border and stops where Coulomb friction stops it; the ball rests on the
static arch's lintel; the hammer, thrown spinning across the border, flies the same path on
both decompositions and lands. In flight its position and velocity match bit for bit and its
orientation to round-off: the zone it migrates to adds it to a rebuilt engine world, which
renormalises the orientation it was given.
Compounds' parts are not carried between zones: each zone builds them from the scene."""
import json
import math
import tempfile
from pathlib import Path

import harness as h

DT = 1.0 / 60.0
# The scene names no solver, so it gets the wide soft step, which spends its 10 velocity iterations
# as 5 sub-steps: the sled's motion is integrated at DT / 5.
SUB_DT = DT / ((10 + 1) // 2)
LONG_TICKS = 600  # 10 s: everything at rest
FLIGHT_TICKS = 50  # the hammer crossed x = 20 at about 40 ticks and is still in the air
SLED = {"v0": 6.0, "x0": 16.0, "friction": math.sqrt(0.1 * 0.5)}
TABLE_CENTRE_Y = (0.2 * 0.85 + 4 * 0.008 * 0.4) / (0.2 + 4 * 0.008)
GALLOWS_TILT = math.atan(1.0 / (4.104 - 0.5))


def run(out, ranks, ticks):
    dump = out / f"{ranks}_{ticks}.jsonl"
    metrics = out / f"metrics_{ranks}_{ticks}"
    h.run(h.mpirun(ranks, h.bin_dir() / "zone_node", "--scene",
                   h.SOURCE_DIR / "scenes/compounds.yaml", "--ticks", ticks, "--no-dds",
                   "--dump-state", dump, "--metrics", metrics),
          out / f"{ranks}_{ticks}.log", h.base_env(), timeout=300)
    rows = [json.loads(line) for line in dump.read_text().splitlines()]
    migrated = sum(json.loads(p.read_text()).get("migrated_out", 0)
                   for p in metrics.glob("zone_*_summary.json"))
    # Named bodies follow the populations in scene order: table, gallows, sled, hammer, (arch,
    # static, no entity), ball.
    by_id = sorted(rows, key=lambda r: r["id"])
    return dict(zip(("table", "gallows", "sled", "hammer", "ball"), by_id)), migrated


def tilt(rot):
    """Angle between the body's local y and world y, from the dump's [x, y, z, w]."""
    x, y, z, w = rot
    up_y = 1.0 - 2.0 * (x * x + z * z)
    return math.acos(max(-1.0, min(1.0, up_y)))


with tempfile.TemporaryDirectory(prefix="zs_compounds_") as tmp:
    out = Path(tmp)
    # Semi-implicit Euler in steps of h stops a body decelerating at a after
    # v0^2 / (2a) - v0 h / 2.
    a = SLED["friction"] * 9.81
    sled_stop = SLED["x0"] + SLED["v0"] ** 2 / (2 * a) - SLED["v0"] * SUB_DT / 2
    for ranks in (1, 2):
        end, migrated = run(out, ranks, LONG_TICKS)
        h.check(len(end) == 5, f"{ranks} ranks: 5 dynamic bodies dumped, the arch is not an entity")
        table_y = end["table"]["pos"][1]
        h.check(abs(table_y - TABLE_CENTRE_Y) < 1e-3,
                f"{ranks} ranks: the table rests at {table_y:.5f} m (legs down: "
                f"{TABLE_CENTRE_Y:.5f})")
        g = tilt(end["gallows"]["rot"])
        h.check(abs(g - GALLOWS_TILT) < 2e-3,
                f"{ranks} ranks: the gallows lies tipped {g:.4f} rad (arm tip down: "
                f"{GALLOWS_TILT:.4f})")
        sled_x = end["sled"]["pos"][0]
        h.check(abs(sled_x - sled_stop) < 0.01,
                f"{ranks} ranks: the sled stopped at x = {sled_x:.4f} (friction: {sled_stop:.4f})")
        ball_y = end["ball"]["pos"][1]
        h.check(abs(ball_y - 3.5) < 1e-3, f"{ranks} ranks: the ball rests at {ball_y:.4f} on the "
                "arch's lintel (3.5)")
        hammer = end["hammer"]["pos"]
        h.check(hammer[0] > 20 and hammer[1] < 0.5 and all(map(math.isfinite, hammer)),
                f"{ranks} ranks: the hammer landed across the border, at {hammer}")
        if ranks == 2:
            h.check(migrated >= 2, f"on 2 ranks {migrated} bodies crossed the border (sled, hammer)")
    flight = {ranks: run(out, ranks, FLIGHT_TICKS)[0]["hammer"] for ranks in (1, 2)}
    h.check(flight[1]["pos"][0] > 20.5 and flight[1]["pos"][1] > 1.0,
            f"after {FLIGHT_TICKS} ticks the hammer is across the border and in the air: "
            f"{flight[1]['pos']}")
    rot_gap = max(abs(x - y) for x, y in zip(flight[1]["rot"], flight[2]["rot"]))
    h.check(flight[1]["pos"] == flight[2]["pos"] and flight[1]["vel"] == flight[2]["vel"]
            and rot_gap < 1e-12,
            f"in flight the hammer flies the same on 1 and 2 ranks (orientations {rot_gap:.1e} "
            "apart)")
print("compounds passed")
