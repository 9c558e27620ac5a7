"""Login through the lobby, end to end with real processes: deploy/clusters/lobby.cluster (zone
ranks, two gateways started with the cluster key, a lobby) and a fleet that logs in at the
lobby. Every player must be granted a token, spread evenly over the two gateways (the lobby
counts grants in flight between load reports), and welcomed by the gateway it was sent to,
which refuses nothing."""
import tempfile
from pathlib import Path

import harness as h

PLAYERS = 8
SECONDS = 6

with tempfile.TemporaryDirectory(prefix="zs_lobby_") as tmp:
    run = Path(tmp) / "run"
    env = h.base_env(h.free_dds_domain())
    env.update(ZONESIM_BIN=str(h.bin_dir()), ZONESIM_CLUSTER_SECONDS=str(SECONDS),
               ZONESIM_CLUSTER_PLAYERS=str(PLAYERS), ZONESIM_CLUSTER_ZONES="2",
               ZONESIM_CLUSTER_SCENE=str(h.SOURCE_DIR / "scenes/test_e2e.yaml"))
    log = Path(tmp) / "cluster.log"
    h.run(["python3", h.SOURCE_DIR / "deploy/cluster.py",
           h.SOURCE_DIR / "deploy/clusters/lobby.cluster", run], log, env, timeout=300)
    h.check("lobby login on here listening on" in log.read_text(), "the lobby started")
    fleet_log = (run / "fleet-players.log").read_text()
    h.check(f"clients logged in {PLAYERS} of {PLAYERS} through lobby" in fleet_log,
            "every player logged in")
    lobby = h.load_json(run / "lobby_summary.json")
    h.check(lobby["granted"] == PLAYERS, f"the lobby granted {PLAYERS} tokens ({lobby['granted']})")
    h.check(lobby["dropped_total"] == 0, "the lobby dropped nothing")
    granted = sorted(g["granted"] for g in lobby["gateways"])
    h.check(granted == [PLAYERS // 2, PLAYERS // 2], f"the players spread over both gateways ({granted})")
    for name in ("g1", "g2"):
        g = h.load_json(run / f"gateway-{name}" / "gateway_summary.json")
        h.check(g["sessions_opened"] == PLAYERS // 2,
                f"gateway {name} opened a session per player sent there ({g['sessions_opened']})")
        refused = {k: v for k, v in g["dropped"].items() if k.startswith("token_") and v}
        h.check(not refused, f"gateway {name} refused no token ({refused})")
        h.check(g["welcomes"] >= PLAYERS // 2, f"gateway {name} welcomed its players")
    clients = h.load_json(run / "clients_summary.json")
    h.check(clients["totals"]["welcomed"] == PLAYERS, "every player was welcomed")
print("lobby login passed")
