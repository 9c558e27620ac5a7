"""Three hosts as network namespaces of this machine, each with its own address on a bridge
and its own hostname, run deploy/clusters/netns3.cluster through the launcher: 4 zone ranks
over h1 and h2 (mpirun with Open MPI's TCP transport between the namespaces), the gateway and 32
players on h3, DDS between them by unicast discovery. Entities and avatars must cross between
ranks on different hosts with nothing lost, doubled or skipped, players must get state, and no
process, namespace or interface may be left, pass or fail. Needs root (CAP_NET_ADMIN)."""
import tempfile
from pathlib import Path

import harness as h
import namespace_hosts as hosts

with tempfile.TemporaryDirectory(prefix="zs_multi_host_") as tmp:
    run = Path(tmp) / "run"
    log = Path(tmp) / "cluster.log"
    with hosts.namespaces(3):
        h.run(["bash", h.SOURCE_DIR / "deploy/cluster.sh", h.SOURCE_DIR / "deploy/clusters/netns3.cluster", run],
              log, hosts.cluster_env(), timeout=150)
        hosts.check_run(run, log.read_text())
    h.check(not hosts.processes_under(run), f"no process left behind {hosts.processes_under(run)}")
print("multi-host passed")
