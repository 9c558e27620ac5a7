"""bench/tune.py end to end, on a local cluster: a budget no setting meets is refused, naming
the limit and the best measured, and nothing is written; a budget that can be met gives an
overlay of the scene (read back by zone_node), chosen from measured runs and confirmed, with the
binding limit named; a malformed budget is refused before any run. Runs one knob with two
values and 3-second runs to stay short. The physics limit: stack_drift on a scene without
rigid bodies is refused before any run; on scenes/stacks.yaml (116 boxes in stacks) a drift
no substep count reaches is refused naming the limit and the best measured drift, after a
reference run and one run per substep count that each measured it. The crowd limit, on
scenes/courtyard_flow_lod.yaml's 400 flow NPCs with runs of the zones alone: a budget mixing it
with a player limit, or on a scene without a flow crowd, is refused before any run; a drift no
far-band steering setting reaches is refused naming the limit and the best measured drift; a
mean drift the bands can meet gives an overlay with the chosen bands, confirmed. The planner
limit on scenes/agents_navmesh.yaml: landmarks, which the loader refuses with a navmesh, make
their runs fail, reported and skipped while the tune goes on to refuse an overhead below the
mesh's; on a scene without planning agents it is refused before any run. The gpu limit on
scenes/crowd_flock.yaml: the flock on the device is measured against the CPU's double run and
an overlay choosing gpu.mode is written; on a scene without flocks it is refused."""
import json
import re
import subprocess
import tempfile
from pathlib import Path

import harness as h

TUNE = h.SOURCE_DIR / "bench" / "tune.py"
SCENE = h.SOURCE_DIR / "scenes" / "test_e2e.yaml"


def tune(work, budget, *extra, scene=SCENE, knobs="avatar order", players=8, seconds=3):
    env = h.base_env(h.free_dds_domain())
    return subprocess.run(["/usr/bin/python3", TUNE, scene, "--budget", budget, "--work", work,
                           "--knobs", knobs, "--seconds", str(seconds), "--confirm-seconds", str(seconds),
                           "--players", str(players), "--bin", h.bin_dir(), *extra],
                          capture_output=True, text=True, env=env, timeout=400)


with tempfile.TemporaryDirectory(prefix="zs_tune_") as tmp:
    tmp = Path(tmp)
    bad = tune(tmp / "bad", "shown_error_p99<=0.25,jitter<=3")
    h.check(bad.returncode == 2 and "unknown limit 'jitter'" in bad.stderr and not (tmp / "bad").exists(),
            f"a malformed budget is refused before any run: {bad.stderr.strip()[-300:]}")

    impossible = tune(tmp / "impossible", "shown_error_p99<=0.0001")
    h.check(impossible.returncode == 2, f"an impossible budget exits 2 ({impossible.returncode}): "
            f"{impossible.stdout[-600:]} {impossible.stderr[-600:]}")
    h.check("refused: no setting meets shown_error_p99 <= 0.0001 m: the best measured is" in impossible.stderr,
            f"the refusal names the limit and the best reached: {impossible.stderr.strip()}")
    h.check(not list((tmp / "impossible").glob("*.tuned.yaml")), "nothing is written for a refused budget")

    out = tmp / "ok" / "e2e.tuned.yaml"
    ok = tune(tmp / "ok", "shown_error_p99<=5,kbps_per_client<=100000", "--out", out)
    h.check(ok.returncode == 0 and out.exists(), f"a budget that can be met writes the overlay: "
            f"{ok.stdout[-800:]} {ok.stderr[-800:]}")
    report = json.loads((tmp / "ok" / "tune.json").read_text())
    h.check(len(report["runs"]) == 3, f"the scene's own run, one more value, one confirming run "
            f"({len(report['runs'])} runs)")
    h.check(report["chosen"]["avatar order"] in ("first", "second") and report["binding"] in
            ("shown_error_p99 <= 5 m", "kbps_per_client <= 100000 kbit/s"),
            f"a value chosen and the binding limit named: {report['chosen']}, {report['binding']}")
    confirmed = report["confirmed"]
    h.check(confirmed["shown_error_p99"] <= 5 and confirmed["samples"] > 0,
            f"the confirming run met the budget with samples to show it: {confirmed}")
    text = out.read_text()
    h.check("overlay_of: ../../" in text or "overlay_of: /" in text, f"the overlay names its base: {text}")
    h.check(f"order: {report['chosen']['avatar order']}" in text, f"the overlay sets the chosen order: {text}")
    h.check((tmp / "ok" / "frontier.png").stat().st_size > 1000, "the frontier plot was drawn")
    # Every program reads the overlay as the scene it changes.
    dump = tmp / "ok" / "state.jsonl"
    h.run(h.mpirun(4, h.bin_dir() / "zone_node", "--scene", out, "--ticks", 5, "--no-dds", "--dump-state", dump),
          tmp / "ok" / "zone.log", h.base_env(), timeout=120)
    h.check(dump.exists() and dump.read_text().count("\n") > 0, "zone_node runs the written overlay")

    # The physics limit.
    skirmish = h.SOURCE_DIR / "scenes" / "skirmish.yaml"
    bodiless = tune(tmp / "bodiless", "stack_drift<=0.01", scene=skirmish, knobs="npc order")
    h.check(bodiless.returncode == 2 and "stack_drift needs rigid bodies, and skirmish.yaml has none"
            in bodiless.stderr and not (tmp / "bodiless").exists(),
            f"a drift limit on a scene without bodies is refused before any run: {bodiless.stderr.strip()[-300:]}")

    stacks = h.SOURCE_DIR / "scenes" / "stacks.yaml"
    drift = tune(tmp / "drift", "stack_drift<=0.000001", scene=stacks, knobs="substeps", players=4)
    h.check(drift.returncode == 2, f"an impossible drift budget exits 2 ({drift.returncode}): "
            f"{drift.stdout[-800:]} {drift.stderr[-600:]}")
    refusal = re.search(r"refused: no setting meets stack_drift <= 1e-06 m: the best measured is "
                        r"(\S+) m \(substeps = (\d)\)", drift.stderr)
    h.check(refusal is not None, f"the refusal names the drift limit, the best drift and where: {drift.stderr.strip()}")
    h.check("116 bodies rest at tick" in drift.stdout, f"the reference run's resting bodies are counted: {drift.stdout[-800:]}")
    measured = [float(m) for m in re.findall(r"stack drift +([0-9.]+) mm", drift.stdout)]
    h.check(len(measured) == 3, f"the scene's own run and substeps 4 and 2 each measured a drift: {measured}")
    h.check(min(measured) > 0 and abs(float(refusal.group(1)) * 1000 - min(measured)) <= 0.01,
            f"the best measured drift is the least of the runs', a real distance: {refusal.group(1)} m, {measured} mm")
    h.check(max(measured) > 2 * min(measured), f"the substep count moves the drift: {measured} mm")
    h.check(not list((tmp / "drift").glob("*.tuned.yaml")) and not (tmp / "drift" / "tune.json").exists(),
            "nothing is written for a refused drift budget")

    # The crowd limit: runs of the zones alone, 40 s of the courtyard (every NPC arrives in 39 s).
    courtyard = h.SOURCE_DIR / "scenes" / "courtyard_flow_lod.yaml"
    mixed = tune(tmp / "mixed", "arrival_drift<=0.5,shown_error_p99<=1", scene=courtyard, knobs="lod bands m")
    h.check(mixed.returncode == 2 and "arrival_drift is measured on runs of the zones alone and shown_error_p99 "
            "needs players" in mixed.stderr and not (tmp / "mixed").exists(),
            f"a crowd limit beside a player limit is refused before any run: {mixed.stderr.strip()[-300:]}")
    flowless = tune(tmp / "flowless", "arrival_drift<=0.5", scene=skirmish, knobs="npc order")
    h.check(flowless.returncode == 2 and "arrival_drift needs a flow-field crowd (populations[].flow), and "
            "skirmish.yaml has none" in flowless.stderr and not (tmp / "flowless").exists(),
            f"a crowd limit on a scene without a flow crowd is refused: {flowless.stderr.strip()[-300:]}")

    steers = tune(tmp / "steers", "arrival_drift<=0.5", "--repeat", "1", scene=courtyard, knobs="lod far steers",
                  seconds=40)
    h.check(steers.returncode == 2, f"an impossible crowd budget exits 2 ({steers.returncode}): "
            f"{steers.stdout[-800:]} {steers.stderr[-600:]}")
    refusal = re.search(r"refused: no setting meets arrival_drift <= 0.5 s: the best measured is (\S+) s",
                        steers.stderr)
    h.check(refusal is not None and float(refusal.group(1)) > 0.5,
            f"the refusal names the crowd limit and the best drift: {steers.stderr.strip()}")
    h.check("400 flow NPCs arrive within the reference's 800 ticks" in steers.stdout,
            f"the reference run's arrivals are counted: {steers.stdout[-800:]}")
    measured = re.findall(r"arrival drift p99 +([0-9.]+) s mean +([0-9.]+) s \((\d+) arrived\)", steers.stdout)
    h.check(len(measured) == 2 and all(390 <= int(n) <= 400 for _, _, n in measured),
            f"the scene's own run and the other steering each measured a drift over their arrivals: {measured}")
    h.check(not list((tmp / "steers").glob("*.tuned.yaml")) and not (tmp / "steers" / "tune.json").exists(),
            "nothing is written for a refused crowd budget")

    out = tmp / "bands" / "courtyard.tuned.yaml"
    bands = tune(tmp / "bands", "arrival_drift_mean<=0.5", "--repeat", "1", "--out", out, scene=courtyard,
                 knobs="lod bands m", seconds=40)
    h.check(bands.returncode == 0 and out.exists(), f"a crowd budget the bands meet writes the overlay: "
            f"{bands.stdout[-800:]} {bands.stderr[-600:]}")
    report = json.loads((tmp / "bands" / "tune.json").read_text())
    h.check(len(report["runs"]) == 7, f"the reference, the scene's own, four more bands and the confirmation "
            f"({len(report['runs'])} runs)")
    confirmed = report["confirmed"]
    h.check(confirmed["arrival_drift_mean"] <= 0.5 and confirmed["arrivals_compared"] == 400 and
            confirmed["arrived"] == 400 and report["binding"] == "arrival_drift_mean <= 0.5 s",
            f"the confirming run met the crowd budget over every NPC: {confirmed}")
    near, far = (float(x) for x in report["chosen"]["lod bands m"].split("/"))
    text = out.read_text()
    h.check(f"near_radius: {near}" in text and f"far_radius: {far}" in text and "the zones alone" in text,
            f"the overlay sets the chosen bands: {text}")

    # The planner limit, on scenes/agents_navmesh.yaml's 60 couriers: the landmarks the loader
    # refuses with a navigation mesh make three runs fail, which are skipped, and an overhead
    # below the mesh's is refused naming the limit and the mesh's overhead.
    navmesh = h.SOURCE_DIR / "scenes" / "agents_navmesh.yaml"
    tight = tune(tmp / "tight", "path_overhead<=0.0001", "--repeat", "1", scene=navmesh, knobs="landmarks",
                 seconds=10)
    h.check(tight.returncode == 2, f"an impossible path budget exits 2 ({tight.returncode}): "
            f"{tight.stdout[-800:]} {tight.stderr[-600:]}")
    h.check(len(re.findall(r"landmarks = \d+ +failed, skipped: the zone run of", tight.stdout)) == 3 and
            "serve the grid, hpa and jps planners only" in tight.stdout,
            f"the three runs the loader refuses are reported and skipped: {tight.stdout[-1500:]}")
    refusal = re.search(r"refused: no setting meets path_overhead <= 0.0001: the best measured is (\S+)", tight.stderr)
    h.check(refusal is not None and float(refusal.group(1)) > 0.0001,
            f"the refusal names the planner limit and the best overhead: {tight.stderr.strip()}")
    nowhere = tune(tmp / "nowhere", "path_overhead<=0.01", scene=courtyard, knobs="lod on")
    h.check(nowhere.returncode == 2 and "path_overhead needs agents that plan paths on a map" in nowhere.stderr,
            f"a planner limit on a scene without planning agents is refused: {nowhere.stderr.strip()[-300:]}")

    # The device's float error, on scenes/crowd_flock.yaml's 3000 flockers (zones alone): the
    # flock on the device ends within a millimetre of the CPU's double run over 2 s, at more AI
    # time (PoCL on these cores): off, the reference itself, is chosen and written. A gpu limit
    # on a scene without flocks is refused before any run.
    flock = h.SOURCE_DIR / "scenes" / "crowd_flock.yaml"
    offload = tune(tmp / "gpu", "gpu_error<=0.001", "--repeat", "1", scene=flock, knobs="gpu", seconds=2)
    out = tmp / "gpu" / "crowd_flock.tuned.yaml"
    h.check(offload.returncode == 0 and out.exists(), f"a gpu budget writes the overlay: {offload.stdout[-800:]} "
            f"{offload.stderr[-400:]}")
    if out.exists():
        report = json.loads((tmp / "gpu" / "tune.json").read_text())
        errors = {r["label"]: r["figures"].get("gpu_error") for r in report["runs"] if "figures" in r}
        h.check(errors.get("gpu = off") == 0 and 0 < errors.get("gpu = on", 0) <= 0.001,
                f"off ends where the reference does, on within the millimetre: {errors}")
        h.check("mode: " in out.read_text() and report["confirmed"]["entities_compared"] == 3000,
                f"the overlay sets gpu.mode, confirmed over 3000 entities: {out.read_text()}")
    gpuless = tune(tmp / "gpuless", "gpu_error<=0.001", scene=courtyard, knobs="lod on")
    h.check(gpuless.returncode == 2 and "gpu_error needs a flocking population" in gpuless.stderr,
            f"a gpu limit on a scene without flocks is refused: {gpuless.stderr.strip()[-300:]}")
print("tune passed")
