"""Zone and gateway crashes survived: a supervised local cluster (deploy/cluster.py, supervise =
zones, gateways) of 4 zone ranks checkpointing every 60 ticks, a gateway and 8 players runs for
60 s while this test SIGKILLs the gateway once, then a random zone rank at a random moment three
times, then SIGSTOPs one (a hung job). Afterwards:
  - the supervisor restarted the gateway on its address, and every player resumed there with
    its Welcome's resume token as the same player with the same avatar, within 2 s of its last
    datagram from the dead one; the time from the kill to each player's next own state is printed;
  - the supervisor restarted the zone job each time from the newest checkpoint, as epochs 1-4,
    the last for a job that stopped writing metrics;
  - the last job began with exactly the checkpoint's entities (count and id hash), and its
    conservation checks found nothing lost or doubled;
  - every player stayed connected (no session closed, no second Welcome) and received its own
    avatar's state after every fault; the time from each kill to that state is printed;
  - no input was lost: the restored zones applied every sequence number in order (none skipped)
    and the gateway still held every input it had to resend;
  - every player made transactions all along (TX_RATE a second, over 10,000 in all), committed
    by the zones to the run's SQLite ledger through every fault: each player's stored
    sequences are 1..k without a gap, every one its client was told is committed is stored
    (none can be stored twice: the ledger's key is player and seq), none failed;
  - entities messaged each other across zone borders all along (scenes/test_faults.yaml: NPCs
    hit each other where the four zones meet, players hand each other items), and every job's
    audit balanced at every check (each message posted applied or refused once: none lost,
    none applied twice), over the transactions and cross-zone messages together > 10,000;
  - unique items were taken through the faults (a contest goes to the nearest claimant) and
    none that a job showed leaving was restored untaken by a later one: events shown and then
    retracted, 0 (an item leaves only once a checkpoint holds its taking);
  - no zone_node, gateway or client_stub of the run is left.
Usage: fault_survival.py [SEED [FAULTS [GATEWAY_FAULTS]]]: SEED default random (printed), FAULTS
zone kills, default 3 (one every 16 s), GATEWAY_FAULTS default 1 (one every 6 s, before them);
docs/benchmarks.md: 10 faults of each kind measure the recovery times."""
import json
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import harness as h

PLAYERS = 8
TX_RATE = 25  # transactions per player a second: 8 x 25 x 80 s = 16,000
FAULTS = int(sys.argv[2]) if len(sys.argv) > 2 else 3
GATEWAY_FAULTS = int(sys.argv[3]) if len(sys.argv) > 3 else 1
# The gateway's kills at a random moment in each 4 s window, 6 s apart from 4 s after the players
# start; then one zone rank's kill in each 8 s window, 16 s apart from 2 s after those.
GATEWAY_KILL_WINDOWS = [(4 + 6 * k, 8 + 6 * k) for k in range(GATEWAY_FAULTS)]
ZONE_START = 6 + 6 * GATEWAY_FAULTS
KILL_WINDOWS = [(ZONE_START + 16 * k, ZONE_START + 8 + 16 * k) for k in range(FAULTS)]
HANG_S = 6  # the supervisor's hang_s
# Then one rank stopped (SIGSTOP): the job hangs in its next collective.
HANG_AT = KILL_WINDOWS[-1][1] + 8
SECONDS = HANG_AT + HANG_S + 14

seed = int(sys.argv[1]) if len(sys.argv) > 1 else random.SystemRandom().randrange(1 << 30)
print(f"fault_survival seed {seed}", flush=True)
rng = random.Random(seed)


def run_pids(run, program):
    """Pids of `program` processes started for this run (their command line names the run)."""
    out = subprocess.run(["pgrep", "-f", f"{program} .*{run}"], capture_output=True, text=True).stdout
    return [int(p) for p in out.split()]


def program_pids(run, program):
    """`program` processes of the run themselves (not mpirun, nor a command line naming it)."""
    def comm(p):
        try:
            return Path(f"/proc/{p}/comm").read_text().strip()
        except OSError:
            return None
    return [p for p in run_pids(run, program) if comm(p) == program]


def zone_rank_pids(run):
    """zone_node ranks of the running job (mpirun's children, not mpirun itself)."""
    return program_pids(run, "zone_node")


def wait_for(what, cond, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if cond():
            return
        time.sleep(0.1)
    h.fail(f"timed out waiting for {what}")


# ZONESIM_KEEP_RUN=DIR keeps the run folder there (to look at a failure).
with tempfile.TemporaryDirectory(prefix="zs_fault_") as tmp:
    tmp = os.environ.get("ZONESIM_KEEP_RUN", tmp)
    Path(tmp).mkdir(parents=True, exist_ok=True)
    run = Path(tmp) / "run"
    cluster = Path(tmp) / "fault.cluster"
    cluster.write_text(f"""[cluster]
scene = scenes/test_faults.yaml
duration = {SECONDS}
supervise = zones, gateways
zone_args = ${{ZONESIM_FAULT_ZONE_ARGS:-}}
checkpoint_every = 60
hang_s = {HANG_S}
[host here]
reach = local
zones = 4
[gateway g1]
host = here
[fleet players]
host = here
players = {PLAYERS}
args = --transactions-per-s {TX_RATE}
""")
    env = h.base_env(h.free_dds_domain())
    env["ZONESIM_BIN"] = str(h.bin_dir())
    log = Path(tmp) / "cluster.log"
    launcher = h.start(["python3", h.SOURCE_DIR / "deploy/cluster.py", cluster, run], log, env)
    wait_for("the fleet to start", lambda: "== fleet players" in log.read_text() or launcher.poll() is not None, 180)
    started = time.monotonic()

    def until_random_moment(window, fault):
        """Sleeps to a random moment of window (seconds after the players started)."""
        at = started + rng.uniform(*window)
        while time.monotonic() < at:
            if launcher.poll() is not None:
                h.fail(f"the cluster ended before {fault}\n{h.tail(log)}")
            time.sleep(0.1)

    gateway_kills = []  # (monotonic time, unix time)
    for k, window in enumerate(GATEWAY_KILL_WINDOWS):
        until_random_moment(window, f"gateway fault {k + 1}")
        gateways = program_pids(run, "gateway")
        h.check(len(gateways) == 1, f"gateway fault {k + 1}: one gateway is running ({gateways})")
        os.kill(gateways[0], signal.SIGKILL)
        gateway_kills.append((time.monotonic(), time.time()))
        print(f"gateway fault {k + 1}: SIGKILL gateway pid {gateways[0]} at {gateway_kills[-1][0] - started:.1f} s",
              flush=True)
        wait_for(f"the gateway's restart {k + 1}", lambda: f"({k + 1}. restart)" in log.read_text(), 60)
    kills = []  # (monotonic time, pid)
    for k, window in enumerate(KILL_WINDOWS):
        until_random_moment(window, f"fault {k + 1}")
        pids = zone_rank_pids(run)
        h.check(len(pids) == 4, f"fault {k + 1}: 4 zone ranks are running ({pids})")
        victim = rng.choice(sorted(pids))
        os.kill(victim, signal.SIGKILL)
        kills.append((time.monotonic(), victim, time.time()))
        print(f"fault {k + 1}: SIGKILL zone rank pid {victim} at {kills[-1][0] - started:.1f} s", flush=True)
        wait_for(f"restart {k + 1}", lambda: f"as epoch {k + 1}" in log.read_text(), 60)
    while time.monotonic() < started + HANG_AT:
        time.sleep(0.1)
    victim = rng.choice(sorted(zone_rank_pids(run)))
    os.kill(victim, signal.SIGSTOP)
    hung_at, hung_mono = time.time(), time.monotonic()
    print(f"fault {FAULTS + 1}: SIGSTOP zone rank pid {victim} at {time.monotonic() - started:.1f} s", flush=True)
    wait_for("the hung job's restart", lambda: f"as epoch {FAULTS + 1}" in log.read_text(), 60)
    try:
        rc = launcher.wait(timeout=SECONDS + 240)
    except subprocess.TimeoutExpired:
        h.stop(launcher)
        h.fail(f"the cluster did not finish\n{h.tail(log)}")
    h.check(rc == 0, f"the cluster finished and reported (exit {rc})\n{h.tail(log)}")

    all_events = [json.loads(l) for l in (run / "supervisor.jsonl").read_text().splitlines()]
    events = [e for e in all_events if e["kind"] == "zones"]
    gateway_events = [e for e in all_events if e["kind"] == "gateway"]
    h.check(len(gateway_events) == GATEWAY_FAULTS and all(e["gateway"] == "g1" for e in gateway_events),
            f"the supervisor restarted the gateway {GATEWAY_FAULTS} times ({gateway_events})")
    detect = sorted(e["detected_unix"] - unix for e, (_, unix) in zip(gateway_events, gateway_kills))
    print(f"gateway kill to its restart: p50 {detect[len(detect) // 2]:.2f} s, max {detect[-1]:.2f} s "
          f"(restart {', '.join(str(e['restart_s']) for e in gateway_events)} s after detection)", flush=True)
    h.check([e["epoch"] for e in events] == list(range(1, FAULTS + 2)),
            f"the supervisor restarted the zones {FAULTS + 1} times ({events})")
    h.check(events[-1]["reason"].startswith("hung"), f"the stopped rank's job was found hung ({events[-1]['reason']})")
    print(f"SIGSTOP to the supervisor's restart: {events[-1]['detected_unix'] - hung_at:.2f} s (hang_s {HANG_S})",
          flush=True)
    h.check(all(e["checkpoint"] for e in events), "each restart continued from a checkpoint")

    # The last job began with the entities of the checkpoint it restored, exactly.
    zones = [h.load_json(run / f"zone_{r}_summary.json") for r in range(4)]
    manifest = h.load_json(run / "checkpoints" / events[-1]["checkpoint"] / "MANIFEST.json")
    start_count = sum(z["entities_start"] for z in zones)
    start_hash = sum(z["id_hash_start"] for z in zones) % (1 << 64)
    h.check(start_count == manifest["entities"] and start_hash == int(manifest["id_hash"], 16),
            f"epoch {FAULTS + 1} began with the checkpoint's {manifest['entities']} entities and id hash "
            f"({start_count}, {start_hash:x} vs {manifest['id_hash']})")
    h.check(all(z["epoch"] == FAULTS + 1 for z in zones), f"the last job ran as epoch {FAULTS + 1}")
    h.check(sum(z["conservation_failures"] for z in zones) == 0 and sum(z["conservation_checks"] for z in zones) > 0,
            "conservation held after the last restart: nothing lost or doubled since the checkpoint")
    skipped = sum(z["inputs_skipped"] for z in zones)
    h.check(skipped == 0, f"the restored zones applied every input in sequence, none skipped ({skipped})")

    # The restarted gateway's figures: it took every player back and followed every zone restart.
    g = h.load_json(run / "gateway_summary.json")
    h.check(g["sessions_resumed"] == PLAYERS and g["sessions_replaced"] == 0,
            f"the restarted gateway took all {PLAYERS} players back by their resume tokens "
            f"({g['sessions_resumed']} resumed, {g['sessions_replaced']} replaced)")
    h.check(g["epochs_entered"] == FAULTS + 1 and g["epoch"] == FAULTS + 1,
            f"the gateway followed {FAULTS + 1} restarts ({g['epochs_entered']})")
    h.check(g["sessions_expired"] == 0 and g["welcomes"] == PLAYERS,
            f"no session expired and no player was welcomed twice ({g['sessions_expired']}, {g['welcomes']})")
    h.check(g["inputs_resent"] > 0 and g["inputs_unresendable"] == 0,
            f"inputs the restarts lost were resent ({g['inputs_resent']}), none beyond the history "
            f"({g['inputs_unresendable']})")
    print(f"position jumps at the restarts: {g.get('epoch_jumps', 0)} entities, p50 "
          f"{g.get('epoch_jump_m_p50', 0):.2f} m, p99 {g.get('epoch_jump_m_p99', 0):.2f} m, "
          f"max {g.get('epoch_jump_m_max', 0):.2f} m", flush=True)

    clients = h.load_json(run / "clients_summary.json")
    t = clients["totals"]
    h.check(t["welcomed"] == PLAYERS, "every player is still welcomed at the end")
    h.check(t["resumes"] == PLAYERS * GATEWAY_FAULTS and t["resume_failed"] == 0 and t["resume_new_avatar"] == 0,
            f"every player resumed after each gateway fault, as itself with its avatar ({t['resumes']} resumed, "
            f"{t['resume_failed']} gave up, {t['resume_new_avatar']} with another avatar)")
    h.check(t["resume_inputs_unresendable"] == 0,
            f"the inputs the dead gateway lost were resent ({t['resume_inputs_resent']}), none beyond "
            f"the history ({t['resume_inputs_unresendable']})")
    h.check(t["resume_s_max"] < 2.0, f"each player was back within 2 s of its last datagram from the dead "
            f"gateway (p50 {t['resume_s_p50']:.2f} s, max {t['resume_s_max']:.2f} s)")
    print(f"resume, last datagram heard to the resumed Welcome: p50 {t['resume_s_p50']:.2f} s, "
          f"max {t['resume_s_max']:.2f} s; {t['resume_inputs_resent']} inputs resent", flush=True)
    # Each player's own-avatar states, on this test's clock.
    base = clients["started_monotonic_s"]
    states = {}
    with open(run / "own_stream.csv") as f:
        next(f)
        for line in f:
            player, event, t_ms, _, _ = line.split(",")
            if event == "U":
                states.setdefault(int(player), []).append(base + float(t_ms) * 1e-3)
    # (fault time, when the supervisor restarted the job), on this test's clock.
    faults = [(at, at + e["detected_unix"] - unix) for (at, unix), e in zip(gateway_kills, gateway_events)]
    faults += [(at, at + e["detected_unix"] - unix) for (at, _, unix), e in zip(kills, events)]
    faults.append((hung_mono, hung_mono + events[-1]["detected_unix"] - hung_at))
    recovery, silent = [], []
    for k, (at, restarted) in enumerate(faults):
        until = faults[k + 1][0] if k + 1 < len(faults) else float("inf")
        for p in range(PLAYERS):
            # The first state after the restart: the restored world's.
            seen = [t for t in states.get(p, []) if restarted < t < until]
            if not seen:
                silent.append((f"gateway {k + 1}" if k < GATEWAY_FAULTS else k + 1 - GATEWAY_FAULTS, p))
                continue
            recovery.append((k, seen[0] - at))
    h.check(not silent, f"every player received its avatar's state after every fault (silent: {silent})")
    after_gateway = sorted(r for k, r in recovery if k < GATEWAY_FAULTS)
    print(f"gateway kill to the player's next own state: p50 {after_gateway[len(after_gateway) // 2]:.2f} s, "
          f"max {after_gateway[-1]:.2f} s over {GATEWAY_FAULTS} faults x {PLAYERS} players", flush=True)
    after_kill = sorted(r for k, r in recovery if GATEWAY_FAULTS <= k < GATEWAY_FAULTS + len(kills))
    detect = sorted(e["detected_unix"] - kill[2] for e, kill in zip(events, kills))
    print(f"kill to the supervisor's restart: p50 {detect[len(detect) // 2]:.2f} s, "
          f"max {detect[-1]:.2f} s", flush=True)
    print(f"kill to the player's next own state: p50 {after_kill[len(after_kill) // 2]:.2f} s, "
          f"max {after_kill[-1]:.2f} s over {len(kills)} faults x {PLAYERS} players "
          f"(restart {', '.join(str(e['restart_s']) for e in events)} s after detection)", flush=True)

    # Transactions, from the ledger itself.
    import sqlite3
    db = sqlite3.connect(run / "ledger.sqlite")
    stored = {}
    for player, seq in db.execute("SELECT player, seq FROM ledger_tx"):
        stored.setdefault(player, []).append(seq)
    db.close()
    tx = clients["transactions"]
    print(f"transactions: {tx['made']} made, {tx['committed']} committed ({tx['already_committed']} "
          f"found stored already), {tx['pending']} pending at the end, {tx['resent']} resends, "
          f"{tx['refused_window_full']} not made (window full); outcome p50 {tx['latency_ms_p50']:.0f} ms, "
          f"p99 {tx['latency_ms_p99']:.0f} ms, max {tx['latency_ms_max']:.0f} ms", flush=True)
    h.check(tx["made"] >= 10000, f"over 10,000 transactions ({tx['made']})")
    h.check(tx["failed"] == 0 and tx["conflicts"] == 0 and tx["outcome_unknown"] == 0,
            f"none failed or conflicted ({tx['failed']}, {tx['conflicts']}, {tx['outcome_unknown']} unknown)")
    lost = []
    for c in clients["clients"]:
        seqs = sorted(stored.get(c["player_id"], []))
        if seqs != list(range(1, len(seqs) + 1)) or not (c["transactions_committed"] <= len(seqs)
                                                         <= c["transactions_made"]):
            lost.append((c["player_id"], len(seqs), c["transactions_committed"], c["transactions_made"]))
    h.check(not lost, f"every player's stored transactions are 1..k without a gap, and hold every one "
                      f"its client was told is committed (bad: {lost})")

    # Messages between entities, over every job: the killed ones' ticks from their metrics, and
    # their audits from the zones' logs (an unbalanced check is logged; the last job's summary
    # counts them too).
    mail = {k: 0 for k in ("mail_posted", "mail_applied", "mail_cross_zone", "mail_forwarded",
                           "mail_refused", "hits", "kills", "gifts", "gifts_returned", "pickups",
                           "pickups_contested", "pickups_denied")}
    for metrics in list(run.glob("epoch-*/zone_*.jsonl")) + list(run.glob("zone_*.jsonl")):
        for line in metrics.read_text().splitlines():
            try:
                row = json.loads(line)
            except ValueError:
                continue  # the line a SIGKILL cut short
            for k in mail:
                mail[k] += row.get(k, 0)
    print("entity messages over every job: " + ", ".join(f"{v} {k}" for k, v in mail.items()), flush=True)
    unbalanced = [p.name for p in run.glob("zones*.log") if "entity messages unbalanced" in p.read_text()]
    h.check(not unbalanced and sum(z["mail_failures"] for z in zones) == 0
            and all(z["mail_posted_cluster"] > 0 for z in zones),
            f"every job's mail audit balanced at every check: none lost, none applied twice "
            f"(unbalanced in: {unbalanced})")
    h.check(mail["mail_cross_zone"] > 500 and mail["hits"] > 1000,
            f"entities messaged each other across borders ({mail['mail_cross_zone']} cross-zone, "
            f"{mail['mail_forwarded']} forwarded after their target)")
    h.check(tx["made"] + mail["mail_cross_zone"] >= 10000,
            f"over 10,000 transactions and cross-zone messages ({tx['made']} + {mail['mail_cross_zone']})")

    # Unique items: what each job showed leaving, and what each restart began with untaken.
    jobs = sorted(run.glob("epoch-*"), key=lambda d: int(d.name.split("-")[1])) + [run]
    left, retracted = set(), []  # items some job showed leaving; those a later job restored
    for job in jobs:
        rows = [line.split(",") for f in job.glob("zone_*_items.csv")
                for line in f.read_text().splitlines()[1:]]
        rows = [r for r in rows if len(r) == 3]  # a SIGKILL may cut the last line short
        retracted += [(job.name, int(i)) for _, event, i in rows if event == "restored" and int(i) in left]
        left |= {int(i) for _, event, i in rows if event == "left"}
    print(f"unique items: {len(left)} left the world over every job ({mail['pickups']} takings, "
          f"{mail['pickups_contested']} contested, {mail['pickups_denied']} claims denied, counting "
          f"re-run ticks); shown and later retracted: {len(retracted)}", flush=True)
    h.check(len(left) > 0, f"items were taken and left the world ({len(left)})")
    h.check(not retracted, f"no item shown leaving came back after a restart (retracted: {retracted})")

    report = h.load_json(run / "report.json")
    h.check(report["transactions"] and report["transactions"]["made"] == tx["made"]
            and report["transactions"]["committed"] == tx["committed"],
            f"the run report counts the transactions ({report['transactions']})")
    f = report["faults"]
    h.check(f["zone_restarts"] == FAULTS + 1 and f["gateway_restarts"] == GATEWAY_FAULTS
            and f["resumes"] == PLAYERS * GATEWAY_FAULTS,
            f"the run report counts the restarts and resumes ({f})")

    left = [p for prog in ("zone_node", "gateway", "client_stub") for p in run_pids(run, prog)]
    h.check(not left, f"no process of the run is left ({left})")
print("fault survival passed")
