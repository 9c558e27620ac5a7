"""What the multi-host tests share: hosts as network namespaces (deploy/netns.sh) that are gone
afterwards, pass or fail, and the checks of a run of 4 zone ranks on h1 and h2 with the gateway
and the players on h3 (deploy/clusters/netns3.cluster, ssh-netns3.cluster)."""
import contextlib
import os
import subprocess
from pathlib import Path

import harness as h

PLAYERS = 32
SECONDS = 8
NETNS = h.SOURCE_DIR / "deploy" / "netns.sh"
PREFIX = f"zsm{os.getpid()}"  # unique per run: parallel runs never share a namespace or link


def netns(*args):
    return subprocess.run(["bash", NETNS, *args], capture_output=True, text=True)


def processes_under(folder):
    """Processes whose command line names folder: what this run started, wherever it runs."""
    found = []
    for cmdline in Path("/proc").glob("[0-9]*/cmdline"):
        try:
            if str(folder).encode() in cmdline.read_bytes():
                found.append(cmdline.parent.name)
        except OSError:
            pass
    return found


@contextlib.contextmanager
def namespaces(count):
    """PREFIX-h1..hCOUNT at 10.77.0.1..COUNT; afterwards none of them, nor their links, is left."""
    up = netns("up", PREFIX, str(count))
    try:
        if up.returncode != 0:
            h.fail("this machine refuses network namespaces, veth pairs or bridges (the test needs "
                   f"root with CAP_NET_ADMIN): {NETNS} up {PREFIX} {count} said: {up.stderr.strip()}")
        yield [f"{PREFIX}-h{i}" for i in range(1, count + 1)]
    finally:
        netns("down", PREFIX)
        left = netns("check", PREFIX)
        h.check(left.returncode == 0, f"no namespace or interface left behind {left.stdout.strip()}")


def cluster_env():
    env = h.base_env(h.free_dds_domain())
    env.update(ZONESIM_NETNS=PREFIX, ZONESIM_CLUSTER_SCENE="scenes/test_e2e.yaml",
               ZONESIM_CLUSTER_SECONDS=str(SECONDS), ZONESIM_CLUSTER_PLAYERS=str(PLAYERS))
    return env


def check_run(run, log_text):
    zones = [h.load_json(run / f"zone_{r}_summary.json") for r in range(4)]
    host_of = {z["rank"]: z["host"] for z in zones}
    h.check(host_of == {0: "h1", 1: "h1", 2: "h2", 3: "h2"}, f"ranks 0, 1 ran on h1 and 2, 3 on h2 ({host_of})")

    def across(key):
        return sum(n for z in zones for to, n in z[key].items() if host_of[int(to)] != z["host"])
    h.check(across("migrated_out_to") > 0, f"entities migrated between hosts ({across('migrated_out_to')})")
    h.check(across("avatars_out_to") > 0, f"avatars handed off between hosts ({across('avatars_out_to')})")
    check_conservation(zones)
    h.check("gateway g1 on h3 listening on 0.0.0.0:" in log_text and "against 10.77.0.3:" in log_text,
            "the gateway bound every interface of h3 and the players reached it at h3's address")
    check_players(run, zones, PLAYERS)


def check_conservation(zones):
    """Every migration received once, and the entities and their ids conserved (slurm_cluster's
    one node shares these checks and check_players)."""
    out_total, in_total = sum(z["migrated_out"] for z in zones), sum(z["migrated_in"] for z in zones)
    h.check(out_total == in_total, f"every migration sent was received once ({out_total} out, {in_total} in)")
    h.check(all(z["conservation_checks"] > 0 and z["conservation_failures"] == 0 for z in zones),
            "count and id hash conserved at every check")
    h.check(sum(z["entities_start"] for z in zones) == sum(z["entities_end"] for z in zones),
            "the world ends with the entities it started with")


def check_players(run, zones, players):
    """That many players welcomed, given state and told of handoffs; every input forwarded applied once."""
    clients = h.load_json(run / "clients_summary.json")["clients"]
    h.check(len(clients) == players and all(c.get("avatar_id", 0) != 0 for c in clients),
            f"{players} players welcomed with an avatar")
    h.check(all(c["updates_per_s"] > 0 for c in clients), "every player received entity state")
    h.check(sum(c.get("handoffs", 0) for c in clients) >= 1, "players were told of handoffs")
    forwarded = h.load_json(run / "gateway_summary.json")["inputs_forwarded"]
    applied = sum(z["inputs_applied"] for z in zones)
    unroutable = sum(z["inputs_unroutable"] for z in zones)
    duplicate = sum(z["inputs_duplicate"] for z in zones)
    skipped = sum(z["inputs_skipped"] for z in zones)
    h.check(forwarded > 0 and applied + unroutable == forwarded and duplicate == 0 and skipped == 0,
            f"no input lost or doubled: applied {applied} + after leaving {unroutable} == forwarded "
            f"{forwarded}, {duplicate} duplicate, {skipped} skipped")
