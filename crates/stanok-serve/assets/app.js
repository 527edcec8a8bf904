// Operator panel: wires the page to the JSON API and the status WebSocket.
//
// Every button is one API call (the same calls the tests make); the page keeps no machine state
// of its own: it shows the last status the server sent (~30 per second) — line, DRO, codes and
// message of the block being executed, all from one frame — and the executed path it has seen.
// A token in the page's URL (?token=…) is sent with every request.
"use strict";

const token = new URLSearchParams(location.search).get("token");
const $ = id => document.getElementById(id);
const AXES = ["X", "Y", "Z", "A", "B", "C", "U", "V", "W"];
const ACTIVE = ["starting", "running", "block_end", "prompt"];
const AT_REST = ["idle", "finished", "stopped", "alarm"];

async function api(method, path, body, signal) {
  const headers = { "Content-Type": "application/json" };
  if (token) headers.Authorization = "Bearer " + token;
  const init = { method, headers, signal };
  if (body !== undefined) init.body = typeof body === "string" ? body : JSON.stringify(body);
  let r;
  try { r = await fetch(path, init); } catch (e) { return { ok: false, status: 0, data: { error: String(e) } }; }
  let data = null;
  try { data = await r.json(); } catch (_) { /* not JSON */ }
  return { ok: r.ok, status: r.status, data };
}

const panel = window.panel = {
  machine: null, view: null, status: null, dirty: false, lastRunState: "idle", lastAlarms: "[]",
  loaded: null,
};

const editor = panel.editor = new Editor({
  textarea: $("editor"), gutter: $("gutter"), highlight: $("highlight"), list: $("diagnostics"),
  big: $("big-view"), bigLines: $("big-lines"),
  fetchLines: async (from, count) => {
    const r = await api("GET", `/api/loaded/lines?from=${from}&count=${count}`);
    return r.ok ? r.data : null;
  },
  onEdit: () => { panel.dirty = true; scheduleCheck(); },
});

function programName() { return $("program-name").value.trim() || "program.ngc"; }
function dialectChoice() { return $("dialect").value || undefined; }

// Check as you type: 400 ms after the last key; a newer check cancels the one in flight (the
// server ends its job when the request goes away).
let checkTimer = null, checkAbort = null;
function scheduleCheck() {
  clearTimeout(checkTimer);
  checkTimer = setTimeout(async () => {
    if (checkAbort) checkAbort.abort();
    checkAbort = new AbortController();
    const r = await api("POST", "/api/check",
      { name: programName(), text: editor.text(), dialect: dialectChoice() }, checkAbort.signal);
    if (r.ok) editor.setDiagnostics(r.data.diagnostics);
  }, 400);
}

async function refreshList() {
  const r = await api("GET", "/api/programs");
  const sel = $("program-select");
  sel.textContent = "";
  for (const name of (r.ok ? r.data.programs : [])) {
    const o = document.createElement("option");
    o.value = o.textContent = name;
    sel.appendChild(o);
  }
}

// A modal question; resolves true for the first button.
function askConfirm(text) {
  $("confirm-text").textContent = text;
  $("confirm").hidden = false;
  return new Promise(resolve => {
    const done = v => { $("confirm").hidden = true; resolve(v); };
    $("confirm-yes").onclick = () => done(true);
    $("confirm-no").onclick = () => done(false);
  });
}

// Loads a program: the editor's text, or (fromFile) the file of that name on the server. While a
// program is in progress the server refuses; the page asks "Stop and load?" and only then sends
// the load again with stop. The editor changes only once the load has succeeded.
async function loadProgram(fromFile) {
  const body = { name: programName(), dialect: dialectChoice() };
  if (!fromFile) body.text = editor.text();
  const stock = $("stock").value.trim();
  if (stock) body.stock = stock;
  let r = await api("POST", "/api/load", body);
  if (r.status === 409 && r.data && r.data.confirm === "stop") {
    const yes = await askConfirm(`${r.data.running} is in progress. Stop it and load ${body.name}?`);
    if (!yes) return r;
    r = await api("POST", "/api/load", { ...body, stop: true });
  }
  if (!r.ok) { showError(r); return r; }
  showLoaded(r.data);
  return r;
}

// The page after a load (also for a page opened while a program is loaded).
function showLoaded(l) {
  panel.loaded = l;
  panel.dirty = false;
  $("program-name").value = l.name;
  if (l.text !== null && l.text !== undefined) {
    if (editor.large || editor.text() !== l.text) editor.setText(l.text);
  } else {
    editor.setLarge(l.lines);
  }
  editor.setDiagnostics(l.diagnostics);
  panel.view.setPreview(l.preview);
  panel.view.clearExecuted();
  const p = l.preview;
  $("preview-info").textContent = !p ? "" :
    `${p.path.points.toLocaleString()} points` +
    (p.path.tolerance_mm >= 0.001 ? ` of ${p.path.points_in.toLocaleString()} (within ${fmt(p.path.tolerance_mm, 3)} mm)` : "") +
    (p.path.truncated_at ? ` · cut at line ${p.path.truncated_at}` : "") +
    (p.violations.length ? ` · ${p.violations.length} travel violation(s)` : "") +
    (p.ends_at_error ? ` · ends at the error in line ${p.ends_at_error.line}` : "") +
    (p.time_estimate === "extrapolated" ? " · time extrapolated" : "");
}

async function openProgram(name) {
  $("program-name").value = name;
  $("dialect").value = "";
  await loadProgram(true);
}

// One alarm line per diagnostic, as the status shows them (`line:column [code] message`).
function alarmItems(alarms) {
  return alarms.map(a => {
    const li = document.createElement("li");
    li.textContent = `${a.line}:${a.column} [${a.code}] ${a.message}`;
    return li;
  });
}

// A refused request. A refusal that carries the program's diagnostics (cycle start of a program
// with errors) shows them, not its summary: the status update that shows the same alarms may
// arrive before or after this answer, and either order must leave the located errors on screen.
function showError(r) {
  const diagnostics = r.data && Array.isArray(r.data.diagnostics) ? r.data.diagnostics : [];
  if (diagnostics.length) {
    $("alarms").replaceChildren(...alarmItems(diagnostics));
    return;
  }
  const li = document.createElement("li");
  li.textContent = (r.data && r.data.error) || ("HTTP " + r.status);
  $("alarms").replaceChildren(li);
}

async function cycleStart(body) {
  const rest = AT_REST.includes(panel.lastRunState);
  if (panel.dirty && rest && !editor.large) {
    const r = await loadProgram(false);
    if (!r.ok) return;
  }
  if (rest) panel.view.clearExecuted();
  const r = await api("POST", "/api/cycle-start", body || {});
  if (!r.ok) showError(r);
}

function fmt(v, d = 3) { return (Math.round(v * 10 ** d) / 10 ** d).toFixed(d); }

function buildDro(axes) {
  const tb = $("dro").tBodies[0];
  if (tb.dataset.axes === axes.join("")) return;
  tb.dataset.axes = axes.join("");
  tb.textContent = "";
  for (const a of axes) {
    const tr = document.createElement("tr");
    tr.dataset.axis = a;
    tr.innerHTML = `<td>${a}</td><td class="work"></td><td class="machine"></td><td class="homed"></td>`;
    tb.appendChild(tr);
  }
}

function codes(el, list) {
  el.replaceChildren(...list.map(c => {
    const s = document.createElement("span");
    s.title = c.group; s.textContent = c.code;
    return s;
  }));
}

// The tool's shape from the machine's tool table (0 / unknown: the view's stub).
function toolShape(number) {
  const t = panel.machine && panel.machine.tools.find(t => t.number === number);
  return { number, diameter: t ? t.diameter : 0, length: t ? t.length : 0 };
}

function show(s) {
  panel.status = s;
  // Tests (and the curious) can keep every frame: panel.frames = [] starts recording.
  if (panel.frames) panel.frames.push(s);
  const was = panel.lastRunState;
  panel.lastRunState = s.run_state;
  const badge = $("run-state");
  badge.textContent = s.run_state.replace("_", " ");
  badge.className = "badge " + s.run_state;
  buildDro(s.axes);
  s.axes.forEach((a, k) => {
    const i = AXES.indexOf(a);
    const tr = $("dro").querySelector(`tr[data-axis="${a}"]`);
    tr.querySelector(".machine").textContent = fmt(s.machine_position[i]);
    tr.querySelector(".work").textContent = fmt(s.work_position[i]);
    tr.querySelector(".homed").textContent = s.homed[k] ? "●" : "○";
  });
  $("feed-actual").textContent = fmt(s.feed_actual, 0);
  $("feed-programmed").textContent = fmt(s.feed_programmed, 0);
  $("spindle").textContent = s.spindles.filter((sp, i) => i === 0 || sp.m !== 5)
    .map((sp, i) => `S${i ? i + 1 : ""}${fmt(sp.rpm, 0)} M${sp.m}` +
      (s.spindle_actual_rpm[i] ? ` (${fmt(s.spindle_actual_rpm[i], 0)} rpm)` : "")).join("  ");
  $("tool").textContent = `T${s.tool} D${s.edge}`;
  $("dialect-used").textContent = s.program ? s.dialect : "";
  $("block").textContent = s.line ? "line " + s.line : "—";
  $("elapsed").textContent = fmt(s.elapsed_s, 1);
  $("estimated").textContent = fmt(s.estimated_s, 1);
  codes($("g-codes"), s.g_codes);
  codes($("m-codes"), s.m_codes);
  $("message").textContent = s.message;
  $("notice").textContent = s.notice || "";
  $("notice-box").hidden = !s.notice;
  $("prompt").hidden = !s.prompt;
  $("prompt-text").textContent = s.prompt || "";
  $("alarms").replaceChildren(...alarmItems(s.alarms));
  const alarmsKey = JSON.stringify(s.alarms);
  if (s.alarms.length && alarmsKey !== panel.lastAlarms) editor.setDiagnostics(s.alarms);
  panel.lastAlarms = alarmsKey;
  $("feed-hold").textContent = s.held ? "Held" : "Feed hold";
  $("single-block").checked = s.single_block;
  $("optional-stop").checked = s.optional_stop;
  for (const [id, v] of [["feed", s.feed_override], ["rapid", s.rapid_override], ["spindle", s.spindle_override]]) {
    if (document.activeElement !== $(id + "-override")) $(id + "-override").value = v;
    $(id + "-override-value").textContent = v + " %";
  }
  editor.setCurrentLine(ACTIVE.includes(s.run_state) ? s.line : 0);
  if (ACTIVE.includes(s.run_state) && AT_REST.includes(was)) panel.view.clearExecuted();
  panel.view.setStatus(s, toolShape(s.tool));
  document.body.classList.toggle("busy", s.run_state !== "idle" && !AT_REST.includes(s.run_state));
}

function connect() {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  const ws = new WebSocket(`${proto}//${location.host}/ws${token ? "?token=" + encodeURIComponent(token) : ""}`);
  ws.onopen = () => { $("connection").textContent = "online"; $("connection").className = "badge"; };
  ws.onmessage = e => {
    const m = JSON.parse(e.data);
    // The stock's live messages (stock.rs) come between the status frames.
    if ("stock" in m) { panel.stock = m.stock; if (panel.view.setStock) panel.view.setStock(m.stock); }
    else show(m);
  };
  ws.onclose = () => {
    $("connection").textContent = "offline"; $("connection").className = "badge off";
    setTimeout(connect, 1000);
  };
}

function setOverride(kind, value) {
  $(kind + "-override").value = value;
  $(kind + "-override-value").textContent = value + " %";
  return api("POST", "/api/override", { [kind]: Number(value) });
}

function wire() {
  $("open").onclick = () => openProgram($("program-select").value);
  $("load").onclick = () => loadProgram(editor.large);
  $("save").onclick = async () => {
    if (editor.large) return;
    const r = await api("PUT", "/api/programs/" + encodeURIComponent(programName()), editor.text());
    if (!r.ok) return showError(r);
    await refreshList();
  };
  $("dialect").onchange = () => { if (!editor.large) scheduleCheck(); };
  $("cycle-start").onclick = () => cycleStart();
  $("feed-hold").onclick = () => api("POST", "/api/feed-hold");
  $("stop").onclick = () => api("POST", "/api/stop");
  $("ack").onclick = () => api("POST", "/api/acknowledge");
  $("notice-ack").onclick = () => api("POST", "/api/acknowledge", { what: "notice" });
  $("prompt-ack").onclick = () => api("POST", "/api/acknowledge");
  $("single-block").onchange = e => api("POST", "/api/switches", { single_block: e.target.checked });
  $("optional-stop").onchange = e => api("POST", "/api/switches", { optional_stop: e.target.checked });
  for (const kind of ["feed", "rapid", "spindle"]) {
    $(kind + "-override").oninput = e => setOverride(kind, e.target.value);
  }
  $("search-start").onclick = () => {
    const n = Number($("search-line").value);
    if (n > 0) cycleStart({ search_line: n });
  };
  $("view-reset").onclick = () => panel.view.fit();
  $("view-top").onclick = () => panel.view.top();
  $("view-iso").onclick = () => panel.view.iso();
}

async function start() {
  const m = await api("GET", "/api/machine");
  panel.machine = m.ok ? m.data : { axes: [], tools: [], dialects: [], lathe: false };
  $("machine-name").textContent = panel.machine.name || "";
  const sel = $("dialect");
  const auto = document.createElement("option");
  auto.value = ""; auto.textContent = "dialect: from the name";
  sel.appendChild(auto);
  for (const d of panel.machine.dialects) {
    const o = document.createElement("option");
    o.value = d.id; o.textContent = d.name;
    sel.appendChild(o);
  }
  panel.view = await createView($("view"), $("labels"), $("view-notice"));
  panel.view.setMachine(panel.machine);
  wire();
  setupManual(panel.machine);
  await refreshList();
  // A page opened while a program is loaded (or running) shows that program.
  const r = await api("GET", "/api/loaded");
  if (r.ok && r.data.name && !editor.text()) {
    $("program-select").value = r.data.name;
    $("dialect").value = r.data.dialect;
    showLoaded(r.data);
  }
  connect();
}

start();
