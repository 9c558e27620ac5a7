"""--gpu probe: rank 0 alone times the kernels at start and broadcasts the thresholds, so every
rank takes the same particle backend (a rank on float and another on double would integrate
the same scene differently)."""
import json
import re
import tempfile
from pathlib import Path

import harness as h

with tempfile.TemporaryDirectory(prefix="zs_probe_") as tmp:
    out = Path(tmp)
    log = out / "run.log"
    h.run(h.mpirun(2, h.bin_dir() / "zone_node", "--scene", h.SOURCE_DIR / "scenes/test_small.yaml",
                   "--ticks", 30, "--no-dds", "--gpu", "probe", "--metrics", out / "m"),
          log, h.base_env(), timeout=300)
    text = log.read_text()
    # One probe, on rank 0, that measured both thresholds: a run that never probed (no OpenCL,
    # or the probe skipped) or whose probe failed proves nothing about the agreement.
    probes = re.findall(r"offload probe on rank 0: particles (never|from \d+), zone flocks (never|from \d+)", text)
    failed = text.count("offload probe failed")
    summaries = sorted((out / "m").glob("zone_*_summary.json"))
    backends = {json.loads(p.read_text())["particle_backend"] for p in summaries}
    h.check(len(probes) == 1 and failed == 0,
            f"rank 0 alone probed and got thresholds ({len(probes)} probe lines, {failed} failed): {probes}")
    h.check(len(summaries) == 2, f"both ranks wrote a summary ({len(summaries)})")
    h.check(len(backends) == 1, f"every rank took the same particle backend: {sorted(backends)}")
print("gpu probe agreement passed")
