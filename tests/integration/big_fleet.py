"""One client_stub drives 1,200 players: more sockets than the usual soft limit of 1,024 open
files, which the test sets for itself first, so the fleet has to raise it. Every player logs
in through a real lobby, is welcomed by a real gateway and sends inputs, and the summary
reports the fleet's own CPU per player-second. With a hard limit below what 1,200 sockets
need, client_stub refuses at once, in one line naming --players and the limit."""
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

import harness as h

PLAYERS = 1200
SECONDS = 6
SCENE = h.SOURCE_DIR / "scenes/test_big_fleet.yaml"
SOFT = 1024  # the usual default, below what PLAYERS sockets need

soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
if hard != resource.RLIM_INFINITY and hard < PLAYERS + 64:
    print(f"skipped: the hard open-file limit here ({hard}) is below {PLAYERS} players")
    sys.exit(77)

# Past the hard limit: the one-line refusal, before any socket or packet.
refused = subprocess.run(
    [str(h.bin_dir() / "client_stub"), "--scene", str(SCENE), "--gateway", "127.0.0.1:9",
     "--players", str(PLAYERS), "--duration", "1"],
    capture_output=True, text=True, timeout=60, env=h.base_env(),
    preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_NOFILE, (256, 512)))
lines = refused.stderr.strip().splitlines()
h.check(refused.returncode == 1 and len(lines) == 1 and f"--players {PLAYERS}" in lines[0]
        and "hard limit of 512" in lines[0],
        f"past the hard limit, one line naming --players and the limit ({refused.stderr.strip()})")

with tempfile.TemporaryDirectory(prefix="zs_fleet_") as tmp:
    out = Path(tmp)
    domain = h.free_dds_domain()
    env = h.base_env()
    key = out / "auth.key"
    key.write_bytes(bytes(range(7, 7 + 32)))
    zones = h.start(h.mpirun(1, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 600,
                             "--realtime", "--metrics", out, "--dds-domain", domain),
                    out / "zones.log", env)
    gateway = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--port", 0, "--port-file",
                       out / "gateway_port", "--dds-domain", domain, "--metrics", out,
                       "--auth-key-file", key], out / "gateway.log", env)
    lobby = h.start([h.bin_dir() / "lobby", "--port", 0, "--port-file", out / "lobby_port",
                     "--dds-domain", domain, "--metrics", out, "--auth-key-file", key],
                    out / "lobby.log", env)
    h.wait_for_port(out / "gateway_port", gateway, out / "gateway.log")
    lobby_port = h.wait_for_port(out / "lobby_port", lobby, out / "lobby.log")
    # The fleet runs only a few seconds: it starts once the zone ticks (welcomes come from it).
    h.wait_for_zone_ticks(out, zones, out / "zones.log")
    # Only now, so that the servers keep the limit they were given: client_stub inherits this.
    resource.setrlimit(resource.RLIMIT_NOFILE, (min(SOFT, hard), hard))
    h.run([h.bin_dir() / "client_stub", "--scene", SCENE, "--lobby", f"127.0.0.1:{lobby_port}",
           "--players", PLAYERS, "--duration", SECONDS, "--login-timeout", 60, "--summary",
           out / "clients.json"], out / "clients.log", env, timeout=180)
    resource.setrlimit(resource.RLIMIT_NOFILE, (soft, hard))
    h.stop(lobby)
    h.stop(gateway)
    h.stop(zones, grace=30)

    log = (out / "clients.log").read_text()
    h.check(f"clients logged in {PLAYERS} of {PLAYERS} through lobby" in log,
            f"all {PLAYERS} players logged in through the lobby")
    c = h.load_json(out / "clients.json")
    h.check(c["totals"]["welcomed"] == PLAYERS,
            f"the gateway welcomed every player ({c['totals']['welcomed']} of {PLAYERS})")
    h.check(all(p["inputs"] > 0 for p in c["clients"]), "every player sent inputs")
    cpu = c["fleet_cpu_s"]
    per_player = c["fleet_cpu_us_per_player_s"]
    h.check(cpu > 0 and abs(per_player - cpu * 1e6 / (PLAYERS * c["duration_s"])) <= 1e-6 * per_player,
            f"the summary reports the fleet's CPU per player-second ({per_player:.1f} us)")
    h.check(c["fleet_wakeups_per_s"] > 0, "and its loop's wake-ups")
    h.check("us per player-second" in log, "client_stub's last line says it too")
    g = h.load_json(out / "gateway_summary.json")
    h.check(g["sessions_opened"] == PLAYERS, f"one session per player ({g['sessions_opened']})")
    lobby_summary = h.load_json(out / "lobby_summary.json")
    h.check(lobby_summary["granted"] == PLAYERS, f"the lobby granted {PLAYERS} tokens")
print("big fleet passed")
