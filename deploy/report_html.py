#!/usr/bin/env python3
"""The run report as one HTML page: RUN/report.html, beside report.json (deploy/report.py).

The page holds the report's tables (zones, totals, players, kinds, faults, transactions, the
error against the truth), plots as PNG images next to it (zone tick time per rank, players'
kbit/s, the phases of the tick), and the command that opens the inspector on the run when it
was recorded. Plots need matplotlib (Debian's python3-matplotlib): without it the page says so
and keeps its tables.

Usage: report_html.py RUN_DIR
"""
import html
import json
import sys
from pathlib import Path

PHASES = ("input", "ai", "avatars", "physics", "gpu", "migrate", "halo", "publish", "checks")


def esc(v):
    return html.escape(str(v))


def fmt(v):
    if isinstance(v, float):
        return f"{v:,.3f}" if abs(v) < 100 else f"{v:,.0f}"
    if isinstance(v, int):
        return f"{v:,}"
    return esc(v)


def table(rows, columns, title):
    if not rows:
        return ""
    head = "".join(f"<th>{esc(label)}</th>" for label, _ in columns)
    body = "".join("<tr>" + "".join(f"<td>{fmt(r.get(key, ''))}</td>" for _, key in columns) + "</tr>"
                   for r in rows)
    return f"<h2>{esc(title)}</h2><table><tr>{head}</tr>{body}</table>"


def pairs(d, title):
    if not d:
        return ""
    rows = "".join(f"<tr><th>{esc(k)}</th><td>{fmt(v)}</td></tr>" for k, v in d.items()
                   if not isinstance(v, (dict, list)))
    return f"<h2>{esc(title)}</h2><table>{rows}</table>"


def jsonl(path):
    out = []
    if path.exists():
        for line in path.read_text().splitlines():
            try:
                out.append(json.loads(line))
            except json.JSONDecodeError:
                pass
    return out


def plots(run):
    """PNG files of the run, with captions; [] and a reason if matplotlib is missing."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return [], "plots need python3-matplotlib, which this python3 lacks"
    made = []
    zones = {int(p.stem.split("_")[1]): jsonl(p) for p in sorted(run.glob("zone_*.jsonl"))
             if p.stem.split("_")[1].isdigit()}
    if zones:
        fig, ax = plt.subplots(figsize=(8, 3.2))
        for rank, lines in sorted(zones.items()):
            ax.plot([l["tick"] for l in lines], [l["tick_ms"] for l in lines], lw=0.7, label=f"zone {rank}")
        ax.set_xlabel("tick")
        ax.set_ylabel("tick time, ms")
        ax.set_yscale("log")
        ax.legend(fontsize=8, ncol=4)
        ax.set_title("Zone tick time per rank")
        fig.tight_layout()
        fig.savefig(run / "report_tick.png", dpi=90)
        plt.close(fig)
        made.append(("report_tick.png", "Wall time of every tick of every zone rank."))

        fig, ax = plt.subplots(figsize=(8, 3.2))
        ranks = sorted(zones)
        bottom = [0.0] * len(ranks)
        for phase in PHASES:
            means = [sum(l.get(f"{phase}_ms", 0) for l in zones[r]) / max(len(zones[r]), 1) for r in ranks]
            ax.bar([str(r) for r in ranks], means, bottom=bottom, label=phase)
            bottom = [b + m for b, m in zip(bottom, means)]
        ax.set_xlabel("zone rank")
        ax.set_ylabel("mean ms per tick")
        ax.legend(fontsize=7, ncol=5)
        ax.set_title("The phases of the tick, per rank")
        fig.tight_layout()
        fig.savefig(run / "report_phases.png", dpi=90)
        plt.close(fig)
        made.append(("report_phases.png", "Mean time per tick of each phase (DESIGN.md's tick list)."))
    clients = jsonl(run / "clients.jsonl")
    if clients:
        fig, ax = plt.subplots(figsize=(8, 3.2))
        t = [c["t"] for c in clients]
        players = [max(c.get("players", 1), 1) for c in clients]
        ax.plot(t, [c["bytes_in_per_s"] * 8 / 1000 / n for c, n in zip(clients, players)], label="down, per player")
        ax.plot(t, [c["bytes_out_per_s"] * 8 / 1000 / n for c, n in zip(clients, players)], label="up, per player")
        ax.set_xlabel("s")
        ax.set_ylabel("kbit/s")
        ax.legend(fontsize=8)
        ax.set_title("Players' bandwidth")
        fig.tight_layout()
        fig.savefig(run / "report_kbps.png", dpi=90)
        plt.close(fig)
        made.append(("report_kbps.png", "Mean bandwidth per player, each second of the fleet."))
    return made, None


STYLE = """body{font:14px system-ui,sans-serif;margin:24px;max-width:1100px;color:#222}
table{border-collapse:collapse;margin:6px 0 18px}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}
th{background:#f2f2f2}h1{font-size:22px}h2{font-size:16px;margin-top:22px}
code{background:#f4f4f4;padding:2px 5px}figure{margin:10px 0}figcaption{color:#555;font-size:12px}"""


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    run = Path(sys.argv[1])
    report = run / "report.json"
    if not report.exists():
        sys.exit(f"report_html: {report} does not exist (run deploy/report.py first)")
    r = json.loads(report.read_text())
    parts = [f"<h1>zonesim run report</h1><p>{esc(r['run'])}</p>"]
    recorded = (run / "record").is_dir()
    if recorded:
        parts.append("<p><b>Inspector:</b> this run was recorded. Open it with "
                     f"<code>deploy/inspect.sh {esc(run)}</code>, then "
                     "<a href='http://127.0.0.1:8765/'>http://127.0.0.1:8765/</a> "
                     "(the map, the tick scrubber, each player's view and bandwidth).</p>")
    else:
        parts.append("<p>Not recorded (the cluster file's <code>record = no</code>): no inspector.</p>")
    zones = [dict(z, rect=", ".join(f"{v:g}" for v in z.get("rect", []))) for z in r.get("zones", [])]
    parts.append(table(zones, [("zone", "rank"), ("rectangle", "rect"), ("ticks", "ticks"),
                               ("entities start", "entities_start"), ("end", "entities_end"),
                               ("migrated out", "migrated_out"), ("in", "migrated_in"),
                               ("handoffs out", "handoffs_out"), ("in", "handoffs_in"),
                               ("tick ms p50", "tick_ms_p50"), ("p99", "tick_ms_p99"),
                               ("inputs applied", "inputs_applied"),
                               ("conservation failures", "conservation_failures")], "Zones"))
    parts.append(pairs(r.get("totals", {}), "Totals"))
    made, why = plots(run)
    for name, caption in made:
        parts.append(f"<figure><img src='{esc(name)}' alt='{esc(caption)}'><figcaption>{esc(caption)}"
                     "</figcaption></figure>")
    if why:
        parts.append(f"<p><i>{esc(why)}</i></p>")
    parts.append(table(r.get("clients", []), [("player", "player_id"), ("kind", "kind"), ("zone", "zone"),
                                              ("bytes/s in", "bytes_in_per_s"), ("out", "bytes_out_per_s"),
                                              ("updates/s", "updates_per_s"), ("welcome ms", "welcome_ms")],
                       "Players"))
    kinds = [dict(v, kind=k) for k, v in (r.get("kinds") or {}).items()]
    parts.append(table(kinds, [("kind", "kind"), ("players", "players"), ("kbit/s in p50", "kbps_in_p50"),
                               ("max", "kbps_in_max")], "Player kinds"))
    parts.append(pairs(r.get("faults") or {}, "Faults"))
    parts.append(pairs(r.get("transactions") or {}, "Transactions"))
    parts.append(pairs(r.get("gateway") or {}, "Gateway (last metrics line)"))
    out = run / "report.html"
    out.write_text("<!doctype html><html><head><meta charset='utf-8'><title>zonesim run report</title>"
                   f"<style>{STYLE}</style></head><body>{''.join(parts)}</body></html>\n")
    print(f"report.html written to {out}")


if __name__ == "__main__":
    main()
