"""--gpu probe and auto: rank 0 alone times the kernels at start and broadcasts the thresholds,
so every rank takes the same backend (a rank on float and another on double would integrate the
same scene differently).

- probe on scenes/test_small.yaml (particles): both workloads timed, one particle backend.
- auto on scenes/flock_large.yaml (a 20,000-agent flock): only the flock is timed, and both
  ranks put it on the backend the broadcast threshold gives for 20,000 agents.
- auto on scenes/test_small.yaml (no flock): nothing is timed (particles keep their default).
- no --gpu: the scene's gpu.mode decides (overlays of flock_large setting off and on)."""
import json
import re
import tempfile
from pathlib import Path

import harness as h

PROBE_LINE = re.compile(r"offload probe on rank 0: particles (never|from \d+), zone flocks (never|from \d+)")
FLOCK_LINE = re.compile(r"offload probe on rank 0: zone flocks (never|from (\d+)) \(particles not probed")


def run(out, scene, mode, ticks, path=None):
    log = out / f"{scene}_{mode}.log"
    metrics = out / f"{scene}_{mode}"
    gpu = ["--gpu", mode] if mode != "scene" else []
    h.run(h.mpirun(2, h.bin_dir() / "zone_node", "--scene", path or h.SOURCE_DIR / f"scenes/{scene}.yaml",
                   "--ticks", ticks, "--no-dds", *gpu, "--metrics", metrics),
          log, h.base_env(), timeout=300)
    summaries = [json.loads(p.read_text()) for p in sorted(metrics.glob("zone_*_summary.json"))]
    h.check(len(summaries) == 2, f"{scene} --gpu {mode}: both ranks wrote a summary ({len(summaries)})")
    return log.read_text(), summaries


with tempfile.TemporaryDirectory(prefix="zs_probe_") as tmp:
    out = Path(tmp)
    text, summaries = run(out, "test_small", "probe", 30)
    # One probe, on rank 0, that measured both thresholds: a run that never probed (no OpenCL,
    # or the probe skipped) or whose probe failed proves nothing about the agreement.
    probes = PROBE_LINE.findall(text)
    failed = text.count("offload probe failed")
    backends = {s["particle_backend"] for s in summaries}
    h.check(len(probes) == 1 and failed == 0,
            f"probe: rank 0 alone probed and got thresholds ({len(probes)} probe lines, {failed} failed): {probes}")
    h.check(len(backends) == 1, f"probe: every rank took the same particle backend: {sorted(backends)}")

    text, summaries = run(out, "flock_large", "auto", 3)
    probes = FLOCK_LINE.findall(text)
    failed = text.count("offload probe failed")
    h.check(len(probes) == 1 and failed == 0 and not PROBE_LINE.search(text),
            f"auto: rank 0 alone probed the flock only ({len(probes)} flock probe lines, {failed} failed)")
    if probes:
        threshold = int(probes[0][1]) if probes[0][1] else None
        want = "opencl" if threshold is not None and 20000 >= threshold else "cpu"
        backends = {s["flock_backend"] for s in summaries}
        print(f"auto: zone flocks {probes[0][0]}; the 20,000-agent flock on {sorted(backends)}")
        h.check(backends == {want}, f"auto: both ranks put the flock on {want}: {sorted(backends)}")

    text, _ = run(out, "test_small", "auto", 5)
    h.check("offload probe" not in text, "auto with no flock times nothing")

    for mode, want in (("off", "cpu"), ("on", "opencl")):
        overlay = out / f"flock_large_{mode}.yaml"
        overlay.write_text(f"overlay_of: {h.SOURCE_DIR / 'scenes/flock_large.yaml'}\ngpu: {{mode: {mode}}}\n")
        text, summaries = run(out, f"flock_large_{mode}", "scene", 2, overlay)
        backends = {s["flock_backend"] for s in summaries}
        h.check(backends == {want} and "offload probe" not in text,
                f"gpu.mode {mode} in the scene, no --gpu: the flock on {want} ({sorted(backends)}), nothing probed")
print("gpu probe agreement passed")
