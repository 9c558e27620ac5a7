"""Checkpoint and restart: a run interrupted at tick 150 and restarted from its checkpoint on a
different number of ranks ends bitwise equal to the uninterrupted run; a damaged or incomplete
checkpoint is refused with a message saying what is wrong."""
import shutil
import subprocess
import tempfile
from pathlib import Path

import harness as h

# NPCs only: rigid bodies restart without the engine's warm-start caches, so contact scenes
# continue close to, not bitwise equal to, the uninterrupted run.
SCENE = h.SOURCE_DIR / "scenes/test_npc_only.yaml"
ZONE = h.bin_dir() / "zone_node"


def zone_run(out, name, ranks, *args):
    h.run(h.mpirun(ranks, ZONE, "--scene", SCENE, "--no-dds", "--gpu", "off", *args),
          out / f"{name}.log", h.base_env(), timeout=300)


def restart_fails(out, ckpt, expect):
    p = subprocess.run([str(a) for a in h.mpirun(1, ZONE, "--scene", SCENE, "--no-dds", "--ticks", 300,
                                                   "--restart", ckpt)],
                       capture_output=True, text=True, env=h.base_env(), timeout=120)
    h.check(p.returncode != 0 and expect in (p.stdout + p.stderr),
            f"restart from a damaged checkpoint is refused: '{expect}'")


with tempfile.TemporaryDirectory(prefix="zs_ckpt_") as tmp:
    out = Path(tmp)
    zone_run(out, "straight", 4, "--ticks", 300, "--dump-state", out / "straight.jsonl")
    zone_run(out, "first_half", 4, "--ticks", 150, "--checkpoint-dir", out / "ckpt", "--checkpoint-every", 50)
    h.check((out / "ckpt/LATEST").read_text().strip() == "ckpt_150", "LATEST names the newest checkpoint")
    for ranks in (2, 4):
        zone_run(out, f"second_half_{ranks}", ranks, "--restart", out / "ckpt", "--ticks", 300,
                 "--dump-state", out / f"restarted_{ranks}.jsonl")
        h.check((out / f"restarted_{ranks}.jsonl").read_text() == (out / "straight.jsonl").read_text(),
                f"restarted on {ranks} ranks == uninterrupted run, bitwise")

    bad = out / "bad"
    shutil.copytree(out / "ckpt/ckpt_100", bad)
    (bad / "MANIFEST.json").unlink()
    restart_fails(out, bad, "no MANIFEST.json")
    shutil.rmtree(bad)
    shutil.copytree(out / "ckpt/ckpt_100", bad)
    rec = bad / "rank_1.rec"
    rec.write_bytes(rec.read_bytes()[:-7])
    restart_fails(out, bad, "size or hash differs")
print("checkpoint/restart passed")
