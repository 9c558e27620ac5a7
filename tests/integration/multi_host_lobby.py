"""deploy/clusters/netns3-lobby.cluster through the launcher: three hosts as network namespaces,
4 zone ranks on h1 and h2, a gateway on h2 and one on h3 (both bound to 0.0.0.0, so they tell
the lobby their host's address), the lobby and the players on h3. Every player must log in,
the players must split evenly over the two hosts' gateways, each gateway must welcome the ones
sent to it and refuse no token, and nothing may be lost or left behind. Needs root."""
import tempfile
from pathlib import Path

import harness as h
import namespace_hosts as hosts

with tempfile.TemporaryDirectory(prefix="zs_multi_host_lobby_") as tmp:
    run = Path(tmp) / "run"
    log = Path(tmp) / "cluster.log"
    with hosts.namespaces(3):
        h.run(["bash", h.SOURCE_DIR / "deploy/cluster.sh",
               h.SOURCE_DIR / "deploy/clusters/netns3-lobby.cluster", run], log, hosts.cluster_env(), timeout=150)
    players = hosts.PLAYERS
    lobby = h.load_json(run / "lobby_summary.json")
    h.check(lobby["granted"] == players and lobby["dropped_total"] == 0,
            f"the lobby granted {players} tokens and dropped nothing ({lobby['granted']})")
    where = {g["address"].split(":")[0]: g["granted"] for g in lobby["gateways"]}
    h.check(where == {"10.77.0.2": players // 2, "10.77.0.3": players // 2},
            f"players split over the gateways at their hosts' addresses ({where})")
    for name in ("g1", "g2"):
        g = h.load_json(run / f"gateway-{name}" / "gateway_summary.json")
        refused = {k: v for k, v in g["dropped"].items() if k.startswith("token_") and v}
        h.check(g["sessions_opened"] == players // 2 and not refused,
                f"gateway {name} opened {players // 2} sessions, refused no token ({g['sessions_opened']}, {refused})")
    clients = h.load_json(run / "clients_summary.json")
    h.check(clients["totals"]["welcomed"] == players, "every player was welcomed")
    zones = [h.load_json(run / f"zone_{r}_summary.json") for r in range(4)]
    hosts.check_conservation(zones)
    h.check(not hosts.processes_under(run), f"no process left behind {hosts.processes_under(run)}")
print("multi-host lobby passed")
