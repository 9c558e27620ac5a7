#!/usr/bin/env python3
"""Players' transactions on a real cluster (issue 15): 4 zone ranks, a gateway and client_stub,
scenes/test_e2e.yaml in real time. Two tables, each from runs in one invocation:

1. Latency, from a transaction's first send to its outcome at the client (which comes only
   once the ledger holds it), for 8 players making 10 a second on an unimpaired link and on
   client_stub --link 4g and --link congested (wire/link_profile.cpp), SQLite ledger.
2. Commit rate and the zone tick: PLAYERS players making RATE a second each, with no
   transactions, with the SQLite ledger (one file, every rank) and with a PostgreSQL server
   started for the run (tests/integration/pg_server.py); committed per second (rows stored over
   the players' seconds), outcome p50/p99, and the zone tick's p99 (the slowest rank's).

3. With --inputs instead: inputs under 19% loss each way (8 players, 20 a second, no
   transactions) with client_stub --input-redundancy 0 and 3: how many the zones skipped as
   never arrived, how many the gateway recovered from later datagrams, the uplink per player.

Usage: bench/cluster/transaction_bench.py [--inputs] [SECONDS [PLAYERS [RATE]]]
       (defaults 20, 32, 50)
"""
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests/integration"))
import transaction_cluster  # noqa: E402

INPUTS = "--inputs" in sys.argv[1:]
ARGS = [a for a in sys.argv[1:] if a != "--inputs"]
SECONDS = float(ARGS[0]) if len(ARGS) > 0 else 20
PLAYERS = int(ARGS[1]) if len(ARGS) > 1 else 32
RATE = float(ARGS[2]) if len(ARGS) > 2 else 50
ZONES = 4


def run(name, players, rate, link=None, backend="sqlite"):
    """One cluster run; its figures."""
    print(f"-- {name}: {players} players x {rate:g} a second for {SECONDS:g} s"
          f"{', link ' + link if link else ''}, ledger {backend if rate else 'unused'}", flush=True)
    with tempfile.TemporaryDirectory(prefix="zs_txbench_") as tmp, \
            transaction_cluster.ledger(tmp, backend) as (ledger, pg):
        out = Path(tmp)
        summary, zs, _ = transaction_cluster.run(out, ZONES, players, rate, SECONDS, ledger,
                                                 ["--link", link] if link else [])
        tx = summary["transactions"]
        rows = len(transaction_cluster.stored(out, pg))
        return {"name": name, "made": tx["made"], "committed": tx["committed"], "rows": rows,
                "resent": tx["resent"], "refused": tx["refused_window_full"],
                "p50": tx["latency_ms_p50"], "p99": tx["latency_ms_p99"], "max": tx["latency_ms_max"],
                "tick_p99": max(z["tick_ms_p99"] for z in zs), "tick_p50": max(z["tick_ms_p50"] for z in zs)}


if INPUTS:
    print(f"\nInputs under 19% loss each way, 4 ranks, 8 players, {SECONDS:g} s")
    print(f"{'redundancy':>10} {'applied':>7} {'skipped':>7} {'share':>7} {'recovered':>9} {'up B/s':>7}")
    for redundancy in (0, 3):
        with tempfile.TemporaryDirectory(prefix="zs_inbench_") as tmp:
            s, zs, g = transaction_cluster.run(tmp, ZONES, 8, 0, SECONDS, f"sqlite:{tmp}/ledger.sqlite",
                                               ["--inject-loss", 0.19, "--input-redundancy", redundancy])
        applied = sum(z["inputs_applied"] for z in zs)
        skipped = sum(z["inputs_skipped"] for z in zs)
        print(f"{redundancy:>10} {applied:>7} {skipped:>7} {skipped / max(1, applied + skipped):>7.2%} "
              f"{g['inputs_recovered']:>9} {s['totals']['bytes_out_per_s'] / 8:>7.0f}")
    sys.exit(0)

latency = [run(f"link {link or 'none'}", 8, 10, link) for link in (None, "4g", "congested")]
rate = [run("no transactions", PLAYERS, 0), run("sqlite", PLAYERS, RATE),
        run("postgres", PLAYERS, RATE, backend="postgres")]

print(f"\nOutcome latency, 4 ranks, 8 players x 10 a second, {SECONDS:g} s, SQLite ledger")
print(f"{'link':>16} {'made':>6} {'committed':>9} {'resends/tx':>10} {'p50 ms':>7} {'p99 ms':>7} {'max ms':>7}")
for r in latency:
    print(f"{r['name']:>16} {r['made']:>6} {r['committed']:>9} {r['resent'] / max(1, r['made']):>10.2f} "
          f"{r['p50']:>7.0f} {r['p99']:>7.0f} {r['max']:>7.0f}")
print(f"\nCommit rate and zone tick, 4 ranks, {PLAYERS} players x {RATE:g} a second offered, {SECONDS:g} s")
print(f"{'ledger':>16} {'made':>6} {'stored':>6} {'stored/s':>8} {'refused':>7} {'p50 ms':>7} {'p99 ms':>7} "
      f"{'tick p50':>8} {'tick p99':>8}")
for r in rate:
    print(f"{r['name']:>16} {r['made']:>6} {r['rows']:>6} {r['rows'] / SECONDS:>8.0f} {r['refused']:>7} "
          f"{r['p50']:>7.0f} {r['p99']:>7.0f} {r['tick_p50']:>8.2f} {r['tick_p99']:>8.2f}")
base = rate[0]["tick_p99"]
print(f"zone tick p99 against no transactions: sqlite x{rate[1]['tick_p99'] / base:.2f}, "
      f"postgres x{rate[2]['tick_p99'] / base:.2f}")
