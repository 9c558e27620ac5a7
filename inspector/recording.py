"""Reader of zonesim recordings (idl/recording.fbs; the file layout is written down in
recorder/recording_file.h), for the inspector and for analysis scripts and notebooks.

    rec = Recording("run/record/zone_0.zsrec")
    rec.header["phase_names"], len(rec), rec.ticks[-1]
    frame = rec.zone_tick(i)            # a dict; frame["entities"] is a numpy structured array
    for frame in rec.zone_ticks(): ...

It checks what the C++ reader checks: the magic, every chunk's length and CRC-32, the Header
first and the Index last agreeing with the frames; a file that fails is refused with
RecordingError naming the file, the byte offset and the reason. `unfinished_ok=True` accepts a
file without its Index (still being written, or its writer was killed) up to its last complete
chunk, and `refresh()` then reads what was appended since (live mode).

Needs python3-flatbuffers and python3-numpy, and the classes flatc generates from
idl/recording.fbs into the build's python/ folder (deploy/inspect.sh puts it on the path).
"""
import os
import struct
import zlib

import numpy as np

from zonesim.recording.EventKind import EventKind  # noqa: F401  (re-exported for callers)
from zonesim.recording.Frame import Frame
from zonesim.recording.Record import Record

MAGIC = b"ZSREC\x00\x00\x01"
FOOTER_MAGIC = b"ZSRECEND"
CHUNK_HEADER = 8
FOOTER = 16
MAX_CHUNK = 256 << 20
FILE_IDENTIFIER = b"ZSRC"

# The structs of idl/recording.fbs as numpy sees them (sizes as flatc lays them out).
ENTITY = np.dtype([("id", "<u8"), ("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("owner", "<i2"),
                   ("kind", "u1"), ("flags", "u1")])
EVENT = np.dtype([("entity", "<u8"), ("value", "<u8"), ("other", "<i4"), ("kind", "u1"),
                  ("_pad", "V3")])
VISIBLE = np.dtype([("id", "<u8"), ("x", "<f4"), ("z", "<f4"), ("kind", "u1"),
                    ("reason", "u1"), ("_pad", "V6")])
ENTITY_BYTES = np.dtype([("id", "<u8"), ("bytes", "<u4"), ("_pad", "V4")])
CELLS = np.dtype([("cell", "<u4"), ("players", "<u2"), ("_pad", "V2")])
assert (ENTITY.itemsize, EVENT.itemsize, VISIBLE.itemsize, ENTITY_BYTES.itemsize,
        CELLS.itemsize) == (24, 24, 24, 16, 8)

FLAG_SLEEPING, FLAG_GHOST, FLAG_QUARANTINED = 1, 2, 4
KIND_NAMES = ("npc", "avatar", "rigid_body", "emitter", "item")
EVENT_NAMES = ("departed", "arrived", "first_input", "rebalance", "checkpoint", "restart",
               "epoch")
REASON_NAMES = ("aura", "nimbus", "cell", "priority")


class RecordingError(Exception):
    """A file that is not a complete, intact recording."""

    def __init__(self, path, offset, reason):
        super().__init__(f"{path}: offset {offset}: {reason}")
        self.path, self.offset, self.reason = path, offset, reason


def _struct_vector(table, vtable_offset, dtype):
    """A vector of structs of `table` (a flatbuffers Table) as a numpy array viewing the buffer."""
    o = table.Offset(vtable_offset)
    if o == 0:
        return np.zeros(0, dtype)
    start = table.Vector(o)
    n = table.VectorLen(o)
    return np.frombuffer(table.Bytes, dtype=dtype, count=n, offset=start)


def _strings(n, get):
    return [get(i).decode() for i in range(n)]


class Recording:
    def __init__(self, path, unfinished_ok=False):
        self.path = str(path)
        self.unfinished_ok = unfinished_ok
        self._data = b""
        self._at = len(MAGIC)    # where the next chunk starts
        self.header = None
        self.ticks = []          # tick of each frame, in file order
        self._frames = []        # payload offset of each frame
        self.finished = False
        self.refresh()
        if self.header is None:
            raise RecordingError(self.path, len(MAGIC), "no Header frame")

    def __len__(self):
        return len(self._frames)

    def _fail(self, offset, reason):
        raise RecordingError(self.path, offset, reason)

    def refresh(self):
        """Reads what was appended since the last call; returns how many frames are new."""
        if self.finished:
            return 0
        try:
            with open(self.path, "rb") as f:
                f.seek(len(self._data))
                more = f.read()
        except OSError as e:
            self._fail(len(self._data), f"cannot read: {e.strerror}")
        self._data += more
        data = self._data
        if len(data) < len(MAGIC) or data[:5] != MAGIC[:5]:
            if self.unfinished_ok and len(data) < len(MAGIC):
                return 0
            self._fail(0, "not a zonesim recording (no ZSREC magic)")
        if data[:len(MAGIC)] != MAGIC:
            self._fail(5, f"layout version {data[7]} is not 1")
        end, index_at = len(data), None
        if len(data) >= len(MAGIC) + FOOTER and data[-8:] == FOOTER_MAGIC:
            end = len(data) - FOOTER
            index_at = struct.unpack_from("<Q", data, end)[0]
            if not len(MAGIC) <= index_at < end:
                self._fail(end, f"footer points outside the file ({index_at})")
        before = len(self._frames)
        at = self._at
        while at < end:
            if end - at < CHUNK_HEADER:
                if self.unfinished_ok and index_at is None:
                    break
                self._fail(at, f"truncated chunk header ({end - at} bytes left)")
            size, crc = struct.unpack_from("<II", data, at)
            if size == 0 or size % 8 or size > MAX_CHUNK:
                self._fail(at, f"chunk length {size} is not a frame's")
            if end - at - CHUNK_HEADER < size:
                if self.unfinished_ok and index_at is None:
                    break
                self._fail(at, f"truncated chunk: {size} bytes announced, "
                               f"{end - at - CHUNK_HEADER} left")
            payload_at = at + CHUNK_HEADER
            payload = memoryview(data)[payload_at:payload_at + size]
            if zlib.crc32(payload) != crc:
                self._fail(at, "chunk CRC mismatch (damaged bytes)")
            if data[payload_at + 4:payload_at + 8] != FILE_IDENTIFIER:
                self._fail(at, "frame without the ZSRC identifier")
            try:
                record = Record.GetRootAs(data, payload_at)
                kind = record.FrameType()
            except Exception as e:  # a corrupt offset inside a frame whose CRC matched
                self._fail(at, f"unreadable frame ({e})")
            if kind == Frame.Header:
                if self.header is not None:
                    self._fail(at, "a second Header frame")
                self.header = self._read_header(record, at)
            elif kind in (Frame.ZoneTick, Frame.GatewayTick):
                if self.header is None:
                    self._fail(at, "a tick frame before the Header")
                self._frames.append(payload_at)
                self.ticks.append(self._frame_table(payload_at).Tick())
            elif kind == Frame.Index:
                if index_at != at:
                    self._fail(at, "an Index frame that the footer does not name")
                self._check_index(record, at)
                self.finished = True
            else:
                self._fail(at, f"a frame of unknown type {kind}")
            at = payload_at + size
            if self.finished and at < end:
                self._fail(at, "data after the Index frame")
        self._at = at
        if index_at is not None and not self.finished:
            self._fail(index_at, "the footer names no Index frame")
        if not self.finished and not self.unfinished_ok:
            self._fail(at, "no Index: the file ends without its footer (its writer did not finish)")
        return len(self._frames) - before

    def _read_header(self, record, at):
        from zonesim.recording.Header import Header
        h = Header()
        h.Init(record.Frame().Bytes, record.Frame().Pos)
        if h.Version() != 1:
            self._fail(at, f"header version {h.Version()} is not 1")
        w = h.World()
        return {
            "version": h.Version(),
            "process": "zone" if h.Process() == 0 else "gateway",
            "index": h.Index(),
            "scene": (h.Scene() or b"").decode(),
            "world": {"min": [w.MinX(), w.MinZ()], "max": [w.MaxX(), w.MaxZ()]} if w else None,
            "dt": h.Dt(),
            "grid": {"origin": [h.GridOriginX(), h.GridOriginZ()], "cell": h.CellSize(),
                     "cols": h.GridCols(), "rows": h.GridRows()},
            "phase_names": _strings(h.PhaseNamesLength(), h.PhaseNames),
            "stage_names": _strings(h.StageNamesLength(), h.StageNames),
            "field_groups": _strings(h.FieldGroupsLength(), h.FieldGroups),
            "entities_every": h.EntitiesEvery(),
            "epoch": h.Epoch(),
            "start_tick": h.StartTick(),
        }

    def _check_index(self, record, at):
        from zonesim.recording.Index import Index
        ix = Index()
        ix.Init(record.Frame().Bytes, record.Frame().Pos)
        ticks = ix.TicksAsNumpy() if ix.TicksLength() else np.zeros(0, "<u8")
        offsets = ix.OffsetsAsNumpy() if ix.OffsetsLength() else np.zeros(0, "<u8")
        if len(ticks) != len(self._frames) or len(offsets) != len(self._frames):
            self._fail(at, f"the Index lists {len(ticks)} frames, the file holds {len(self._frames)}")
        for i, (t, o) in enumerate(zip(ticks, offsets)):
            if int(o) + CHUNK_HEADER != self._frames[i] or int(t) != self.ticks[i]:
                self._fail(at, f"the Index disagrees with frame {i}")

    def _frame_table(self, payload_at):
        record = Record.GetRootAs(self._data, payload_at)
        if record.FrameType() == Frame.ZoneTick:
            from zonesim.recording.ZoneTick import ZoneTick as T
        else:
            from zonesim.recording.GatewayTick import GatewayTick as T
        t = T()
        t.Init(record.Frame().Bytes, record.Frame().Pos)
        return t

    def zone_tick(self, i):
        """Frame i of a zone's recording as a dict of plain values and numpy arrays."""
        t = self._frame_table(self._frames[i])
        r = t.Rect()
        tab = t._tab
        return {
            "tick": t.Tick(), "sim_time": t.SimTime(), "epoch": t.Epoch(),
            "rect": {"min": [r.MinX(), r.MinZ()], "max": [r.MaxX(), r.MaxZ()]} if r else None,
            "entities": _struct_vector(tab, 12, ENTITY),
            "entity_count": t.EntityCount(),
            "events": _struct_vector(tab, 16, EVENT),
            "phase_ms": t.PhaseMsAsNumpy() if t.PhaseMsLength() else np.zeros(0, "<f4"),
            "stage_ms": t.StageMsAsNumpy() if t.StageMsLength() else np.zeros(0, "<f4"),
            "tick_ms": t.TickMs(),
        }

    def gateway_tick(self, i):
        """Frame i of a gateway's recording as a dict; players as a list of dicts."""
        t = self._frame_table(self._frames[i])
        players = []
        for k in range(t.PlayersLength()):
            p = t.Players(k)
            players.append({
                "player": p.Player(), "avatar": p.Avatar(), "x": p.X(), "z": p.Z(),
                "nimbus": p.Nimbus(),
                "visible": _struct_vector(p._tab, 14, VISIBLE),
                "socket_bytes": p.SocketBytes(),
                "field_bytes": p.FieldBytesAsNumpy() if p.FieldBytesLength() else np.zeros(0, "<u4"),
                "entity_bytes": _struct_vector(p._tab, 20, ENTITY_BYTES),
            })
        return {"tick": t.Tick(), "sim_time": t.SimTime(),
                "cells": _struct_vector(t._tab, 8, CELLS), "players": players,
                "events": _struct_vector(t._tab, 12, EVENT)}

    def zone_ticks(self):
        for i in range(len(self._frames)):
            yield self.zone_tick(i)

    def gateway_ticks(self):
        for i in range(len(self._frames)):
            yield self.gateway_tick(i)

    def frame_at_or_before(self, tick):
        """Index of the last frame whose tick is at most `tick` (the first frame if none)."""
        import bisect
        i = bisect.bisect_right(self.ticks, tick) - 1
        return max(i, 0)


def open_run(record_dir, unfinished_ok=False):
    """Every recording of a run's record folder: {"zones": {rank: Recording}, "gateways":
    {index: Recording}}. Files named zone_<rank>.zsrec and gateway_<index>.zsrec."""
    zones, gateways = {}, {}
    names = sorted(os.listdir(record_dir))
    for name in names:
        if not name.endswith(".zsrec"):
            continue
        rec = Recording(os.path.join(record_dir, name), unfinished_ok=unfinished_ok)
        (zones if rec.header["process"] == "zone" else gateways)[rec.header["index"]] = rec
    if not zones and not gateways:
        raise FileNotFoundError(f"{record_dir}: no .zsrec recordings")
    return {"zones": zones, "gateways": gateways}
