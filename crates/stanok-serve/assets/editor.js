// Program editor: a plain textarea with a line-number gutter and a highlight layer behind it.
//
// The textarea is sized to its text, so the surrounding box scrolls gutter, highlights and text
// together. The gutter is one text node ("1\n2\n…"), and the highlight layer holds only a few
// absolutely placed bars (the current block, the lines with diagnostics), so a program of
// 100 000 lines costs one string, not 100 000 elements. Line height is fixed (18 px, style.css).
"use strict";

const LINE_PX = 18, PAD_PX = 4;

class Editor {
  constructor({ textarea, gutter, highlight, list, onEdit }) {
    this.ta = textarea; this.gutter = gutter; this.hl = highlight; this.list = list;
    this.diagnostics = []; this.current = 0; this.lines = 0;
    this.ta.addEventListener("input", () => { this.layout(); onEdit(this.ta.value); });
  }

  text() { return this.ta.value; }

  setText(text) { this.ta.value = text; this.layout(); }

  layout() {
    const lines = this.ta.value.split("\n");
    if (lines.length !== this.lines) {
      this.lines = lines.length;
      let s = "";
      for (let i = 1; i <= this.lines; i++) s += i + "\n";
      this.gutter.textContent = s;
    }
    const cols = lines.reduce((m, l) => Math.max(m, l.length), 0);
    this.ta.style.height = (this.lines * LINE_PX + 2 * PAD_PX + 20) + "px";
    this.ta.style.width = "max(100%, " + (cols + 4) + "ch)";
    this.paint();
  }

  bar(line, cls) {
    const d = document.createElement("div");
    d.className = cls;
    d.style.position = "absolute"; d.style.left = "0"; d.style.right = "0";
    d.style.top = (PAD_PX + (line - 1) * LINE_PX) + "px";
    d.dataset.line = line;
    this.hl.appendChild(d);
  }

  paint() {
    this.hl.textContent = "";
    for (const d of this.diagnostics) if (d.severity === "error") this.bar(d.line, "err");
    if (this.current > 0) this.bar(this.current, "current");
  }

  // Diagnostics [{line, column, severity, code, message}] beside their lines and in the list.
  setDiagnostics(list) {
    this.diagnostics = list || [];
    this.list.textContent = "";
    for (const d of this.diagnostics) {
      const li = document.createElement("li");
      li.className = d.severity;
      li.dataset.line = d.line;
      li.textContent = `${d.line}:${d.column} ${d.severity} [${d.code}] ${d.message}`;
      li.addEventListener("click", () => this.reveal(d.line));
      this.list.appendChild(li);
    }
    this.paint();
  }

  // The block the machine executes; scrolled into view when it leaves it.
  setCurrentLine(line) {
    if (line === this.current) return;
    this.current = line;
    this.paint();
    if (line > 0) this.reveal(line, true);
  }

  reveal(line, onlyIfHidden) {
    const box = this.ta.closest("#editor-wrap");
    const y = PAD_PX + (line - 1) * LINE_PX;
    if (onlyIfHidden && y >= box.scrollTop && y + LINE_PX <= box.scrollTop + box.clientHeight) return;
    box.scrollTop = Math.max(0, y - box.clientHeight / 3);
  }
}
