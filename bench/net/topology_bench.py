#!/usr/bin/env python3
"""Client-server, client-hosted and peer to peer on one duel arena (issue 18, "Topologies";
docs/networking.md): 16 players on scenes/duel_arena_16.yaml for SECONDS, each topology run as
real processes over loopback UDP (tests/integration/topology_runs.py). Per topology: bandwidth
per player (UDP payload bytes a second, up and down), the latency from an input to its first
effect seen at each other player, and the distance between where two players show the same
third player at the same tick (p50/p99). Then the cheating runs of tests/integration/
topologies.py, with what each judge caught of each cheater and whom the peers' vote excluded.

With --link PRESET every player's access link, both ways, is that wire/link_profile.h preset
(client_stub --link, topology_node --link, and bench/net/link_relay in front of the Python
players that time client-server's latency) and the cheating runs are skipped.

Usage: bench/net/topology_bench.py [--link PRESET] [SECONDS] [OUT_DIR]
       (defaults: no link, 20, runs/topology_bench or runs/topology_bench_PRESET)
Writes OUT_DIR/topologies.json and OUT_DIR/topologies.csv."""
import csv
import json
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests/integration"))
import topology_runs as tr  # noqa: E402

ARGS = sys.argv[1:]
LINK = None
if "--link" in ARGS:
    i = ARGS.index("--link")
    LINK = ARGS[i + 1]
    del ARGS[i:i + 2]
SECONDS = float(ARGS[0]) if len(ARGS) > 0 else 20
OUT = Path(ARGS[1]) if len(ARGS) > 1 else ROOT / "runs" / ("topology_bench" + (f"_{LINK}" if LINK else ""))
CHEATERS = {13: "teleport", 14: "speed", 15: "hit"}
# Peer to peer with voting, as tests/integration/topologies.py runs it: a liar, a teleporter that
# stops after 2.5 s, an equivocator, a speed hacker and a hit cheater, 7 s.
P2P_CHEATERS = {11: "vote", 12: "teleport", 13: "equivocate", 14: "speed", 15: "hit"}
P2P_CHEAT_SECONDS = {12: 2.5}
P2P_SECONDS = 7
COLUMNS = ["topology", "up_bytes_per_s", "down_bytes_per_s", "latency_ms_p50", "latency_ms_p99",
           "latency_samples", "consistency_m_p50", "consistency_m_p99", "consistency_pairs",
           "truth_error_m_p50", "truth_error_m_p99",
           "host_up_bytes_per_s", "host_down_bytes_per_s", "client_up_bytes_per_s",
           "client_down_bytes_per_s"]


def cheat_rows(tmp):
    """(run, judge, what it caught) for the cheating runs."""
    rows = []
    s = tr.run_nodes(tmp / "p2p_cheat", "p2p", P2P_SECONDS, cheats=P2P_CHEATERS,
                     cheat_seconds=P2P_CHEAT_SECONDS)
    honest = [p for p in s if p not in P2P_CHEATERS]
    for c, what in P2P_CHEATERS.items():
        if c in P2P_CHEAT_SECONDS:
            what += f" for {P2P_CHEAT_SECONDS[c]} s"
        judges = [p for p in honest if s[p]["detected_by_player"].get(str(c), 0) > 0]
        excluders = [p for p in honest if str(c) in s[p]["excluded_since_tick"]]
        at_end = [p for p in honest if c in s[p]["excluded_at_end"]]
        since = sorted(s[p]["excluded_since_tick"][str(c)] for p in excluders)
        back = sorted(s[p]["readmitted_at_tick"][str(c)] for p in honest
                      if str(c) in s[p]["readmitted_at_tick"])
        rows.append(("p2p", f"peer {c} ({what})",
                     f"caught by {len(judges)}, excluded by {len(excluders)} (from tick "
                     f"{since[0] if since else '-'}-{since[-1] if since else '-'}), at the end by "
                     f"{len(at_end)} of {len(honest)} honest peers; re-admitted by {len(back)}"
                     + (f" (at tick {back[0]}-{back[-1]})" if back else ""),
                     sum(s[p]["detected_by_player"].get(str(c), 0) for p in honest)))
    false = sum(n for p in honest for k, n in s[p]["detected_by_player"].items() if int(k) in honest)
    wrongly = sum(1 for p in honest for k in s[p]["excluded_since_tick"] if int(k) in honest)
    rows.append(("p2p", "honest peers", "rejections of honest peers, exclusions of honest peers",
                 f"{false}, {wrongly}"))
    rows.append(("p2p", "peer 0's drops and violations", json.dumps(s[0]["drops"]),
                 json.dumps(s[0]["violations"])))
    rows.append(("p2p", "votes peer 0 sent, took in, per voter against anyone", s[0]["votes_sent"],
                 f"{s[0]['votes_in']} {json.dumps(s[0]['votes_against_by_voter'])}"))
    s = tr.run_nodes(tmp / "hosted_cheat", "client_hosted", 4, cheats=CHEATERS)
    for c, what in CHEATERS.items():
        rows.append(("client_hosted", f"client {c} ({what})", "the host",
                     s[0]["detected_by_player"].get(str(c), 0)))
    rows.append(("client_hosted", "host's drops and rejections", json.dumps(s[0]["drops"]),
                 json.dumps(s[0]["violations"])))
    s = tr.run_nodes(tmp / "host_cheat", "client_hosted", 4, cheats={0: "teleport,speed,hit"},
                     cross_check={1, 2, 3, 4})
    for label, group in (("cross-checking clients", [1, 2, 3, 4]), ("other clients", range(5, 16))):
        caught = [s[p]["detected_by_player"].get("0", 0) for p in group]
        rows.append(("client_hosted", f"host 0 (teleport,speed,hit) seen by {label}",
                     f"{sum(1 for n in caught if n)} of {len(caught)}", sum(caught)))
    rows.append(("client_hosted", "a cross-checking client's violations", "",
                 json.dumps(s[1]["violations"])))
    run = tr.run_client_server(tmp / "cs_cheat", 4, cheat=True)
    cheater = run["cheater"].avatar_id
    rows.append(("client_server", "player (speed x3, forged state frames)", "the gateway",
                 json.dumps({r: n for r, n in run["gateway"]["dropped"].items() if n})))
    rows.append(("client_server", "the cheater's fastest speed seen by others (m/s)", "",
                 round(max(a.max_speed_seen.get(cheater, 0.0) for a in run["actors"]), 3)))
    return rows


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    results = []
    with tempfile.TemporaryDirectory(prefix="zs_topobench_") as tmp:
        tmp = Path(tmp)
        run = tr.run_client_server(tmp / "cs", SECONDS, link=LINK)
        row = tr.client_server_figures(tmp / "cs", run, SECONDS)
        results.append({"topology": "client_server", **row})
        s = tr.run_nodes(tmp / "hosted", "client_hosted", SECONDS, link=LINK)
        results.append({"topology": "client_hosted", **tr.node_figures(tmp / "hosted", s, SECONDS)})
        s = tr.run_nodes(tmp / "p2p", "p2p", SECONDS, link=LINK)
        results.append({"topology": "p2p", **tr.node_figures(tmp / "p2p", s, SECONDS)})
        cheats = [] if LINK else cheat_rows(tmp)
    with open(OUT / "topologies.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in results:
            w.writerow(r)
    (OUT / "topologies.json").write_text(json.dumps({"seconds": SECONDS, "players": tr.PLAYERS, "link": LINK,
                                                     "results": results, "cheats": cheats}, indent=1))
    print(f"{'topology':15} {'up B/s':>8} {'down B/s':>9} {'lat p50':>8} {'lat p99':>8} "
          f"{'n':>5} {'cons p50':>9} {'cons p99':>9} {'err p50':>8} {'err p99':>8}")
    for r in results:
        print(f"{r['topology']:15} {r['up_bytes_per_s']:8.0f} {r['down_bytes_per_s']:9.0f} "
              f"{r['latency_ms_p50']:8.1f} {r['latency_ms_p99']:8.1f} {r['latency_samples']:5d} "
              f"{r['consistency_m_p50']:9.3f} {r['consistency_m_p99']:9.3f} "
              f"{r['truth_error_m_p50']:8.3f} {r['truth_error_m_p99']:8.3f}")
        if "host_up_bytes_per_s" in r:
            print(f"{'  host':15} {r['host_up_bytes_per_s']:8.0f} {r['host_down_bytes_per_s']:9.0f}")
            print(f"{'  clients':15} {r['client_up_bytes_per_s']:8.0f} {r['client_down_bytes_per_s']:9.0f}")
    if cheats:
        print(f"\ncheating runs (4 s each; peer to peer with votes {P2P_SECONDS} s):")
    for row in cheats:
        print("  " + " | ".join(str(x) for x in row))
    print(f"\nwrote {OUT / 'topologies.json'} and {OUT / 'topologies.csv'}")


if __name__ == "__main__":
    main()
