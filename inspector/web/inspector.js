// The zonesim inspector: a recorded (or live) run from inspector/server.py's JSON, drawn on
// canvases. x runs right and z runs down on the map. Ids are strings (64-bit).
// window.inspector exposes the state and a few actions for tests (tests/integration/
// inspector_browser.py): state.tick, state.drawnEntities, state.drawnGhosts, state.zones,
// state.selectedPlayer, state.visibleList, state.ready; setTick, selectPlayer, selectEntity,
// worldToScreen.
"use strict";

const RANK_COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
                      "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"];
const MARKER_COLOURS = { handoff: "#1f77b4", rebalance: "#2ca02c", checkpoint: "#7f7f7f",
                         fault: "#d62728", restart: "#d62728" };
const FIELD_COLOURS = { position: "#1f77b4", orientation: "#9467bd", velocity: "#2ca02c",
                        lifecycle: "#ff7f0e", headers: "#7f7f7f" };
const PHASE_COLOURS = ["#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1", "#9c755f",
                       "#76b7b2", "#edc948", "#bab0ac"];

const state = {
  meta: null, tick: 0, tickData: null, series: null,
  selectedPlayer: null, playerData: null, selectedEntity: null, entityData: null,
  drawnEntities: 0, drawnGhosts: 0, zones: [], visibleList: [],
  view: { scale: 1, ox: 0, oy: 0 }, playing: false, following: false, ready: false,
};

const $ = (id) => document.getElementById(id);
const rankColour = (r) => RANK_COLOURS[((r % RANK_COLOURS.length) + RANK_COLOURS.length) % RANK_COLOURS.length];

function setStatus(text) { $("status").textContent = text || ""; }

async function getJSON(path) {
  const r = await fetch(path);
  const body = await r.json();
  if (!r.ok) throw new Error(body.error || `${path}: HTTP ${r.status}`);
  return body;
}

// ---- the map ----

function worldToScreen(x, z) {
  const v = state.view;
  return [(x - state.meta.world.min[0]) * v.scale + v.ox, (z - state.meta.world.min[1]) * v.scale + v.oy];
}

function screenToWorld(sx, sy) {
  const v = state.view;
  return [(sx - v.ox) / v.scale + state.meta.world.min[0], (sy - v.oy) / v.scale + state.meta.world.min[1]];
}

function fitView() {
  const c = $("map"), w = state.meta.world;
  const dx = w.max[0] - w.min[0], dz = w.max[1] - w.min[1];
  const scale = Math.min((c.clientWidth - 20) / dx, (c.clientHeight - 20) / dz);
  state.view = { scale, ox: (c.clientWidth - dx * scale) / 2, oy: (c.clientHeight - dz * scale) / 2 };
}

function sizeCanvas(c) {
  const ratio = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.floor(c.clientWidth * ratio)), h = Math.max(1, Math.floor(c.clientHeight * ratio));
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  const g = c.getContext("2d");
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  return g;
}

function hatch(g) {
  const p = document.createElement("canvas");
  p.width = p.height = 6;
  const h = p.getContext("2d");
  h.strokeStyle = "rgba(0,0,0,0.55)";
  h.beginPath(); h.moveTo(0, 6); h.lineTo(6, 0); h.stroke();
  return g.createPattern(p, "repeat");
}

function drawMap() {
  const c = $("map"), g = sizeCanvas(c), d = state.tickData, m = state.meta;
  g.clearRect(0, 0, c.clientWidth, c.clientHeight);
  if (!d) return;
  const s = state.view.scale;
  // Interest cells, shaded by how many players subscribe.
  const grid = m.interest, most = Math.max(1, ...d.cells.map((cell) => cell.subscribers));
  for (const cell of d.cells) {
    const col = cell.cell % grid.cols, row = Math.floor(cell.cell / grid.cols);
    const [x, y] = worldToScreen(grid.origin[0] + col * grid.cell, grid.origin[1] + row * grid.cell);
    g.fillStyle = `rgba(246,193,119,${0.12 + 0.38 * cell.subscribers / most})`;
    g.fillRect(x, y, grid.cell * s, grid.cell * s);
  }
  // Zones, as they stand at this tick.
  state.zones = d.zones.map((z) => ({ rank: z.rank, min: z.min, max: z.max }));
  g.font = "12px system-ui";
  for (const z of d.zones) {
    const [x0, y0] = worldToScreen(z.min[0], z.min[1]), [x1, y1] = worldToScreen(z.max[0], z.max[1]);
    g.fillStyle = rankColour(z.rank) + "14";
    g.fillRect(x0, y0, x1 - x0, y1 - y0);
    g.strokeStyle = rankColour(z.rank);
    g.lineWidth = 2;
    g.strokeRect(x0, y0, x1 - x0, y1 - y0);
    g.fillStyle = rankColour(z.rank);
    g.fillText(`zone ${z.rank}`, x0 + 4, y0 + 14);
  }
  // Entities coloured by owner; ghosts (a neighbour's copy) hatched and hollow.
  const visible = new Set(state.visibleList);
  const pattern = hatch(g);
  let owned = 0, ghosts = 0;
  const r = Math.max(2, Math.min(6, s * 0.6));
  for (const e of d.entities) {
    const [x, y] = worldToScreen(e.x, e.z);
    if (e.ghost) {
      ghosts++;
      g.fillStyle = pattern;
      g.strokeStyle = rankColour(e.owner);
      g.lineWidth = 1;
      g.beginPath(); g.arc(x, y, r + 1, 0, 2 * Math.PI); g.fill(); g.stroke();
      continue;
    }
    owned++;
    g.fillStyle = e.quarantined ? "#000" : e.sleeping ? "#b0b4bc" : rankColour(e.owner);
    g.beginPath();
    if (e.kind === "avatar") g.rect(x - r - 1, y - r - 1, 2 * r + 2, 2 * r + 2);
    else if (e.kind === "item") { g.moveTo(x, y - r - 2); g.lineTo(x + r + 2, y); g.lineTo(x, y + r + 2); g.lineTo(x - r - 2, y); }
    else g.arc(x, y, r, 0, 2 * Math.PI);
    g.fill();
    if (visible.has(e.id)) { g.strokeStyle = "#000"; g.lineWidth = 1.5; g.stroke(); }
  }
  state.drawnEntities = owned;
  state.drawnGhosts = ghosts;
  // The selected player's nimbus, where the gateway placed it.
  const p = state.playerData;
  if (p) {
    const [x, y] = worldToScreen(p.x, p.z);
    g.strokeStyle = "#e15759"; g.lineWidth = 2; g.setLineDash([6, 4]);
    g.beginPath(); g.arc(x, y, p.nimbus * s, 0, 2 * Math.PI); g.stroke(); g.setLineDash([]);
  }
  if (state.entityData) {
    const e = d.entities.find((x) => x.id === state.entityData.id && !x.ghost);
    if (e) {
      const [x, y] = worldToScreen(e.x, e.z);
      g.strokeStyle = "#000"; g.lineWidth = 2;
      g.beginPath(); g.arc(x, y, r + 5, 0, 2 * Math.PI); g.stroke();
    }
  }
}

function entityAt(sx, sy) {
  if (!state.tickData) return null;
  let best = null, bestD = 10 * 10;
  for (const e of state.tickData.entities) {
    if (e.ghost) continue;
    const [x, y] = worldToScreen(e.x, e.z);
    const d = (x - sx) ** 2 + (y - sy) ** 2;
    if (d < bestD) { bestD = d; best = e; }
  }
  return best;
}

// ---- the side panel ----

function fmt(v, digits = 3) { return v === null || v === undefined ? "–" : Number(v).toFixed(digits); }

function renderPlayers() {
  const box = $("players");
  box.textContent = "";
  for (const p of state.meta.players) {
    const b = document.createElement("button");
    b.textContent = p.id.slice(-6);
    b.title = `player ${p.id}, avatar ${p.avatar}, gateway ${p.gateway}`;
    b.dataset.playerId = p.id;
    if (p.id === state.selectedPlayer) b.className = "selected";
    b.onclick = () => selectPlayer(p.id);
    box.appendChild(b);
  }
}

function table(columns, rows, rowAttrs) {
  const t = document.createElement("table");
  const head = t.insertRow();
  for (const c of columns) { const th = document.createElement("th"); th.textContent = c; head.appendChild(th); }
  rows.forEach((cells, i) => {
    const tr = t.insertRow();
    if (rowAttrs) rowAttrs(tr, i);
    for (const v of cells) tr.insertCell().textContent = v;
  });
  return t;
}

function renderPlayer() {
  const box = $("selection"), p = state.playerData;
  box.textContent = "";
  if (!p) return;
  const h = document.createElement("h2");
  h.textContent = `Player ${p.id} (avatar ${p.avatar}) at tick ${p.tick}`;
  box.appendChild(h);
  const info = document.createElement("p");
  const errs = p.visible.map((v) => v.error_m).filter((e) => e !== null).sort((a, b) => a - b);
  info.textContent = `nimbus ${fmt(p.nimbus, 1)} m, ${p.visible.length} entities held` +
    (errs.length ? `, error against the truth: median ${fmt(errs[errs.length >> 1])} m, max ${fmt(errs[errs.length - 1])} m` : "");
  box.appendChild(info);
  // Bandwidth by field group since the gateway's previous frame.
  const total = Object.values(p.bytes.by_field).reduce((a, b) => a + b, 0);
  const bw = document.createElement("div");
  bw.innerHTML = `<h2>Bytes sent: ${p.bytes.total} (by field: ${total})</h2>`;
  const bar = document.createElement("div");
  bar.className = "bar";
  for (const [field, n] of Object.entries(p.bytes.by_field)) {
    const seg = document.createElement("div");
    seg.style.width = `${total ? (100 * n) / total : 0}%`;
    seg.style.background = FIELD_COLOURS[field] || "#999";
    seg.title = `${field}: ${n} bytes`;
    bar.appendChild(seg);
  }
  bw.appendChild(bar);
  bw.appendChild(table(["field", "bytes"], Object.entries(p.bytes.by_field).map(([f, n]) => [f, n])));
  const top = p.bytes.by_entity.slice(0, 8);
  if (top.length) bw.appendChild(table(["entity (most bytes)", "bytes"], top.map((e) => [e.id, e.bytes])));
  box.appendChild(bw);
  const vh = document.createElement("h2");
  vh.textContent = "Visible set (why, and the error it shows)";
  box.appendChild(vh);
  box.appendChild(table(["entity", "kind", "reason", "error m"],
    p.visible.map((v) => [v.id, v.kind, v.reason, fmt(v.error_m)]),
    (tr, i) => { tr.dataset.entityId = p.visible[i].id; tr.onclick = () => selectEntity(p.visible[i].id); }));
}

function renderEntity() {
  const box = $("selection"), e = state.entityData;
  box.textContent = "";
  if (!e) return;
  const h = document.createElement("h2");
  h.textContent = `Entity ${e.id} (${e.kind})`;
  box.appendChild(h);
  box.appendChild(table(["owner rank", "from tick", "to tick"], e.owners.map((o) => [o.rank, o.from_tick, o.to_tick])));
  const hh = document.createElement("h2");
  hh.textContent = `Handoffs (${e.handoffs.length})`;
  box.appendChild(hh);
  box.appendChild(table(["from", "to", "crossing", "ownership", "first input"],
    e.handoffs.map((x) => [x.from, x.to, x.crossing_tick, x.ownership_tick ?? "–", x.first_input_tick ?? "–"])));
}

// ---- actions ----

let tickRequest = 0;
async function setTick(t) {
  const m = state.meta;
  t = Math.max(m.first_tick, Math.min(m.last_tick, Math.round(t)));
  state.tick = t;
  $("tick").value = t;
  const mine = ++tickRequest;
  const d = await getJSON(`/api/tick?t=${t}`);
  if (mine !== tickRequest) return;  // a newer request superseded this one
  state.tickData = d;
  $("tick-label").textContent = `tick ${d.tick}  (${(d.tick * m.dt).toFixed(2)} s)` + (d.truncated ? " — entities capped" : "");
  if (state.selectedPlayer) await loadPlayer();
  drawMap();
  drawCharts();
  state.ready = true;
}

async function loadPlayer() {
  state.playerData = await getJSON(`/api/player?id=${state.selectedPlayer}&t=${state.tick}`);
  state.visibleList = state.playerData.visible.map((v) => v.id);
  renderPlayer();
}

async function selectPlayer(id) {
  state.selectedPlayer = id;
  state.entityData = state.selectedEntity = null;
  renderPlayers();
  await loadPlayer();
  drawMap();
}

async function selectEntity(id) {
  state.entityData = await getJSON(`/api/entity?id=${id}`);
  state.selectedEntity = id;
  state.selectedPlayer = state.playerData = null;
  state.visibleList = [];
  renderPlayers();
  renderEntity();
  drawMap();
}

// ---- the timeline and charts ----

function renderMarkers() {
  const box = $("markers"), m = state.meta, span = Math.max(1, m.last_tick - m.first_tick);
  box.textContent = "";
  for (const mk of m.markers) {
    const s = document.createElement("span");
    s.style.left = `calc(${(100 * (mk.tick - m.first_tick)) / span}% - 1px)`;
    s.style.background = MARKER_COLOURS[mk.kind] || "#333";
    s.title = `tick ${mk.tick}: ${mk.kind}: ${mk.text}`;
    s.onclick = () => setTick(mk.tick);
    box.appendChild(s);
  }
}

function cursor(g, w, h, ticks) {
  if (!ticks.length) return;
  const x = ((state.tick - ticks[0]) / Math.max(1, ticks[ticks.length - 1] - ticks[0])) * w;
  g.strokeStyle = "#000"; g.lineWidth = 1;
  g.beginPath(); g.moveTo(x, 0); g.lineTo(x, h); g.stroke();
}

function drawCharts() {
  const s = state.series;
  if (!s) return;
  const ticks = s.ticks, n = ticks.length;
  // Phases: one stacked band per rank, side by side vertically.
  {
    const c = $("phases"), g = sizeCanvas(c), w = c.clientWidth, h = c.clientHeight;
    g.clearRect(0, 0, w, h);
    const ranks = Object.keys(s.ranks), bandH = h / Math.max(1, ranks.length);
    ranks.forEach((rank, k) => {
      const phases = s.ranks[rank];
      const totals = new Array(n).fill(0);
      for (const p of s.phases) (phases[p] || []).forEach((v, i) => { totals[i] += v; });
      const top = Math.max(0.001, ...totals.map((v) => v).sort((a, b) => a - b).slice(0, Math.ceil(n * 0.99)));
      const base = (k + 1) * bandH;
      const acc = new Array(n).fill(0);
      s.phases.forEach((p, j) => {
        const vals = phases[p] || [];
        g.fillStyle = PHASE_COLOURS[j % PHASE_COLOURS.length];
        g.beginPath();
        g.moveTo(0, base);
        for (let i = 0; i < n; i++) g.lineTo((i / Math.max(1, n - 1)) * w, base - Math.min(1, (acc[i] + (vals[i] || 0)) / top) * (bandH - 2));
        for (let i = n - 1; i >= 0; i--) g.lineTo((i / Math.max(1, n - 1)) * w, base - Math.min(1, acc[i] / top) * (bandH - 2));
        g.closePath(); g.fill();
        for (let i = 0; i < n; i++) acc[i] += vals[i] || 0;
      });
      g.fillStyle = "#000"; g.font = "10px system-ui";
      g.fillText(`zone ${rank} (p99 ${top.toFixed(2)} ms)`, 4, base - bandH + 11);
    });
    g.font = "10px system-ui";
    s.phases.forEach((p, j) => { g.fillStyle = PHASE_COLOURS[j % PHASE_COLOURS.length]; g.fillText(p, w - 60, 11 + j * 11); });
    cursor(g, w, h, ticks);
  }
  // Players' kbit/s.
  {
    const c = $("kbps"), g = sizeCanvas(c), w = c.clientWidth, h = c.clientHeight;
    g.clearRect(0, 0, w, h);
    const players = Object.keys(s.clients);
    const top = Math.max(1, ...players.flatMap((p) => s.clients[p]));
    players.forEach((p, k) => {
      g.strokeStyle = p === state.selectedPlayer ? "#000" : RANK_COLOURS[k % RANK_COLOURS.length] + "99";
      g.lineWidth = p === state.selectedPlayer ? 2 : 1;
      g.beginPath();
      s.clients[p].forEach((v, i) => { const x = (i / Math.max(1, n - 1)) * w, y = h - (v / top) * (h - 4); i ? g.lineTo(x, y) : g.moveTo(x, y); });
      g.stroke();
    });
    g.fillStyle = "#000"; g.font = "10px system-ui";
    g.fillText(`max ${top.toFixed(0)} kbit/s`, 4, 11);
    cursor(g, w, h, ticks);
  }
}

// ---- input ----

function installInput() {
  const c = $("map");
  let drag = null;
  c.addEventListener("mousedown", (ev) => { drag = { x: ev.offsetX, y: ev.offsetY, moved: false }; });
  c.addEventListener("mousemove", (ev) => {
    if (!drag) return;
    const dx = ev.offsetX - drag.x, dy = ev.offsetY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
    if (drag.moved) { state.view.ox += dx; state.view.oy += dy; drag.x = ev.offsetX; drag.y = ev.offsetY; drawMap(); }
  });
  c.addEventListener("mouseup", (ev) => {
    const click = drag && !drag.moved;
    drag = null;
    if (!click) return;
    const e = entityAt(ev.offsetX, ev.offsetY);
    if (!e) return;
    const player = state.meta.players.find((p) => p.avatar === e.id);
    if (player) selectPlayer(player.id); else selectEntity(e.id);
  });
  c.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    const [wx, wz] = screenToWorld(ev.offsetX, ev.offsetY);
    state.view.scale *= ev.deltaY < 0 ? 1.2 : 1 / 1.2;
    const [sx, sy] = worldToScreen(wx, wz);
    state.view.ox += ev.offsetX - sx; state.view.oy += ev.offsetY - sy;
    drawMap();
  }, { passive: false });
  $("tick").addEventListener("input", (ev) => { state.following = false; setTick(Number(ev.target.value)); });
  $("play").addEventListener("click", togglePlay);
  document.addEventListener("keydown", (ev) => { if (ev.code === "Space" && ev.target === document.body) { ev.preventDefault(); togglePlay(); } });
  window.addEventListener("resize", () => { drawMap(); drawCharts(); });
}

function togglePlay() {
  state.playing = !state.playing;
  $("play").innerHTML = state.playing ? "&#10074;&#10074;" : "&#9654;";
}

async function playLoop() {
  if (state.playing && state.tick < state.meta.last_tick) await setTick(state.tick + 3);
  else if (state.playing) togglePlay();
  setTimeout(playLoop, 100);
}

async function liveLoop() {
  // Live: the server re-reads the recordings at most once a second; follow the newest tick
  // while the scrubber is at the end.
  try {
    const m = await getJSON("/api/meta");
    const atEnd = state.tick >= state.meta.last_tick - 1;
    state.meta = m;
    $("tick").max = m.last_tick;
    renderMarkers();
    if (m.players.length !== $("players").children.length) renderPlayers();
    if (atEnd || state.following) { state.following = true; await setTick(m.last_tick); }
    state.series = await getJSON("/api/series");
    drawCharts();
  } catch (err) {
    setStatus(`live: ${err.message}`);
  }
  setTimeout(liveLoop, 1000);
}

async function start() {
  try {
    state.meta = await getJSON("/api/meta");
    const m = state.meta;
    $("run-info").textContent = `${m.ranks.length} zone ranks, ${m.gateways.length} gateway(s), ` +
      `${m.players.length} players, ticks ${m.first_tick}–${m.last_tick}` + (m.live ? " (live)" : "");
    $("legend").innerHTML = m.ranks.map((r) => `<span><i style="background:${rankColour(r)}"></i>zone ${r}</span>`).join("") +
      "<span>■ avatar ● NPC/body ◆ item, hatched: ghost, grey: asleep</span>";
    const range = $("tick");
    range.min = m.first_tick; range.max = m.last_tick;
    fitView();
    installInput();
    renderPlayers();
    renderMarkers();
    state.series = await getJSON("/api/series");
    await setTick(m.live ? m.last_tick : m.first_tick + Math.floor((m.last_tick - m.first_tick) / 2));
    playLoop();
    if (m.live) { state.following = true; setTimeout(liveLoop, 1000); }
  } catch (err) {
    setStatus(err.message);
  }
}

window.inspector = { state, setTick, selectPlayer, selectEntity, worldToScreen };
start();
