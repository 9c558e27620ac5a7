#!/usr/bin/env python3
"""Starts a zonesim cluster from one cluster file: the zone ranks with mpirun over a generated
hostfile, the gateways and the client fleets on their hosts; gathers every process's metrics into
one run folder and prints deploy/report.py's report. Called by deploy/cluster.sh (which builds
first when ZONESIM_BIN is not set); usage: cluster.py CLUSTER_FILE [RUN_DIR], or
cluster.py --dry-run CLUSTER_FILE to check the file and print what would run where.

The format is in deploy/cluster_file.py.

Hosts that share cores (processes on one machine, namespaces included, beyond its cores) get
mpi_yield_when_idle: Open MPI only knows the slots it is given and otherwise busy-polls, so a
collective waits a scheduler slice for every descheduled rank (24 ms ticks instead of 0.9 ms
for 4 ranks in 2 namespaces on 2 cores, issue 13).
"""
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cluster_file import ROOT, ClusterError, load, plan  # noqa: E402  (deploy/cluster_file.py)
import process_group  # noqa: E402  (deploy/process_group.py)

# Zones outlive the players by this much at most: they are stopped once the fleets are done.
ZONE_SAFETY_S = 300
DEBIAN_PYTHON = "/usr/bin/python3"  # where python3-matplotlib is (report_html.py's plots)
# The line a zonesim program writes before it exits on an error ("zone_node: what went wrong").
OWN_ERROR = re.compile(r"^(zone_node|gateway|client_stub|lobby): ")


# A command run over ssh without a terminal is not signalled when its connection goes: a SIGTERM
# to the local ssh stops only ssh, and the gateway would run on, its summary unwritten. So a
# process started over ssh watches the ssh's stdin, which the launcher holds open: at its end
# (the launcher closes it to stop the process, or the launcher died) the process gets SIGTERM.
STOP_AT_EOF = ('exec 3<&0 </dev/null; "$@" 3<&- & pid=$!; '
               '(while read -r _ <&3; do :; done; kill -TERM "$pid" 2>/dev/null) & watch=$!; '
               'wait "$pid"; rc=$?; kill "$watch" 2>/dev/null; exit "$rc"')


def ssh_argv(host):
    return ["ssh", "-o", "BatchMode=yes", *host.ssh_options, host.target]


def on_host(host, argv, env=None, stop_at_eof=False):
    """argv run on host, with env (a dict) set there. stop_at_eof (ssh, slurm): SIGTERM it when
    the stdin of the returned command ends (STOP_AT_EOF)."""
    env = dict(env or {})
    if host.tmp:
        env["TMPDIR"] = host.tmp
    assignments = [f"{k}={v}" for k, v in env.items()]
    argv = [str(a) for a in argv]
    if host.reach == "local":
        return ["env", *assignments, *argv]
    if host.reach == "netns":
        # Its own hostname (a UTS namespace) as well as its own network: Open MPI names session
        # folders and shared-memory segments after the host, and two daemons that think they
        # are the same host collide (an orted crashed in hwloc's topology write, issue 13).
        return ["ip", "netns", "exec", host.target, "unshare", "--uts", "sh", "-c",
                'hostname "$0" && exec "$@"', host.name, "env", *assignments, *argv]
    if host.reach == "ssh":
        command = ["env", *assignments, *argv]
        if stop_at_eof:
            command = ["sh", "-c", STOP_AT_EOF, "sh", *command]
        return [*ssh_argv(host), f"cd {shlex.quote(str(ROOT))} && exec {shlex.join(command)}"]
    # srun answers a SIGTERM by killing the step (SIGKILL after KillWait), so a gateway would
    # write no summary; srun hands its stdin to the task, so STOP_AT_EOF works as over ssh.
    command = ["env", *assignments, *argv]
    if stop_at_eof:
        command = ["sh", "-c", STOP_AT_EOF, "sh", *command]
    return ["srun", "--nodes=1", "--ntasks=1", "--overlap", "-w", host.target, *command]


def mpi_agent(cluster, path):
    """mpirun's plm_rsh_agent: `agent HOST COMMAND...` runs COMMAND (a shell line) on HOST."""
    lines = ["#!/bin/sh", "# Written by deploy/cluster.py: starts Open MPI's daemon on a host of the cluster file.",
             'host="$1"; shift', 'case "$host" in']
    for h in cluster.hosts.values():
        if h.reach == "slurm":
            continue  # Open MPI starts its daemons with srun itself
        if h.reach == "ssh":  # as Open MPI calls ssh by default
            lines.append(f"  {shlex.quote(h.name)}) exec {shlex.join(ssh_argv(h))} \"$@\" ;;")
            continue
        lines.append(f"  {shlex.quote(h.name)}) exec {shlex.join(on_host(h, ['sh', '-c']))} \"$*\" ;;")
    lines += ['  *) echo "mpi agent: $host is not a host of the cluster file" >&2; exit 1 ;;', "esac"]
    path.write_text("\n".join(lines) + "\n")
    path.chmod(0o755)


def dds_config(host, peers, max_index):
    peer_lines = "\n".join(f'        <Peer address="{p}"/>' for p in peers)
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<!-- Written by deploy/cluster.py for host {host.name}: its cluster address only, unicast
     discovery to every host that runs zones or gateways (multicast is often filtered between
     hosts and is off), and participant indices enough for the DDS processes of one host. -->
<CycloneDDS xmlns="https://cdds.io/config">
  <Domain Id="any">
    <General>
      <Interfaces>
        <NetworkInterface address="{host.address}"/>
      </Interfaces>
      <AllowMulticast>false</AllowMulticast>
      <MaxMessageSize>65500B</MaxMessageSize>
    </General>
    <Discovery>
      <ParticipantIndex>auto</ParticipantIndex>
      <MaxAutoParticipantIndex>{max_index}</MaxAutoParticipantIndex>
      <LeaseDuration>3 s</LeaseDuration>
      <Peers>
{peer_lines}
      </Peers>
    </Discovery>
    <Tracing>
      <Verbosity>warning</Verbosity>
      <OutputFile>stderr</OutputFile>
    </Tracing>
  </Domain>
</CycloneDDS>
"""


class Launch:
    def __init__(self, cluster, run_dir, bin_dir):
        self.c = cluster
        self.run = run_dir
        self.bin = bin_dir
        self.procs = []  # (Popen, what, log), stopped in reverse order
        self.zones = None
        self.tmp = None
        self.key = None  # the cluster's key file: connect tokens (with a lobby) and resume tokens
        self.epoch = 0  # the cluster epoch of the zone job running (supervise: one more per restart)

    def log(self, msg):
        print(msg, flush=True)

    def start(self, what, argv, log_path, held_stdin=False):
        """held_stdin: a pipe that stop() closes to end the process (STOP_AT_EOF)."""
        log = open(log_path, "w")
        p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT,
                             stdin=subprocess.PIPE if held_stdin else subprocess.DEVNULL,
                             start_new_session=True)
        self.procs.append((p, what, log_path))
        return p

    def fail(self, what, msg, log_path=None):
        shown = []
        if log_path and Path(log_path).exists():
            lines = Path(log_path).read_text(errors="replace").splitlines()
            # A rank's own error ("zone_node: ...") comes first, before mpirun's follow-on
            # warnings about the peers it took down, which alone fill the tail.
            shown = [l for l in lines[:-12] if OWN_ERROR.match(l)][:6] + lines[-12:]
        raise ClusterError(f"{what}: {msg}" + "".join("\n    " + l for l in shown))

    def probe_hosts(self):
        """Every host answers (nproc), or the start stops naming it."""
        for h in self.c.hosts.values():
            if h.reach in ("local", "netns"):
                h.tmp = str(Path(self.tmp) / h.name)
                Path(h.tmp).mkdir(parents=True, exist_ok=True)
            try:
                r = subprocess.run(on_host(h, ["nproc"]), capture_output=True, text=True, timeout=60)
            except (OSError, subprocess.TimeoutExpired) as e:
                raise ClusterError(f"{h.describe()}: cannot run a command there ({e})")
            if r.returncode != 0 or not r.stdout.strip().isdigit():
                msg = (r.stderr.strip().splitlines() or ["no output"])[-1]
                raise ClusterError(f"{h.describe()}: cannot run a command there ({msg})")
            h.cores = h.cores or int(r.stdout)

    def shared_cores(self):
        """Machines whose zone ranks, gateways and fleets outnumber their cores."""
        load, cores = {}, {}
        for h in self.c.hosts.values():
            m = h.machine()
            load[m] = load.get(m, 0) + h.zones
            cores[m] = min(cores.get(m, h.cores), h.cores)
        for p in self.c.gateways + self.c.fleets + ([self.c.lobby] if self.c.lobby else []):
            load[p.host.machine()] += 1
        return [f"{m}: {load[m]} processes on {cores[m]} cores" for m in load if load[m] > cores[m]]

    def write_dds_configs(self):
        hosts = list(self.c.hosts.values())
        if all(h.reach == "local" for h in hosts):
            return {h.name: ROOT / "deploy" / "cyclonedds.xml" for h in hosts}
        lobby_host = self.c.lobby.host if self.c.lobby else None
        users = {g.host.name for g in self.c.gateways} | {h.name for h in hosts if h.zones}
        users |= {lobby_host.name} if lobby_host else set()
        peers = sorted({self.c.hosts[n].address for n in users})
        per_host = [h.zones + sum(g.host is h for g in self.c.gateways) + (h is lobby_host) for h in hosts]
        # Cyclone probes every index up to the cap on every peer: enough for this cluster's
        # processes on one host, plus a few for tools (ddsls, ddsperf) run beside it.
        max_index = max(per_host) + 4
        folder = self.run / "dds"
        folder.mkdir(exist_ok=True)
        paths = {}
        for h in hosts:
            paths[h.name] = folder / f"{h.name}.xml"
            paths[h.name].write_text(dds_config(h, peers, max_index))
        return paths

    def start_zones(self, dds, ranks=None, restart=None):
        """The zone job; ranks: the count on the one zone host (a supervised restart may
        change it); restart: the checkpoint folder it continues from, in epoch self.epoch."""
        zone_hosts = [h for h in self.c.hosts.values() if h.zones]
        slots = {h.name: (ranks if ranks and len(zone_hosts) == 1 else h.zones) for h in zone_hosts}
        hostfile = self.run / "hostfile"
        hostfile.write_text("".join(f"{self.mpi_name(h)} slots={slots[h.name]}\n" for h in zone_hosts))
        mca = []
        if any(h.reach in ("netns", "ssh") for h in zone_hosts):
            agent = self.run / "mpi-agent.sh"
            mpi_agent(self.c, agent)
            mca += ["--mca", "plm", "rsh", "--mca", "plm_rsh_agent", str(agent)]
        if self.c.network:
            mca += ["--mca", "btl_tcp_if_include", self.c.network, "--mca", "oob_tcp_if_include", self.c.network]
        if self.c.btl:
            mca += ["--mca", "btl", self.c.btl]
        shared = self.shared_cores()
        if self.c.yield_mode == "on" or (self.c.yield_mode == "auto" and shared):
            why = "; ".join(shared) if shared else "yield = on"
            self.log(f"== hosts share cores ({why}): mpi_yield_when_idle 1")
            mca += ["--mca", "mpi_yield_when_idle", "1"]
        zone_argv = [self.bin / "zone_node", "--scene", self.c.scene, "--realtime",
                     "--duration", int(self.c.duration + ZONE_SAFETY_S), "--metrics", self.run,
                     "--dds-domain", self.c.dds_domain, "--truth-every", self.c.truth_every, *self.c.zone_args]
        if self.c.ledger != "none":
            zone_argv += ["--ledger", f"sqlite:{self.run / 'ledger.sqlite'}" if self.c.ledger == "sqlite"
                          else self.c.ledger]
        if self.c.checkpoint_every:
            zone_argv += ["--checkpoint-dir", self.run / "checkpoints", "--checkpoint-every", self.c.checkpoint_every]
        if self.epoch:
            zone_argv += ["--epoch", self.epoch] + (["--restart", restart] if restart else [])
        if self.c.record:
            record = self.run / "record" / (f"epoch-{self.epoch}" if self.epoch else "")
            zone_argv += ["--record", record]
        contexts = []
        for h in zone_hosts:
            contexts += [":"] if contexts else []
            contexts += ["-np", slots[h.name], "--host", f"{self.mpi_name(h)}:{slots[h.name]}",
                         "-x", f"CYCLONEDDS_URI=file://{dds[h.name]}", *zone_argv]
        argv = ["mpirun", "--hostfile", hostfile, "--bind-to", "none", *mca, *contexts]
        # mpirun runs where it reaches every daemon: inside the first host's namespace for a
        # namespace cluster, else here.
        first = zone_hosts[0]
        launch_argv = on_host(first, argv) if first.reach == "netns" else ["env", *([f"TMPDIR={first.tmp}"] if first.tmp else []), *map(str, argv)]
        suffix = f"-epoch{self.epoch}" if self.epoch else ""
        (self.run / f"zones{suffix}.cmd").write_text(shlex.join(map(str, launch_argv)) + "\n")
        self.zones_log = self.run / f"zones{suffix}.log"
        # Ranks of earlier jobs (killed, maybe not yet reaped) are never this job's.
        self.old_pids = self.local_rank_pids() if self.epoch else set()
        self.zones = self.start("zones (mpirun over " + ", ".join(h.name for h in zone_hosts) + ")",
                                launch_argv, self.zones_log)
        self.zones_started = time.monotonic()
        self.zones_started_unix = time.time()
        self.rank_pids = set()  # the job's local zone_node ranks, once all have started

    def zones_hung(self):
        """True when no rank has written a metrics line for hang_s (every rank writes one per
        tick, buffered: a stalled collective stops them all), or, before the job's first line,
        for 60 s (a restart reads its checkpoint first)."""
        files = list(self.run.glob("zone_*.jsonl"))
        newest = max((f.stat().st_mtime for f in files), default=0)
        since_start = time.monotonic() - self.zones_started
        if newest < self.zones_started_unix:
            return since_start > max(self.c.hang_s, 60)
        return time.time() - newest > self.c.hang_s

    def local_rank_pids(self):
        """Live (not zombie) zone_node processes on this machine started for this run."""
        out = subprocess.run(["pgrep", "-x", "zone_node"], capture_output=True, text=True).stdout.split()
        pids = set()
        for pid in out:
            try:
                stat = Path(f"/proc/{pid}/stat").read_text()
                if stat[stat.rindex(")") + 2] != "Z" and \
                        str(self.run) in Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace"):
                    pids.add(int(pid))
            except (OSError, ValueError, IndexError):
                pass
        return pids

    def local_rank_lost(self):
        """A zone_node rank of this job on this machine (local or netns hosts) has gone. mpirun
        takes about 2 s to end a job after a rank dies; the supervisor need not wait for that."""
        if any(h.reach in ("ssh", "slurm") for h in self.c.hosts.values() if h.zones):
            return False
        mine = self.local_rank_pids() - self.old_pids
        ranks = self.c.restart_zones if self.epoch and self.c.restart_zones else sum(h.zones for h in self.c.hosts.values())
        if not self.rank_pids:
            if len(mine) == ranks:
                self.rank_pids = mine
            return False
        return not self.rank_pids <= mine

    def supervise_zones(self, dds):
        """Restarts a zone job that died or hung from the newest complete checkpoint, in the
        next cluster epoch; gateways and players stay connected (gateway/gateway_epochs.cpp)."""
        died = self.zones.poll() is not None
        lost = not died and self.local_rank_lost()
        if not died and not lost and not self.zones_hung():
            return
        detected = time.monotonic()
        reason = (f"exited with {self.zones.returncode}" if died else "lost a rank" if lost
                  else f"hung (no metrics for {self.c.hang_s:g} s)")
        slot = next(i for i, p in enumerate(self.procs) if p[0] is self.zones)
        # A job that lost a rank or hung cannot finish a tick: its ranks are killed at once.
        process_group.stop(self.zones, 2 if died else 0)
        old = self.run / f"epoch-{self.epoch}"
        old.mkdir(exist_ok=True)
        for f in self.run.glob("zone_*"):
            f.rename(old / f.name)
        for f in self.run.glob("truth_*.csv"):
            f.rename(old / f.name)
        latest = self.run / "checkpoints" / "LATEST"
        restart = self.run / "checkpoints" if latest.exists() else None
        self.epoch += 1
        self.start_zones(dds, self.c.restart_zones or None, restart)
        self.procs[slot] = self.procs.pop()  # stopped first-started-last, as the job it replaces
        event = {"epoch": self.epoch, "reason": reason, "checkpoint": latest.read_text().strip() if restart else None,
                 "detected_unix": time.time(), "restart_s": round(time.monotonic() - detected, 3)}
        self.record({"kind": "zones", **event})
        self.log(f"== zones {reason}: restarted from {event['checkpoint'] or 'the scene'} as epoch {self.epoch}")

    def record(self, event):
        """One line of supervisor.jsonl: a restart, what it restarted and why."""
        with open(self.run / "supervisor.jsonl", "a") as f:
            f.write(json.dumps(event) + "\n")

    def supervise_gateways(self, dds):
        """Restarts a gateway that died on the address it listened on, with the cluster's key:
        its players say Hello there with their resume tokens and go on as themselves."""
        for g in self.c.gateways:
            if g.proc.poll() is None:
                continue
            detected = time.monotonic()
            reason = f"exited with {g.proc.returncode}"
            g.restarts += 1
            # The dead one's metrics stay beside the new one's, out of report.py's way.
            old = g.folder / f"before-restart-{g.restarts}"
            old.mkdir(exist_ok=True)
            for name in ("gateway.jsonl", "gateway_summary.json"):
                if (g.folder / name).exists():
                    (g.folder / name).rename(old / name)
            g.log.rename(old / g.log.name)
            # Its recording too: the restarted gateway writes a new one under the same name.
            recording = self.run / "record" / f"gateway_{g.id}.zsrec"
            if recording.exists():
                (self.run / "record" / f"before-restart-{g.name}-{g.restarts}").mkdir(exist_ok=True)
                recording.rename(self.run / "record" / f"before-restart-{g.name}-{g.restarts}" / recording.name)
            slot = next(i for i, p in enumerate(self.procs) if p[0] is g.proc)
            bind = g.bind.split(":")[0] + ":" + g.address.rsplit(":", 1)[1]
            self.launch_gateway(g, dds, bind)
            self.procs[slot] = self.procs.pop()
            address = self.wait_listening(f"{g.host.describe()}, gateway {g.name}", "gateway", g.proc, g.log)
            if address.rsplit(":", 1)[1] != g.address.rsplit(":", 1)[1]:
                self.fail(f"{g.host.describe()}, gateway {g.name}", f"restarted on {address}, not {g.address}", g.log)
            self.record({"kind": "gateway", "gateway": g.name, "restart": g.restarts, "reason": reason,
                         "detected_unix": time.time(), "restart_s": round(time.monotonic() - detected, 3)})
            self.log(f"== gateway {g.name} {reason}: restarted on {address} ({g.restarts}. restart)")

    def mpi_name(self, h):
        return "localhost" if h.reach == "local" else (h.target if h.reach == "slurm" else h.name)

    def folder(self, kind, name, count):
        """One process of its kind writes into the run folder itself (report.py's layout);
        several get a subfolder each."""
        f = self.run if count == 1 else self.run / f"{kind}-{name}"
        f.mkdir(parents=True, exist_ok=True)
        return f

    def launch_gateway(self, g, dds, bind):
        expect = sum(h.zones for h in self.c.hosts.values())
        # Every gateway signs resume tokens with the cluster's key and takes any of them back.
        argv = [self.bin / "gateway", "--scene", self.c.scene, "--bind", bind, "--dds-domain",
                self.c.dds_domain, "--gateway-id", g.id, "--metrics", g.folder, "--expect-zones", expect,
                "--duration", int(self.c.duration + ZONE_SAFETY_S), "--resume-key-file", self.key, *g.args]
        if self.c.record:
            argv += ["--record", self.run / "record"]
        if self.c.lobby:
            # The lobby tells players where the gateway is: one bound to every interface
            # names its host's cluster address.
            argv += ["--auth-key-file", self.key]
            if g.bind.split(":")[0] == "0.0.0.0":
                argv += ["--public-address", g.host.address]
        g.log = self.run / f"gateway-{g.name}.log"
        g.proc = self.start(f"{g.host.describe()}, gateway {g.name}",
                            on_host(g.host, argv, {"CYCLONEDDS_URI": f"file://{dds[g.host.name]}"}, stop_at_eof=True),
                            g.log, held_stdin=g.host.reach in ("ssh", "slurm"))

    def start_gateways(self, dds):
        for g in self.c.gateways:
            g.folder = self.folder("gateway", g.name, len(self.c.gateways))
            self.launch_gateway(g, dds, g.bind)
        for g in self.c.gateways:
            g.address = self.wait_listening(f"{g.host.describe()}, gateway {g.name}", "gateway",
                                            g.proc, g.log, watch_zones=True)
            self.log(f"== gateway {g.name} on {g.host.name} listening on {g.address}")

    def wait_listening(self, what, program, proc, log, watch_zones=False):
        """The address a started gateway or lobby prints as "PROGRAM listening on ADDR"; fails the
        run (naming `what`) if it exits first, if the zones do (watch_zones), or after 120 s."""
        deadline = time.monotonic() + 120  # a loaded 2-core machine can take long to start one
        while True:
            m = re.search(program + r" listening on (\S+)", log.read_text(errors="replace"))
            if m:
                return m.group(1)
            if proc.poll() is not None:
                self.fail(what, f"exited with {proc.returncode} before listening", log)
            elif watch_zones and self.zones.poll() is not None:
                self.fail(self.procs[0][1], f"exited with {self.zones.returncode}", self.zones_log)
            elif time.monotonic() > deadline:
                self.fail(what, "not listening after 120 s", log)
            time.sleep(0.1)

    def write_key(self):
        """The cluster's key: 32 random bytes in the run folder, copied to the hosts that do not
        share it (shared_storage = no) and run a gateway or the lobby."""
        self.key = self.run / "auth.key"
        fd = os.open(self.key, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        with os.fdopen(fd, "wb") as f:
            f.write(os.urandom(32))
        if self.c.shared_storage:
            return
        for h in {p.host.name: p.host for p in [*self.c.gateways, self.c.lobby] if p}.values():
            if h.reach in ("ssh", "slurm"):
                line = f"mkdir -p {shlex.quote(str(self.run))} && umask 077 && cat > {shlex.quote(str(self.key))}"
                with open(self.key, "rb") as f:
                    r = subprocess.run(on_host(h, ["sh", "-c", line]), stdin=f, capture_output=True, text=True)
                if r.returncode != 0:
                    raise ClusterError(f"{h.describe()}: cannot copy the cluster key there "
                                       f"({(r.stderr.strip().splitlines() or ['no output'])[-1]})")

    def start_lobby(self, dds):
        lobby = self.c.lobby
        argv = [self.bin / "lobby", "--bind", lobby.bind, "--auth-key-file", self.key,
                "--dds-domain", self.c.dds_domain, "--expect-gateways", len(self.c.gateways),
                "--metrics", self.run, "--duration", int(self.c.duration + ZONE_SAFETY_S), *lobby.args]
        lobby.log = self.run / f"lobby-{lobby.name}.log"
        what = f"{lobby.host.describe()}, lobby {lobby.name}"
        lobby.proc = self.start(what, on_host(lobby.host, argv, {"CYCLONEDDS_URI": f"file://{dds[lobby.host.name]}"},
                                              stop_at_eof=True),
                                lobby.log, held_stdin=lobby.host.reach in ("ssh", "slurm"))
        lobby.address = self.wait_listening(what, "lobby", lobby.proc, lobby.log)
        self.log(f"== lobby {lobby.name} on {lobby.host.name} listening on {lobby.address}")

    @staticmethod
    def reached_at(server):
        """ADDR:PORT players send to: one bound to every interface is reached at its host's address."""
        address, port = server.address.rsplit(":", 1)
        return f"{server.host.address if address == '0.0.0.0' else address}:{port}"

    def start_fleets(self):
        for f in self.c.fleets:
            f.folder = self.folder("fleet", f.name, len(self.c.fleets))
            server = f.gateway or self.c.lobby
            address, port = self.reached_at(server).rsplit(":", 1)
            option = "--gateway" if f.gateway else "--lobby"
            # A player whose gateway dies resumes there (restarted) or at the next of the others.
            fallbacks = [a for g in self.c.gateways if f.gateway and g is not f.gateway
                         for a in ("--fallback-gateway", self.reached_at(g))]
            argv = [self.bin / "client_stub", "--scene", self.c.scene, option, f"{address}:{port}",
                    "--players", f.players, "--duration", self.c.duration, "--metrics", f.folder,
                    "--summary", f.folder / "clients_summary.json", "--truth-every", self.c.truth_every,
                    *fallbacks, *self.c.client_args, *f.args]
            f.log = self.run / f"fleet-{f.name}.log"
            to = "against" if f.gateway else "logging in at lobby"
            self.log(f"== fleet {f.name} on {f.host.name}: {f.players} players for {self.c.duration:g} s {to} {address}:{port}")
            f.proc = self.start(f"{f.host.describe()}, fleet {f.name}", on_host(f.host, argv, stop_at_eof=True), f.log,
                                held_stdin=f.host.reach in ("ssh", "slurm"))

    def wait_fleets(self, dds):
        report = ROOT / "deploy" / "report.py"
        next_progress = time.monotonic() + 5
        # A cluster without fleets (players from elsewhere) runs for the duration.
        end = time.monotonic() + self.c.duration
        while (any(f.proc.poll() is None for f in self.c.fleets) if self.c.fleets else time.monotonic() < end):
            time.sleep(0.2)
            if self.c.supervise:
                self.supervise_zones(dds)
            if self.c.supervise_gateways:
                self.supervise_gateways(dds)
            for p, what, log in self.procs:
                if p not in (f.proc for f in self.c.fleets) and p.poll() is not None:
                    self.fail(what, f"exited with {p.returncode} while players played", log)
            if self.c.fleets and time.monotonic() >= next_progress and (self.c.fleets[0].folder / "clients.jsonl").exists():
                subprocess.run([sys.executable, report, "--progress", self.c.fleets[0].folder])
                next_progress += 5
        for f in self.c.fleets:
            if f.proc.returncode != 0:
                self.fail(f"{f.host.describe()}, fleet {f.name}", f"exited with {f.proc.returncode}", f.log)

    def stop(self, p, grace):
        # Over ssh or srun, ending its stdin SIGTERMs the remote process, and ssh or srun returns once
        # it is done.
        return process_group.stop(p, grace, close_stdin=p.stdin is not None)

    def finish(self):
        time.sleep(2)  # 60 ticks for the last goodbyes and despawns to reach the zones
        for g in self.c.gateways:
            self.stop(g.proc, 10)
        if self.c.lobby:
            self.stop(self.c.lobby.proc, 10)
        # SIGTERM: the ranks finish their tick and write their summaries; mpirun then reports
        # the signal in its own status, so the summaries are what is checked.
        self.stop(self.zones, 30)
        ranks = (self.c.restart_zones if self.epoch and self.c.restart_zones
                 else sum(h.zones for h in self.c.hosts.values()))
        if not self.c.shared_storage:
            self.fetch_remote_folders()
        written = len(list(self.run.glob("zone_*_summary.json")))
        if written != ranks:
            self.fail(self.procs[0][1], f"{written} of {ranks} ranks wrote their summary", self.zones_log)
        # A process that ran but wrote no summary would leave the report with a hole that looks
        # like a quiet run: name it instead.
        for g in self.c.gateways:
            if not (g.folder / "gateway_summary.json").exists():
                self.fail(f"{g.host.describe()}, gateway {g.name}", "wrote no gateway_summary.json", g.log)
        if self.c.lobby and not (self.run / "lobby_summary.json").exists():
            self.fail(f"{self.c.lobby.host.describe()}, lobby {self.c.lobby.name}", "wrote no lobby_summary.json",
                      self.c.lobby.log)
        for f in self.c.fleets:
            if not (f.folder / "clients_summary.json").exists():
                self.fail(f"{f.host.describe()}, fleet {f.name}", "wrote no clients_summary.json", f.log)

    def fetch_remote_folders(self):
        used = {p.host.name for p in self.c.gateways + self.c.fleets} | {h.name for h in self.c.hosts.values() if h.zones}
        used |= {self.c.lobby.host.name} if self.c.lobby else set()
        for h in (self.c.hosts[n] for n in sorted(used)):
            if h.reach in ("ssh", "slurm"):
                pack = subprocess.Popen(on_host(h, ["tar", "-C", self.run, "-cf", "-", "."]), stdout=subprocess.PIPE)
                subprocess.run(["tar", "-C", self.run, "-xf", "-", "--skip-old-files"], stdin=pack.stdout, check=False)
                pack.wait()

    def cleanup(self):
        for p, _, _ in reversed(self.procs):
            self.stop(p, 5)

    def go(self):
        self.run.mkdir(parents=True, exist_ok=True)
        # Short, so that Open MPI's unix socket paths under it stay within their 108 characters.
        self.tmp = tempfile.mkdtemp(prefix="zsc")
        try:
            self.probe_hosts()
            dds = self.write_dds_configs()
            self.log(f"== run folder: {self.run} (DDS domain {self.c.dds_domain}, hosts "
                     + ", ".join(f"{h.name}={h.address}" for h in self.c.hosts.values()) + ")")
            self.start_zones(dds)
            self.write_key()
            self.start_gateways(dds)
            if self.c.lobby:
                self.start_lobby(dds)
            time.sleep(2)  # let DDS discovery between zones and gateways settle before players ask for avatars
            self.start_fleets()
            self.wait_fleets(dds)
            self.finish()
        finally:
            self.cleanup()
            subprocess.run(["rm", "-rf", self.tmp])
        r = subprocess.run([sys.executable, ROOT / "deploy" / "report.py", self.run])
        if r.returncode != 0:
            raise ClusterError(f"report.py {self.run}: exited with {r.returncode}")
        # The same report as one page with plots: matplotlib is Debian's, for Debian's python3.
        page = subprocess.run([DEBIAN_PYTHON if Path(DEBIAN_PYTHON).exists() else sys.executable,
                               ROOT / "deploy" / "report_html.py", self.run])
        if page.returncode != 0:
            raise ClusterError(f"report_html.py {self.run}: exited with {page.returncode}")


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--dry-run":
        try:
            print(plan(load(sys.argv[2])))
        except ClusterError as e:
            sys.exit(f"cluster.sh: error: {e}")
        return
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: cluster.py CLUSTER_FILE [RUN_DIR] | cluster.py --dry-run CLUSTER_FILE")
    bin_dir = Path(os.environ.get("ZONESIM_BIN", ROOT / "build" / "bin"))
    run_dir = Path(sys.argv[2] if len(sys.argv) == 3 else ROOT / "runs" / time.strftime("cluster-%Y%m%d-%H%M%S")).resolve()
    # A signal ends the launch through the same clean-up as an error.
    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, lambda n, _: sys.exit(f"cluster.sh: stopped by signal {n}"))
    try:
        cluster = load(sys.argv[1])
        for prog in ("zone_node", "gateway", "client_stub") + (("lobby",) if cluster.lobby else ()):
            if not (bin_dir / prog).is_file():
                raise ClusterError(f"{bin_dir / prog}: not built (set ZONESIM_BIN or build first)")
        Launch(cluster, run_dir, bin_dir).go()
    except ClusterError as e:
        sys.exit(f"cluster.sh: error: {e}")


if __name__ == "__main__":
    main()
