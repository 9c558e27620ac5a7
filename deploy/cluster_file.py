"""Cluster files for deploy/cluster.sh: reading, checking and the plan of what runs where.

The cluster file is INI (sections and `key = value`, `#` comments); values may use ${VAR} and
${VAR:-default} from the environment. Relative paths are relative to the source folder.

  [cluster]   scene, duration (seconds of player traffic), network (CIDR that MPI's TCP uses,
              needed with several hosts), btl, yield (auto | on | off), dds_domain (default:
              $ZONESIM_DDS_DOMAIN or random), truth_every, zone_args, client_args,
              shared_storage (yes | no: copy each ssh host's run folder back at the end),
              ssh_options (added to every ssh the launcher and Open MPI's daemons run, e.g.
              -i KEY -o UserKnownHostsFile=/dev/null; ssh's own ~/.ssh/config is the other way),
              supervise (no, or zones and/or gateways, comma-separated. zones: a zone job that
              died, lost a rank on this machine or hung is restarted from its newest checkpoint
              in a new cluster epoch while gateways and players stay; gateways: a gateway that
              died is restarted on its address, and its players resume there with the token
              of their Welcome, as the same players with the same avatars), checkpoint_every
              (ticks between checkpoints, default 60 when supervising), hang_s (a zone job whose
              metrics stay unwritten this long is hung, default 10), restart_zones (the rank count
              of restarted jobs, default the same), ledger (where zones commit players'
              transactions: sqlite, the default where every zone host is this machine, a file
              ledger.sqlite in the run folder that all ranks share; sqlite:PATH; postgres:CONNINFO;
              none, the default across machines, where one file cannot be shared safely),
              record (no | yes: zones and gateways write a recording of every tick into the
              run folder's record/ for deploy/inspect.sh; a restarted zone job into
              record/epoch-N/)
  [host NAME] reach (local | netns NAMESPACE | ssh [USER@]HOST | slurm NODE), address (IPv4 on
              the cluster network; default 127.0.0.1 for local, else NAME resolved), zones
              (ranks there, default 0), cores (default: nproc there)
  [gateway NAME]  host, bind (ADDR[:PORT], default the host's address), id (default 1, 2, ...)
  [lobby NAME]    (at most one) host, bind (ADDR[:PORT], default the host's address), args: the
              players log in there for a connect token to the least-loaded gateway; the
              launcher writes a random cluster key into the run folder and starts every
              gateway with it, so a gateway then takes only players the lobby sent
  [fleet NAME]    host, gateway (not with a lobby: its players go where the lobby sends them),
              players, args

Every mistake is a ClusterError whose message names the file, the section and the key.
"""
import configparser
import ipaddress
import os
import random
import re
import shlex
import socket
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KEYS = {
    "cluster": {"scene", "duration", "network", "btl", "yield", "dds_domain", "truth_every",
                "zone_args", "client_args", "shared_storage", "ssh_options", "supervise",
                "checkpoint_every", "hang_s", "restart_zones", "ledger", "record"},
    "host": {"reach", "address", "zones", "cores"},
    "gateway": {"host", "bind", "id", "args"},
    "lobby": {"host", "bind", "args"},
    "fleet": {"host", "gateway", "players", "args"},
}
REACHES = ("local", "netns", "ssh", "slurm")
# Zones outlive the players by this much at most: they are stopped once the fleets are done.


class ClusterError(Exception):
    """A bad cluster file or a failed start: one line naming what and where."""


@dataclass
class Host:
    name: str
    reach: str
    target: str  # namespace, ssh destination or node; "" for local
    address: str
    zones: int
    cores: int = 0
    tmp: str = ""  # TMPDIR (Open MPI's session folder) of processes there; "" = theirs
    ssh_options: list = field(default_factory=list)  # [cluster] ssh_options, for reach = ssh

    def machine(self):
        """Hosts on the same machine share its cores."""
        return "this machine" if self.reach in ("local", "netns") else self.target

    def describe(self):
        return f"host {self.name} ({self.reach}{' ' + self.target if self.target else ''})"


@dataclass
class Gateway:
    name: str
    host: Host
    bind: str
    id: int
    args: list
    folder: Path = None
    proc: subprocess.Popen = None
    log: Path = None
    address: str = ""  # ADDR:PORT it listens on
    restarts: int = 0  # by the supervisor


@dataclass
class Lobby:
    name: str
    host: Host
    bind: str
    args: list
    proc: subprocess.Popen = None
    log: Path = None
    address: str = ""  # ADDR:PORT it listens on


@dataclass
class Fleet:
    name: str
    host: Host
    gateway: Gateway  # None with a lobby
    players: int
    args: list
    folder: Path = None
    proc: subprocess.Popen = None
    log: Path = None


@dataclass
class Cluster:
    scene: Path
    duration: float
    network: str
    btl: str
    yield_mode: str
    dds_domain: int
    truth_every: int
    zone_args: list
    client_args: list
    shared_storage: bool
    hosts: dict
    gateways: list
    fleets: list = field(default_factory=list)
    lobby: Lobby = None
    supervise: bool = False  # the zone job
    checkpoint_every: int = 0
    hang_s: float = 10
    restart_zones: int = 0  # 0: as many ranks as the first job
    supervise_gateways: bool = False
    ledger: str = "none"  # none, sqlite (the run folder's file), sqlite:PATH or postgres:CONNINFO
    record: bool = False  # zones and gateways write record/ (deploy/inspect.sh)


def expand(text, where):
    def var(m):
        name, default = m.group(1), m.group(3)
        if name in os.environ and os.environ[name] != "":
            return os.environ[name]
        if default is not None:
            return default
        raise ClusterError(f"{where}: ${{{name}}} is not set and has no default")
    return re.sub(r"\$\{([A-Za-z_][A-Za-z0-9_]*)(:-([^}]*))?\}", var, text)


def number(text, where, kind=int, low=0):
    try:
        v = kind(text)
    except ValueError:
        raise ClusterError(f"{where}: '{text}' is not a number")
    if v < low:
        raise ClusterError(f"{where}: {text} is below {low}")
    return v


def ipv4_of(name, where):
    try:
        return str(ipaddress.IPv4Address(name))
    except ValueError:
        pass
    try:
        return socket.gethostbyname(name)
    except OSError as e:
        raise ClusterError(f"{where}: cannot resolve '{name}' to an IPv4 address ({e})")


def load(path):
    parser = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",),
                                       comment_prefixes=("#",), empty_lines_in_values=False)
    try:
        with open(path) as f:
            parser.read_file(f)
    except (OSError, configparser.Error) as e:
        raise ClusterError(f"{path}: {str(e).splitlines()[0]}")
    sections = {"cluster": {}, "host": {}, "gateway": {}, "lobby": {}, "fleet": {}}
    for title in parser.sections():
        kind, _, name = title.partition(" ")
        where = f"{path} [{title}]"
        if kind not in sections or (kind == "cluster") != (name == ""):
            raise ClusterError(f"{where}: unknown section (expected [cluster], [host NAME], "
                               f"[gateway NAME], [lobby NAME] or [fleet NAME])")
        values = {k: expand(v, f"{where} {k}") for k, v in parser.items(title)}
        unknown = set(values) - KEYS[kind]
        if unknown:
            raise ClusterError(f"{where}: unknown key {sorted(unknown)[0]} (known: {', '.join(sorted(KEYS[kind]))})")
        if kind == "cluster":
            sections["cluster"] = values
        else:
            sections[kind][name] = (values, where)

    c = sections["cluster"]
    where = f"{path} [cluster]"
    if "scene" not in c:
        raise ClusterError(f"{where}: scene is missing")
    scene = (ROOT / c["scene"]).resolve()
    if not scene.is_file():
        raise ClusterError(f"{where} scene: no such file {scene}")
    hosts = {}
    for name, (v, w) in sections["host"].items():
        if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._-]*", name):
            raise ClusterError(f"{w}: host names are letters, digits, '.', '_' and '-'")
        reach = v.get("reach", "local").split()
        if not reach or reach[0] not in REACHES or (reach[0] == "local") != (len(reach) == 1) or len(reach) > 2:
            raise ClusterError(f"{w} reach: '{v.get('reach')}' (expected local, netns NAMESPACE, "
                               f"ssh [USER@]HOST or slurm NODE)")
        target = reach[1] if len(reach) == 2 else ""
        default_address = "127.0.0.1" if reach[0] == "local" else (target.split("@")[-1] if target else name)
        address = ipv4_of(v.get("address", default_address), f"{w} address")
        hosts[name] = Host(name, reach[0], target, address, number(v.get("zones", "0"), f"{w} zones"),
                           number(v.get("cores", "0"), f"{w} cores"))
    if not hosts:
        raise ClusterError(f"{path}: no [host NAME] section")
    try:
        ssh_options = shlex.split(c.get("ssh_options", ""))
    except ValueError as e:
        raise ClusterError(f"{where} ssh_options: {e}")
    for h in hosts.values():
        h.ssh_options = ssh_options if h.reach == "ssh" else []
    reaches = {h.reach for h in hosts.values()}
    if sum(h.reach == "local" for h in hosts.values()) > 1:
        raise ClusterError(f"{path}: more than one host with reach = local")
    if "slurm" in reaches and reaches - {"slurm", "local"}:
        raise ClusterError(f"{path}: slurm hosts cannot be mixed with netns or ssh hosts")
    if sum(h.zones for h in hosts.values()) == 0:
        raise ClusterError(f"{path}: no host runs zones (zones = N)")

    def host_of(v, w):
        if v.get("host") not in hosts:
            raise ClusterError(f"{w} host: '{v.get('host')}' is not a [host NAME] of this file")
        return hosts[v["host"]]

    gateways = {}
    for i, (name, (v, w)) in enumerate(sections["gateway"].items()):
        h = host_of(v, w)
        gateways[name] = Gateway(name, h, v.get("bind", h.address), number(v.get("id", str(i + 1)), f"{w} id", low=1),
                                 shlex.split(v.get("args", "")))
    lobby = None
    if len(sections["lobby"]) > 1:
        raise ClusterError(f"{path}: more than one [lobby NAME] section (one lobby per cluster)")
    for name, (v, w) in sections["lobby"].items():
        if not gateways:
            raise ClusterError(f"{w}: a lobby needs at least one [gateway NAME] to send players to")
        h = host_of(v, w)
        lobby = Lobby(name, h, v.get("bind", h.address), shlex.split(v.get("args", "")))
    fleets = []
    for name, (v, w) in sections["fleet"].items():
        h = host_of(v, w)
        if lobby is not None:
            if "gateway" in v:
                raise ClusterError(f"{w} gateway: with a [lobby] the players log in there and go "
                                   f"to the gateway it names; remove this key")
            fleets.append(Fleet(name, h, None, number(v.get("players", "32"), f"{w} players", low=1),
                                shlex.split(v.get("args", ""))))
            continue
        g = v.get("gateway", next(iter(gateways), None) if len(gateways) == 1 else None)
        if g not in gateways:
            raise ClusterError(f"{w} gateway: '{v.get('gateway')}' is not a [gateway NAME] of this file")
        fleets.append(Fleet(name, h, gateways[g], number(v.get("players", "32"), f"{w} players", low=1),
                            shlex.split(v.get("args", ""))))
    domain = os.environ.get("ZONESIM_DDS_DOMAIN") or c.get("dds_domain", "auto")
    # Domains 1-90: their ports (7400 + 250 d + [0, 250)) lie below the ephemeral range, so no
    # player or gateway socket can draw one and receive Cyclone's discovery packets.
    domain = random.randint(1, 90) if domain == "auto" else number(domain, f"{where} dds_domain")
    network = c.get("network", "")
    if network:
        try:
            ipaddress.IPv4Network(network, strict=False)
        except ValueError:
            raise ClusterError(f"{where} network: '{network}' is not an IPv4 network (a.b.c.d/n)")
    if len(hosts) > 1 and not network and reaches != {"slurm"}:
        raise ClusterError(f"{where}: network (a.b.c.d/n) is needed with several hosts, so MPI "
                           f"uses the cluster network and no other interface")
    yield_mode = c.get("yield", "auto")
    if yield_mode not in ("auto", "on", "off"):
        raise ClusterError(f"{where} yield: '{yield_mode}' (expected auto, on or off)")
    storage = c.get("shared_storage", "yes")
    if storage not in ("yes", "no"):
        raise ClusterError(f"{where} shared_storage: '{storage}' (expected yes or no)")
    supervise = {w for w in re.split(r"[\s,]+", c.get("supervise", "no")) if w}
    if supervise != {"no"} and not supervise <= {"zones", "gateways"}:
        raise ClusterError(f"{where} supervise: '{c.get('supervise')}' (expected no, or zones and/or "
                           f"gateways, comma-separated)")
    restart_zones = number(c.get("restart_zones", "0"), f"{where} restart_zones")
    if restart_zones and len([h for h in hosts.values() if h.zones]) > 1:
        raise ClusterError(f"{where} restart_zones: only for zones on one host")
    one_machine = all(h.reach in ("local", "netns") for h in hosts.values() if h.zones)
    ledger = c.get("ledger", "sqlite" if one_machine else "none")
    backend, _, target = ledger.partition(":")
    if ledger not in ("none", "sqlite") and not (backend in ("sqlite", "postgres") and target):
        raise ClusterError(f"{where} ledger: '{ledger}' (expected none, sqlite, sqlite:PATH or "
                           f"postgres:CONNINFO)")
    if ledger == "sqlite" and not one_machine:
        raise ClusterError(f"{where} ledger: sqlite in the run folder needs every zone host on this "
                           f"machine (each ssh or slurm host would write its own file); use "
                           f"postgres:CONNINFO")
    record = c.get("record", "no")
    if record not in ("yes", "no"):
        raise ClusterError(f"{where} record: '{record}' (expected yes or no)")
    return Cluster(scene, number(c.get("duration", "20"), f"{where} duration", float, 1), network,
                   c.get("btl", ""), yield_mode, domain, number(c.get("truth_every", "0"), f"{where} truth_every"),
                   shlex.split(c.get("zone_args", "")), shlex.split(c.get("client_args", "")),
                   storage == "yes", hosts, list(gateways.values()), fleets, lobby,
                   "zones" in supervise,
                   number(c.get("checkpoint_every", "60" if "zones" in supervise else "0"), f"{where} checkpoint_every"),
                   number(c.get("hang_s", "10"), f"{where} hang_s", float, 1), restart_zones,
                   "gateways" in supervise, ledger, record == "yes")


def plan(cluster):
    """What runs where, one line each."""
    lines = [f"scene {cluster.scene}, {cluster.duration:g} s of players, DDS domain {cluster.dds_domain}"
             + (f", network {cluster.network}" if cluster.network else "")]
    if cluster.supervise:
        lines.append(f"supervised: a dead zone job, or one silent for {cluster.hang_s:g} s, restarts from its "
                     f"newest checkpoint (every {cluster.checkpoint_every} ticks)"
                     + (f" on {cluster.restart_zones} ranks" if cluster.restart_zones else ""))
    if cluster.supervise_gateways:
        lines.append("supervised: a dead gateway restarts on its address; its players resume there")
    lines.append("ledger: " + {"none": "none (players' transactions fail with that reason)",
                               "sqlite": "sqlite, ledger.sqlite in the run folder"}.get(cluster.ledger, cluster.ledger))
    if cluster.record:
        lines.append("recorded: zones and gateways write record/ in the run folder (deploy/inspect.sh)")
    for h in cluster.hosts.values():
        lines.append(f"{h.describe()} at {h.address}: {h.zones} zone ranks")
    for g in cluster.gateways:
        lines.append(f"gateway {g.name} (id {g.id}) on {g.host.name}, --bind {g.bind}")
    if cluster.lobby:
        lines.append(f"lobby {cluster.lobby.name} on {cluster.lobby.host.name}, --bind {cluster.lobby.bind}; "
                     f"gateways take its connect tokens only")
    for f in cluster.fleets:
        to = f"logging in at lobby {cluster.lobby.name}" if f.gateway is None else f"to gateway {f.gateway.name}"
        lines.append(f"fleet {f.name} on {f.host.name}: {f.players} players {to}")
    return "\n".join(lines)
