"""Moving boundaries: on the hotspot scene the zones move their boundaries until the crowd is
shared out, nothing is lost while entities follow the boundaries, and the final state equals a
single-rank run bit for bit (boundaries change who computes an entity, never what)."""
import tempfile
from pathlib import Path

import harness as h

SCENE = h.SOURCE_DIR / "scenes/hotspot.yaml"
ZONE = h.bin_dir() / "zone_node"

with tempfile.TemporaryDirectory(prefix="zs_balance_") as tmp:
    out = Path(tmp)
    common = ["--scene", SCENE, "--ticks", 300, "--no-dds", "--check-every", 1]
    h.run(h.mpirun(4, ZONE, *common, "--balance-every", 20, "--metrics", out,
                   "--dump-state", out / "balanced.jsonl"), out / "balanced.log", h.base_env(), timeout=300)
    h.run(h.mpirun(1, ZONE, *common, "--dump-state", out / "single.jsonl"), out / "single.log",
          h.base_env(), timeout=300)
    zones = [h.load_json(out / f"zone_{r}_summary.json") for r in range(4)]
    start = max(z["entities_start"] for z in zones)
    end = max(z["entities_end"] for z in zones)
    h.check(sum(z["rebalances"] for z in zones) > 0, "boundaries moved")
    h.check(end < 0.6 * start, f"the busiest zone's share fell from {start} to {end} entities")
    h.check(all(z["conservation_failures"] == 0 for z in zones), "nothing lost while boundaries moved")
    h.check((out / "balanced.jsonl").read_text() == (out / "single.jsonl").read_text(),
            "4 balanced ranks end bitwise equal to 1 rank")
print("load balancing passed")
