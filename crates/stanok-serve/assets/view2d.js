// The fallback view: a small orthographic renderer of 3D polylines on a 2D canvas (own code),
// used when the panel is built without three.js or the browser has no WebGL (view3d.js says so
// in a notice). Same methods as View3D, fewer layers: path, violations, executed path, tool.
//
// Model space is machine X Y Z in mm. A point p goes to the screen by
//   q = Rx(pitch) · Rz(yaw) · (p − centre);   screen = (w/2 + panX + s·q.x, h/2 + panY − s·q.y)
// so pitch 0 is the top view and pitch −55° with yaw −45° an isometric-like view, Z up; the lathe
// view maps (Z, X) to the screen's (x, y). The programmed path is drawn into an off-screen layer
// only when the path or the view changes; the executed path and the tool on every frame.
"use strict";

class PathView {
  constructor(canvas, labels) {
    this.kind = "2d";
    this.canvas = canvas;
    this.labelsEl = labels;
    this.ctx = canvas.getContext("2d");
    this.layer = document.createElement("canvas");
    this.path = [];
    this.marks = [];
    this.executed = [];
    this.tool = null;
    this.toolAxis = [0, 0, 1];
    this.centre = [0, 0, 0];
    this.scale = 1;
    this.pan = [0, 0];
    this.lathe = false;
    this.iso();
    this.layerDirty = true;
    this.pointers = new Map();
    this.listen();
    new ResizeObserver(() => this.redraw()).observe(canvas);
  }

  iso() { this.yaw = -Math.PI / 4; this.pitch = -55 * Math.PI / 180; this.redraw(); }
  top() { this.yaw = 0; this.pitch = 0; this.redraw(); }
  addMesh() {}
  removeMesh() {}

  setMachine(info) { this.lathe = !!info.lathe; this.fit(); }

  setPreview(preview) {
    this.path = [];
    this.marks = preview ? preview.violations || [] : [];
    if (preview) {
      if (preview.lathe !== undefined) this.lathe = preview.lathe;
      for (const piece of preview.path.pieces) {
        const pts = [];
        for (let i = 0; i + 2 < piece.points.length; i += 3) pts.push([piece.points[i], piece.points[i + 1], piece.points[i + 2]]);
        this.path.push({ rapid: piece.rapid, points: pts });
      }
    }
    this.fit();
  }

  clearExecuted() { this.executed = []; this.draw(); }

  setStatus(s, shape) {
    const p = s.machine_position;
    if (["running", "prompt", "block_end", "mdi", "jogging", "homing"].includes(s.run_state)) {
      const last = this.executed[this.executed.length - 1];
      if (!last || Math.hypot(p[0] - last[0], p[1] - last[1], p[2] - last[2]) > 1e-4) {
        this.executed.push([p[0], p[1], p[2]]);
        if (this.executed.length > 200000) this.executed.splice(0, 100000);
      }
    }
    this.tool = p;
    this.toolAxis = s.tool_axis || [0, 0, 1];
    this.shape = shape;
    this.draw();
  }

  stats() {
    return {
      kind: this.kind, lathe: this.lathe,
      pathVertices: this.path.reduce((n, p) => n + p.points.length, 0),
      violations: this.marks.length, executed: this.executed.length,
    };
  }

  bounds() {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const piece of this.path) for (const p of piece.points) for (let i = 0; i < 3; i++) {
      lo[i] = Math.min(lo[i], p[i]); hi[i] = Math.max(hi[i], p[i]);
    }
    if (!isFinite(lo[0])) return [[-50, -50, -50], [50, 50, 50]];
    return [lo, hi];
  }

  fit() {
    const [lo, hi] = this.bounds();
    this.centre = [0, 1, 2].map(i => (lo[i] + hi[i]) / 2);
    const diag = Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 1);
    const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 300;
    this.scale = 0.85 * Math.min(w, h) / diag;
    this.pan = [0, 0];
    this.redraw();
  }

  project(p) {
    const x = p[0] - this.centre[0], y = p[1] - this.centre[1], z = p[2] - this.centre[2];
    if (this.lathe) return [this.w / 2 + this.pan[0] + this.scale * z, this.h / 2 + this.pan[1] - this.scale * x];
    const cy = Math.cos(this.yaw), sy = Math.sin(this.yaw);
    const x1 = cy * x - sy * y, y1 = sy * x + cy * y;
    const cp = Math.cos(this.pitch), sp = Math.sin(this.pitch);
    const y2 = cp * y1 - sp * z;
    return [this.w / 2 + this.pan[0] + this.scale * x1, this.h / 2 + this.pan[1] - this.scale * y2];
  }

  redraw() { this.layerDirty = true; this.draw(); }

  resize() {
    const dpr = window.devicePixelRatio || 1;
    this.w = this.canvas.clientWidth; this.h = this.canvas.clientHeight;
    const W = Math.max(1, Math.round(this.w * dpr)), H = Math.max(1, Math.round(this.h * dpr));
    if (this.canvas.width !== W || this.canvas.height !== H) {
      this.canvas.width = W; this.canvas.height = H;
      this.layer.width = W; this.layer.height = H;
      this.layerDirty = true;
    }
    return dpr;
  }

  drawLayer(dpr) {
    const c = this.layer.getContext("2d");
    c.setTransform(1, 0, 0, 1, 0, 0);
    c.clearRect(0, 0, this.layer.width, this.layer.height);
    c.setTransform(dpr, 0, 0, dpr, 0, 0);
    c.lineWidth = 1.5;
    for (const piece of this.path) {
      c.strokeStyle = piece.rapid ? "#d9480f" : "#1b2733";
      c.setLineDash(piece.rapid ? [6, 5] : []);
      c.beginPath();
      piece.points.forEach((p, i) => {
        const [sx, sy] = this.project(p);
        if (i === 0) c.moveTo(sx, sy); else c.lineTo(sx, sy);
      });
      c.stroke();
    }
    c.setLineDash([]);
    c.fillStyle = "#e03131";
    for (const m of this.marks) {
      const [sx, sy] = this.project(m.at);
      c.beginPath(); c.arc(sx, sy, 5, 0, 2 * Math.PI); c.fill();
    }
    this.layerDirty = false;
  }

  draw() {
    const dpr = this.resize();
    if (this.layerDirty) this.drawLayer(dpr);
    const c = this.ctx;
    c.setTransform(1, 0, 0, 1, 0, 0);
    c.clearRect(0, 0, this.canvas.width, this.canvas.height);
    c.drawImage(this.layer, 0, 0);
    c.setTransform(dpr, 0, 0, dpr, 0, 0);
    if (this.executed.length > 1) {
      c.strokeStyle = "#1c7ed6"; c.lineWidth = 2.5; c.globalAlpha = 0.6;
      c.beginPath();
      this.executed.forEach((p, i) => {
        const [sx, sy] = this.project(p);
        if (i === 0) c.moveTo(sx, sy); else c.lineTo(sx, sy);
      });
      c.stroke(); c.globalAlpha = 1;
    }
    if (this.tool) {
      const [tx, ty] = this.project(this.tool);
      const len = ((this.shape && this.shape.length) || 30);
      const top = [0, 1, 2].map(i => this.tool[i] + this.toolAxis[i] * len);
      const [ax, ay] = this.project(top);
      c.strokeStyle = "#f08c00"; c.lineWidth = Math.max(3, ((this.shape && this.shape.diameter) || 6) * this.scale);
      c.globalAlpha = 0.75;
      c.beginPath(); c.moveTo(tx, ty); c.lineTo(ax, ay); c.stroke();
      c.globalAlpha = 1;
      c.fillStyle = "#c92a2a"; c.beginPath(); c.arc(tx, ty, 4, 0, 2 * Math.PI); c.fill();
    }
  }

  // Mouse, pen and touch through pointer events: one pointer rotates (pans with shift or the right
  // button), two pointers pinch-zoom and pan; the wheel zooms about the cursor.
  listen() {
    const cv = this.canvas;
    cv.addEventListener("contextmenu", e => e.preventDefault());
    cv.addEventListener("pointerdown", e => {
      cv.setPointerCapture(e.pointerId);
      this.pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 || this.lathe });
    });
    const end = e => this.pointers.delete(e.pointerId);
    cv.addEventListener("pointerup", end);
    cv.addEventListener("pointercancel", end);
    cv.addEventListener("pointermove", e => {
      const p = this.pointers.get(e.pointerId);
      if (!p) return;
      const dx = e.clientX - p.x, dy = e.clientY - p.y;
      if (this.pointers.size >= 2) {
        const o = [...this.pointers.entries()].find(([id]) => id !== e.pointerId)[1];
        const before = Math.hypot(p.x - o.x, p.y - o.y);
        const after = Math.hypot(e.clientX - o.x, e.clientY - o.y);
        if (before > 0) this.scale *= after / before;
        this.pan[0] += dx / 2; this.pan[1] += dy / 2;
      } else if (p.pan) {
        this.pan[0] += dx; this.pan[1] += dy;
      } else {
        this.yaw += dx * 0.01;
        this.pitch = Math.max(-Math.PI, Math.min(0, this.pitch + dy * 0.01));
      }
      p.x = e.clientX; p.y = e.clientY;
      this.redraw();
    });
    cv.addEventListener("wheel", e => {
      e.preventDefault();
      const f = Math.exp(-e.deltaY * 0.001);
      const r = cv.getBoundingClientRect();
      const mx = e.clientX - r.left - this.w / 2 - this.pan[0];
      const my = e.clientY - r.top - this.h / 2 - this.pan[1];
      this.pan[0] -= mx * (f - 1); this.pan[1] -= my * (f - 1);
      this.scale *= f;
      this.redraw();
    }, { passive: false });
  }
}
