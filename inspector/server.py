#!/usr/bin/env python3
"""The inspector's web server: the page (inspector/web/) and a run's recordings as JSON
(inspector/run_data.py), on 127.0.0.1 only, with no network at run time.

    server.py RUN_DIR [--port P] [--port-file F] [--live] [--max-entities N]

GET /                      the page
GET /api/meta              the run: world, ticks, ranks, players, markers
GET /api/tick?t=T          zones, entities (at most --max-entities), subscribed cells at T
GET /api/player?id=P&t=T   a player's view at T: visible set with reasons and errors, bytes
GET /api/entity?id=E       an entity's owners over time and its handoffs
GET /api/series            per-rank phase times per tick, per-player kbit/s

--live follows a run whose recordings still grow: at most one re-read a second (however many
requests come), and the cluster never waits for it (the files are only read). A request with
a missing or bad parameter is answered 400, an unknown player or entity 404, with a JSON
error that names what is wrong.
"""
import argparse
import json
import mimetypes
import sys
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import parse_qs, urlparse

from run_data import RecordingError, RunData

WEB = Path(__file__).resolve().parent / "web"
REFRESH_EVERY_S = 1.0


class Inspector:
    """The run's data behind one lock: the HTTP threads share it, a live refresh replaces it."""

    def __init__(self, run_dir, live, max_entities):
        self.data = RunData(run_dir, live=live)
        self.live = live
        self.max_entities = max_entities
        self.lock = threading.Lock()
        self.last_refresh = time.monotonic()

    def call(self, fn, *args):
        with self.lock:
            if self.live and time.monotonic() - self.last_refresh >= REFRESH_EVERY_S:
                self.data.refresh()
                self.last_refresh = time.monotonic()
            return fn(self.data, *args)


def make_handler(inspector):
    class Handler(BaseHTTPRequestHandler):
        def log_message(self, fmt, *args):  # quiet: a page polls
            pass

        def reply(self, code, body, kind="application/json"):
            data = body if isinstance(body, bytes) else json.dumps(body).encode()
            self.send_response(code)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(data)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(data)

        def error(self, code, message):
            self.reply(code, {"error": message})

        def number(self, q, name):
            if name not in q:
                raise ValueError(f"missing parameter '{name}'")
            try:
                return int(q[name][0])
            except ValueError:
                raise ValueError(f"parameter '{name}' is not an integer: '{q[name][0]}'")

        def do_GET(self):
            url = urlparse(self.path)
            q = parse_qs(url.query)
            try:
                if url.path == "/api/meta":
                    return self.reply(200, inspector.call(RunData.meta))
                if url.path == "/api/tick":
                    t = self.number(q, "t")
                    return self.reply(200, inspector.call(RunData.tick, t, inspector.max_entities))
                if url.path == "/api/player":
                    pid, t = self.number(q, "id"), self.number(q, "t")
                    return self.reply(200, inspector.call(RunData.player, str(pid), t))
                if url.path == "/api/entity":
                    eid = self.number(q, "id")
                    return self.reply(200, inspector.call(RunData.entity, str(eid)))
                if url.path == "/api/series":
                    return self.reply(200, inspector.call(RunData.series))
                if url.path.startswith("/api/"):
                    return self.error(404, f"no such query: {url.path}")
                return self.static(url.path)
            except ValueError as e:
                return self.error(400, str(e))
            except KeyError as e:
                return self.error(404, e.args[0] if e.args else "not found")
            except RecordingError as e:
                return self.error(500, str(e))

        def static(self, path):
            name = "index.html" if path in ("", "/") else path.lstrip("/")
            target = (WEB / name).resolve()
            if WEB.resolve() not in target.parents or not target.is_file():
                return self.error(404, f"no such file: {path}")
            kind = mimetypes.guess_type(target.name)[0] or "application/octet-stream"
            return self.reply(200, target.read_bytes(), kind)

    return Handler


def main():
    ap = argparse.ArgumentParser(description="serve a run's recordings to the web inspector")
    ap.add_argument("run_dir")
    ap.add_argument("--port", type=int, default=8765, help="0: any free port")
    ap.add_argument("--port-file", help="write the port listened on here")
    ap.add_argument("--live", action="store_true", help="follow recordings that still grow")
    ap.add_argument("--max-entities", type=int, default=5000,
                    help="at most this many entities per tick answered")
    a = ap.parse_args()
    try:
        inspector = Inspector(a.run_dir, a.live, a.max_entities)
    except (RecordingError, FileNotFoundError) as e:
        sys.exit(f"inspector: {e}")
    server = ThreadingHTTPServer(("127.0.0.1", a.port), make_handler(inspector))
    port = server.server_address[1]
    if a.port_file:
        Path(a.port_file).write_text(f"{port}\n")
    print(f"inspector on http://127.0.0.1:{port}/ for {a.run_dir}" + (" (live)" if a.live else ""),
          flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
