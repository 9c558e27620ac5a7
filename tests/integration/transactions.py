"""Players' transactions, end to end, under 19% injected loss each way and across handoffs.

Four zone ranks share one ledger (SQLite, or a PostgreSQL server this test starts); each player's link loses 19% of the datagrams each
way (client_stub --inject-loss drops on sending and on receiving), so transactions, their
outcomes, or both are lost often. Each of 8 players makes 10 transactions a second (loot, purchases, scores) for 20 s on
its reliable channel (clients/transaction_stream.h) while it wanders across the zones. The
client resends until an outcome comes; the zone owning the avatar hands each to the ledger in
sequence order and answers only once the database holds it (zone_node/transactions.h).

Afterwards, from the ledger file itself:
- each player's stored sequences are exactly 1..k, no gap (applied in order, none lost);
- every transaction a client was told is committed is stored; none stored twice (one row per
  key, and the zones' fresh inserts add up to the rows);
- nothing a client made is unaccounted for: committed + failed + still pending = made, and
  nothing failed;
- avatars changed zones while their transactions flowed (handoffs > 0);
- every player asked for the leaderboard every 2 s and got it, best first, topped by a score
  the ledger holds;
- inputs lost on the link reached the zones anyway, carried again by the next inputs: at most
  1% skipped (four datagrams in a row lost, 0.13% at 19%).
Prints the latency of an outcome (p50, p99) and how many sends were resends.
Usage: transactions.py [LOSS [ZONES [BACKEND]]]: defaults 0.19, 4, sqlite (or postgres)."""
import sys
import tempfile
from pathlib import Path

import harness as h
import transaction_cluster

PLAYERS = 8
RATE = 10
CLIENT_SECONDS = 20
# Arguments, for measuring: LOSS (default 0.19) and ZONES (default 4).
LOSS = float(sys.argv[1]) if len(sys.argv) > 1 else 0.19
ZONES = int(sys.argv[2]) if len(sys.argv) > 2 else 4
BACKEND = sys.argv[3] if len(sys.argv) > 3 else "sqlite"
if BACKEND not in ("sqlite", "postgres"):
    h.fail(f"back end '{BACKEND}': expected sqlite or postgres")

with tempfile.TemporaryDirectory(prefix="zs_tx_") as tmp, \
        transaction_cluster.ledger(tmp, BACKEND) as (ledger, pg):
    out = Path(tmp)
    s, zone_summaries, g = transaction_cluster.run(out, ZONES, PLAYERS, RATE, CLIENT_SECONDS, ledger,
                                                   ["--inject-loss", LOSS, "--leaderboard-every-s", 2])
    tx, cs = s["transactions"], s["clients"]
    zone_sums = {}
    for z in zone_summaries:
        for k, v in z.items():
            if k.startswith("transactions_") and isinstance(v, int):
                zone_sums[k] = zone_sums.get(k, 0) + v
    rows = transaction_cluster.stored(out, pg)
    by_player = {}
    for player, seq in rows:
        by_player.setdefault(player, []).append(seq)
    players = {c["player_id"] for c in cs if c["player_id"] != 0}

    print(f"made {tx['made']}, committed {tx['committed']} (already committed "
          f"{tx['already_committed']}), failed {tx['failed']}, pending {tx['pending']}; sent "
          f"{tx['sent']}, resent {tx['resent']}; outcome repeats {tx['outcome_repeats']}")
    print(f"outcome latency p50 {tx['latency_ms_p50']:.0f} ms, p99 {tx['latency_ms_p99']:.0f} ms, "
          f"max {tx['latency_ms_max']:.0f} ms")
    print("zones: " + ", ".join(f"{k[len('transactions_'):]} {v}" for k, v in sorted(zone_sums.items())))
    print(f"ledger ({BACKEND}): {len(rows)} rows for {len(by_player)} players")
    print(f"gateway: forwarded {g['transactions_forwarded']}, outcomes delivered "
          f"{g['outcomes_delivered']}, dropped {g['dropped']}")
    batches = sum(z["ledger_batches"] for z in zone_summaries)
    print(f"ledger batches {batches}")

    h.check(len(players) == PLAYERS, f"all {PLAYERS} players welcomed")
    h.check(tx["made"] >= PLAYERS * RATE * CLIENT_SECONDS * 0.8,
            f"the players made their transactions ({tx['made']})")
    h.check(tx["resent"] > 0, f"loss made the clients resend ({tx['resent']} resends)")
    h.check(tx["failed"] == 0 and tx["conflicts"] == 0,
            f"no transaction failed or conflicted ({tx['failed']}, {tx['conflicts']})")
    h.check(tx["committed"] + tx["pending"] == tx["made"],
            f"committed {tx['committed']} + pending {tx['pending']} = made {tx['made']}")
    h.check(tx["outcome_unknown"] == 0, "no outcome for a transaction never made")
    h.check(set(by_player) <= players, "the ledger holds only these players")
    for player, seqs in sorted(by_player.items()):
        seqs.sort()
        h.check(seqs == list(range(1, len(seqs) + 1)),
                f"player {player}: stored sequences are 1..{len(seqs)} without a gap")
    h.check(len(rows) >= tx["committed"], f"every transaction told committed is stored "
                                          f"({len(rows)} rows >= {tx['committed']})")
    h.check(len(rows) <= tx["made"], f"nothing stored that was not made ({len(rows)} <= {tx['made']})")
    h.check(zone_sums["transactions_committed"] == len(rows),
            f"the zones' fresh inserts ({zone_sums['transactions_committed']}) are the rows: "
            f"none applied twice")
    # Inputs ride their own mechanism: each carries the three before it again.
    applied = sum(z["inputs_applied"] for z in zone_summaries)
    skipped = sum(z["inputs_skipped"] for z in zone_summaries)
    print(f"inputs: {applied} applied, {skipped} skipped as lost, {g['inputs_recovered']} recovered from "
          f"a later datagram at the gateway")
    h.check(g["inputs_recovered"] > 0 and skipped <= 0.01 * applied,
            f"inputs lost on the link were recovered from the next ones ({g['inputs_recovered']}); at most "
            f"1% skipped ({skipped} of {applied})")
    # The leaderboard, asked for every 2 s: best first, and never a score the ledger lacks.
    best = transaction_cluster.query(out, pg, "SELECT MAX(score) FROM ledger_tx WHERE kind = 4")[0][0]
    answered = sum(z["leaderboards_answered"] for z in zone_summaries)
    print(f"leaderboard: {s['totals']['leaderboards']} answers to {s['totals']['leaderboard_queries']} "
          f"queries ({answered} sent by the zones); best score in the ledger {best}")
    h.check(all(c["leaderboards"] > 0 and c["leaderboard_rows"] > 0 for c in cs),
            "every player got the leaderboard, with rows")
    h.check(s["totals"]["leaderboards_unordered"] == 0, "every leaderboard came best first")
    h.check(all(0 < c["leaderboard_top"] <= best for c in cs),
            f"each player's newest top score is one the ledger holds (<= {best})")
    handoffs = s["totals"]["handoffs"]
    h.check(handoffs > 0, f"avatars changed zones during the run ({handoffs} handoffs)")
print("transactions passed")
