"""Three hosts as network namespaces of this machine, each with its own address on a bridge
and its own hostname, run deploy/clusters/netns3.cluster through the launcher: 4 zone ranks
over h1 and h2 (mpirun with Open MPI's TCP transport between the namespaces), the gateway and 32
players on h3, DDS between them by unicast discovery. Entities and avatars must cross between
ranks on different hosts with nothing lost, doubled or skipped, players must get state, and no
process, namespace or interface may be left, pass or fail. Needs root (CAP_NET_ADMIN)."""
import os
import subprocess
import tempfile
from pathlib import Path

import harness as h

PLAYERS = 32
SECONDS = 8
NETNS = h.SOURCE_DIR / "deploy" / "netns.sh"
PREFIX = f"zsm{os.getpid()}"  # unique per run: parallel runs never share a namespace or link


def netns(*args):
    return subprocess.run(["bash", NETNS, *args, ], capture_output=True, text=True)


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


def check_run(run, log_text):
    zones = [h.load_json(run / f"zone_{r}_summary.json") for r in range(4)]
    host_of = {z["rank"]: z["host"] for z in zones}
    h.check(host_of == {0: "h1", 1: "h1", 2: "h2", 3: "h2"}, f"ranks 0, 1 ran on h1 and 2, 3 on h2 ({host_of})")

    def across(key):
        return sum(n for z in zones for to, n in z[key].items() if host_of[int(to)] != z["host"])
    h.check(across("migrated_out_to") > 0, f"entities migrated between hosts ({across('migrated_out_to')})")
    h.check(across("avatars_out_to") > 0, f"avatars handed off between hosts ({across('avatars_out_to')})")
    out_total, in_total = sum(z["migrated_out"] for z in zones), sum(z["migrated_in"] for z in zones)
    h.check(out_total == in_total, f"every migration sent was received once ({out_total} out, {in_total} in)")
    h.check(all(z["conservation_checks"] > 0 and z["conservation_failures"] == 0 for z in zones),
            "count and id hash conserved at every check")
    h.check(sum(z["entities_start"] for z in zones) == sum(z["entities_end"] for z in zones),
            "the world ends with the entities it started with")

    h.check("gateway g1 on h3 listening on 0.0.0.0:" in log_text and "against 10.77.0.3:" in log_text,
            "the gateway bound every interface of h3 and the players reached it at h3's address")
    clients = h.load_json(run / "clients_summary.json")["clients"]
    h.check(len(clients) == PLAYERS and all(c.get("avatar_id", 0) != 0 for c in clients),
            f"{PLAYERS} players welcomed with an avatar")
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


with tempfile.TemporaryDirectory(prefix="zs_multi_host_") as tmp:
    run = Path(tmp) / "run"
    log = Path(tmp) / "cluster.log"
    up = netns("up", PREFIX, "3")
    try:
        if up.returncode != 0:
            h.fail("this machine refuses network namespaces, veth pairs or bridges (the test needs "
                   f"root with CAP_NET_ADMIN): {NETNS} up {PREFIX} 3 said: {up.stderr.strip()}")
        env = h.base_env(h.free_dds_domain())
        env.update(ZONESIM_NETNS=PREFIX, ZONESIM_CLUSTER_SCENE="scenes/test_e2e.yaml",
                   ZONESIM_CLUSTER_SECONDS=str(SECONDS), ZONESIM_CLUSTER_PLAYERS=str(PLAYERS))
        h.run(["bash", h.SOURCE_DIR / "deploy/cluster.sh", h.SOURCE_DIR / "deploy/clusters/netns3.cluster", run],
              log, env, timeout=150)
        check_run(run, log.read_text())
    finally:
        netns("down", PREFIX)
    left = netns("check", PREFIX)
    h.check(left.returncode == 0, f"no namespace or interface left behind {left.stdout.strip()}")
    h.check(not processes_under(run), f"no process left behind {processes_under(run)}")
print("multi-host passed")
