"""deploy/cluster.sh's cluster files: the shipped ones parse; every mistake is refused with one
line naming the file, section and key at fault; the Slurm batch script turns an allocation into
a cluster file; and a start that fails (a gateway that cannot bind) names the host and the
process and leaves nothing running."""
import os
import subprocess
import tempfile
from pathlib import Path

import harness as h

CLUSTER = h.SOURCE_DIR / "deploy" / "cluster.py"
GOOD_HEAD = "[cluster]\nscene = scenes/test_e2e.yaml\nduration = 4\n"
LOCAL = "[host a]\nreach = local\nzones = 2\n[gateway g]\nhost = a\n[fleet f]\nhost = a\nplayers = 2\n"


def dry_run(path, env=None):
    return subprocess.run(["python3", CLUSTER, "--dry-run", path], capture_output=True, text=True,
                          env={**os.environ, **(env or {})})


def refused(tmp, name, text, expect):
    path = Path(tmp) / f"{name}.cluster"
    path.write_text(text)
    r = dry_run(path)
    message = r.stderr.strip()
    h.check(r.returncode != 0 and len(message.splitlines()) == 1 and expect in message
            and str(path) in message, f"{name}: refused with '{message}'")


# The launcher's own cluster files and the benchmarks' (bench/cluster/world_eighth.cluster).
for shipped in sorted([*(h.SOURCE_DIR / "deploy" / "clusters").glob("*.cluster"),
                       *(h.SOURCE_DIR / "bench" / "cluster").glob("*.cluster")]):
    r = dry_run(shipped)
    h.check(r.returncode == 0 and "zone ranks" in r.stdout, f"{shipped.name} parses {r.stderr.strip()}")
netns = dry_run(h.SOURCE_DIR / "deploy/clusters/netns3.cluster", {"ZONESIM_NETNS": "zsq"})
h.check("host h2 (netns zsq-h2) at 10.77.0.2: 2 zone ranks" in netns.stdout,
        "${ZONESIM_NETNS} names the namespaces")

with tempfile.TemporaryDirectory(prefix="zs_cluster_file_") as tmp:
    refused(tmp, "unknown_key", GOOD_HEAD + LOCAL + "colour = red\n", "[fleet f]: unknown key colour")
    refused(tmp, "no_scene", "[cluster]\nduration = 4\n" + LOCAL, "[cluster]: scene is missing")
    refused(tmp, "lobby_fleet_gateway", GOOD_HEAD + LOCAL.replace("players = 2", "gateway = g") +
            "[lobby l]\nhost = a\n", "[fleet f] gateway: with a [lobby]")
    refused(tmp, "two_lobbies", GOOD_HEAD + LOCAL + "[lobby l]\nhost = a\n[lobby m]\nhost = a\n",
            "more than one [lobby NAME]")
    refused(tmp, "missing_scene", "[cluster]\nscene = scenes/nope.yaml\n" + LOCAL, "no such file")
    refused(tmp, "bad_reach", GOOD_HEAD + LOCAL.replace("reach = local", "reach = telnet x"), "[host a] reach")
    refused(tmp, "no_zones", GOOD_HEAD + LOCAL.replace("zones = 2", "zones = 0"), "no host runs zones")
    refused(tmp, "bad_number", GOOD_HEAD + LOCAL.replace("players = 2", "players = many"),
            "[fleet f] players: 'many' is not a number")
    refused(tmp, "unknown_gateway", GOOD_HEAD + LOCAL + "gateway = g9\n", "gateway: 'g9' is not")
    refused(tmp, "unknown_host", GOOD_HEAD + LOCAL.replace("[fleet f]\nhost = a", "[fleet f]\nhost = b"),
            "host: 'b' is not a [host NAME]")
    refused(tmp, "no_network", GOOD_HEAD + LOCAL + "[host b]\nreach = netns x\naddress = 10.0.0.2\n",
            "network (a.b.c.d/n) is needed")
    refused(tmp, "bad_network", GOOD_HEAD.replace("duration", "network = 10.0.0/33\nduration") + LOCAL,
            "network: '10.0.0/33'")
    refused(tmp, "bad_supervise", GOOD_HEAD + "supervise = everything\n" + LOCAL,
            "[cluster] supervise: 'everything' (expected no, or zones and/or gateways, comma-separated)")
    refused(tmp, "bad_supervise_part", GOOD_HEAD + "supervise = zones, lobby\n" + LOCAL,
            "[cluster] supervise: 'zones, lobby'")
    both = Path(tmp) / "both.cluster"
    both.write_text(GOOD_HEAD + "supervise = zones, gateways\n" + LOCAL)
    r = dry_run(both)
    h.check(r.returncode == 0 and "restarts from its newest checkpoint" in r.stdout
            and "a dead gateway restarts on its address" in r.stdout,
            f"supervise = zones, gateways plans both ({r.stdout.strip()} {r.stderr.strip()})")
    gateways = Path(tmp) / "gateways.cluster"
    gateways.write_text(GOOD_HEAD + "supervise = gateways\n" + LOCAL)
    r = dry_run(gateways)
    h.check(r.returncode == 0 and "checkpoint" not in r.stdout and "a dead gateway restarts" in r.stdout,
            f"supervise = gateways plans gateways only ({r.stdout.strip()} {r.stderr.strip()})")
    refused(tmp, "bad_ledger", GOOD_HEAD + "ledger = mysql:x\n" + LOCAL,
            "[cluster] ledger: 'mysql:x' (expected none, sqlite, sqlite:PATH or postgres:CONNINFO)")
    refused(tmp, "ledger_without_target", GOOD_HEAD + "ledger = postgres:\n" + LOCAL, "[cluster] ledger: 'postgres:'")
    refused(tmp, "sqlite_across_machines", GOOD_HEAD + "ledger = sqlite\nnetwork = 10.0.0.0/24\n"
            + LOCAL + "[host b]\nreach = ssh b.example\naddress = 10.0.0.2\nzones = 1\n",
            "[cluster] ledger: sqlite in the run folder needs every zone host on this machine")
    r = dry_run(both)
    h.check("ledger: sqlite, ledger.sqlite in the run folder" in r.stdout,
            f"one machine: the zones share a SQLite ledger by default ({r.stdout.strip()})")
    refused(tmp, "bad_hang", GOOD_HEAD + "supervise = zones\nhang_s = 0\n" + LOCAL, "[cluster] hang_s: 0 is below 1")
    refused(tmp, "unset_variable", GOOD_HEAD + LOCAL.replace("players = 2", "players = ${ZONESIM_NO_SUCH_VAR}"),
            "${ZONESIM_NO_SUCH_VAR} is not set")
    refused(tmp, "bad_section", GOOD_HEAD + LOCAL + "[router r]\n", "[router r]: unknown section")
    refused(tmp, "bad_ssh_options", GOOD_HEAD + "ssh_options = -i 'key\n" + LOCAL,
            "[cluster] ssh_options: No closing quotation")

    # The batch script under a fake allocation of two nodes (scontrol and the launcher replaced
    # by stand-ins that print what they were given).
    fake = Path(tmp) / "bin"
    fake.mkdir()
    (fake / "scontrol").write_text("#!/bin/sh\necho localhost\necho 127.0.0.1\n")
    (fake / "scontrol").chmod(0o755)
    root = Path(tmp) / "root"
    (root / "deploy").mkdir(parents=True)
    (root / "deploy" / "cluster.sh").write_text(f'#!/bin/sh\nexec python3 {CLUSTER} --dry-run "$1"\n')
    (root / "deploy" / "cluster.sh").chmod(0o755)
    env = {**os.environ, "PATH": f"{fake}:{os.environ['PATH']}", "ZONESIM_ROOT": str(root),
           "SLURM_JOB_ID": "42", "SLURM_JOB_NODELIST": "localhost,127.0.0.1",
           "SLURM_NTASKS_PER_NODE": "2(x2)", "SLURM_NTASKS": "4"}
    r = subprocess.run(["bash", h.SOURCE_DIR / "deploy/zonesim.sbatch", "scenes/test_e2e.yaml"],
                       capture_output=True, text=True, env=env)
    h.check(r.returncode == 0 and "host localhost (slurm localhost) at 127.0.0.1: 2 zone ranks" in r.stdout
            and "gateway g1 (id 1) on 127.0.0.1, --bind 0.0.0.0" in r.stdout,
            "the sbatch script made a cluster file of the allocation" + ("" if r.returncode == 0 else f": {r.stderr.strip()}"))

    # A gateway that cannot bind (TEST-NET-1 is never a local address): the launcher names it
    # and stops the zones it had started.
    bad = Path(tmp) / "bad_bind.cluster"
    bad.write_text(GOOD_HEAD + LOCAL.replace("[gateway g]\nhost = a", "[gateway g]\nhost = a\nbind = 192.0.2.1"))
    run = Path(tmp) / "run"
    env = {**h.base_env(h.free_dds_domain()), "ZONESIM_BIN": str(h.bin_dir())}
    r = subprocess.run(["bash", h.SOURCE_DIR / "deploy/cluster.sh", bad, run], capture_output=True,
                       text=True, env=env, timeout=120)
    h.check(r.returncode != 0 and "cluster.sh: error: host a (local), gateway g: exited with 1 before "
            "listening" in r.stderr and "--bind 192.0.2.1" in r.stderr,
            f"a failed start names the host and the process: {r.stderr.strip()}")
    left = [p.parent.name for p in Path("/proc").glob("[0-9]*/cmdline")
            if str(run).encode() in (p.read_bytes() if p.exists() else b"")]
    h.check(not left, f"nothing left running ({left})")
print("cluster file passed")
