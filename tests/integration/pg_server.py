"""A throw-away PostgreSQL server for a test or a benchmark, from Debian's `postgresql` package
(deploy/setup.sh installs it): initdb in a temporary folder, the server on a Unix socket there
(no TCP), fsync and synchronous_commit on as a real ledger would run, removed with its folder on
exit, whatever happened. As root it runs as the package's `postgres` user, since the server
refuses root. The same recipe as tests/ledger/pg_server.cpp, for the Python tests.

    with PgServer() as pg:
        zone_node ... --ledger f"postgres:{pg.conninfo}"
        rows = pg.query("SELECT player, seq FROM ledger_tx")
"""
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import harness as h

PORT = 5433  # on its own socket folder: never a system server's


def bindir():
    found = sorted(Path("/usr/lib/postgresql").glob("*/bin/postgres"))
    if not found:
        h.fail("no PostgreSQL server under /usr/lib/postgresql/*/bin (install Debian's postgresql, "
               "deploy/setup.sh does)")
    return found[-1].parent


class PgServer:
    def __init__(self):
        self.bin = bindir()
        self.dir = Path(tempfile.mkdtemp(prefix="zonesim-pg-"))
        self.proc = None
        self.as_user = {}
        if os.geteuid() == 0:
            import pwd
            pw = pwd.getpwnam("postgres")
            os.chown(self.dir, pw.pw_uid, pw.pw_gid)
            self.as_user = {"user": pw.pw_uid, "group": pw.pw_gid, "extra_groups": []}
        self.conninfo = f"host={self.dir} port={PORT} user=postgres dbname=postgres"

    def __enter__(self):
        try:
            r = subprocess.run([self.bin / "initdb", "-D", self.dir / "data", "-U", "postgres", "-A",
                                "trust", "-E", "UTF8", "--no-sync", "--no-instructions"],
                               capture_output=True, text=True, timeout=120, **self.as_user)
            if r.returncode != 0:
                h.fail(f"initdb failed in {self.dir}: {r.stderr.strip() or r.stdout.strip()}")
            log = open(self.dir / "server.log", "w")
            if self.as_user:
                os.chown(self.dir / "server.log", self.as_user["user"], self.as_user["group"])
            self.proc = subprocess.Popen(
                [self.bin / "postgres", "-D", self.dir / "data", "-k", self.dir, "-p", str(PORT),
                 "-c", "listen_addresses=", "-c", "shared_buffers=16MB", "-c", "max_connections=40",
                 "-c", "logging_collector=off"],
                stdout=log, stderr=subprocess.STDOUT, start_new_session=True, **self.as_user)
            deadline = time.monotonic() + 60
            while subprocess.run(["pg_isready", "-q", "-h", str(self.dir), "-p", str(PORT)]).returncode != 0:
                if self.proc.poll() is not None or time.monotonic() > deadline:
                    h.fail(f"the PostgreSQL server in {self.dir} did not start: "
                           f"{h.tail(self.dir / 'server.log')}")
                time.sleep(0.1)
            return self
        except BaseException:
            self.__exit__(None, None, None)
            raise

    def query(self, sql):
        """Rows of a query, each a list of strings."""
        r = subprocess.run(["psql", "-X", "-A", "-t", "-F", ",", "-h", str(self.dir), "-p", str(PORT),
                            "-U", "postgres", "-d", "postgres", "-c", sql],
                           capture_output=True, text=True, timeout=60)
        if r.returncode != 0:
            h.fail(f"psql: {r.stderr.strip()}")
        return [line.split(",") for line in r.stdout.splitlines() if line]

    def __exit__(self, *exc):
        if self.proc is not None and self.proc.poll() is None:
            self.proc.send_signal(3)  # SIGQUIT: immediate shutdown
            try:
                self.proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        shutil.rmtree(self.dir, ignore_errors=True)
        return False
