"""--gpu on steps the 20,000-agent flock of scenes/flock_large.yaml on the OpenCL device
(gpu/planar_flock.h, PoCL here), ghosts included, on 2 ranks; every rank reports the backend in
its summary, and the run stays close to --gpu off (the crowd library's double flock) over 10
ticks. Bounds: one step differs by at most 3e-2 m/s per agent and typically 1e-6 m/s
(tests/zone_node/test_flock_backend.cpp); a flock amplifies differences, so the horizon is short:
after 10 ticks (0.5 s) positions within 1e-4 m at p99 and 2e-2 m at most, velocities within
1e-3 m/s at p99 and 1e-1 m/s at most (measured: docs/gpu.md)."""
import json
import math
import tempfile
from pathlib import Path

import harness as h

TICKS = 10
with tempfile.TemporaryDirectory(prefix="zs_gpu_flock_") as tmp:
    out = Path(tmp)
    states = {}
    for mode in ("off", "on"):
        dump = out / f"{mode}.jsonl"
        metrics = out / f"{mode}_metrics"
        h.run(h.mpirun(2, h.bin_dir() / "zone_node", "--scene",
                       h.SOURCE_DIR / "scenes/flock_large.yaml", "--ticks", TICKS, "--no-dds",
                       "--gpu", mode, "--dump-state", dump, "--metrics", metrics),
              out / f"{mode}.log", h.base_env(), timeout=300)
        summaries = [json.loads(p.read_text()) for p in metrics.glob("zone_*_summary.json")]
        backends = {s["flock_backend"] for s in summaries}
        want = "opencl" if mode == "on" else "cpu"
        h.check(len(summaries) == 2 and backends == {want},
                f"--gpu {mode}: both ranks report flock_backend {want}: {sorted(backends)}")
        h.check(all(s["ticks"] == TICKS for s in summaries), f"--gpu {mode}: {TICKS} ticks ran")
        h.check(sum(s["ghosts"] for s in summaries) > 0, f"--gpu {mode}: ranks saw ghosts")
        states[mode] = {r["id"]: r for r in map(json.loads, dump.read_text().splitlines())}
    h.check(len(states["off"]) == 20000 and states["off"].keys() == states["on"].keys(),
            f"the same {len(states['off'])} agents on both backends")

    def errors(field):
        return sorted(math.hypot(states["on"][i][field][0] - states["off"][i][field][0],
                                 states["on"][i][field][2] - states["off"][i][field][2])
                      for i in states["off"])

    for field, p99_bound, max_bound, unit in (("pos", 1e-4, 2e-2, "m"), ("vel", 1e-3, 1e-1, "m/s")):
        e = errors(field)
        p50, p99, top = e[len(e) // 2], e[int(0.99 * (len(e) - 1))], e[-1]
        print(f"{field}: on vs off after {TICKS} ticks: median {p50:.2e}, p99 {p99:.2e}, "
              f"max {top:.2e} {unit}")
        h.check(p99 < p99_bound and top < max_bound,
                f"{field} p99 {p99:.2e} < {p99_bound:g} and max {top:.2e} < {max_bound:g} {unit}")
print("gpu flock passed")
