"""A run's recordings (RUN/record/*.zsrec) as the inspector asks for them: plain dicts, ready for
JSON. inspector/server.py serves them; tests and scripts may call them directly.

    data = RunData("runs/demo-x")
    data.meta(); data.tick(300); data.player("123", 300); data.entity("456"); data.series()

Ids are decimal strings: 64-bit ids lose precision as JavaScript numbers. A zone frame holds
what the zone owned after the tick (its truth) and the ghosts it held; a gateway frame holds,
per player, what the client holds and where the stream shows it. The error a player shows for
an entity is the distance between the two at the same tick, where the entity was recorded
(zone_node --record-every may sample ids).
"""
import bisect
import json
import math
from pathlib import Path

import numpy as np

from recording import (EVENT_NAMES, FLAG_GHOST, FLAG_QUARANTINED, FLAG_SLEEPING, KIND_NAMES,
                       REASON_NAMES, RecordingError, open_run)  # noqa: F401  (RecordingError: for callers)

EVENT = {name: i for i, name in enumerate(EVENT_NAMES)}


def _kind(k):
    return KIND_NAMES[k] if k < len(KIND_NAMES) else f"kind{k}"


def _rect(r):
    return {"min": [float(r["min"][0]), float(r["min"][1])], "max": [float(r["max"][0]), float(r["max"][1])]}


class RunData:
    def __init__(self, run_dir, live=False):
        run_dir = Path(run_dir)
        self.run_dir = run_dir
        self.record_dir = run_dir / "record" if (run_dir / "record").is_dir() else run_dir
        self.live = live
        recs = open_run(self.record_dir, unfinished_ok=live)
        self.zones, self.gateways = recs["zones"], recs["gateways"]
        self._supervisor = self._read_supervisor()
        self._reset_caches()

    def _reset_caches(self):
        self._truth_cache = {}
        # Gathered from the frames read so far and extended with new ones only: a live run's
        # meta must not cost a pass over its whole history every second.
        self._events, self._events_read = [], {}
        self._players, self._gateway_events, self._gateway_read = {}, [], {}

    def refresh(self):
        """Reads what the recordings gained (live mode); True if any gained frames."""
        grew = sum(r.refresh() for r in list(self.zones.values()) + list(self.gateways.values()))
        if grew:
            self._truth_cache = {}
            self._supervisor = self._read_supervisor()
        return grew > 0

    def _read_supervisor(self):
        path = self.run_dir / "supervisor.jsonl"
        out = []
        if path.exists():
            for line in path.read_text().splitlines():
                try:
                    out.append(json.loads(line))
                except json.JSONDecodeError:
                    continue  # a line being written
        return out

    # ---- what every view needs ----

    def _any_header(self):
        rec = next(iter(self.zones.values()), None) or next(iter(self.gateways.values()))
        return rec.header

    def _zone_events(self):
        """[(tick, rank, event row)] over every zone frame, in tick order."""
        new = False
        for rank, rec in self.zones.items():
            for i in range(self._events_read.get(rank, 0), len(rec)):
                f = rec.zone_tick(i)
                self._events.extend((f["tick"], rank, e) for e in f["events"])
                new = new or len(f["events"]) > 0
            self._events_read[rank] = len(rec)
        if new:
            # Within a tick: departures, then arrivals, then first inputs (EventKind order).
            self._events.sort(key=lambda x: (x[0], int(x[2]["kind"]), x[1]))
        return self._events

    def _gateway_frames_read(self):
        """Players (id -> newest avatar, gateway) and epoch events [(tick, gateway, epoch)]."""
        for gid, rec in self.gateways.items():
            for i in range(self._gateway_read.get(gid, 0), len(rec)):
                f = rec.gateway_tick(i)
                for p in f["players"]:
                    self._players[p["player"]] = (p["avatar"], gid)
                self._gateway_events.extend((int(f["tick"]), gid, int(e["other"])) for e in f["events"])
            self._gateway_read[gid] = len(rec)
        return self._players, self._gateway_events

    def meta(self):
        h = self._any_header()
        ticks = [t for rec in list(self.zones.values()) + list(self.gateways.values())
                 for t in (rec.ticks[:1] + rec.ticks[-1:])]
        markers = []
        checkpoints = set()
        for tick, rank, e in self._zone_events():
            name = EVENT_NAMES[e["kind"]] if e["kind"] < len(EVENT_NAMES) else "?"
            if name == "first_input":
                markers.append({"tick": int(tick), "kind": "handoff",
                                "text": f"avatar {int(e['entity'])} handed to zone {rank} "
                                        f"({int(e['value'])} ticks to its first input)"})
            elif name == "rebalance":
                markers.append({"tick": int(tick), "kind": "rebalance",
                                "text": f"zone {rank}: boundaries moved"})
            elif name == "checkpoint" and tick not in checkpoints:
                checkpoints.add(tick)
                markers.append({"tick": int(tick), "kind": "checkpoint",
                                "text": f"checkpoint of tick {int(e['value'])}"})
            elif name == "restart":
                markers.append({"tick": int(tick), "kind": "restart",
                                "text": f"zone {rank} restarted from tick {int(e['value'])}, "
                                        f"epoch {int(e['other'])}"})
        # A zone job's fault shows where the gateway first heard the restored world; the
        # supervisor (supervisor.jsonl) says why the job was restarted.
        why = {int(line["epoch"]): line.get("reason", "") for line in self._supervisor
               if line.get("kind") == "zones" and "epoch" in line}
        players, epochs = self._gateway_frames_read()
        for tick, gid, epoch in epochs:
            reason = f" ({why[epoch]})" if epoch in why else ""
            markers.append({"tick": tick, "kind": "fault",
                            "text": f"zones restarted{reason}: gateway {gid} in epoch {epoch}"})
        markers.sort(key=lambda m: (m["tick"], m["kind"]))
        grid = h["grid"]
        return {
            "world": _rect(h["world"]),
            "dt": h["dt"],
            "first_tick": int(min(ticks)) if ticks else 0,
            "last_tick": int(max(ticks)) if ticks else 0,
            "ranks": sorted(self.zones),
            "gateways": sorted(self.gateways),
            "interest": {"origin": grid["origin"], "cell": grid["cell"], "cols": grid["cols"],
                         "rows": grid["rows"]},
            "players": [{"id": str(p), "avatar": str(a), "gateway": g}
                        for p, (a, g) in sorted(players.items())],
            "markers": markers,
            "truth": bool(self.zones),
            "live": self.live,
        }

    def _zone_frames(self, t):
        return {rank: rec.zone_tick(rec.frame_at_or_before(t))
                for rank, rec in self.zones.items() if len(rec)}

    def _gateway_frames(self, t):
        return {gid: rec.gateway_tick(rec.frame_at_or_before(t))
                for gid, rec in self.gateways.items() if len(rec)}

    def tick(self, t, max_entities=None):
        t = int(t)
        frames = self._zone_frames(t)
        shown = max((f["tick"] for f in frames.values()), default=t)
        entities, truncated = [], False
        for rank, f in sorted(frames.items()):
            for e in f["entities"]:
                if max_entities is not None and len(entities) >= max_entities:
                    truncated = True
                    break
                flags = int(e["flags"])
                entities.append({"id": str(int(e["id"])), "kind": _kind(int(e["kind"])),
                                 "owner": int(e["owner"]), "x": float(e["x"]), "z": float(e["z"]),
                                 "sleeping": bool(flags & FLAG_SLEEPING),
                                 "ghost": bool(flags & FLAG_GHOST),
                                 "quarantined": bool(flags & FLAG_QUARANTINED)})
        cells = {}
        for f in self._gateway_frames(t).values():
            for c in f["cells"]:
                cells[int(c["cell"])] = cells.get(int(c["cell"]), 0) + int(c["players"])
        return {"tick": int(shown),
                "zones": [dict(rank=rank, **_rect(f["rect"])) for rank, f in sorted(frames.items())],
                "entities": entities,
                "cells": [{"cell": c, "subscribers": n} for c, n in sorted(cells.items())],
                "truncated": truncated}

    def _truth(self, tick):
        """{id: (x, z)} of every recorded owned entity at exactly this tick (zones record
        every tick)."""
        if tick not in self._truth_cache:
            truth = {}
            for rec in self.zones.values():
                i = bisect.bisect_left(rec.ticks, tick)
                if i < len(rec) and rec.ticks[i] == tick:
                    ents = rec.zone_tick(i)["entities"]
                    own = ents[(ents["flags"] & FLAG_GHOST) == 0]
                    truth.update(zip(own["id"].tolist(), zip(own["x"].tolist(), own["z"].tolist())))
            if len(self._truth_cache) > 64:
                self._truth_cache.clear()
            self._truth_cache[tick] = truth
        return self._truth_cache[tick]

    def player(self, player_id, t):
        pid = int(player_id)
        for gid, rec in sorted(self.gateways.items()):
            if not len(rec):
                continue
            # The newest frame at or before t that lists the player.
            for i in range(rec.frame_at_or_before(int(t)), -1, -1):
                f = rec.gateway_tick(i)
                p = next((p for p in f["players"] if p["player"] == pid), None)
                if p is None:
                    continue
                truth = self._truth(f["tick"])
                visible = []
                for v in p["visible"]:
                    at = truth.get(int(v["id"]))
                    err = math.hypot(float(v["x"]) - at[0], float(v["z"]) - at[1]) if at else None
                    visible.append({"id": str(int(v["id"])), "kind": _kind(int(v["kind"])),
                                    "reason": REASON_NAMES[int(v["reason"])],
                                    "x": float(v["x"]), "z": float(v["z"]), "error_m": err})
                groups = rec.header["field_groups"]
                by_entity = sorted(((int(e["id"]), int(e["bytes"])) for e in p["entity_bytes"]),
                                   key=lambda x: -x[1])
                return {"id": str(pid), "avatar": str(p["avatar"]), "tick": int(f["tick"]),
                        "gateway": gid, "x": float(p["x"]), "z": float(p["z"]),
                        "nimbus": float(p["nimbus"]), "visible": visible,
                        "bytes": {"total": int(p["socket_bytes"]),  # since its previous frame
                                  "by_field": {g: int(b) for g, b in zip(groups, p["field_bytes"])},
                                  "by_entity": [{"id": str(e), "bytes": b} for e, b in by_entity]}}
        raise KeyError(f"player {player_id} is in no gateway recording at or before tick {t}")

    def entity(self, entity_id):
        eid = int(entity_id)
        spans, kind = [], None
        for rank, rec in self.zones.items():
            start = prev = None
            for i in range(len(rec)):
                f = rec.zone_tick(i)
                ents = f["entities"]
                hit = ents[(ents["id"] == eid) & ((ents["flags"] & FLAG_GHOST) == 0)]
                if len(hit):
                    kind = kind or _kind(int(hit[0]["kind"]))
                    if start is None:
                        start = f["tick"]
                    prev = f["tick"]
                elif start is not None:
                    spans.append({"from_tick": int(start), "to_tick": int(prev), "rank": rank})
                    start = None
            if start is not None:
                spans.append({"from_tick": int(start), "to_tick": int(prev), "rank": rank})
        if not spans:
            raise KeyError(f"entity {entity_id} is in no zone recording (sampled out, or unknown)")
        spans.sort(key=lambda s: s["from_tick"])
        handoffs = []
        for tick, rank, e in self._zone_events():
            if int(e["entity"]) != eid:
                continue
            name = EVENT_NAMES[e["kind"]]
            if name == "departed" and int(e["other"]) >= 0:
                handoffs.append({"from": rank, "to": int(e["other"]), "crossing_tick": int(tick),
                                 "ownership_tick": None, "first_input_tick": None})
            elif name == "arrived":
                h = next((h for h in handoffs if h["to"] == rank and h["ownership_tick"] is None), None)
                if h is not None:
                    h["ownership_tick"] = int(tick)
            elif name == "first_input":
                h = next((h for h in reversed(handoffs) if h["to"] == rank
                          and h["first_input_tick"] is None), None)
                if h is not None:
                    h["first_input_tick"] = int(tick)
        return {"id": str(eid), "kind": kind, "owners": spans, "handoffs": handoffs}

    def series(self):
        h = next(iter(self.zones.values())).header if self.zones else None
        ranks, ticks = {}, []
        for rank, rec in sorted(self.zones.items()):
            rows = [rec.zone_tick(i) for i in range(len(rec))]
            if not ticks:
                ticks = [int(f["tick"]) for f in rows]
            phases = np.array([f["phase_ms"] for f in rows]) if rows else np.zeros((0, 0))
            ranks[str(rank)] = {name: [round(float(v), 4) for v in phases[:, k]]
                                for k, name in enumerate(h["phase_names"])} if len(rows) else {}
        # A gateway frame holds each player's bytes since its previous frame (gateway
        # --record-every-ticks): a rate over that interval, held over the ticks it covers.
        rates = {}  # player -> ([frame tick], [kbit/s])
        for rec in self.gateways.values():
            dt = rec.header["dt"] or 1 / 30
            last = {}
            for i in range(len(rec)):
                f = rec.gateway_tick(i)
                for p in f["players"]:
                    pid, tick = str(p["player"]), int(f["tick"])
                    if pid in last and tick > last[pid]:
                        ts, vs = rates.setdefault(pid, ([], []))
                        ts.append(tick)
                        vs.append(p["socket_bytes"] * 8 / 1000 / ((tick - last[pid]) * dt))
                    last[pid] = tick
        kbps = {}
        for pid, (ts, vs) in rates.items():
            kbps[pid] = [round(vs[min(bisect.bisect_left(ts, t), len(vs) - 1)], 2) for t in ticks]
        return {"ticks": ticks, "phases": h["phase_names"] if h else [], "ranks": ranks,
                "clients": kbps}
