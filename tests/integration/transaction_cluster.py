"""One run of players making transactions on a real cluster, for tests/integration/
transactions.py and bench/cluster/transaction_bench.py: ZONES zone ranks of
scenes/test_e2e.yaml in real time committing to `ledger` (a zone_node --ledger value), a
gateway, and a client_stub of `players` making `rate` transactions a second each for `seconds`
(with `client_args`, e.g. --inject-loss 0.19 or --link 4g). Returns what the run wrote: the
fleet's summary, the zones' summaries and the gateway's."""
import contextlib
import sqlite3
from pathlib import Path

import harness as h
from pg_server import PgServer

SCENE = h.SOURCE_DIR / "scenes/test_e2e.yaml"


def run(out, zones, players, rate, seconds, ledger, client_args=()):
    out = Path(out)
    domain = h.free_dds_domain()
    env = h.base_env()
    zone_job = h.start(h.mpirun(zones, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 900,
                                "--realtime", "--dds-domain", domain, "--metrics", out,
                                "--ledger", ledger), out / "zones.log", env)
    gateway = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--port", 0, "--port-file",
                       out / "port", "--dds-domain", domain, "--metrics", out, "--expect-zones",
                       zones], out / "gateway.log", env)
    port = h.wait_for_port(out / "port", gateway, out / "gateway.log")
    h.wait_for_zone_ticks(out, zone_job, out / "zones.log")
    clients = h.start([h.bin_dir() / "client_stub", "--scene", SCENE, "--gateway",
                       f"127.0.0.1:{port}", "--players", players, "--duration", seconds,
                       "--summary", out / "clients.json", "--transactions-per-s", rate,
                       *client_args], out / "clients.log", env)
    try:
        rc = clients.wait(timeout=seconds + 120)
    except Exception:
        h.fail(f"client_stub did not finish\n{h.tail(out / 'clients.log')}")
    h.check(rc == 0, f"client_stub exited cleanly\n{h.tail(out / 'clients.log')}")
    h.stop(gateway)
    h.stop(zone_job, grace=30)
    return (h.load_json(out / "clients.json"),
            [h.load_json(out / f"zone_{r}_summary.json") for r in range(zones)],
            h.load_json(out / "gateway_summary.json"))


def ledger(out, backend):
    """A context giving (the zone_node --ledger value, the PgServer or None) for a run in `out`:
    SQLite's file in it, or a PostgreSQL server started for the run and removed after."""
    @contextlib.contextmanager
    def made():
        if backend == "postgres":
            with PgServer() as pg:
                yield f"postgres:{pg.conninfo}", pg
        else:
            yield f"sqlite:{Path(out) / 'ledger.sqlite'}", None
    return made()


def query(out, pg, sql):
    """Rows of integers a query on the run's ledger returns ([] where it has none)."""
    if pg:
        return [tuple(int(v) for v in row) for row in pg.query(sql)]
    path = Path(out) / "ledger.sqlite"
    if not path.exists():
        return []
    db = sqlite3.connect(path)
    rows = db.execute(sql).fetchall()
    db.close()
    return rows


def stored(out, pg):
    """(player, seq) of every transaction the run's ledger holds."""
    return query(out, pg, "SELECT player, seq FROM ledger_tx")
