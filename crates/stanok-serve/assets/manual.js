// Manual modes and keyboard shortcuts.
//
// Jog: a − and + button per axis. With an increment chosen, a press moves by it; "continuous"
// moves while the button (or key) is held: the page tells the server "still held" every 200 ms and
// "released" on release, so a lost page stops the jog within half a second. Home all / per axis,
// touch-off (the active work offset so that the axis reads the typed value), MDI (one block at a
// time in the selected dialect — else the loaded program's —, Enter runs it, ↑/↓ recall).
//
// Keys (as LinuxCNC's AXIS; not while typing in a field): ←/→ X (lathe: Z), ↑/↓ Y (lathe: X),
// PageUp/PageDown Z, Home: reference return of all axes, F1 or Esc: stop, ` and 1…9, 0: feed
// override 0 %, 10…90 %, 100 %.
"use strict";

const jog = { held: null, timer: null };

function jogStart(axis, direction) {
  if (jog.held) return;
  const step = $("jog-step").value;
  const speed = Number($("jog-speed").value) || 1000;
  const body = { axis, direction, speed };
  if (step) {
    body.increment = Number(step);
    api("POST", "/api/jog", body).then(manualResult);
    return;
  }
  jog.held = axis + direction;
  api("POST", "/api/jog", body).then(manualResult);
  jog.timer = setInterval(() => api("POST", "/api/jog/alive"), 200);
}

function jogEnd() {
  if (!jog.held) return;
  jog.held = null;
  clearInterval(jog.timer);
  api("POST", "/api/jog/stop");
}

function manualResult(r) {
  const out = $("manual-result");
  if (r.ok) out.textContent = r.data.done || (r.data.moving ? "moving" : "");
  else out.textContent = (r.data && r.data.error) || ("HTTP " + r.status);
  out.className = r.ok ? "muted" : "error";
  return r;
}

const mdiHistory = [];
let mdiRecall = -1;

async function runMdi() {
  const text = $("mdi-text").value.trim();
  if (!text) return;
  const dialect = $("dialect").value || (panel.status && panel.status.dialect) || undefined;
  const r = manualResult(await api("POST", "/api/mdi", { text, dialect }));
  mdiHistory.unshift(text);
  mdiRecall = -1;
  const li = document.createElement("li");
  li.textContent = text;
  li.className = r.ok ? "" : "error";
  if (!r.ok && r.data && r.data.diagnostics && r.data.diagnostics[0]) {
    const d = r.data.diagnostics[0];
    li.title = `${d.column}: [${d.code}] ${d.message}`;
  }
  $("mdi-history").prepend(li);
  while ($("mdi-history").children.length > 20) $("mdi-history").lastChild.remove();
  if (r.ok) $("mdi-text").value = "";
}

function setupManual(machine) {
  const box = $("jog-axes"), homes = $("home-axes"), touch = $("touch-axis");
  $("jog-speed").value = Math.round(machine.jog_speed || 1000);
  for (const a of machine.axes) {
    const row = document.createElement("div");
    row.className = "jog-row";
    const name = document.createElement("span");
    name.textContent = a.name;
    row.appendChild(name);
    for (const [text, dir] of [["−", -1], ["+", 1]]) {
      const b = document.createElement("button");
      b.textContent = a.name + text;
      b.id = `jog-${a.name}${dir > 0 ? "plus" : "minus"}`;
      b.className = "jog";
      b.addEventListener("pointerdown", e => { e.preventDefault(); jogStart(a.name, dir); });
      for (const ev of ["pointerup", "pointerleave", "pointercancel"]) b.addEventListener(ev, jogEnd);
      row.appendChild(b);
    }
    box.appendChild(row);
    const h = document.createElement("button");
    h.textContent = "Home " + a.name;
    h.id = "home-" + a.name;
    h.onclick = async () => manualResult(await api("POST", "/api/home", { axis: a.name }));
    homes.appendChild(h);
    const o = document.createElement("option");
    o.value = o.textContent = a.name;
    touch.appendChild(o);
  }
  $("home-all").onclick = async () => manualResult(await api("POST", "/api/home", {}));
  $("touch-off").onclick = async () => {
    const r = manualResult(await api("POST", "/api/touch-off",
      { axis: touch.value, value: Number($("touch-value").value) }));
    // The preview was made with the old offset: load it again (the server checks the travel).
    if (r.ok && panel.loaded && AT_REST.includes(panel.lastRunState)) loadProgram(editor.large || !panel.dirty);
  };
  $("mdi-run").onclick = runMdi;
  $("mdi-text").addEventListener("keydown", e => {
    if (e.key === "Enter") { e.preventDefault(); runMdi(); }
    else if (e.key === "ArrowUp" && mdiHistory.length) {
      mdiRecall = Math.min(mdiHistory.length - 1, mdiRecall + 1);
      $("mdi-text").value = mdiHistory[mdiRecall];
      e.preventDefault();
    } else if (e.key === "ArrowDown") {
      mdiRecall = Math.max(-1, mdiRecall - 1);
      $("mdi-text").value = mdiRecall >= 0 ? mdiHistory[mdiRecall] : "";
      e.preventDefault();
    }
  });
  window.addEventListener("blur", jogEnd);
  document.addEventListener("keydown", onKey);
  document.addEventListener("keyup", e => { if (jogKey(e.key)) jogEnd(); });
}

// The axis and direction of a jog key (module doc).
function jogKey(key) {
  const lathe = panel.machine && panel.machine.lathe;
  const keys = lathe
    ? { ArrowLeft: ["Z", -1], ArrowRight: ["Z", 1], ArrowUp: ["X", 1], ArrowDown: ["X", -1] }
    : { ArrowLeft: ["X", -1], ArrowRight: ["X", 1], ArrowUp: ["Y", 1], ArrowDown: ["Y", -1],
        PageUp: ["Z", 1], PageDown: ["Z", -1] };
  const k = keys[key];
  return k && panel.machine.axes.some(a => a.name === k[0]) ? k : null;
}

function onKey(e) {
  if (e.key === "F1" || e.key === "Escape") {
    e.preventDefault();
    jogEnd();
    api("POST", "/api/stop");
    return;
  }
  const t = e.target;
  if (t && (t.tagName === "INPUT" || t.tagName === "TEXTAREA" || t.tagName === "SELECT") && t.type !== "range" && t.type !== "checkbox") return;
  if (e.ctrlKey || e.altKey || e.metaKey) return;
  const k = jogKey(e.key);
  if (k) {
    e.preventDefault();
    if (!e.repeat) jogStart(k[0], k[1]);
    return;
  }
  if (e.key === "Home") { e.preventDefault(); $("home-all").click(); return; }
  const percent = e.key === "`" ? 0 : /^[0-9]$/.test(e.key) ? (e.key === "0" ? 100 : 10 * Number(e.key)) : null;
  if (percent !== null) { e.preventDefault(); setOverride("feed", percent); }
}
