"""The three topologies of docs/networking.md ("Topologies") on scenes/duel_arena_16.yaml, run
as real processes on this machine over loopback UDP, and the figures taken from what they wrote.
tests/integration/topologies.py asserts what each detects of cheating players;
bench/net/topology_bench.py measures them.

- client-server: zone_node (one zone) + gateway + client_stub players, and four Python clients
  (clients/python/zonesim_client.py) that follow the topology nodes' kind of script, log their
  inputs and the velocity changes they see of each other: the input-to-effect latency (with a
  link profile, through link_relay, which gives them client_stub's link model);
  client_stub --truth-every 1 logs where every player showed every avatar each server tick:
  the consistency between views. A Python cheater sends what a client can fake: an input over
  full speed, a forged state frame.
- client-hosted: discovery + topology_node --role host (player 0) and --role client.
- peer to peer: discovery + topology_node --role peer.
"""
import csv
import json
import math
import random
import secrets
import socket
import sys
import threading
import time
from collections import defaultdict
from pathlib import Path

import harness as h

SCENE = h.SOURCE_DIR / "scenes/duel_arena_16.yaml"
PLAYERS = 16
# Seconds between the launch and tick 0: every node must have joined through discovery by then.
START_DELAY_S = 4.0
# A velocity change this large is "seen" (topologies/topology_node.cpp, kSeenVelocityChange).
SEEN_VELOCITY_CHANGE = 0.25
# Client-server: Python players that time inputs to their effect at each other (each input is
# seen by the other three), beside client_stub's players.
SCRIPTED_PYTHON_PLAYERS = 4
# The scene's arena, speed, retarget period and tick (scenes/duel_arena_16.yaml).
ARENA, WALL_MARGIN, RETARGET_S, TICK_S = 40.0, 2.0, 1.0, 0.05
# How much of a tick each Python player's retarget drifts (ScriptedClient).
PHASE_STEP = (math.sqrt(5) - 1) / 2


def percentile(values, p):
    if not values:
        return float("nan")
    s = sorted(values)
    k = (len(s) - 1) * p / 100.0
    lo, hi = math.floor(k), math.ceil(k)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


# ---- client-hosted and peer to peer ----

def run_nodes(out, topology, seconds, cheats=None, cross_check=(), players=PLAYERS, link=None,
              cheat_seconds=None):
    """topology 'client_hosted' (player 0 hosts) or 'p2p'. cheats: {player: 'teleport'|'speed'|
    'hit', or a peer's 'vote'|'equivocate', or several joined by commas}; cheat_seconds:
    {player: seconds it cheats before playing honestly}; cross_check: clients that judge their
    host; link: every player's access link both ways (a wire/link_profile.h preset). Returns
    the nodes' summaries by player."""
    out.mkdir(parents=True, exist_ok=True)
    env = h.base_env()
    disc = h.start([h.bin_dir() / "discovery", "--bind", "127.0.0.1", "--port", 0,
                    "--port-file", out / "discovery_port", "--duration", seconds + 120],
                   out / "discovery.log", env)
    port = h.wait_for_port(out / "discovery_port", disc, out / "discovery.log")
    token = secrets.token_hex(8)
    start_at = time.time() + START_DELAY_S
    nodes = []
    for p in range(players):
        role = ("host" if p == 0 else "client") if topology == "client_hosted" else "peer"
        cmd = [h.bin_dir() / "topology_node", "--role", role, "--player", p, "--players", players,
               "--scene", SCENE, "--discovery", f"127.0.0.1:{port}", "--token", token,
               "--start-at", f"{start_at:.6f}", "--duration", seconds, "--out", out,
               "--cheat", (cheats or {}).get(p, "none")]
        if p in cross_check:
            cmd.append("--cross-check")
        if p in (cheat_seconds or {}):
            cmd += ["--cheat-seconds", cheat_seconds[p]]
        if link:
            cmd += ["--link", link]
        nodes.append(h.start(cmd, out / f"node_{p}.log", env))
    for p, proc in enumerate(nodes):
        try:
            rc = proc.wait(timeout=seconds + START_DELAY_S + 60)
        except Exception:
            h.fail(f"topology_node {p} did not finish\n{h.tail(out / f'node_{p}.log')}")
        h.check(rc == 0, f"topology_node {p} ({topology}) exited 0" +
                ("" if rc == 0 else "\n" + h.tail(out / f"node_{p}.log")))
    h.stop(disc)
    return {p: h.load_json(out / f"node_{p}.json") for p in range(players)}


def node_views(out):
    """{(tick, player): {observer: (x, z)}} from every node's views file."""
    views = defaultdict(dict)
    for f in sorted(out.glob("views_*.csv")):
        with open(f) as fh:
            for r in csv.DictReader(fh):
                views[(int(r["tick"]), int(r["player"]))][int(r["observer"])] = (float(r["x"]), float(r["z"]))
    return views


def node_events(out):
    """Input events {player: [(t_s, dx, dz)]} and seen events {(observer, player): [(t_s, vx, vz)]}."""
    inputs, seen = defaultdict(list), defaultdict(list)
    for f in sorted(out.glob("events_*.csv")):
        with open(f) as fh:
            for r in csv.DictReader(fh):
                e = (int(r["t_ns"]) * 1e-9, float(r["vx"]), float(r["vz"]))
                if r["event"] == "input":
                    inputs[int(r["player"])].append(e)
                else:
                    seen[(int(r["observer"]), int(r["player"]))].append(e)
    return inputs, seen


# ---- figures shared by every topology ----

def consistency(views, truth_holder):
    """Distances between where two observers show the same player at the same tick, over all
    pairs of observers but the one that holds the player's truth (truth_holder(player): the
    peer itself, the host; None: none among the observers). Returns (p50, p99, pairs)."""
    d = []
    for (tick, player), by_observer in views.items():
        holder = truth_holder(player)
        pts = [xz for o, xz in by_observer.items() if o != holder]
        for i in range(len(pts)):
            for j in range(i + 1, len(pts)):
                d.append(math.dist(pts[i], pts[j]))
    return percentile(d, 50), percentile(d, 99), len(d)


def truth_error(views, truth):
    """Distances between where each observer shows a player and where it truly was at that tick
    (truth: {(tick, player): (x, z)}). Returns (p50, p99, samples)."""
    d = [math.dist(xz, truth[key]) for key, by_observer in views.items() if key in truth
         for xz in by_observer.values()]
    return percentile(d, 50), percentile(d, 99), len(d)


def latency(inputs, seen, min_turn_deg=20.0):
    """From each input that turned its player by more than min_turn_deg to the first velocity
    change of that player each other player saw after it (and before the next input). Returns
    (p50 ms, p99 ms, matched, unmatched)."""
    lat, unmatched = [], 0
    for player, evs in inputs.items():
        evs = sorted(evs)
        for k in range(1, len(evs)):
            t0, dx, dz = evs[k]
            pdx, pdz = evs[k - 1][1], evs[k - 1][2]
            cos = (dx * pdx + dz * pdz) / max(1e-9, math.hypot(dx, dz) * math.hypot(pdx, pdz))
            if cos > math.cos(math.radians(min_turn_deg)):
                continue
            t_next = evs[k + 1][0] if k + 1 < len(evs) else float("inf")
            for (obs, p), s in seen.items():
                if p != player or obs == player:
                    continue
                first = next((t for t, _, _ in s if t0 < t < t_next), None)
                if first is None:
                    unmatched += 1
                else:
                    lat.append((first - t0) * 1e3)
    return percentile(lat, 50), percentile(lat, 99), len(lat), unmatched


def node_figures(out, summaries, seconds):
    """The table's row for a client-hosted or peer-to-peer run."""
    inputs, seen = node_events(out)
    l50, l99, matched, unmatched = latency(inputs, seen)
    views = node_views(out)
    hosted = any(s["role"] == "host" for s in summaries.values())
    holder = (lambda player: 0) if hosted else (lambda player: player)
    c50, c99, pairs = consistency(views, holder)
    # The truth: the host's world, or each peer's own avatar.
    truth = {key: obs[holder(key[1])] for key, obs in views.items() if holder(key[1]) in obs}
    others = {key: {o: xz for o, xz in obs.items() if o != holder(key[1])} for key, obs in views.items()}
    e50, e99, _ = truth_error(others, truth)
    players = [s for p, s in summaries.items()]
    row = {
        "up_bytes_per_s": sum(s["bytes_out_per_s"] for s in players) / len(players),
        "down_bytes_per_s": sum(s["bytes_in_per_s"] for s in players) / len(players),
        "latency_ms_p50": l50, "latency_ms_p99": l99, "latency_samples": matched,
        "latency_unmatched": unmatched,
        "consistency_m_p50": c50, "consistency_m_p99": c99, "consistency_pairs": pairs,
        "truth_error_m_p50": e50, "truth_error_m_p99": e99,
        "seconds": seconds,
    }
    host = [s for s in players if s["role"] == "host"]
    if host:
        others = [s for s in players if s["role"] != "host"]
        row["host_up_bytes_per_s"] = host[0]["bytes_out_per_s"]
        row["host_down_bytes_per_s"] = host[0]["bytes_in_per_s"]
        row["client_up_bytes_per_s"] = sum(s["bytes_out_per_s"] for s in others) / len(others)
        row["client_down_bytes_per_s"] = sum(s["bytes_in_per_s"] for s in others) / len(others)
    return row


def detections(summaries):
    """{judge: {suspect: count}} from the nodes' summaries."""
    return {p: {int(k): v for k, v in s["detected_by_player"].items()} for p, s in summaries.items()}


# ---- client-server: the real gateway and zone ----

def _zonesim_client():
    sys.path.insert(0, str(h.SOURCE_DIR / "clients/python"))
    sys.path.insert(0, str(h.bin_dir().parent / "python"))
    import zonesim_client
    return zonesim_client


def _receive_one(c, timeout):
    """One datagram handled as Client.poll handles it; False when none came in time. (poll()
    handles many before returning, which would blur the moment a state arrived.)"""
    c.sock.settimeout(max(timeout, 1e-4))
    try:
        data, frm = c.sock.recvfrom(1401)
    except socket.timeout:
        return False
    if frm != c.addr or len(data) < 8 or len(data) > 1400:
        c.dropped += 1
        return True
    try:
        if data[0] & 0x80:
            c._frame(data)
        else:
            c._flatbuffer(data)
    except (ValueError, IndexError, TypeError):
        c.dropped += 1
    return True


class ScriptedClient(threading.Thread):
    """A Python player of the real gateway with the topology nodes' script: each second a new
    target in the arena, an input toward it 20 times a second. It logs its inputs and every
    velocity change it sees of the avatars it watches, with the wall time they arrived.
    speed_factor > 1 makes it a speed hacker: every other second its inputs ask for that many
    times full speed, which the gateway must drop.
    The zone and the gateway act on 50 ms ticks, so an input's latency depends on where in the
    tick it arrives: a player that sent every input at one phase would sample one latency (and a
    link's delay would add either nothing or a whole tick). So a new input goes out as soon as it
    is chosen, restarting the 20 Hz cadence, and each retarget comes PHASE_STEP of a tick later
    than a whole second, which sweeps the tick's phases evenly (the golden ratio's fraction)."""

    def __init__(self, client, seconds, seed, speed_factor=1.0):
        super().__init__(daemon=True)
        self.c, self.seconds, self.rng = client, seconds, random.Random(seed)
        self.speed_factor = speed_factor
        self.watch = set()
        self.inputs, self.seen = [], defaultdict(list)
        self.max_speed_seen = defaultdict(float)
        self._logged = {}

    def run(self):
        end = time.monotonic() + self.seconds
        next_input = next_target = time.monotonic()
        move, cheat = (0.0, 0.0), False
        while time.monotonic() < end:
            now = time.monotonic()
            if now >= next_target:
                me = self.c.avatar()
                x, z = (me["pos"][0], me["pos"][2]) if me else (ARENA / 2, ARENA / 2)
                tx = self.rng.uniform(WALL_MARGIN, ARENA - WALL_MARGIN)
                tz = self.rng.uniform(WALL_MARGIN, ARENA - WALL_MARGIN)
                n = math.hypot(tx - x, tz - z) or 1.0
                move = ((tx - x) / n, (tz - z) / n)
                cheat = self.speed_factor > 1 and not cheat
                self.inputs.append((time.time(), move[0], move[1]))
                next_target += RETARGET_S + PHASE_STEP * TICK_S
                next_input = now
            if now >= next_input:
                f = self.speed_factor if cheat else 1.0
                self.c.send_input(move[0] * f, move[1] * f)
                next_input += 0.05
            if _receive_one(self.c, min(next_input, next_target, end) - time.monotonic()):
                self._look(time.time())

    def _look(self, t):
        for eid in self.watch:
            e = self.c.entities.get(eid)
            if e is None:
                continue
            vx, vz = e["vel"][0], e["vel"][2]
            self.max_speed_seen[eid] = max(self.max_speed_seen[eid], math.hypot(vx, vz))
            last = self._logged.get(eid)
            if last is None or math.hypot(vx - last[0], vz - last[1]) > SEEN_VELOCITY_CHANGE:
                self._logged[eid] = (vx, vz)
                self.seen[eid].append((t, vx, vz))


def forged_state_frame():
    """A lean StateBatch frame such as a gateway sends, claiming an avatar stands somewhere
    else: a client trying to tell the server where it is. Its checksum is the plain one of
    client datagrams, so the gateway refuses it for what it is, not for a bad checksum."""
    zc = _zonesim_client()
    return zc.with_checksum(bytes([0xA1]) + (1).to_bytes(4, "little") + bytes([5, 1]) + bytes(12))


def run_client_server(out, seconds, cheat=False, players=PLAYERS, link=None):
    """zone_node (one zone) + gateway + client_stub + four scripted Python players (+ a
    Python cheater). link: every player's access link both ways, client_stub --link for its
    players and bench/net/link_relay (the same model) in front of the Python ones. Returns what
    the figures and the checks need."""
    zc = _zonesim_client()
    out.mkdir(parents=True, exist_ok=True)
    env = h.base_env()
    domain = h.free_dds_domain()
    zones = h.start([h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", seconds + 120,
                     "--realtime", "--metrics", out, "--dds-domain", domain, "--truth-every", 1],
                    out / "zones.log", env)
    h.wait_for_zone_ticks(out, zones, out / "zones.log")
    gateway = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--bind", "127.0.0.1", "--port", 0,
                       "--port-file", out / "gateway_port", "--dds-domain", domain, "--metrics", out],
                      out / "gateway.log", env)
    port = int(h.wait_for_port(out / "gateway_port", gateway, out / "gateway.log"))
    ports = [port] * (SCRIPTED_PYTHON_PLAYERS + 1)
    relay = None
    if link:
        relay = h.start([h.bin_dir() / "link_relay", "--to", f"127.0.0.1:{port}", "--link", link,
                         "--pairs", len(ports), "--port-file", out / "relay_ports"],
                        out / "link_relay.log", env)
        h.wait_for_port(out / "relay_ports", relay, out / "link_relay.log")
        ports = [int(x) for x in (out / "relay_ports").read_text().split()]
    py = [zc.Client("127.0.0.1", ports[i], name=f"scripted{i}") for i in range(SCRIPTED_PYTHON_PLAYERS)]
    cheater = zc.Client("127.0.0.1", ports[-1], name="cheater") if cheat else None
    for c in py + ([cheater] if cheater else []):
        h.check(c.connect(timeout=30), f"a Python player was welcomed (avatar {c.avatar_id})")
    stub_players = players - len(py) - (1 if cheater else 0)
    stub = h.start([h.bin_dir() / "client_stub", "--scene", SCENE, "--gateway", f"127.0.0.1:{port}",
                    "--players", stub_players, "--duration", seconds, "--metrics", out / "clients",
                    "--summary", out / "clients_summary.json", "--truth-every", 1,
                    *(["--link", link] if link else [])],
                   out / "client_stub.log", env)
    actors = [ScriptedClient(c, seconds, seed=1000 + i) for i, c in enumerate(py)]
    for a in actors:
        a.watch = {c.avatar_id for c in py if c is not a.c} | ({cheater.avatar_id} if cheater else set())
    cheat_thread, forged = None, 0
    if cheater:
        cheat_thread = ScriptedClient(cheater, seconds, seed=999, speed_factor=3.0)
        cheat_thread.start()
    for a in actors:
        a.start()
    if cheater:
        # Besides the speed hack, a forged state frame every half second.
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            cheater.sock.sendto(forged_state_frame(), cheater.addr)
            forged += 1
            time.sleep(0.5)
    for a in actors + ([cheat_thread] if cheat_thread else []):
        a.join(timeout=seconds + 30)
    try:
        rc = stub.wait(timeout=seconds + 120)
    except Exception:
        h.fail("client_stub did not finish\n" + h.tail(out / "client_stub.log"))
    h.check(rc == 0, "client_stub exited 0" + ("" if rc == 0 else "\n" + h.tail(out / "client_stub.log")))
    if relay:
        h.stop(relay)
    h.stop(gateway)
    h.stop(zones)
    return {
        "gateway": h.load_json(out / "gateway_summary.json"),
        "clients": h.load_json(out / "clients_summary.json"),
        "actors": actors, "py": py, "cheater": cheater, "cheat_thread": cheat_thread,
        "forged_frames": forged,
    }


def display_views(out, clients_summary, avatars):
    """{(tick, avatar): {observer: (x, z)}} from client_stub's display.csv for the players'
    avatars only (the scene's crates are no player), observers numbered as client_stub's
    players, each one's own avatar (from the summary) left out."""
    views = defaultdict(dict)
    avatar_of = {i: c.get("avatar_id", 0) for i, c in enumerate(clients_summary["clients"])}
    with open(out / "clients" / "display.csv") as fh:
        for r in csv.DictReader(fh):
            obs, eid = int(r["player"]), int(r["id"])
            if avatar_of.get(obs) == eid or eid not in avatars:
                continue
            views[(int(r["tick"]), eid)][obs] = (float(r["x"]), float(r["z"]))
    return views


def client_server_figures(out, run, seconds):
    """The table's row for a client-server run."""
    inputs, seen = {}, {}
    for a in run["actors"]:
        inputs[a.c.avatar_id] = a.inputs
        for eid, s in a.seen.items():
            seen[(a.c.avatar_id, eid)] = s
    l50, l99, matched, unmatched = latency(inputs, seen)
    avatars = {c.get("avatar_id", 0) for c in run["clients"]["clients"]} | \
        {c.avatar_id for c in run["py"]} | ({run["cheater"].avatar_id} if run["cheater"] else set())
    views = display_views(out, run["clients"], avatars)
    c50, c99, pairs = consistency(views, lambda player: None)  # the zone holds every truth
    e50, e99, _ = truth_error(views, zone_truth(out))
    t = run["clients"]["totals"]
    n = max(1, t.get("welcomed", 1))
    return {
        "up_bytes_per_s": t["bytes_out_per_s"] / n, "down_bytes_per_s": t["bytes_in_per_s"] / n,
        "latency_ms_p50": l50, "latency_ms_p99": l99, "latency_samples": matched,
        "latency_unmatched": unmatched,
        "consistency_m_p50": c50, "consistency_m_p99": c99, "consistency_pairs": pairs,
        "truth_error_m_p50": e50, "truth_error_m_p99": e99,
        "seconds": seconds,
    }


def zone_truth(out):
    """{(tick, id): (x, z)} from zone_node --truth-every 1 (truth_0.csv: one zone)."""
    truth = {}
    for f in sorted(out.glob("truth_*.csv")):
        with open(f) as fh:
            for r in csv.DictReader(fh):
                truth[(int(r["tick"]), int(r["id"]))] = (float(r["x"]), float(r["z"]))
    return truth
