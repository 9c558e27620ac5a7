"""mpirun -np 4 zone_node on a small scene: migrations happen, and the global entity count
and id hash are conserved at every tick (checked by the zones themselves each tick)."""
import sys
import tempfile
from pathlib import Path

import harness as h

ranks = int(sys.argv[1]) if len(sys.argv) > 1 else 4
with tempfile.TemporaryDirectory(prefix="zs_cluster_") as tmp:
    out = Path(tmp)
    h.run(h.mpirun(ranks, h.bin_dir() / "zone_node", "--scene", h.SOURCE_DIR / "scenes/test_small.yaml",
                   "--ticks", 600, "--no-dds", "--check-every", 1, "--gpu", "off", "--metrics", out),
          out / "zones.log", h.base_env(), timeout=300)
    zones = [h.load_json(out / f"zone_{r}_summary.json") for r in range(ranks)]
    start = sum(z["entities_start"] for z in zones)
    end = sum(z["entities_end"] for z in zones)
    out_total = sum(z["migrated_out"] for z in zones)
    in_total = sum(z["migrated_in"] for z in zones)
    h.check(all(z["ticks"] == 600 for z in zones), "every zone ran 600 ticks")
    h.check(all(z["conservation_checks"] == 600 for z in zones), "conservation checked every tick")
    h.check(all(z["conservation_failures"] == 0 for z in zones), "count and id hash conserved every tick")
    h.check(start == end, f"entities at start ({start}) == at end ({end})")
    if ranks > 1:
        h.check(out_total > 0, f"migrations happened ({out_total})")
    h.check(out_total == in_total, f"every migration sent was received once ({out_total} out, {in_total} in)")
print("cluster conservation passed")
