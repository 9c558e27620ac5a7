"""Scenes end in the same state, bit for bit, on 1, 2 and 4 ranks: entity ids, initial states
and per-entity random streams do not depend on the decomposition, migration carries state
exactly, and (scenes/crowd.yaml) walkers that keep apart read their neighbours across zone
borders from ghosts that are bitwise the owners' state."""
import json
import tempfile
from pathlib import Path

import harness as h

SCENES = {"test_npc_only": 300, "crowd": 300}

with tempfile.TemporaryDirectory(prefix="zs_decomp_") as tmp:
    out = Path(tmp)
    for scene, ticks in SCENES.items():
        dumps = {}
        ghosts_sent = {}
        for ranks in (1, 2, 4):
            dump = out / f"{scene}_{ranks}.jsonl"
            metrics = out / f"{scene}_{ranks}_metrics"
            h.run(h.mpirun(ranks, h.bin_dir() / "zone_node", "--scene",
                           h.SOURCE_DIR / f"scenes/{scene}.yaml", "--ticks", ticks, "--no-dds",
                           "--dump-state", dump, "--metrics", metrics),
                  out / f"{scene}_{ranks}.log", h.base_env(), timeout=300)
            dumps[ranks] = dump.read_text()
            ghosts_sent[ranks] = sum(json.loads(p.read_text()).get("ghosts_sent", 0)
                                     for p in metrics.glob("zone_*_summary.json"))
        lines = dumps[1].count("\n")
        h.check(lines > 0, f"{scene}: the dump lists {lines} entities")
        h.check(dumps[1] == dumps[2], f"{scene}: 2 ranks end bitwise equal to 1 rank")
        h.check(dumps[1] == dumps[4], f"{scene}: 4 ranks end bitwise equal to 1 rank")
        if scene == "crowd":
            h.check(ghosts_sent[2] > 0 and ghosts_sent[4] > 0,
                    f"{scene}: ghosts were exchanged ({ghosts_sent[2]} copies on 2 ranks, "
                    f"{ghosts_sent[4]} on 4)")
print("decomposition invariance passed")
