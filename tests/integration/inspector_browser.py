"""The web inspector in a real browser: a short recorded demo (deploy/demo.sh records by
default), inspector/server.py on it, and Debian's headless Chromium driven over its DevTools
protocol (tests/integration/cdp.py). The page must load with no console error; at a tick T it
must draw as many entities as the recording holds and the zone rectangles of the layout at T;
a click on a player's avatar must list exactly the visible set the gateway recorded for it;
and the scrubber must move the view to another tick. Screenshots go to $ZONESIM_TEST_OUT (or
build/test-output/inspector_browser/). Runs under Debian's python3 (python3-websockets,
python3-flatbuffers, python3-numpy)."""
import asyncio
import os
import sys
import tempfile
from pathlib import Path

import harness as h

sys.path.insert(0, str(h.SOURCE_DIR / "inspector"))
sys.path.insert(0, str(h.bin_dir().parent / "python"))
import cdp  # noqa: E402
from run_data import RunData  # noqa: E402

OUT = Path(os.environ.get("ZONESIM_TEST_OUT", h.bin_dir().parent / "test-output" / "inspector_browser"))


def visible_ids(data, player, t):
    return [v["id"] for v in data.player(player, t)["visible"]]


async def drive(url, data):
    meta = data.meta()
    span = meta["last_tick"] - meta["first_tick"]
    t1 = meta["first_tick"] + span * 2 // 3
    t2 = meta["first_tick"] + span // 3
    async with cdp.Browser() as b:
        page = await b.open(url)
        await page.wait_for("window.inspector && window.inspector.state.ready", timeout=60)
        print("page loaded", flush=True)

        async def scrub(t):
            # As a person would: the range input moved, its input event fired.
            await page.eval(f"(() => {{ const r = document.getElementById('tick'); r.value = {t};"
                            f" r.dispatchEvent(new Event('input')); }})()")
            want = data.tick(t)["tick"]
            await page.wait_for(f"window.inspector.state.tickData && "
                                f"window.inspector.state.tickData.tick === {want} && "
                                f"window.inspector.state.tick === {t}")
            return want

        shown = await scrub(t1)
        expected = data.tick(t1)
        owned = sum(not e["ghost"] for e in expected["entities"])
        drawn = await page.eval("window.inspector.state.drawnEntities")
        h.check(drawn == owned, f"tick {shown}: {drawn} entities drawn, the recording holds {owned}")
        zones = await page.eval("window.inspector.state.zones")
        want_zones = [{"rank": z["rank"], "min": z["min"], "max": z["max"]} for z in expected["zones"]]
        h.check(zones == want_zones, f"the {len(zones)} zone rectangles drawn are the layout at tick {shown}")
        await page.screenshot(OUT / "map.png")

        # A click on a player's avatar: the page takes the entity nearest the pointer, so
        # the avatar's own pixel selects it unless another entity sits almost on top of it.
        entities = [e for e in expected["entities"] if not e["ghost"]]
        scale = await page.eval("window.inspector.state.view.scale")  # pixels per metre
        clicked = None
        for p in meta["players"]:
            avatar = next((e for e in entities if e["id"] == p["avatar"]), None)
            if avatar is None or any(e is not avatar and (e["x"] - avatar["x"]) ** 2 + (e["z"] - avatar["z"]) ** 2
                                     < (4 / scale) ** 2 for e in entities):
                continue
            # worldToScreen is the map canvas's own pixels; the mouse event wants the page's.
            x, y = await page.eval(
                f"(() => {{ const r = document.getElementById('map').getBoundingClientRect();"
                f" const [x, y] = window.inspector.worldToScreen({avatar['x']}, {avatar['z']});"
                f" return [x + r.left, y + r.top]; }})()")
            await page.click(x, y)
            clicked = p["id"]
            break
        h.check(clicked is not None, "some player's avatar stood clear enough to click")
        await page.wait_for(f"window.inspector.state.selectedPlayer === '{clicked}' && "
                            f"window.inspector.state.playerData")
        listed = await page.eval("Array.from(document.querySelectorAll('#selection tr[data-entity-id]'))"
                                 ".map(tr => tr.dataset.entityId)")
        recorded = visible_ids(data, clicked, shown)
        h.check(listed == recorded, f"player {clicked}: the page lists exactly the {len(recorded)} entities "
                                    f"the gateway recorded in its view ({len(listed)} listed)")
        await page.screenshot(OUT / "player.png")

        shown2 = await scrub(t2)
        drawn2 = await page.eval("window.inspector.state.drawnEntities")
        label = await page.eval("document.getElementById('tick-label').textContent")
        owned2 = sum(not e["ghost"] for e in data.tick(t2)["entities"])
        h.check(shown2 != shown and f"tick {shown2}" in label and drawn2 == owned2,
                f"the scrubber moved the view from tick {shown} to {shown2} ({drawn2} entities drawn)")
        listed2 = await page.eval("Array.from(document.querySelectorAll('#selection tr[data-entity-id]'))"
                                  ".map(tr => tr.dataset.entityId)")
        h.check(listed2 == visible_ids(data, clicked, shown2), "the player's view followed the scrubber")
        await page.screenshot(OUT / "scrubbed.png")
        await asyncio.sleep(0.5)
        h.check(not page.errors, f"no console error or exception ({page.errors[:3]})")


OUT.mkdir(parents=True, exist_ok=True)
with tempfile.TemporaryDirectory(prefix="zs_inspect_") as tmp:
    run = Path(tmp) / "run"
    env = h.base_env(h.free_dds_domain())
    env.update(ZONESIM_BIN=str(h.bin_dir()), ZONESIM_DEMO_SECONDS="8", ZONESIM_DEMO_PLAYERS="6",
               ZONESIM_DEMO_RECORD="yes", ZONESIM_DEMO_SCENE=str(h.SOURCE_DIR / "scenes/test_e2e.yaml"))
    print("recording a short demo ...", flush=True)
    h.run(["bash", h.SOURCE_DIR / "deploy/demo.sh", run], Path(tmp) / "demo.log", env, timeout=300)
    data = RunData(run)
    server_env = dict(env, ZONESIM_BUILD_DIR=str(h.bin_dir().parent))
    server = h.start(["bash", h.SOURCE_DIR / "deploy/inspect.sh", run, "--port", "0",
                      "--port-file", Path(tmp) / "port"], Path(tmp) / "server.log", server_env)
    port = h.wait_for_port(Path(tmp) / "port", server, Path(tmp) / "server.log")
    asyncio.run(drive(f"http://127.0.0.1:{port}/", data))
    h.stop(server)
for shot in sorted(OUT.glob("*.png")):
    print(f"screenshot: {shot}")
print("inspector browser test passed")
