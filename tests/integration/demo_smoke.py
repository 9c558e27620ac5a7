"""deploy/demo.sh end to end, short: 4 zones, a gateway and a few players on the e2e scene for a
few seconds, with the programs already built (ZONESIM_BIN: no apt-get, no build), its own run
folder and DDS domain; then report.py's report.json must hold figures that make sense."""
import tempfile
from pathlib import Path

import harness as h

PLAYERS = 12
SECONDS = 8

with tempfile.TemporaryDirectory(prefix="zs_demo_") as tmp:
    run = Path(tmp) / "run"
    env = h.base_env(h.free_dds_domain())
    env.update(ZONESIM_BIN=str(h.bin_dir()), ZONESIM_DEMO_SECONDS=str(SECONDS),
               ZONESIM_DEMO_PLAYERS=str(PLAYERS),
               ZONESIM_DEMO_SCENE=str(h.SOURCE_DIR / "scenes/test_e2e.yaml"))
    log = Path(tmp) / "demo.log"
    h.run(["bash", h.SOURCE_DIR / "deploy/demo.sh", run], log, env, timeout=300)
    text = log.read_text()
    h.check("zonesim run report" in text and "report.json written" in text, "the report was printed")
    r = h.load_json(run / "report.json")
    zones, t, clients = r["zones"], r["totals"], r["clients"]
    h.check(sorted(z["rank"] for z in zones) == [0, 1, 2, 3], "four zones reported")
    h.check(all(z["ticks"] > 0 for z in zones), "every zone ticked")
    h.check(t["entities_start"] == sum(z["entities_start"] for z in zones) > 0, "entities counted")
    h.check(t["conservation_failures"] == 0, "nothing lost or doubled")
    h.check(t["migrations"] > 0, f"entities migrated ({t['migrations']})")
    h.check(t["clients"] == PLAYERS and len(clients) == PLAYERS, f"{PLAYERS} players reported")
    h.check(t["avatar_handoffs"] >= 1, f"an avatar changed zone ({t['avatar_handoffs']})")
    h.check(t["client_handoffs_observed"] >= 1, f"clients were told of handoffs ({t['client_handoffs_observed']})")
    h.check(all(c["bytes_in_per_s"] > 0 and c["bytes_out_per_s"] > 0 and c["updates_per_s"] > 0
                for c in clients), "every player had traffic both ways and updates")
    # A datagram is at most 1400 bytes and carries at least one update; a player whose
    # bandwidth per update were outside that would be a units or counting error.
    per_update = t["bytes_in_per_s_mean"] / t["updates_per_s_mean"]
    h.check(1 < per_update < 1400, f"bytes per update plausible ({per_update:.1f})")
    h.check(t["bytes_in_per_s_mean"] < 1e6, f"download per player plausible ({t['bytes_in_per_s_mean']:.0f} B/s)")
    h.check(bool(r["gateway"]), "the gateway's last metrics line is in the report")
    page = (run / "report.html").read_text() if (run / "report.html").exists() else ""
    h.check("Zones" in page and "report_tick.png" in page and (run / "report_tick.png").exists(),
            "the report is also one HTML page, with its plots")
    h.check(f"deploy/inspect.sh {run}" in page and (run / "record").is_dir(),
            "the demo was recorded and its page says how to open the inspector on it")
print("demo smoke passed")
