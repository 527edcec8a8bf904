// Operator panel: wires the page to the JSON API and the status WebSocket.
//
// Every button is one API call (the same calls the tests make); the page never keeps machine
// state of its own: it shows the last status the server sent (~30 per second) and the executed
// path it has seen. A token in the page's URL (?token=…) is sent with every request.
"use strict";

const token = new URLSearchParams(location.search).get("token");
const $ = id => document.getElementById(id);
const AXES = ["X", "Y", "Z", "A", "B", "C", "U", "V", "W"];

async function api(method, path, body) {
  const headers = { "Content-Type": "application/json" };
  if (token) headers.Authorization = "Bearer " + token;
  const init = { method, headers };
  if (body !== undefined) init.body = typeof body === "string" ? body : JSON.stringify(body);
  const r = await fetch(path, init);
  let data = null;
  try { data = await r.json(); } catch (_) { /* not JSON */ }
  return { ok: r.ok, status: r.status, data };
}

const view = new PathView($("view"));
const editor = new Editor({
  textarea: $("editor"), gutter: $("gutter"), highlight: $("highlight"), list: $("diagnostics"),
  onEdit: () => { dirty = true; scheduleCheck(); },
});
let dirty = false;
let checkTimer = null;
let lastRunState = "idle";
let lastAlarms = "[]";

function programName() { return $("program-name").value.trim() || "program.ngc"; }

// Check as you type: 400 ms after the last key.
function scheduleCheck() {
  clearTimeout(checkTimer);
  checkTimer = setTimeout(async () => {
    const r = await api("POST", "/api/check", { name: programName(), text: editor.text() });
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

async function openProgram(name) {
  const r = await api("GET", "/api/programs/" + encodeURIComponent(name));
  if (!r.ok) return showError(r);
  $("program-name").value = name;
  editor.setText(r.data.text);
  await loadProgram();
}

// Hands the editor's text to the machine: check, path preview, estimated time.
async function loadProgram() {
  const r = await api("POST", "/api/load", { name: programName(), text: editor.text() });
  if (!r.ok) return showError(r);
  dirty = false;
  editor.setDiagnostics(r.data.diagnostics);
  view.setPath(r.data.preview ? r.data.preview.path : []);
  view.clearExecuted();
  return r;
}

function showError(r) {
  const li = document.createElement("li");
  li.textContent = (r.data && r.data.error) || ("HTTP " + r.status);
  $("alarms").replaceChildren(li);
}

async function cycleStart(body) {
  if (dirty && ["idle", "finished", "stopped", "alarm"].includes(lastRunState)) await loadProgram();
  if (["idle", "finished", "stopped", "alarm"].includes(lastRunState)) view.clearExecuted();
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
    tr.innerHTML = `<td>${a}</td><td class="machine"></td><td class="work"></td>`;
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

function show(s) {
  lastRunState = s.run_state;
  const badge = $("run-state");
  badge.textContent = s.run_state.replace("_", " ");
  badge.className = "badge " + s.run_state;
  buildDro(s.axes);
  for (const a of s.axes) {
    const i = AXES.indexOf(a);
    const tr = $("dro").querySelector(`tr[data-axis="${a}"]`);
    tr.querySelector(".machine").textContent = fmt(s.machine_position[i]);
    tr.querySelector(".work").textContent = fmt(s.work_position[i]);
  }
  $("feed-actual").textContent = fmt(s.feed_actual, 0);
  $("feed-programmed").textContent = fmt(s.feed_programmed, 0);
  $("spindle").textContent = s.spindles.filter((sp, i) => i === 0 || sp.m !== 5)
    .map((sp, i) => `S${i ? i + 1 : ""}${fmt(sp.rpm, 0)} M${sp.m}`).join("  ");
  $("tool").textContent = `T${s.tool} D${s.edge}`;
  $("block").textContent = s.line ? "line " + s.line : "—";
  $("elapsed").textContent = fmt(s.elapsed_s, 1);
  $("estimated").textContent = fmt(s.estimated_s, 1);
  codes($("g-codes"), s.g_codes);
  codes($("m-codes"), s.m_codes);
  $("message").textContent = s.message;
  $("prompt").hidden = !s.prompt;
  $("prompt-text").textContent = s.prompt || "";
  $("alarms").replaceChildren(...s.alarms.map(a => {
    const li = document.createElement("li");
    li.textContent = `${a.line}:${a.column} [${a.code}] ${a.message}`;
    return li;
  }));
  const alarmsKey = JSON.stringify(s.alarms);
  if (s.alarms.length && alarmsKey !== lastAlarms) editor.setDiagnostics(s.alarms);
  lastAlarms = alarmsKey;
  $("feed-hold").textContent = s.held ? "Held" : "Feed hold";
  $("single-block").checked = s.single_block;
  $("optional-stop").checked = s.optional_stop;
  editor.setCurrentLine(["running", "prompt", "block_end"].includes(s.run_state) ? s.line : 0);
  view.toolAxis = s.tool_axis;
  if (s.run_state !== "idle") view.setTool(s.machine_position);
}

function connect() {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  const ws = new WebSocket(`${proto}//${location.host}/ws${token ? "?token=" + encodeURIComponent(token) : ""}`);
  ws.onopen = () => { $("connection").textContent = "online"; $("connection").className = "badge"; };
  ws.onmessage = e => show(JSON.parse(e.data));
  ws.onclose = () => {
    $("connection").textContent = "offline"; $("connection").className = "badge off";
    setTimeout(connect, 1000);
  };
}

$("open").onclick = () => openProgram($("program-select").value);
$("load").onclick = () => loadProgram();
$("save").onclick = async () => {
  const r = await api("PUT", "/api/programs/" + encodeURIComponent(programName()), editor.text());
  if (!r.ok) return showError(r);
  await refreshList();
};
$("cycle-start").onclick = () => cycleStart();
$("feed-hold").onclick = () => api("POST", "/api/feed-hold");
$("stop").onclick = () => api("POST", "/api/stop");
$("ack").onclick = () => api("POST", "/api/acknowledge");
$("prompt-ack").onclick = () => api("POST", "/api/acknowledge");
$("single-block").onchange = e => api("POST", "/api/switches", { single_block: e.target.checked });
$("optional-stop").onchange = e => api("POST", "/api/switches", { optional_stop: e.target.checked });
$("feed-override").oninput = e => {
  $("feed-override-value").textContent = e.target.value + " %";
  api("POST", "/api/override", { feed: Number(e.target.value) });
};
$("rapid-override").oninput = e => {
  $("rapid-override-value").textContent = e.target.value + " %";
  api("POST", "/api/override", { rapid: Number(e.target.value) });
};
$("search-start").onclick = () => {
  const n = Number($("search-line").value);
  if (n > 0) cycleStart({ search_line: n });
};
$("view-reset").onclick = () => view.fit();
$("view-top").onclick = () => view.top();
$("view-iso").onclick = () => view.iso();

// A page opened while a program is loaded (or running) shows that program.
async function showLoaded() {
  const r = await api("GET", "/api/loaded");
  if (!r.ok || !r.data.name || editor.text()) return;
  $("program-name").value = r.data.name;
  $("program-select").value = r.data.name;
  editor.setText(r.data.text);
  editor.setDiagnostics(r.data.diagnostics);
  view.setPath(r.data.preview ? r.data.preview.path : []);
}

refreshList().then(showLoaded);
connect();
