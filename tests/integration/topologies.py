"""What each topology of docs/networking.md ("Topologies") detects of cheating players, on
scenes/duel_arena_16.yaml with 16 players (tests/integration/topology_runs.py runs them):

- client-server: a Python player asks for three times full speed every other second and sends
  forged state frames; the gateway drops both (out_of_range, and the frame as bad_identifier:
  not a message a client sends), and no player ever sees its avatar faster than the scene's speed;
- client-hosted, cheating clients (a forged state, a speed hack, far hits): the host drops or
  rejects each one's claims and none of an honest client's; clients see nothing of it;
- client-hosted, cheating host (teleport, speed and far hits at once): only the clients that
  cross-check the host's states and hits detect it;
- peer to peer, cheating peers (teleport, speed, far hits): every honest peer rejects every
  cheater, and no honest peer rejects an honest one.
Counts only, never times. About 35 s."""
import tempfile
from pathlib import Path

import harness as h
import topology_runs as tr

SECONDS = 4
SPEED = 5.0  # scenes/duel_arena_16.yaml clients.speed
CHEATERS = {13: "teleport", 14: "speed", 15: "hit"}
HONEST = [p for p in range(tr.PLAYERS) if p not in CHEATERS]

with tempfile.TemporaryDirectory(prefix="zs_topologies_") as tmp:
    out = Path(tmp)

    # Peer to peer: every honest peer judges every other peer.
    s = tr.run_nodes(out / "p2p", "p2p", SECONDS, cheats=CHEATERS)
    found = tr.detections(s)
    for judge in HONEST:
        for cheater in CHEATERS:
            h.check(found[judge].get(cheater, 0) > 0,
                    f"p2p: peer {judge} rejected the {CHEATERS[cheater]} cheater {cheater} "
                    f"({found[judge].get(cheater, 0)} claims)")
        false = {p: n for p, n in found[judge].items() if p in HONEST}
        h.check(not false, f"p2p: peer {judge} rejected no honest peer ({false})")
    h.check(s[0]["violations"].get("teleport", 0) > 0 and s[0]["violations"].get("speed", 0) > 0
            and s[0]["violations"].get("hit_out_of_reach", 0) > 0,
            f"p2p: each cheat shows as its own violation ({s[0]['violations']})")

    # Client-hosted, cheating clients: the host is the only judge.
    s = tr.run_nodes(out / "hosted_clients", "client_hosted", SECONDS, cheats=CHEATERS)
    host = s[0]
    by = {int(k): v for k, v in host["detected_by_player"].items()}
    h.check(all(by.get(p, 0) > 0 for p in CHEATERS),
            f"client-hosted: the host caught every cheating client ({by})")
    h.check(not any(p in HONEST for p in by), "client-hosted: the host caught no honest client")
    h.check(host["drops"].get("out_of_range", 0) > 0,
            f"client-hosted: the speed hacker's inputs were dropped as out_of_range ({host['drops']})")
    h.check(host["drops"].get("unexpected_type", 0) > 0,
            "client-hosted: the forged state frames were dropped (a client never sends states)")
    h.check(host["violations"].get("hit_out_of_reach", 0) > 0,
            f"client-hosted: the far hits were rejected ({host['violations']})")
    h.check(all(not s[p]["detected_by_player"] for p in range(1, tr.PLAYERS)),
            "client-hosted: clients that do not cross-check detect nothing themselves")

    # Client-hosted, cheating host: undetectable, unless a client cross-checks.
    checkers = {1, 2, 3, 4}
    s = tr.run_nodes(out / "hosted_host", "client_hosted", SECONDS,
                     cheats={0: "teleport,speed,hit"}, cross_check=checkers)
    for p in range(1, tr.PLAYERS):
        caught = {int(k): v for k, v in s[p]["detected_by_player"].items()}
        if p in checkers:
            h.check(caught.get(0, 0) > 0 and set(caught) == {0},
                    f"client-hosted: cross-checking client {p} caught the host and no one else ({caught})")
            v = s[p]["violations"]
            h.check(v.get("speed", 0) > 0 and v.get("hit_out_of_reach", 0) > 0,
                    f"client-hosted: client {p} saw the host's speed and far hits ({v})")
        else:
            h.check(not caught, f"client-hosted: client {p}, not cross-checking, saw nothing wrong")

    # Client-server: the real gateway and zone.
    run = tr.run_client_server(out / "client_server", SECONDS, cheat=True)
    g = {reason: n for reason, n in run["gateway"]["dropped"].items() if n}
    h.check(g.get("out_of_range", 0) > 0,
            f"client-server: the gateway dropped the speed hacker's inputs as out_of_range ({g})")
    h.check(g.get("bad_identifier", 0) >= run["forged_frames"] > 0,
            f"client-server: the gateway dropped all {run['forged_frames']} forged state frames "
            f"as bad_identifier ({g})")
    cheater = run["cheater"].avatar_id
    fastest = max(a.max_speed_seen.get(cheater, 0.0) for a in run["actors"])
    h.check(0 < fastest <= SPEED + 0.05,
            f"client-server: no player saw the cheater faster than {SPEED} m/s (fastest {fastest:.2f})")
print("topologies: all checks passed")
