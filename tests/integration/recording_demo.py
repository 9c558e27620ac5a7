"""The recorder end to end on a short demo (deploy/demo.sh records into RUN/record/ by
default): every zone rank and the gateway wrote a finished recording that both readers accept;
the zones' frames agree with their summaries; the gateway's per-field bandwidth attribution
adds up to the bytes it counted on its socket within 1%, with no frame its bit accounting could
not explain; handoffs carry their timeline; and a damaged or cut copy is refused with the
offset and the reason. Runs under Debian's python3 (python3-flatbuffers, python3-numpy)."""
import shutil
import sys
import tempfile
from pathlib import Path

import harness as h

sys.path.insert(0, str(h.SOURCE_DIR / "inspector"))
sys.path.insert(0, str(h.bin_dir().parent / "python"))
from recording import Recording, RecordingError  # noqa: E402
from run_data import RunData  # noqa: E402

PLAYERS = 6
SECONDS = 8

with tempfile.TemporaryDirectory(prefix="zs_rec_") as tmp:
    run = Path(tmp) / "run"
    env = h.base_env(h.free_dds_domain())
    env.update(ZONESIM_BIN=str(h.bin_dir()), ZONESIM_DEMO_SECONDS=str(SECONDS),
               ZONESIM_DEMO_PLAYERS=str(PLAYERS), ZONESIM_DEMO_RECORD="yes",
               ZONESIM_DEMO_SCENE=str(h.SOURCE_DIR / "scenes/test_e2e.yaml"))
    print("running a recorded demo ...", flush=True)
    h.run(["bash", h.SOURCE_DIR / "deploy/demo.sh", run], Path(tmp) / "demo.log", env, timeout=300)

    data = RunData(run)
    h.check(sorted(data.zones) == [0, 1, 2, 3] and sorted(data.gateways) == [1],
            f"4 zone recordings and one gateway's ({sorted(data.zones)}, {sorted(data.gateways)})")
    h.check(all(r.finished for r in list(data.zones.values()) + list(data.gateways.values())),
            "every recording is finished (index and footer)")
    for rank, rec in sorted(data.zones.items()):
        s = h.load_json(run / f"zone_{rank}_summary.json")
        last = rec.zone_tick(len(rec) - 1)
        h.check(len(rec) == s["ticks"] and last["entity_count"] == s["entities_end"],
                f"zone {rank}: {len(rec)} frames for {s['ticks']} ticks, {last['entity_count']} "
                f"entities at the end as its summary says ({s['entities_end']})")
        owned = last["entities"][(last["entities"]["flags"] & 2) == 0]
        h.check(len(owned) == last["entity_count"], f"zone {rank}: every owned entity recorded")

    gw = data.gateways[1]
    socket = attributed = 0
    for i in range(len(gw)):
        for p in gw.gateway_tick(i)["players"]:
            socket += p["socket_bytes"]
            attributed += int(p["field_bytes"].sum())
    summary = h.load_json(run / "gateway_summary.json")
    print(f"gateway: {len(gw)} frames, {socket} bytes to players counted on the socket, "
          f"{attributed} attributed by field ({attributed / max(socket, 1):.4%})", flush=True)
    h.check(socket > 10000 and abs(attributed - socket) <= 0.01 * socket,
            "the per-field attribution adds up to the socket's bytes within 1%")
    h.check(summary.get("record_frames_mismatched") == 0,
            f"no frame the attribution could not account for ({summary.get('record_frames_mismatched')})")

    meta = data.meta()
    h.check(len(meta["players"]) == PLAYERS, f"{PLAYERS} players recorded ({len(meta['players'])})")
    t = meta["last_tick"] - 30
    for p in meta["players"]:
        view = data.player(p["id"], t)
        ids = {v["id"] for v in view["visible"]}
        h.check(view["avatar"] in ids, f"player {p['id']} sees its own avatar at tick {view['tick']}")
    errors = [v["error_m"] for p in meta["players"] for v in data.player(p["id"], t)["visible"]
              if v["error_m"] is not None]
    errors.sort()
    h.check(errors and errors[len(errors) // 2] < 1.0,
            f"shown against truth: {len(errors)} entities, median error {errors[len(errors) // 2]:.3f} m")
    handoffs = [ho for p in meta["players"] for ho in data.entity(p["avatar"])["handoffs"]
                if ho["first_input_tick"] is not None]
    h.check(handoffs and all(ho["crossing_tick"] <= ho["ownership_tick"] <= ho["first_input_tick"]
                             for ho in handoffs),
            f"avatar handoffs with their timeline (crossing, ownership, first input): {len(handoffs)}")

    # Damage: a flipped byte inside the 10th frame, a file cut short, one not ours.
    original = run / "record" / "zone_0.zsrec"
    raw = bytearray(original.read_bytes())
    at = 8
    for _ in range(10):
        at += 8 + int.from_bytes(raw[at:at + 4], "little")
    raw[at + 8 + 40] ^= 0x04
    damaged = Path(tmp) / "damaged.zsrec"
    damaged.write_bytes(raw)
    for path, want in ((damaged, f"offset {at}: chunk CRC mismatch"),):
        try:
            Recording(path)
            h.fail(f"{path.name} was read")
        except RecordingError as e:
            h.check(want in str(e), f"damaged copy refused: {e}")
    cut = Path(tmp) / "cut.zsrec"
    cut.write_bytes(original.read_bytes()[:len(raw) // 2])
    try:
        Recording(cut)
        h.fail("a cut copy was read")
    except RecordingError as e:
        h.check("truncated" in str(e) or "no Index" in str(e), f"cut copy refused: {e}")
    h.check(len(Recording(cut, unfinished_ok=True)) > 0, "a cut copy reads to its last complete frame when asked")
    shutil.copy(h.SOURCE_DIR / "README.md", Path(tmp) / "readme.zsrec")
    try:
        Recording(Path(tmp) / "readme.zsrec")
        h.fail("a text file was read as a recording")
    except RecordingError as e:
        h.check("offset 0: not a zonesim recording" in str(e), f"another file refused: {e}")
print("recording demo passed")
