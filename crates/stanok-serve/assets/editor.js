// Program editor: a plain textarea with a line-number gutter and a highlight layer behind it, and
// for large programs a read-only view that holds only the lines on screen.
//
// Small programs: the textarea is sized to its text, so the surrounding box scrolls gutter,
// highlights and text together. The gutter is one text node ("1\n2\n…"), and the highlight layer
// holds only a few absolutely placed bars (the current block, the lines with errors), so a program
// of 100 000 lines costs one string, not 100 000 elements. Line height is fixed (18 px, style.css).
//
// Large programs (the server does not send text over 2 MB; a 10-million-block file is 100 MB
// and more): a scroller whose height stands for the whole program (capped at 8 million px:
// browsers cap element heights, so a scroll position maps to a line by proportion) and a block of
// the ~50 lines on screen, fetched from /api/loaded/lines as the view scrolls.
"use strict";

const LINE_PX = 18, PAD_PX = 4, BIG_MAX_PX = 8e6;

class Editor {
  constructor({ textarea, gutter, highlight, list, big, bigLines, fetchLines, onEdit }) {
    this.ta = textarea; this.gutter = gutter; this.hl = highlight; this.list = list;
    this.big = big; this.bigLines = bigLines; this.fetchLines = fetchLines;
    this.diagnostics = []; this.current = 0; this.lines = 0;
    this.large = false; this.total = 0; this.cache = null; this.fetching = null;
    this.ta.addEventListener("input", () => { this.layout(); onEdit(this.ta.value); });
    this.big.addEventListener("scroll", () => this.paintBig());
    this.spacer = document.createElement("div");
    this.big.prepend(this.spacer);
  }

  text() { return this.large ? null : this.ta.value; }

  setText(text) {
    this.large = false;
    this.big.hidden = true;
    this.ta.closest("#editor-wrap").hidden = false;
    this.ta.value = text;
    this.layout();
  }

  // A program too large to edit in the page: `total` lines, fetched as shown.
  setLarge(total) {
    this.large = true;
    this.total = total;
    this.cache = null;
    this.ta.value = "";
    this.ta.closest("#editor-wrap").hidden = true;
    this.big.hidden = false;
    this.spacer.style.height = Math.min(total * LINE_PX, BIG_MAX_PX) + "px";
    this.big.scrollTop = 0;
    this.paintBig();
  }

  visibleLines() { return Math.max(1, Math.ceil(this.big.clientHeight / LINE_PX)); }

  // The first line shown for the scroll position (module doc: by proportion).
  firstLine() {
    const room = Math.max(1, this.spacer.offsetHeight - this.big.clientHeight);
    const span = Math.max(0, this.total - this.visibleLines());
    return 1 + Math.round(Math.min(1, this.big.scrollTop / room) * span);
  }

  async paintBig() {
    if (!this.large) return;
    const first = this.firstLine(), n = this.visibleLines() + 2;
    const c = this.cache;
    if (!c || first < c.from || first + n > c.from + c.lines.length) {
      const from = Math.max(1, first - 40);
      if (this.fetching === from) return;
      this.fetching = from;
      const got = await this.fetchLines(from, n + 80);
      this.fetching = null;
      if (!got || !this.large) return;
      this.cache = { from: got.from, lines: got.lines };
    }
    const errs = new Set(this.diagnostics.filter(d => d.severity === "error").map(d => d.line));
    const rows = [];
    const cached = this.cache;
    for (let k = first; k < first + n && k <= this.total; k++) {
      const row = document.createElement("div");
      row.dataset.line = k;
      if (k === this.current) row.className = "current";
      else if (errs.has(k)) row.className = "err";
      const num = document.createElement("span");
      num.className = "num"; num.textContent = k;
      row.append(num, cached.lines[k - cached.from] ?? "");
      rows.push(row);
    }
    this.bigLines.style.top = this.big.scrollTop + "px";
    this.bigLines.replaceChildren(...rows);
  }

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
    if (this.large) return void this.paintBig();
    this.hl.textContent = "";
    for (const d of this.diagnostics) if (d.severity === "error") this.bar(d.line, "err");
    if (this.current > 0) this.bar(this.current, "current");
  }

  // Diagnostics [{line, column, severity, code, message}] beside their lines and in the list.
  setDiagnostics(list) {
    this.diagnostics = list || [];
    this.list.textContent = "";
    for (const d of this.diagnostics.slice(0, 500)) {
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
    if (this.large) {
      const first = this.firstLine(), n = this.visibleLines();
      if (onlyIfHidden && line >= first && line < first + n) return;
      const want = Math.max(1, line - Math.floor(n / 3));
      const span = Math.max(1, this.total - n);
      const room = Math.max(1, this.spacer.offsetHeight - this.big.clientHeight);
      this.big.scrollTop = Math.min(1, (want - 1) / span) * room;
      this.paintBig();
      return;
    }
    const box = this.ta.closest("#editor-wrap");
    const y = PAD_PX + (line - 1) * LINE_PX;
    if (onlyIfHidden && y >= box.scrollTop && y + LINE_PX <= box.scrollTop + box.clientHeight) return;
    box.scrollTop = Math.max(0, y - box.clientHeight / 3);
  }
}
