"""Helpers for tests that start zonesim processes: paths, isolation and clean-up.

Every run gets its own DDS domain id and its own ports, and every process is started in its
own process group and killed on exit, so parallel ctest runs never see each other and never
leave processes behind.
"""
import atexit
import fcntl
import json
import os
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SOURCE_DIR = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE_DIR / "deploy"))
import process_group  # noqa: E402  (deploy/process_group.py)

_children = []


def bin_dir():
    return Path(os.environ.get("ZONESIM_BIN", SOURCE_DIR / "build" / "bin"))


def base_env(domain=None):
    env = dict(os.environ)
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["CYCLONEDDS_URI"] = "file://" + str(SOURCE_DIR / "deploy" / "cyclonedds.xml")
    if domain is not None:
        env["ZONESIM_DDS_DOMAIN"] = str(domain)
    return env


_domain_locks = []


def _ephemeral_ports():
    try:
        lo, hi = Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()
        return int(lo), int(hi)
    except (OSError, ValueError):
        return 32768, 60999


def free_dds_domain():
    """A DDS domain for this run only, by the rule of tests/support/dds_test_domain.h: Cyclone's
    domain d uses UDP ports 7400 + 250 d + [0, 250) and announces itself to all of them, so only
    domains clear of the ephemeral port range are used (else a gateway or player socket could draw
    one and count Cyclone's packets as drops), and a lock file held for the life of this process
    keeps parallel tests (C++ and Python alike) on different domains."""
    lo, hi = _ephemeral_ports()
    clear = [d for d in range(1, 233) if 7400 + 250 * d + 249 < lo or 7400 + 250 * d > hi] or list(range(1, 233))
    start = random.Random(os.getpid() ^ time.time_ns()).randrange(len(clear))
    for i in range(len(clear)):
        d = clear[(start + i) % len(clear)]
        f = open(Path(tempfile.gettempdir()) / f"zonesim_test_dds_domain_{d}.lock", "a+")
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            f.close()
            continue
        _domain_locks.append(f)  # held until this process exits
        return d
    return clear[start]


def mpirun(np, *args):
    # Sanitizer options (deploy/sanitize.sh) go to every rank explicitly, wherever it runs.
    forward = [a for v in ("ASAN_OPTIONS", "UBSAN_OPTIONS") if v in os.environ for a in ("-x", v)]
    return ["mpirun", "-np", str(np), "--oversubscribe", "--bind-to", "none", *forward, *map(str, args)]


def start(cmd, log_path, env):
    log = open(log_path, "w")
    cmd = [str(c) for c in cmd]
    p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=env, start_new_session=True)
    _children.append(p)
    return p


def run(cmd, log_path, env, timeout):
    p = start(cmd, log_path, env)
    try:
        rc = p.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        stop(p)
        fail(f"timed out after {timeout} s: {' '.join(map(str, cmd))}\n{tail(log_path)}")
    if rc != 0:
        fail(f"exit {rc}: {' '.join(map(str, cmd))}\n{tail(log_path)}")


def stop(p, grace=5.0):
    """SIGTERM the process group, then SIGKILL what is left."""
    return process_group.stop(p, grace)


@atexit.register
def _cleanup():
    for p in _children:
        stop(p, grace=2.0)


def wait_for_port(port_file, proc, log_path, timeout=120.0):
    """The port a process wrote to port_file once it listens. The wait is long because a loaded
    CI machine (2 cores, a fuzzer and four ranks beside us) can take many seconds to start it;
    a process that dies meanwhile ends the wait at once, with its log."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        text = port_file.read_text().strip() if port_file.exists() else ""
        if text:
            return text
        if proc.poll() is not None:
            fail(f"exited with {proc.returncode} before writing {port_file}\n{tail(log_path)}")
        time.sleep(0.1)
    fail(f"no port in {port_file} after {timeout:.0f} s\n{tail(log_path)}")


def wait_for_zone_ticks(metrics_dir, proc, log_path, timeout=120.0):
    """Until rank 0 of a zone job writing metrics to metrics_dir has written its first line of
    zone_0.jsonl: the zones are ticking and will answer spawn requests. mpirun can take longer
    to start the ranks on a loaded machine than a short fleet runs."""
    path = Path(metrics_dir) / "zone_0.jsonl"
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if path.exists() and path.read_text().strip():
            return
        if proc.poll() is not None:
            fail(f"exited with {proc.returncode} before ticking\n{tail(log_path)}")
        time.sleep(0.2)
    fail(f"no line in {path} after {timeout:.0f} s\n{tail(log_path)}")


def tail(path, lines=40):
    try:
        return "".join(Path(path).read_text(errors="replace").splitlines(True)[-lines:])
    except OSError:
        return ""


def load_json(path):
    return json.loads(Path(path).read_text())


def fail(msg):
    print("FAIL: " + msg, file=sys.stderr)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
    print("ok: " + msg)
