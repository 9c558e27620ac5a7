"""deploy/zonesim.sbatch under a real Slurm on this machine: a one-node cluster made for this run
(slurmctld and slurmd from a slurm.conf in a temporary folder, munged on its own socket with its
own key, free ports, proctrack/linuxproc and task/none so no cgroup is needed), the script
submitted with sbatch --wait: it writes the cluster file from SLURM_JOB_NODELIST, the launcher
starts the 4 zone ranks with mpirun (Open MPI's daemons through srun) and the gateway and 32
players with srun --overlap. The run folder must hold every rank's summary with entities
conserved, players that got state and no input lost or doubled; slurmd, slurmctld, munged, the
job's processes and the folder must be gone afterwards, pass or fail. Needs root and the
slurmctld, slurmd, slurm-client and munge packages (deploy/setup.sh)."""
import os
import shutil
import socket
import subprocess
import tempfile
import time
from pathlib import Path

import harness as h
import namespace_hosts as hosts

RANKS = 4
PLAYERS = 32
SECONDS = 8
NODE = socket.gethostname().split(".")[0]  # hostname -s: the name slurmd registers as

SLURM_CONF = """# Written by tests/integration/slurm_cluster.py: one node, this machine, for one test run.
ClusterName=zs{pid}
SlurmctldHost={node}
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={tmp}/munge.socket
StateSaveLocation={tmp}/state
SlurmdSpoolDir={tmp}/spool
SlurmctldPidFile={tmp}/slurmctld.pid
SlurmdPidFile={tmp}/slurmd.pid
SlurmctldLogFile={tmp}/slurmctld.log
SlurmdLogFile={tmp}/slurmd.log
# No cgroup: process tracking by parentage, no task binding.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
# The node offers RANKS CPUs even on fewer cores (the ranks yield, deploy/cluster.py): slurmd
# reports the CPUs configured here, not the cores it finds. sbatch --overcommit is refused.
SlurmdParameters=config_overrides
KillWait=5
MinJobAge=5
NodeName={node} CPUs={cpus} State=UNKNOWN
PartitionName=zs Nodes={node} Default=YES MaxTime=10 State=UP
"""


def free_ports(count):
    """count distinct ports free now: all held open until each is known, so none comes twice."""
    sockets = [socket.socket() for _ in range(count)]
    try:
        for s in sockets:
            s.bind(("", 0))
        return [s.getsockname()[1] for s in sockets]
    finally:
        for s in sockets:
            s.close()


def daemon_path(name):
    # Daemons live in /usr/sbin, which a test's PATH may lack.
    path = shutil.which(name) or shutil.which(name, path="/usr/sbin:/usr/local/sbin:/sbin")
    if not path:
        h.fail(f"{name} not found: install slurmctld, slurmd, slurm-client and munge (deploy/setup.sh lists them)")
    return path


def slurmstepds():
    """This run's job step daemons: they inherit slurmd's SLURM_CONF, in the folder of this run
    (a Slurm test of another checkout may be running beside this one)."""
    found = set()
    for comm in Path("/proc").glob("[0-9]*/comm"):
        try:
            if (comm.read_text().strip() == "slurmstepd"
                    and f"SLURM_CONF={tmp}/".encode() in (comm.parent / "environ").read_bytes()):
                found.add(int(comm.parent.name))
        except OSError:
            pass
    return found


def wait_for(what, ready, daemons, deadline):
    while not ready():
        for p, log in daemons:
            if p.poll() is not None:
                h.fail(f"{what}: {Path(log).name[:-4]} exited with {p.returncode}\n{h.tail(log)}")
        if time.monotonic() > deadline:
            h.fail(f"{what}: not after 30 s\n" + "".join(h.tail(log, 10) for _, log in daemons))
        time.sleep(0.2)


daemons = []  # (Popen, log path), stopped in reverse order
tmp = tempfile.mkdtemp(prefix="zs_slurm_")  # short: munged's socket path must fit 108 characters
env = h.base_env(h.free_dds_domain())
env["SLURM_CONF"] = f"{tmp}/slurm.conf"
for name in [n for n in env if n.startswith("SLURM_") and n != "SLURM_CONF"]:
    del env[name]  # a Slurm job around the test is not the one made here


def slurm(*args, timeout=30):
    return subprocess.run(list(args), capture_output=True, text=True, env=env, timeout=timeout)


def start_daemon(name, *args):
    log = f"{tmp}/{name}.out"
    daemons.append((subprocess.Popen([daemon_path(name), *args], stdout=open(log, "w"), stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL, env=env, start_new_session=True), log))


try:
    for d in ("state", "spool", "runs"):
        Path(tmp, d).mkdir()
    key = Path(tmp, "munge.key")
    key.write_bytes(os.urandom(1024))
    key.chmod(0o400)
    # --force: the folder sits under the world-writable /tmp, which munged otherwise refuses.
    start_daemon("munged", "--foreground", "--force", f"--socket={tmp}/munge.socket", f"--key-file={key}",
                 f"--pid-file={tmp}/munged.pid", f"--log-file={tmp}/munged.log", f"--seed-file={tmp}/munged.seed")
    wait_for("munged's socket", lambda: Path(tmp, "munge.socket").exists(), daemons, time.monotonic() + 30)
    ctld_port, slurmd_port = free_ports(2)
    Path(env["SLURM_CONF"]).write_text(SLURM_CONF.format(pid=os.getpid(), node=NODE, tmp=tmp, cpus=max(os.cpu_count(), RANKS),
                                                         ctld_port=ctld_port, slurmd_port=slurmd_port))
    start_daemon("slurmctld", "-D", "-i")  # -i: no state from an earlier run
    start_daemon("slurmd", "-D", "-N", NODE)

    def node_idle():
        r = slurm("sinfo", "--noheader", "--nodes", NODE, "--format=%t")
        return r.returncode == 0 and r.stdout.strip() == "idle"
    wait_for(f"sinfo shows node {NODE} idle", node_idle, daemons, time.monotonic() + 30)
    print(f"ok: slurmctld and slurmd up, node {NODE} idle")

    env.update(ZONESIM_ROOT=str(h.SOURCE_DIR), ZONESIM_RUNS=f"{tmp}/runs", ZONESIM_SECONDS=str(SECONDS),
               ZONESIM_PLAYERS=str(PLAYERS))
    # One node, RANKS zone ranks, and the gateway and the players beside them (srun --overlap).
    try:
        job = slurm("sbatch", "--wait", "--parsable", "--nodes=1", f"--ntasks-per-node={RANKS}",
                    "--time=2", f"--output={tmp}/job-%j.out", f"--chdir={tmp}",
                    h.SOURCE_DIR / "deploy/zonesim.sbatch", "scenes/test_e2e.yaml", timeout=150)
    except subprocess.TimeoutExpired:
        h.fail("sbatch --wait deploy/zonesim.sbatch: the job had not ended after 150 s\n"
               + "".join(h.tail(p, 20) for p in sorted(Path(tmp).glob("job-*.out"))))
    outputs = sorted(Path(tmp).glob("job-*.out"))
    job_log = outputs[0].read_text(errors="replace") if outputs else ""
    if job.returncode != 0:
        h.fail(f"sbatch --wait deploy/zonesim.sbatch: exit {job.returncode} {job.stderr.strip()}\n{job_log[-4000:]}")
    job_id = job.stdout.strip().split(";")[0]
    h.check(job_id.isdigit(), f"job {job_id} ran deploy/zonesim.sbatch and ended with exit 0")
    # Steps: the launcher's probe (nproc), the gateway, the fleet. On one node mpirun starts the
    # ranks itself: Open MPI needs no daemon on its own node, so no srun of orted here.
    steps = Path(tmp, "slurmd.log").read_text(errors="replace").count(f"launch task StepId={job_id}.")
    h.check(steps >= 3, f"slurmd launched the probe, the gateway and the fleet as job steps ({steps} steps)")
    run = Path(tmp, "runs", f"slurm-{job_id}")
    h.check((run / "slurm.cluster").is_file(), f"the script wrote its cluster file into {run}")
    h.check(f"reach = slurm {NODE}" in (run / "slurm.cluster").read_text(),
            f"its host is node {NODE}, reached through Slurm")

    zones = [h.load_json(run / f"zone_{r}_summary.json") for r in range(RANKS)]
    h.check({z["rank"] for z in zones} == set(range(RANKS)), f"{RANKS} ranks wrote their summaries")
    h.check(all(z["host"] == NODE for z in zones), f"every rank ran on {NODE} ({[z['host'] for z in zones]})")
    hosts.check_conservation(zones)
    h.check(f"gateway g1 on {NODE} listening on 0.0.0.0:" in job_log,
            f"the gateway started on {NODE}, bound to every interface")
    hosts.check_players(run, zones, PLAYERS)
finally:
    # Jobs first (slurmd would leave their slurmstepds running), then the daemons.
    if daemons and all(p.poll() is None for p, _ in daemons[1:]):
        slurm("scancel", "--full", "--partition=zs")
        deadline = time.monotonic() + 20
        while slurm("squeue", "--noheader").stdout.strip() and time.monotonic() < deadline:
            time.sleep(0.5)
    # A finished job's slurmstepd takes a moment to report to slurmd and exit.
    deadline = time.monotonic() + 15
    while slurmstepds() and time.monotonic() < deadline:
        time.sleep(0.2)
    for p, _ in reversed(daemons):
        h.stop(p, grace=10)
    for pid in slurmstepds():
        try:
            os.kill(pid, 9)
        except ProcessLookupError:
            pass
    deadline = time.monotonic() + 5
    while slurmstepds() and time.monotonic() < deadline:
        time.sleep(0.2)
    left = hosts.processes_under(tmp)
    shutil.rmtree(tmp, ignore_errors=True)
stepds_left = sorted(slurmstepds())
h.check(not left and not stepds_left,
        f"no process left behind (daemons, job steps, cluster) {left} {stepds_left}")
h.check(not Path(tmp).exists(), "configuration, key, state and run folder removed")
print("slurm cluster passed")
