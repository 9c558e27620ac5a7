"""The wire protocol outside C++: clients/python/zonesim_client.py (Python, the FlatBuffers
classes the build generates) logs in to a live gateway in front of 4 zone ranks, is welcomed,
sends inputs and decodes the states the gateway streams. What it decoded of its own avatar is
checked against the zones' recording of the truth at the same ticks: within the codec's
position resolution (half a step each axis), so every bit of the packing was read right.
Meanwhile the inspector attaches live (deploy/inspect.sh --live) to the zones' growing
recordings: it must follow them, and cap the entities it answers per tick.
Runs under Debian's python3 (python3-flatbuffers, python3-numpy)."""
import json
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import harness as h

sys.path.insert(0, str(h.SOURCE_DIR / "clients/python"))
sys.path.insert(0, str(h.SOURCE_DIR / "inspector"))
sys.path.insert(0, str(h.bin_dir().parent / "python"))
import zonesim_client  # noqa: E402
from run_data import RunData  # noqa: E402

SCENE = h.SOURCE_DIR / "scenes/test_e2e.yaml"
SECONDS = 6

with tempfile.TemporaryDirectory(prefix="zs_pyclient_") as tmp:
    out = Path(tmp)
    domain = h.free_dds_domain()
    env = h.base_env()
    zones = h.start(h.mpirun(4, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 600,
                             "--realtime", "--metrics", out, "--dds-domain", domain,
                             "--record", out / "record"), out / "zones.log", env)
    gateway = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--bind", "127.0.0.1", "--port", 0,
                       "--port-file", out / "port", "--dds-domain", domain, "--metrics", out],
                      out / "gateway.log", env)
    port = h.wait_for_port(out / "port", gateway, out / "gateway.log")
    time.sleep(2)
    c = zonesim_client.Client("127.0.0.1", int(port), name="pytest")
    h.check(c.connect(timeout=20), f"the Python client was welcomed (player {c.player_id}, avatar {c.avatar_id})")
    # (tick, x, z) of its own avatar as decoded: a walker at a steady pace is sent a new state
    # only when dead reckoning drifts past its threshold, a few a second.
    seen = []
    end = time.monotonic() + SECONDS
    while time.monotonic() < end:
        c.send_input(1.0, 0.0)  # walk along +x
        c.poll(time.monotonic() + 0.1)
        av = c.avatar()
        if av and (not seen or seen[-1][0] != av["tick"]):
            seen.append((av["tick"], av["pos"][0], av["pos"][2]))
    # The inspector attached live to the running zones: it follows the recordings as they
    # grow, at most one re-read a second, and answers at most --max-entities a tick.
    server_env = dict(env, ZONESIM_BUILD_DIR=str(h.bin_dir().parent))
    server = h.start(["bash", h.SOURCE_DIR / "deploy/inspect.sh", out, "--live", "--port", "0",
                      "--port-file", out / "inspect_port", "--max-entities", "40"],
                     out / "inspect.log", server_env)
    inspect_port = h.wait_for_port(out / "inspect_port", server, out / "inspect.log")
    base = f"http://127.0.0.1:{inspect_port}/api"
    first = json.load(urllib.request.urlopen(f"{base}/meta"))
    time.sleep(2.5)
    later = json.load(urllib.request.urlopen(f"{base}/meta"))
    capped = json.load(urllib.request.urlopen(f"{base}/tick?t={later['last_tick']}"))
    h.stop(server)
    h.check(later["live"] and later["last_tick"] > first["last_tick"],
            f"live: the inspector followed the growing recordings (tick {first['last_tick']} -> "
            f"{later['last_tick']})")
    h.check(len(capped["entities"]) == 40 and capped["truncated"],
            "live: at most --max-entities entities a tick answered")
    h.stop(gateway)
    h.stop(zones, grace=30)

    print(f"python client: {c.frames} frames, {c.records} states decoded, {len(c.entities)} entities "
          f"held, {c.dropped} dropped, {len(seen)} own states", flush=True)
    h.check(c.dropped == 0, "no datagram failed the client's checks")
    h.check(c.records > 100 and len(c.entities) > 10, "it decoded states of the world around it")
    h.check(all(e["kind"] <= 4 for e in c.entities.values()), "every decoded kind is one the zones have")
    h.check(len(seen) >= 3 and seen[-1][1] > seen[0][1] + 1,
            f"its avatar walked where its inputs sent it (x {seen[0][1]:.2f} -> {seen[-1][1]:.2f})")

    data = RunData(out)
    step = c.codec.px.resolution
    worst, compared = 0.0, 0
    for tick, x, z in seen:
        truth = data._truth(tick).get(c.avatar_id)
        if truth is None:
            continue
        compared += 1
        worst = max(worst, abs(x - truth[0]), abs(z - truth[1]))
    h.check(compared >= 3 and worst <= step / 2 + 1e-3,
            f"decoded against the zones' truth at the same tick: {compared} states, worst axis error "
            f"{worst * 1000:.2f} mm (half a step: {step * 500:.2f} mm)")
print("python client passed")
