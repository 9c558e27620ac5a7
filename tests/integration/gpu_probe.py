"""--gpu probe: rank 0 alone times the kernels at start and broadcasts the thresholds, so every
rank takes the same particle backend (a rank on float and another on double would integrate
the same scene differently)."""
import json
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
    probes = text.count("offload probe on rank 0") + text.count("offload probe failed")
    backends = {json.loads(p.read_text())["particle_backend"] for p in (out / "m").glob("zone_*_summary.json")}
    h.check(probes <= 1, f"at most one rank probed ({probes} probe lines)")
    h.check(len(backends) == 1, f"every rank took the same particle backend: {sorted(backends)}")
print("gpu probe agreement passed")
