"""A small driver of headless Chromium (Debian's `chromium`) over its DevTools protocol, with
python3-websockets: start a browser in a fresh profile, open a page, evaluate JavaScript,
click, take screenshots, and collect every console error and uncaught exception. The browser
and its profile are removed on exit, whatever happened.

    async with Browser() as b:
        page = await b.open("http://127.0.0.1:8765/")
        await page.wait_for("window.inspector && window.inspector.state.ready")
        n = await page.eval("window.inspector.state.drawnEntities")
        await page.click(100, 200)
        await page.screenshot("shot.png")
        page.errors  # console errors and exceptions seen so far
"""
import asyncio
import base64
import json
import shutil
import subprocess
import tempfile
import time
import urllib.request
from pathlib import Path

import websockets

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-extensions", "--mute-audio", "--hide-scrollbars"]


class CdpError(Exception):
    pass


class Page:
    def __init__(self, ws):
        self.ws = ws
        self.next_id = 0
        self.pending = {}
        self.errors = []
        self.reader = asyncio.ensure_future(self._read())

    async def _read(self):
        async for raw in self.ws:
            msg = json.loads(raw)
            if "id" in msg and msg["id"] in self.pending:
                self.pending.pop(msg["id"]).set_result(msg)
            elif msg.get("method") == "Runtime.consoleAPICalled" and msg["params"]["type"] == "error":
                self.errors.append("console.error: " + " ".join(
                    str(a.get("value", a.get("description", ""))) for a in msg["params"]["args"]))
            elif msg.get("method") == "Runtime.exceptionThrown":
                d = msg["params"]["exceptionDetails"]
                self.errors.append("exception: " + d.get("exception", {}).get("description", d.get("text", "")))
            elif msg.get("method") == "Log.entryAdded" and msg["params"]["entry"]["level"] == "error":
                e = msg["params"]["entry"]
                self.errors.append(f"log: {e.get('text')} {e.get('url', '')}")

    async def send(self, method, params=None, timeout=30):
        self.next_id += 1
        fut = asyncio.get_event_loop().create_future()
        self.pending[self.next_id] = fut
        await self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params or {}}))
        msg = await asyncio.wait_for(fut, timeout)
        if "error" in msg:
            raise CdpError(f"{method}: {msg['error'].get('message')}")
        return msg["result"]

    async def eval(self, expression):
        r = await self.send("Runtime.evaluate", {"expression": expression, "awaitPromise": True,
                                                 "returnByValue": True})
        if "exceptionDetails" in r:
            raise CdpError(f"{expression}: {r['exceptionDetails'].get('exception', {}).get('description')}")
        return r["result"].get("value")

    async def wait_for(self, expression, timeout=30):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if await self.eval(f"Boolean({expression})"):
                return
            await asyncio.sleep(0.1)
        raise CdpError(f"not true after {timeout} s: {expression}")

    async def click(self, x, y):
        for kind in ("mousePressed", "mouseReleased"):
            await self.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y,
                                                         "button": "left", "clickCount": 1})

    async def screenshot(self, path):
        r = await self.send("Page.captureScreenshot", {"format": "png"})
        Path(path).write_bytes(base64.b64decode(r["data"]))
        return path


class Browser:
    def __init__(self, width=1400, height=900):
        self.size = (width, height)
        self.profile = None
        self.proc = None
        self.pages = []

    async def __aenter__(self):
        self.profile = Path(tempfile.mkdtemp(prefix="zs_chromium_"))
        self.proc = subprocess.Popen([CHROMIUM, *FLAGS, f"--user-data-dir={self.profile}",
                                      f"--window-size={self.size[0]},{self.size[1]}",
                                      "--remote-debugging-port=0", "about:blank"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = self.profile / "DevToolsActivePort"
        end = time.monotonic() + 60
        while not (port_file.exists() and port_file.read_text().strip()):
            if self.proc.poll() is not None or time.monotonic() > end:
                raise CdpError(f"{CHROMIUM} did not start (exit {self.proc.poll()})")
            await asyncio.sleep(0.1)
        self.port = int(port_file.read_text().split()[0])
        return self

    async def open(self, url):
        with urllib.request.urlopen(f"http://127.0.0.1:{self.port}/json/list") as r:
            target = next(t for t in json.load(r) if t["type"] == "page")
        ws = await websockets.connect(target["webSocketDebuggerUrl"], max_size=64 << 20)
        page = Page(ws)
        self.pages.append(page)
        for domain in ("Page", "Runtime", "Log"):
            await page.send(f"{domain}.enable")
        await page.send("Emulation.setDeviceMetricsOverride", {"width": self.size[0], "height": self.size[1],
                                                               "deviceScaleFactor": 1, "mobile": False})
        await page.send("Page.navigate", {"url": url})
        return page

    async def __aexit__(self, *exc):
        for p in self.pages:
            p.reader.cancel()
            try:
                await p.ws.close()
            except Exception:
                pass
        if self.proc and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        if self.profile:
            shutil.rmtree(self.profile, ignore_errors=True)
