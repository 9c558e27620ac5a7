"""bake_fields end to end: it writes the flow fields of scenes/courtyard_flow.yaml to a file,
an overlay of the scene that names the file as map.fields runs to the same final state, bit for
bit, on 1 and 2 ranks as the scene whose zones build the fields at start, and a scene without
flow destinations or without a map is refused with a message that says so."""
import subprocess
import tempfile
from pathlib import Path

import harness as h

TICKS = 300
SCENE = h.SOURCE_DIR / "scenes/courtyard_flow.yaml"

with tempfile.TemporaryDirectory(prefix="zs_bake_") as tmp:
    out = Path(tmp)
    fields = out / "courtyard.fields"
    baked = subprocess.run([str(h.bin_dir() / "bake_fields"), str(SCENE), "--out", str(fields)],
                           capture_output=True, text=True, timeout=120)
    h.check(baked.returncode == 0 and fields.exists(), f"bake_fields wrote {fields}: {baked.stdout}"
            f"{baked.stderr}")
    # An overlay of the scene names the fields file (beside the overlay: a relative path).
    loaded = out / "courtyard_loaded.yaml"
    loaded.write_text(f"overlay_of: {SCENE}\nmap:\n  fields: {fields.name}\n")
    for ranks in (1, 2):
        dumps = []
        for scene in (SCENE, loaded):
            dump = out / f"{scene.stem}_{ranks}.jsonl"
            h.run(h.mpirun(ranks, h.bin_dir() / "zone_node", "--scene", scene, "--ticks", TICKS,
                           "--no-dds", "--dump-state", dump),
                  out / f"{scene.stem}_{ranks}.log", h.base_env(), timeout=300)
            dumps.append(dump.read_text())
        h.check(dumps[0] == dumps[1] and dumps[0].count("\n") == 400,
                f"{ranks} ranks: the crowd on baked fields ends bit for bit where it ends on "
                "fields built at start")
    no_flow = subprocess.run([str(h.bin_dir() / "bake_fields"),
                              str(h.SOURCE_DIR / "scenes/agents_paths.yaml"), "--out",
                              str(out / "none.fields")], capture_output=True, text=True)
    h.check(no_flow.returncode == 2 and "no flow destinations" in no_flow.stderr,
            f"a scene without flow destinations is refused: {no_flow.stderr.strip()}")
    no_map = subprocess.run([str(h.bin_dir() / "bake_fields"), str(h.SOURCE_DIR / "scenes/demo.yaml"),
                             "--out", str(out / "none.fields")], capture_output=True, text=True)
    h.check(no_map.returncode == 2 and "has no map" in no_map.stderr,
            f"a scene without a map is refused: {no_map.stderr.strip()}")
print("bake_fields passed")
