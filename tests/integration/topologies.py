"""What each topology of docs/networking.md ("Topologies") detects of cheating players, on
scenes/duel_arena_16.yaml with 16 players (tests/integration/topology_runs.py runs them):

- client-server: a Python player asks for three times full speed every other second and sends
  forged state frames; the gateway drops both (out_of_range, and the frame as bad_identifier:
  not a message a client sends), and no player ever sees its avatar faster than the scene's speed;
- client-hosted, cheating clients (a forged state, a speed hack, far hits): the host drops or
  rejects each one's claims and none of an honest client's; clients see nothing of it;
- client-hosted, cheating host (teleport, speed and far hits at once): only the clients that
  cross-check the host's states and hits detect it;
- peer to peer, cheating peers (teleport, speed, far hits, false votes, equivocation): every
  honest peer rejects every cheater it was lied to, and the peers' majority vote excludes every
  cheater at every honest peer, even one the cheater never lied to; the liar's votes against
  everyone exclude no honest peer, its votes in others' names and unkeyed ones are dropped and
  counted; the teleporter that stops is let back in and shown where it is; no honest peer
  rejects or excludes an honest one.
Counts and distances only, never times. About 40 s."""
import math
import tempfile
from pathlib import Path

import harness as h
import topology_runs as tr

SECONDS = 4
SPEED = 5.0  # scenes/duel_arena_16.yaml clients.speed
CHEATERS = {13: "teleport", 14: "speed", 15: "hit"}
HONEST = [p for p in range(tr.PLAYERS) if p not in CHEATERS]
# Peer to peer, with voting: a liar, a teleporter that stops after 2.5 s, an equivocator (its
# teleports reach only the lowest-numbered 3/5 of the others: peers 0-8), a speed hacker and
# a hit cheater. 7 s: the teleporter is caught at 2 s and let back in about 2.5 s after its
# last lie (topologies/node_rules.h: a 1 s probation, a 2 s verdict, votes every 0.5 s).
P2P_SECONDS = 7
P2P_CHEATERS = {11: "vote", 12: "teleport", 13: "equivocate", 14: "speed", 15: "hit"}
P2P_HONEST = [p for p in range(tr.PLAYERS) if p not in P2P_CHEATERS]
REFORMED, EQUIVOCATOR, LIAR = 12, 13, 11
NOT_FOOLED = [9, 10]  # honest peers the equivocator shows the truth
# How far an honest peer may show the reformed teleporter from where it is at the end: the
# extrapolation's error (a few cm), far below the 8 m of a teleport.
CORRECTED_M = 1.0

with tempfile.TemporaryDirectory(prefix="zs_topologies_") as tmp:
    out = Path(tmp)

    # Peer to peer: every honest peer judges every other peer, and they vote.
    s = tr.run_nodes(out / "p2p", "p2p", P2P_SECONDS, cheats=P2P_CHEATERS,
                     cheat_seconds={REFORMED: 2.5})
    found = tr.detections(s)
    ever = {p: {int(k) for k in s[p]["excluded_since_tick"]} for p in s}
    at_end = {p: set(s[p]["excluded_at_end"]) for p in s}
    for judge in P2P_HONEST:
        for cheater in (REFORMED, 14, 15):
            h.check(found[judge].get(cheater, 0) > 0,
                    f"p2p: peer {judge} rejected the {P2P_CHEATERS[cheater]} cheater {cheater} "
                    f"({found[judge].get(cheater, 0)} claims)")
        fooled = judge not in NOT_FOOLED
        h.check((found[judge].get(EQUIVOCATOR, 0) > 0) == fooled,
                f"p2p: peer {judge} {'caught' if fooled else 'never saw'} the equivocator's "
                f"teleports itself ({found[judge].get(EQUIVOCATOR, 0)} claims)")
        h.check(set(P2P_CHEATERS) <= ever[judge],
                f"p2p: peer {judge} excluded every cheater by the vote, the liar for its forged "
                f"votes ({sorted(ever[judge])} of {sorted(P2P_CHEATERS)})")
        h.check({EQUIVOCATOR, 14, 15} <= at_end[judge],
                f"p2p: peer {judge} still excludes the cheaters that never stopped ({sorted(at_end[judge])})")
        h.check(REFORMED not in at_end[judge] and str(REFORMED) in s[judge]["readmitted_at_tick"]
                and s[judge]["reanchored"].get(str(REFORMED), 0) > 0,
                f"p2p: peer {judge} let the reformed teleporter {REFORMED} back in after its "
                f"probation (at ticks {s[judge]['readmitted_at_tick']}, re-anchored {s[judge]['reanchored']})")
        false = {p: n for p, n in found[judge].items() if p in P2P_HONEST}
        h.check(not false, f"p2p: peer {judge} rejected no honest peer ({false})")
        wrongly = ever[judge] & set(P2P_HONEST)
        h.check(not wrongly, f"p2p: peer {judge} excluded 0 honest peers ({sorted(wrongly)})")
        h.check(s[judge]["votes_against_by_voter"].get(str(LIAR), 0) > 0,
                f"p2p: peer {judge} counted the liar's votes against everyone "
                f"({s[judge]['votes_against_by_voter'].get(str(LIAR), 0)}) and still excluded no honest peer")
        d = s[judge]["drops"]
        h.check(d.get("out_of_range", 0) > 0 and d.get("bad_checksum", 0) > 0,
                f"p2p: peer {judge} dropped the liar's votes in others' names (out_of_range) and "
                f"unkeyed ones (bad_checksum) ({d})")
    for judge in NOT_FOOLED:
        h.check(EQUIVOCATOR in ever[judge] and found[judge].get(EQUIVOCATOR, 0) == 0,
                f"p2p: peer {judge} excluded the equivocator on the others' word alone")
    h.check(s[0]["violations"].get("teleport", 0) > 0 and s[0]["violations"].get("speed", 0) > 0
            and s[0]["violations"].get("hit_out_of_reach", 0) > 0,
            f"p2p: each cheat shows as its own violation ({s[0]['violations']})")
    # Correction: at the end every honest peer shows the reformed teleporter where it is.
    views = tr.node_views(out / "p2p")
    last = max(t for (t, p), obs in views.items() if p == REFORMED and REFORMED in obs
               and all(j in obs for j in P2P_HONEST))
    truth = views[(last, REFORMED)][REFORMED]
    far = {j: round(math.dist(views[(last, REFORMED)][j], truth), 3) for j in P2P_HONEST}
    h.check(max(far.values()) < CORRECTED_M,
            f"p2p: at tick {last} every honest peer shows the reformed teleporter within "
            f"{CORRECTED_M} m of where it is ({far})")

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
