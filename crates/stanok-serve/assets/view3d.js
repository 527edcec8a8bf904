// Tool-path view in WebGL with three.js (pinned in package.json, embedded by build.rs and loaded
// from /assets/ as a module). Without three.js or WebGL the page uses PathView (view2d.js).
//
// Scene (machine coordinates, mm; one group per layer, so another layer — e.g. the cut stock
// mesh — is one `view.addMesh(name, object)` away):
//   grid     lines every `step` mm (1-2-5 series, about 12 over the work) in the XY plane at Z 0
//            (lathe: the ZX plane), with coordinate labels along two edges;
//   travel   the machine's travel box (soft limits), light grey;
//   extents  the program's bounding box with its dimensions as labels;
//   path     feeds solid, rapids dashed (the server sends at most a few hundred thousand points:
//            level of detail, lod.rs); the programmed contour of a lathe program in green;
//   marks    travel violations: red points at the end of each offending move, labelled "line N";
//   ticks    tool-axis ticks of a 5-axis program under tool-centre-point control;
//   executed the path the machine has run (blue), from the status positions;
//   tool     a cylinder of the tool's diameter and length from the tool table (a cone on a lathe),
//            its tip at the tool position, along the tool axis;
//   stock    the stock as the run cuts it (setStock: a height field of at most 128² cells, or a
//            lathe's revolved profile, a few times a second) and its collisions as red points
//            labelled with their lines.
// Camera: orthographic. Mill: orbit (azimuth, elevation) about a target, Z up. Lathe: fixed view,
// Z to the right and X up (looking along −Y), pan and zoom only. Rendering is on demand.
"use strict";

class View3D {
  constructor(canvas, THREE, labels) {
    this.T = THREE;
    this.canvas = canvas;
    this.labelsEl = labels;
    this.kind = "webgl";
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xfbfbfb);
    this.scene = new THREE.Scene();
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.1, 4e6);
    this.target = new THREE.Vector3();
    this.scale = 1;               // mm per pixel
    this.lathe = false;
    this.azimuth = -Math.PI / 4; this.elevation = 35.264 * Math.PI / 180;
    this.layers = {};
    for (const name of ["grid", "travel", "extents", "path", "programmed", "marks", "ticks",
                        "executed", "tool", "stock", "extra"]) {
      const g = new THREE.Group(); g.name = name; this.scene.add(g); this.layers[name] = g;
    }
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.7));
    const sun = new THREE.DirectionalLight(0xffffff, 0.9); sun.position.set(1, -2, 3);
    this.scene.add(sun);
    this.labels = [];             // {el, p: Vector3}
    this.machine = null; this.preview = null; this.extents = null;
    this.toolShape = { diameter: 0, length: 0, number: -1 };
    this.makeExecuted();
    this.pointers = new Map();
    this.listen();
    new ResizeObserver(() => { this.resize(); this.render(); }).observe(canvas);
    this.resize();
    this.top(); this.iso();
  }

  // --- layers -------------------------------------------------------------------------------

  clear(name) {
    const g = this.layers[name];
    for (const c of [...g.children]) {
      g.remove(c);
      c.traverse(o => { if (o.geometry) o.geometry.dispose(); if (o.material) o.material.dispose(); });
    }
  }

  // Adds a mesh (or any object) in its own layer, replacing one of the same name.
  addMesh(name, object) { this.removeMesh(name); object.name = name; this.layers.extra.add(object); this.render(); }
  removeMesh(name) {
    const old = this.layers.extra.getObjectByName(name);
    if (old) this.layers.extra.remove(old);
    this.render();
  }

  segments(positions, material) {
    const T = this.T, geo = new T.BufferGeometry();
    geo.setAttribute("position", new T.Float32BufferAttribute(positions, 3));
    const line = new T.LineSegments(geo, material);
    if (material.isLineDashedMaterial) line.computeLineDistances();
    return line;
  }

  // Flattened polylines → segment pairs (LineSegments draws them as one call).
  static pairs(pieces, wantRapid) {
    let n = 0;
    for (const p of pieces) if (p.rapid === wantRapid && p.points.length >= 6) n += p.points.length / 3 - 1;
    const out = new Float32Array(n * 6);
    let k = 0;
    for (const p of pieces) {
      if (p.rapid !== wantRapid) continue;
      const a = p.points;
      for (let i = 3; i < a.length; i += 3) {
        out[k++] = a[i - 3]; out[k++] = a[i - 2]; out[k++] = a[i - 1];
        out[k++] = a[i]; out[k++] = a[i + 1]; out[k++] = a[i + 2];
      }
    }
    return out;
  }

  setMachine(info) {
    this.machine = info;
    this.lathe = !!info.lathe;
    this.drawTravel();
    this.drawGrid();
    this.fit();
  }

  travelBox() {
    const m = this.machine;
    if (!m) return null;
    const lo = [0, 0, 0], hi = [0, 0, 0];
    let any = false;
    for (const a of m.axes) {
      if (a.index > 2 || a.min === null || a.max === null) continue;
      lo[a.index] = a.min; hi[a.index] = a.max; any = true;
    }
    return any ? [lo, hi] : null;
  }

  static boxEdges(lo, hi) {
    const c = (i, j, k) => [i ? hi[0] : lo[0], j ? hi[1] : lo[1], k ? hi[2] : lo[2]];
    const e = [];
    const edge = (a, b) => e.push(...c(...a), ...c(...b));
    for (const j of [0, 1]) for (const k of [0, 1]) edge([0, j, k], [1, j, k]);
    for (const i of [0, 1]) for (const k of [0, 1]) edge([i, 0, k], [i, 1, k]);
    for (const i of [0, 1]) for (const j of [0, 1]) edge([i, j, 0], [i, j, 1]);
    return e;
  }

  drawTravel() {
    this.clear("travel");
    const box = this.travelBox();
    if (!box) return;
    const mat = new this.T.LineDashedMaterial({ color: 0x9aa4b0, dashSize: 10, gapSize: 6 });
    this.layers.travel.add(this.segments(View3D.boxEdges(...box), mat));
  }

  // 1-2-5 step giving about `n` lines over `span`.
  static niceStep(span, n) {
    const raw = Math.max(span, 1e-3) / n;
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
    return 10 * p;
  }

  drawGrid() {
    this.clear("grid");
    this.labels = this.labels.filter(l => { if (l.layer === "grid") { l.el.remove(); return false; } return true; });
    const region = this.extents || this.travelBox() || [[-50, -50, -50], [50, 50, 50]];
    // Horizontal axes of the grid plane: mill X (0) and Y (1); lathe Z (2) and X (0).
    const [u, v] = this.lathe ? [2, 0] : [0, 1];
    const span = Math.max(region[1][u] - region[0][u], region[1][v] - region[0][v], 1);
    const step = View3D.niceStep(span, 12);
    this.gridStep = step;
    const lo = [0, 1].map(k => Math.floor(region[0][[u, v][k]] / step - 1) * step);
    const hi = [0, 1].map(k => Math.ceil(region[1][[u, v][k]] / step + 1) * step);
    const pos = [];
    const P = (a, b) => { const p = [0, 0, 0]; p[u] = a; p[v] = b; return p; };
    for (let a = lo[0]; a <= hi[0] + 1e-9; a += step) pos.push(...P(a, lo[1]), ...P(a, hi[1]));
    for (let b = lo[1]; b <= hi[1] + 1e-9; b += step) pos.push(...P(lo[0], b), ...P(hi[0], b));
    const mat = new this.T.LineBasicMaterial({ color: 0xe2e6ea });
    this.layers.grid.add(this.segments(pos, mat));
    // The machine's axes through zero, stronger.
    const axes = [...P(lo[0], 0), ...P(hi[0], 0), ...P(0, lo[1]), ...P(0, hi[1])];
    this.layers.grid.add(this.segments(axes, new this.T.LineBasicMaterial({ color: 0xb8c0c8 })));
    if (this.lathe) {
      // The spindle centre line (X = 0 along Z), dash-dot.
      const cl = new this.T.LineDashedMaterial({ color: 0x7a3b9a, dashSize: step / 2, gapSize: step / 6 });
      const line = this.segments([0, 0, lo[0], 0, 0, hi[0]], cl);
      line.name = "centre-line";
      this.layers.grid.add(line);
    }
    // Coordinates along the near edges of the region shown (the grid reaches a step beyond it).
    const names = ["X", "Y", "Z"];
    const edgeU = Math.floor(region[0][v] / step) * step, edgeV = Math.floor(region[0][u] / step) * step;
    const every = Math.max(1, Math.round((hi[0] - lo[0]) / step / 6));
    for (let i = 0, a = lo[0]; a <= hi[0] + 1e-9; a += step, i++) {
      if (i % every === 0) this.label(`${names[u]}${fmtNum(a)}`, P(a, edgeU), "grid");
    }
    const everyV = Math.max(1, Math.round((hi[1] - lo[1]) / step / 6));
    for (let i = 0, b = lo[1]; b <= hi[1] + 1e-9; b += step, i++) {
      if (i % everyV === 0) this.label(`${names[v]}${fmtNum(b)}`, P(edgeV, b), "grid");
    }
  }

  label(text, p, layer, cls) {
    const el = document.createElement("span");
    el.textContent = text;
    el.className = "label " + (cls || layer);
    this.labelsEl.appendChild(el);
    this.labels.push({ el, p: new this.T.Vector3(p[0], p[1], p[2]), layer });
  }

  dropLabels(layer) {
    this.labels = this.labels.filter(l => { if (l.layer === layer) { l.el.remove(); return false; } return true; });
  }

  setPreview(preview) {
    this.preview = preview;
    for (const n of ["path", "programmed", "marks", "ticks", "extents"]) this.clear(n);
    for (const n of ["marks", "extents"]) this.dropLabels(n);
    this.extents = null;
    if (preview) {
      if (preview.lathe !== undefined) this.lathe = preview.lathe || (this.machine && this.machine.lathe);
      const pieces = preview.path.pieces;
      const T = this.T;
      const feed = View3D.pairs(pieces, false), rapid = View3D.pairs(pieces, true);
      this.layers.path.add(this.segments(feed, new T.LineBasicMaterial({ color: 0x1b2733 })));
      const dashed = new T.LineDashedMaterial({ color: 0xd9480f, dashSize: 3, gapSize: 2 });
      const r = this.segments(rapid, dashed); r.name = "rapids";
      this.layers.path.add(r);
      if (preview.programmed) {
        const prog = View3D.pairs(preview.programmed.pieces, false);
        this.layers.programmed.add(this.segments(prog, new T.LineBasicMaterial({ color: 0x2b8a3e })));
      }
      if (preview.tool_axis && preview.tool_axis.length) {
        const t = new Float32Array(preview.tool_axis.length * 6);
        preview.tool_axis.forEach(([a, b], i) => t.set([...a, ...b], i * 6));
        this.layers.ticks.add(this.segments(t, new T.LineBasicMaterial({ color: 0x862e9c })));
      }
      const marks = preview.violations || [];
      if (marks.length) {
        const geo = new T.BufferGeometry();
        geo.setAttribute("position", new T.Float32BufferAttribute(marks.flatMap(m => m.at), 3));
        const mat = new T.PointsMaterial({ color: 0xe03131, size: 11, sizeAttenuation: false });
        this.layers.marks.add(new T.Points(geo, mat));
        marks.slice(0, 30).forEach(m => this.label(`line ${m.line}`, m.at, "marks", "violation"));
      }
      if (preview.path.extents) {
        const [lo, hi] = preview.path.extents;
        this.extents = [lo, hi];
        const mat = new T.LineDashedMaterial({ color: 0x74c0fc, dashSize: 2, gapSize: 2 });
        const box = this.segments(View3D.boxEdges(lo, hi), mat); box.name = "extents-box";
        this.layers.extents.add(box);
        const mid = [0, 1, 2].map(i => (lo[i] + hi[i]) / 2);
        const dims = [["X", 0, [mid[0], lo[1], lo[2]]], ["Y", 1, [hi[0], mid[1], lo[2]]],
                      ["Z", 2, [hi[0], lo[1], mid[2]]]];
        for (const [name, i, at] of dims) {
          if (this.lathe && name === "Y") continue;
          this.label(`${name} ${fmtNum(hi[i] - lo[i], 3)}`, at, "extents", "dimension");
        }
      }
    }
    this.drawGrid();
    this.fit();
  }

  // --- the machine -------------------------------------------------------------------------

  makeExecuted() {
    const T = this.T;
    this.execCap = 200000;
    this.execBuf = new Float32Array(this.execCap * 3);
    this.execN = 0;
    const geo = new T.BufferGeometry();
    geo.setAttribute("position", new T.BufferAttribute(this.execBuf, 3));
    geo.setDrawRange(0, 0);
    // Drawn over the programmed path it follows (no depth test), blue.
    this.execLine = new T.Line(geo, new T.LineBasicMaterial({ color: 0x1c7ed6, depthTest: false }));
    this.execLine.frustumCulled = false;
    this.execLine.renderOrder = 10;
    this.layers.executed.add(this.execLine);
  }

  clearExecuted() {
    this.execN = 0;
    this.execLine.geometry.setDrawRange(0, 0);
    this.render();
  }

  appendExecuted(p) {
    const b = this.execBuf;
    if (this.execN > 0) {
      const k = (this.execN - 1) * 3;
      if (Math.hypot(p[0] - b[k], p[1] - b[k + 1], p[2] - b[k + 2]) < 1e-4) return;
    }
    if (this.execN >= this.execCap) {
      b.copyWithin(0, (this.execCap / 2) * 3);
      this.execN = this.execCap / 2;
    }
    b.set([p[0], p[1], p[2]], this.execN * 3);
    this.execN++;
    const attr = this.execLine.geometry.getAttribute("position");
    attr.needsUpdate = true;
    this.execLine.geometry.setDrawRange(0, this.execN);
  }

  // The tool solid: diameter and length from the tool table (a 6 × 30 mm stub without them).
  makeTool(diameter, length) {
    this.clear("tool");
    const T = this.T;
    const d = diameter > 0 ? diameter : 6, l = length > 0 ? length : 30;
    const g = new T.Group();
    const mat = new T.MeshLambertMaterial({ color: 0xf08c00, transparent: true, opacity: 0.75 });
    let body;
    if (this.lathe) {
      // An insert: a flat cone with its tip at the cutting point.
      const h = Math.min(l / 2, 12);
      body = new T.Mesh(new T.ConeGeometry(Math.max(d / 2, 1) + h / 4, h, 3), mat);
      body.rotation.x = Math.PI;
      body.position.y = h / 2;
    } else {
      body = new T.Mesh(new T.CylinderGeometry(d / 2, d / 2, l, 24), mat);
      body.position.y = l / 2;
    }
    body.name = "tool-body";
    g.add(body);
    if (!this.lathe) {
      const axis = this.segments([0, 0, 0, 0, l * 1.6, 0], new T.LineBasicMaterial({ color: 0xc92a2a }));
      g.add(axis);
    }
    this.tool = g;
    this.toolSize = { diameter: d, length: l };
    this.layers.tool.add(g);
  }

  // Shows the status: tool position and axis, the executed path while a program runs.
  setStatus(s, shape) {
    const key = `${shape.number}:${shape.diameter}:${shape.length}:${this.lathe}`;
    if (key !== this.toolKey) { this.toolKey = key; this.makeTool(shape.diameter, shape.length); }
    const p = s.machine_position;
    this.tool.position.set(p[0], p[1], p[2]);
    const a = s.tool_axis || [0, 0, 1];
    const up = this.lathe ? new this.T.Vector3(1, 0, 0) : new this.T.Vector3(a[0], a[1], a[2]).normalize();
    this.tool.quaternion.setFromUnitVectors(new this.T.Vector3(0, 1, 0), up);
    if (["running", "prompt", "block_end", "mdi", "jogging", "homing"].includes(s.run_state)) this.appendExecuted(p);
    this.render();
  }

  // --- the stock ---------------------------------------------------------------------------

  // A live message of the stock (stock.rs): heights base64 u16 LE, 65535 = no material; null =
  // no stock. A height field keeps its geometry while its size stays, only the heights change.
  setStock(st) {
    const T = this.T;
    this.stockUpdates = (this.stockUpdates || 0) + 1;
    this.stockInfo = st;
    if (!st) { this.clear("stock"); this.stockMesh = null; this.stockKey = null; this.dropLabels("stock"); this.render(); return; }
    const bin = atob(st.heights), q = new Uint16Array(bin.length >> 1);
    for (let i = 0; i < q.length; i++) q[i] = bin.charCodeAt(2 * i) | (bin.charCodeAt(2 * i + 1) << 8);
    const [lo, hi] = st.range, h = v => v === 65535 ? null : lo + (hi - lo) * v / 65534;
    const key = `${st.kind}:${st.n[0]}x${st.n[1]}:${st.origin}:${st.cell}:${st.range}:${st.offset}:${st.rotation_deg}`;
    if (st.kind === "mill") {
      const [nx, ny] = st.n;
      if (key !== this.stockKey) {
        this.clear("stock");
        // (nx × ny) top vertices at the cell centres and as many at the bottom for the walls.
        const pos = new Float32Array(nx * ny * 2 * 3), idx = [];
        for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) {
          const k = j * nx + i, x = st.origin[0] + (i + 0.5) * st.cell[0], y = st.origin[1] + (j + 0.5) * st.cell[1];
          pos.set([x, y, hi], k * 3); pos.set([x, y, lo], (nx * ny + k) * 3);
        }
        for (let j = 0; j + 1 < ny; j++) for (let i = 0; i + 1 < nx; i++) {
          const a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
          idx.push(a, b, d, a, d, c);
        }
        const B = nx * ny, wall = (a, b) => idx.push(a, B + a, B + b, a, B + b, b);
        for (let i = 0; i + 1 < nx; i++) { wall(i + 1, i); wall((ny - 1) * nx + i, (ny - 1) * nx + i + 1); }
        for (let j = 0; j + 1 < ny; j++) { wall(j * nx, (j + 1) * nx); wall((j + 1) * nx + nx - 1, j * nx + nx - 1); }
        const geo = new T.BufferGeometry();
        geo.setAttribute("position", new T.BufferAttribute(pos, 3));
        geo.setAttribute("color", new T.BufferAttribute(new Float32Array(nx * ny * 2 * 3).fill(0.62), 3));
        geo.setIndex(idx);
        // Drawn over the grid lines that lie in its top (Z 0).
        const mat = new T.MeshLambertMaterial({ vertexColors: true, side: T.DoubleSide,
          polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -4 });
        this.stockMesh = new T.Mesh(geo, mat);
        this.stockMesh.name = "stock-mesh";
        this.stockMesh.position.set(...st.offset);
        this.stockMesh.rotation.z = st.rotation_deg * Math.PI / 180;
        this.layers.stock.add(this.stockMesh);
        this.stockKey = key;
      }
      const attr = this.stockMesh.geometry.getAttribute("position");
      const col = this.stockMesh.geometry.getAttribute("color");
      // A cell without material is drawn at the stock's bottom (a hole through). The raw top is
      // steel grey; a cut surface is tan, darker the deeper it is.
      for (let k = 0; k < nx * ny; k++) {
        const z = h(q[k]), at = z === null ? lo : z;
        attr.array[k * 3 + 2] = at;
        const d = q[k] >= 65534 ? -1 : (hi - at) / Math.max(hi - lo, 1e-9);
        col.array.set(d < 0 ? [0.62, 0.68, 0.74] : [0.93 - 0.45 * d, 0.76 - 0.45 * d, 0.46 - 0.3 * d], k * 3);
      }
      attr.needsUpdate = true; col.needsUpdate = true;
      this.stockMesh.geometry.computeVertexNormals();
      this.stockMesh.geometry.computeBoundingSphere();
    } else {
      // A lathe: the outer radius along Z revolved about the spindle axis.
      this.clear("stock");
      const pts = [new T.Vector2(0, st.z0)];
      for (let k = 0; k < st.n[0]; k++) {
        const r = h(q[k]) || 0, z0 = st.z0 + k * st.cell[0];
        pts.push(new T.Vector2(r, z0), new T.Vector2(r, z0 + st.cell[0]));
      }
      pts.push(new T.Vector2(0, st.z0 + st.n[0] * st.cell[0]));
      const mesh = new T.Mesh(new T.LatheGeometry(pts, 48), new T.MeshLambertMaterial({ color: 0x9fb4c7, side: T.DoubleSide }));
      // LatheGeometry turns about its Y axis: Y → Z.
      mesh.rotation.x = Math.PI / 2;
      mesh.position.set(st.offset[0] + st.origin[0], st.offset[1] + st.origin[1], st.offset[2]);
      mesh.name = "stock-mesh";
      this.layers.stock.add(mesh);
      this.stockMesh = mesh;
      this.stockKey = key;
    }
    // Collisions: red points at their positions, labelled with their lines.
    const old = this.layers.stock.getObjectByName("stock-collisions");
    if (old) { this.layers.stock.remove(old); old.geometry.dispose(); old.material.dispose(); }
    this.dropLabels("stock");
    const cs = st.collisions || [];
    if (cs.length) {
      const geo = new T.BufferGeometry();
      geo.setAttribute("position", new T.Float32BufferAttribute(cs.flatMap(c => c.position), 3));
      const pts = new T.Points(geo, new T.PointsMaterial({ color: 0xe03131, size: 12, sizeAttenuation: false, depthTest: false }));
      pts.name = "stock-collisions"; pts.renderOrder = 11;
      this.layers.stock.add(pts);
      cs.slice(0, 30).forEach(c => this.label(`line ${c.line} ${c.kind.replace(/_/g, " ")}`, c.position, "stock", "violation"));
    }
    this.render();
  }

  // The stock's top at machine (x, y) as the last message drew it (null: no material or no
  // stock): what the tests read.
  stockZ(x, y) {
    const st = this.stockInfo;
    if (!st || st.kind !== "mill") return null;
    const a = -st.rotation_deg * Math.PI / 180, dx = x - st.offset[0], dy = y - st.offset[1];
    const qx = Math.cos(a) * dx - Math.sin(a) * dy, qy = Math.sin(a) * dx + Math.cos(a) * dy;
    const i = Math.floor((qx - st.origin[0]) / st.cell[0]), j = Math.floor((qy - st.origin[1]) / st.cell[1]);
    if (i < 0 || j < 0 || i >= st.n[0] || j >= st.n[1]) return null;
    const k = j * st.n[0] + i, bin = atob(st.heights);
    const v = bin.charCodeAt(2 * k) | (bin.charCodeAt(2 * k + 1) << 8);
    return v === 65535 ? null : st.range[0] + (st.range[1] - st.range[0]) * v / 65534 + st.offset[2];
  }

  // --- camera ------------------------------------------------------------------------------

  iso() { if (!this.lathe) { this.azimuth = -Math.PI / 4; this.elevation = 35.264 * Math.PI / 180; } this.render(); }
  top() { if (!this.lathe) { this.azimuth = -Math.PI / 2; this.elevation = Math.PI / 2; } this.render(); }

  fit() {
    const box = this.extents || this.travelBox() || [[-50, -50, -50], [50, 50, 50]];
    const [lo, hi] = box;
    this.target.set((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    if (this.lathe) this.target.y = 0;
    const diag = Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 1);
    const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 300;
    this.scale = diag / (0.85 * Math.min(w, h));
    this.render();
  }

  placeCamera() {
    const T = this.T, c = this.camera;
    let dir, up;
    if (this.lathe) {
      dir = new T.Vector3(0, 1, 0); up = new T.Vector3(1, 0, 0);
    } else {
      const ce = Math.cos(this.elevation), se = Math.sin(this.elevation);
      const ca = Math.cos(this.azimuth), sa = Math.sin(this.azimuth);
      dir = new T.Vector3(ce * ca, ce * sa, se);
      up = new T.Vector3(-se * ca, -se * sa, ce);
    }
    c.position.copy(this.target).addScaledVector(dir, 1e6);
    c.up.copy(up);
    c.lookAt(this.target);
    const w = this.canvas.clientWidth || 1, h = this.canvas.clientHeight || 1;
    c.left = -w / 2 * this.scale; c.right = w / 2 * this.scale;
    c.top = h / 2 * this.scale; c.bottom = -h / 2 * this.scale;
    c.updateProjectionMatrix();
    // Dashes about 8 px long whatever the zoom.
    const rapids = this.layers.path.getObjectByName("rapids");
    if (rapids) { rapids.material.dashSize = 8 * this.scale; rapids.material.gapSize = 5 * this.scale; }
    const box = this.layers.extents.getObjectByName("extents-box");
    if (box) { box.material.dashSize = 3 * this.scale; box.material.gapSize = 3 * this.scale; }
  }

  resize() {
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    if (w && h) this.renderer.setSize(w, h, false);
  }

  render() {
    if (this.pending) return;
    this.pending = requestAnimationFrame(() => { this.pending = 0; this.draw(); });
  }

  draw() {
    this.placeCamera();
    this.renderer.render(this.scene, this.camera);
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    const v = new this.T.Vector3();
    for (const l of this.labels) {
      v.copy(l.p).project(this.camera);
      const x = (v.x + 1) / 2 * w, y = (1 - v.y) / 2 * h;
      const inside = x >= 0 && x <= w && y >= 0 && y <= h;
      l.el.style.display = inside ? "" : "none";
      if (inside) l.el.style.transform = `translate(${x.toFixed(1)}px, ${y.toFixed(1)}px)`;
    }
  }

  // What the tests read.
  stats() {
    const count = g => g.children.reduce((n, o) => n + (o.geometry ? o.geometry.getAttribute("position").count : 0), 0);
    return {
      kind: this.kind, lathe: this.lathe, gridStep: this.gridStep,
      pathVertices: count(this.layers.path), programmedVertices: count(this.layers.programmed),
      violations: count(this.layers.marks), ticks: count(this.layers.ticks) / 2,
      executed: this.execN, travelBox: this.layers.travel.children.length > 0,
      stock: this.stockInfo ? {
        updates: this.stockUpdates, kind: this.stockInfo.kind, n: this.stockInfo.n,
        removed_mm3: this.stockInfo.removed_mm3, initial_mm3: this.stockInfo.initial_mm3,
        done: this.stockInfo.done, collisions: (this.stockInfo.collisions || []).length,
        vertices: this.stockMesh ? this.stockMesh.geometry.getAttribute("position").count : 0,
      } : null,
      extents: this.extents, tool: this.toolSize,
      labels: this.labels.map(l => l.el.textContent),
      toolAxis: this.tool ? [0, 1, 0].map((_, i) => new this.T.Vector3(0, 1, 0).applyQuaternion(this.tool.quaternion).toArray()[i]) : null,
    };
  }

  // Mouse, pen and touch: one pointer orbits (pans with shift or the right button; always pans in
  // the lathe view), two pinch-zoom; the wheel zooms about the cursor.
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
        const before = Math.hypot(p.x - o.x, p.y - o.y), after = Math.hypot(e.clientX - o.x, e.clientY - o.y);
        if (after > 0) this.scale *= before / after;
      } else if (p.pan) {
        const c = this.camera;
        const right = new this.T.Vector3().setFromMatrixColumn(c.matrix, 0);
        const up = new this.T.Vector3().setFromMatrixColumn(c.matrix, 1);
        this.target.addScaledVector(right, -dx * this.scale).addScaledVector(up, dy * this.scale);
      } else {
        this.azimuth -= dx * 0.01;
        this.elevation = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, this.elevation + dy * 0.01));
      }
      p.x = e.clientX; p.y = e.clientY;
      this.render();
    });
    cv.addEventListener("wheel", e => {
      e.preventDefault();
      const f = Math.exp(e.deltaY * 0.001);
      const r = cv.getBoundingClientRect();
      const mx = e.clientX - r.left - r.width / 2, my = e.clientY - r.top - r.height / 2;
      const c = this.camera;
      const right = new this.T.Vector3().setFromMatrixColumn(c.matrix, 0);
      const up = new this.T.Vector3().setFromMatrixColumn(c.matrix, 1);
      // Keep the point under the cursor where it is.
      this.target.addScaledVector(right, mx * this.scale * (1 - f)).addScaledVector(up, -my * this.scale * (1 - f));
      this.scale *= f;
      this.render();
    }, { passive: false });
  }
}

// A coordinate as a label: no trailing zeros.
function fmtNum(v, digits = 3) {
  return String(Math.round(v * 10 ** digits) / 10 ** digits);
}

// The view: WebGL when three.js is built in and WebGL works, else the 2D canvas with a notice.
async function createView(canvas, labels, notice) {
  if (STANOK_THREE) {
    try {
      const THREE = await import("/assets/three.module.js");
      return new View3D(canvas, THREE, labels);
    } catch (e) {
      notice.textContent = "3D view unavailable (" + (e && e.message ? e.message : e) + "): drawn in 2D.";
      notice.hidden = false;
      console.warn(e);
    }
  } else {
    notice.textContent = "This panel was built without three.js (npm ci in crates/stanok-serve, then rebuild): the path is drawn in 2D.";
    notice.hidden = false;
  }
  // The 2D canvas cannot share a canvas that WebGL already claimed: take a fresh one.
  const fresh = canvas.cloneNode(false);
  canvas.replaceWith(fresh);
  return new PathView(fresh, labels);
}
