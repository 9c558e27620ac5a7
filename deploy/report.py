#!/usr/bin/env python3
"""Joins a run folder's zone, gateway and client summaries into one report.

Prints the handoff/bandwidth report and writes the same figures to RUN_DIR/report.json.
Usage: deploy/report.py RUN_DIR              (the report)
       deploy/report.py --progress RUN_DIR   (one line on the clients' latest second)
"""
import json
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import own_stream  # noqa: E402  (deploy/own_stream.py)
import truth_error  # noqa: E402  (deploy/truth_error.py)


def load(path):
    return json.loads(Path(path).read_text())


def last_json_line(path):
    lines = [l for l in Path(path).read_text().splitlines() if l.strip()] if Path(path).exists() else []
    for line in reversed(lines[-2:]):  # the last may be half written while the run goes on
        try:
            return json.loads(line)
        except json.JSONDecodeError:
            continue
    return {}


def kind_figures(per_client):
    """Figures per player kind, from every fleet's clients (a fleet before kinds: walkers):
    players, kbit/s received p50 and max, the worst client's correction error p99 and max, and
    the mean of the players' time-averaged views."""
    kinds = {}
    for c in per_client:
        kinds.setdefault(c.get("kind", "walker"), []).append(c)
    order = ["walker", "rider", "flyer"]  # common/player_kind.h's ids
    out = {}
    for kind, cs in sorted(kinds.items(), key=lambda kv: order.index(kv[0]) if kv[0] in order else 9):
        kbps = sorted(c["bytes_in_per_s"] * 8 / 1000 for c in cs)
        out[kind] = {
            "players": len(cs),
            "kbps_in_p50": kbps[(len(kbps) - 1) // 2],
            "kbps_in_max": kbps[-1],
            "dr_error_m_p99_worst": max(c.get("dr_error_m_p99", 0) for c in cs),
            "dr_error_m_max": max(c.get("dr_error_m_max", 0) for c in cs),
            "visible_entities_mean": statistics.mean(
                c.get("visible_entities_mean", c.get("visible_entities", 0)) for c in cs),
        }
    return out


def fault_figures(run, per_client):
    """What the supervisor restarted (supervisor.jsonl) and how the players came back; None for
    a run without either."""
    log = run / "supervisor.jsonl"
    events = [json.loads(l) for l in log.read_text().splitlines() if l.strip()] if log.exists() else []
    resumes = sum(c.get("resumes", 0) for c in per_client)
    if not events and not resumes:
        return None
    # A line from before gateways were supervised has no kind: it was the zones'.
    zones = [e for e in events if e.get("kind", "zones") == "zones"]
    gateways = [e for e in events if e.get("kind") == "gateway"]
    resumed = [c for c in per_client if c.get("resumes", 0)]
    return {
        "zone_restarts": len(zones),
        "zone_restart_reasons": [e["reason"] for e in zones],
        "gateway_restarts": len(gateways),
        "resumes": resumes,
        "resume_failed": sum(c.get("resume_failed", 0) for c in per_client),
        "resume_new_avatar": sum(c.get("resume_new_avatar", 0) for c in per_client),
        "resume_s_max": max((c.get("resume_s_max", 0) for c in resumed), default=0),
    }


def transaction_figures(per_client):
    """What the players' transaction channels did (client_stub --transactions-per-s); None for
    a run without transactions."""
    made = sum(c.get("transactions_made", 0) for c in per_client)
    if not made:
        return None
    return {"made": made,
            "committed": sum(c.get("transactions_committed", 0) for c in per_client),
            "failed": sum(c.get("transactions_failed", 0) for c in per_client),
            "pending": sum(c.get("transactions_pending", 0) for c in per_client)}


def build_report(run):
    zones = sorted((load(p) for p in run.glob("zone_*_summary.json")), key=lambda z: z["rank"])
    # One fleet or gateway writes into the run folder itself; a cluster with several gives each
    # a folder of its own (deploy/cluster.py): fleet-NAME/, gateway-NAME/.
    per_client = [c for f in sorted([run, *run.glob("fleet-*")]) if (f / "clients_summary.json").exists()
                  for c in load(f / "clients_summary.json").get("clients", [])]
    gateways = {f.name: last_json_line(f / "gateway.jsonl")
                for f in sorted([run, *run.glob("gateway-*")]) if (f / "gateway.jsonl").exists()}
    gateway = next(iter(gateways.values()), {})
    own = run / "own_stream.csv"
    gaps = own_stream.analyse(own_stream.load(own)) if own.exists() else None
    truth = truth_error.figures(*truth_error.join(run)) if (run / "display.csv").exists() else None
    return {
        "truth_error": truth,
        "own_stream": own_stream.summary(gaps) if gaps else None,
        "_own_stream": gaps,
        "run": str(run),
        "zones": [{
            "rank": z["rank"], "rect": z["rect"], "ticks": z["ticks"],
            "entities_start": z["entities_start"], "entities_end": z["entities_end"],
            "migrated_out": z["migrated_out"], "migrated_in": z["migrated_in"],
            "handoffs_out": z["handoffs_out"], "handoffs_in": z["handoffs_in"],
            "tick_ms_p50": z["tick_ms_p50"], "tick_ms_p99": z["tick_ms_p99"],
            "inputs_applied": z["inputs_applied"], "published_updates": z["published_updates"],
            "conservation_failures": z["conservation_failures"],
        } for z in zones],
        "totals": {
            "entities_start": sum(z["entities_start"] for z in zones),
            "entities_end": sum(z["entities_end"] for z in zones),
            "migrations": sum(z["migrated_out"] for z in zones),
            "avatar_handoffs": sum(z["handoffs_in"] for z in zones),
            "conservation_failures": sum(z["conservation_failures"] for z in zones),
            # Messages between entities (a scene's interactions), over the last zone job.
            "entity_messages": {k: sum(z.get(k, 0) for z in zones)
                                for k in ("mail_posted", "mail_applied", "mail_cross_zone",
                                          "mail_forwarded", "mail_refused", "mail_failures")},
            "clients": len(per_client),
            "client_handoffs_observed": sum(c.get("handoffs", 0) for c in per_client),
            "bytes_in_per_s_mean": statistics.mean([c["bytes_in_per_s"] for c in per_client]) if per_client else 0,
            "bytes_out_per_s_mean": statistics.mean([c["bytes_out_per_s"] for c in per_client]) if per_client else 0,
            "updates_per_s_mean": statistics.mean([c["updates_per_s"] for c in per_client]) if per_client else 0,
        },
        "clients": per_client,
        "kinds": kind_figures(per_client),
        "gateway": gateway,
        "gateways": gateways if len(gateways) > 1 else None,
        "faults": fault_figures(run, per_client),
        "transactions": transaction_figures(per_client),
    }


def print_report(r):
    print(f"\n== zonesim run report: {r['run']}")
    print(f"{'zone':>4} {'entities start':>14} {'end':>6} {'migr out':>8} {'migr in':>8} "
          f"{'handoff out':>11} {'in':>4} {'tick p50 ms':>11} {'p99 ms':>7}")
    for z in r["zones"]:
        print(f"{z['rank']:>4} {z['entities_start']:>14} {z['entities_end']:>6} {z['migrated_out']:>8} "
              f"{z['migrated_in']:>8} {z['handoffs_out']:>11} {z['handoffs_in']:>4} "
              f"{z['tick_ms_p50']:>11.3f} {z['tick_ms_p99']:>7.3f}")
    t = r["totals"]
    print(f"total entities {t['entities_start']} -> {t['entities_end']}, migrations {t['migrations']}, "
          f"avatar handoffs {t['avatar_handoffs']} (clients observed {t['client_handoffs_observed']}), "
          f"conservation failures {t['conservation_failures']}")
    m = t["entity_messages"]
    if m["mail_posted"]:
        print(f"entity messages: {m['mail_posted']} posted, {m['mail_applied']} applied "
              f"({m['mail_cross_zone']} across a zone border, {m['mail_forwarded']} after their target), "
              f"{m['mail_refused']} refused (target gone); unbalanced audits {m['mail_failures']}")
    print(f"\n{'client':>6} {'player':>14} {'kind':>6} {'bytes/s in':>11} {'bytes/s out':>11} "
          f"{'updates/s':>9} {'handoffs':>8}")
    for i, c in enumerate(r["clients"]):
        print(f"{i:>6} {c.get('player_id', 0):>14} {c.get('kind', 'walker'):>6} {c['bytes_in_per_s']:>11.0f} "
              f"{c['bytes_out_per_s']:>11.0f} {c['updates_per_s']:>9.1f} {c.get('handoffs', 0):>8}")
    print(f"mean per client: {t['bytes_in_per_s_mean']:.0f} B/s in, {t['bytes_out_per_s_mean']:.0f} B/s out, "
          f"{t['updates_per_s_mean']:.1f} updates/s")
    f = r.get("faults")
    if f:
        print(f"\nfaults: restarts of the zone job {f['zone_restarts']}, of gateways {f['gateway_restarts']}; "
              f"player resumes {f['resumes']} (given up {f['resume_failed']}, with another avatar "
              f"{f['resume_new_avatar']}, slowest {f['resume_s_max']:.2f} s)")
    x = r.get("transactions")
    if x:
        print(f"transactions: {x['made']} made, {x['committed']} committed to the ledger, {x['failed']} failed, "
              f"{x['pending']} still waiting for their outcome at the end")
    if len(r["kinds"]) > 1:
        print(f"\n{'kind':>6} {'players':>7} {'kbit/s in p50':>13} {'max':>6} {'error m p99 (worst)':>19} "
              f"{'max':>6} {'in view (mean)':>14}")
        for kind, k in r["kinds"].items():
            print(f"{kind:>6} {k['players']:>7} {k['kbps_in_p50']:>13.1f} {k['kbps_in_max']:>6.1f} "
                  f"{k['dr_error_m_p99_worst']:>19.3f} {k['dr_error_m_max']:>6.3f} "
                  f"{k['visible_entities_mean']:>14.1f}")
    if r.get("_own_stream"):
        print()
        own_stream.print_table(r["_own_stream"])
    if r.get("truth_error") and r["truth_error"]["orders"]:
        print()
        truth_error.print_table(r["truth_error"])


def print_progress(run):
    l = last_json_line(run / "clients.jsonl")
    if l:
        print(f"   t={l['t']:5.1f} s  welcomed {l['welcomed']}/{l['players']}  updates/s {l['updates_per_s']}  "
              f"in {l['bytes_in_per_s'] / 1e3:.1f} kB/s  out {l['bytes_out_per_s'] / 1e3:.1f} kB/s  "
              f"handoffs {l['handoffs']}", flush=True)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--progress":
        print_progress(Path(sys.argv[2]))
        return
    if len(sys.argv) != 2:
        sys.exit("usage: report.py RUN_DIR | report.py --progress RUN_DIR")
    run = Path(sys.argv[1])
    report = build_report(run)
    saved = {k: v for k, v in report.items() if not k.startswith("_")}
    (run / "report.json").write_text(json.dumps(saved, indent=2) + "\n")
    print_report(report)
    print(f"\nreport.json written to {run / 'report.json'}")


if __name__ == "__main__":
    main()
