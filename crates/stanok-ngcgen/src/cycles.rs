//! Sections that need set-up around them: canned cycles (G73, G74, G76 is in `threading`,
//! G81–G89) in every plane with G98/G99, G90/G91 and L repeats; cutter compensation on contours
//! that compensate (G41/G42 with D, G41.1/G42.1); splines G5/G5.1/G5.2; G33/G33.1/G76; lathe
//! cycles G70–G72 with their profile subroutine.
//!
//! Each leaves no cycle or compensation active, the feed mode G94, and the position unknown
//! (cycles end at levels that depend on G98/G99).

use crate::sections::{feed_word, r4};
use crate::{Gen, TOOLS};

fn need_g94(g: &mut Gen) {
    if g.st.feed_mode != 94 {
        g.line("G94");
        g.st.feed_mode = 94;
    }
    let f = g.rlen(50.0, 1500.0);
    let fw = g.w('F', f);
    g.line(fw);
}

fn need_spindle(g: &mut Gen) {
    if !g.st.spindle {
        g.line("S500 M3");
        g.st.spindle = true;
    }
}

/// Canned drilling, boring and tapping cycles.
pub fn canned(g: &mut Gen) {
    need_g94(g);
    if g.st.diameter {
        g.line("G8");
        g.st.diameter = false;
    }
    let plane = *g.rng.pick(&[17u8, 17, 18, 19]);
    g.st.plane = plane;
    g.line(format!("G{plane}"));
    g.feat(match plane {
        17 => "cycle: in G17",
        18 => "cycle: in G18",
        _ => "cycle: in G19",
    });
    // (first, second) position axes and the drilling axis.
    let (a1, a2, ad) = g.plane_axes();
    let code = *g.rng.pick(&[
        "G73", "G74", "G81", "G82", "G83", "G84", "G85", "G86", "G87", "G88", "G89",
    ]);
    g.feat(match code {
        "G73" => "cycle: G73",
        "G74" => "cycle: G74",
        "G81" => "cycle: G81",
        "G82" => "cycle: G82",
        "G83" => "cycle: G83",
        "G84" => "cycle: G84",
        "G85" => "cycle: G85",
        "G86" => "cycle: G86",
        "G87" => "cycle: G87",
        "G88" => "cycle: G88",
        _ => "cycle: G89",
    });
    if matches!(code, "G74" | "G84" | "G86" | "G87" | "G88") {
        need_spindle(g);
    }
    let retract = if g.rng.chance(0.5) { "G98" } else { "G99" };
    g.feat(if retract == "G98" {
        "cycle: G98"
    } else {
        "cycle: G99"
    });
    // Start above the work in absolute coordinates.
    if !g.st.absolute {
        g.line("G90");
        g.st.absolute = true;
    }
    let start_level = g.rlen(10.0, 30.0);
    let (p1, p2) = (g.slen(0.0, 40.0), g.slen(0.0, 40.0));
    let (w1, w2, wd) = (g.w(a1, p1), g.w(a2, p2), g.w(ad, start_level));
    g.line(format!("G0 {w1} {w2} {wd}"));
    let incremental = g.rng.chance(0.4);
    if incremental {
        g.feat("cycle: G91 with L repeats");
        g.line("G91");
        g.st.absolute = false;
    } else {
        g.feat("cycle: G90");
    }
    let r_level = g.rlen(0.0, 8.0);
    let depth = g.rlen(2.0, 12.0);
    let mut words = vec![retract.to_string(), code.to_string()];
    let (q1, q2) = if incremental {
        (g.slen(0.0, 15.0), g.slen(0.0, 15.0))
    } else {
        (g.slen(0.0, 40.0), g.slen(0.0, 40.0))
    };
    if g.rng.chance(0.9) {
        words.push(g.wx(a1, q1));
    }
    words.push(g.wx(a2, q2));
    if incremental {
        // R from the start level, the bottom from R.
        let r = r4(r_level - start_level);
        words.push(g.w('R', r));
        words.push(g.w(ad, -depth));
    } else {
        words.push(g.w('R', r_level));
        words.push(g.w(ad, r4(r_level - depth)));
    }
    match code {
        "G73" | "G83" => {
            let q = g.rlen(0.5, 4.0);
            words.push(g.w('Q', q));
        }
        "G82" | "G89" => {
            let p = g.rng.value(0.1, 2.0);
            words.push(g.w('P', p));
        }
        "G87" => {
            // Back boring: I J offsets, K the back level (absolute).
            let (i, j) = (g.slen(0.5, 3.0), g.slen(0.5, 3.0));
            let (iw, jw) = (g.w('I', i), g.w('J', j));
            words.push(iw);
            words.push(jw);
            let k = if incremental {
                g.rlen(0.5, 3.0)
            } else {
                r4(r_level - depth + g.rlen(0.5, 3.0))
            };
            words.push(g.w('K', k));
        }
        _ => {}
    }
    if incremental && g.rng.chance(0.6) {
        let l = g.rng.int(2, 4);
        words.push(format!("L{l}"));
    }
    g.line(words.join(" "));
    // Further holes at other positions (the cycle is modal).
    for _ in 0..g.rng.below(3) {
        g.feat("cycle: modal repeat block");
        let v = if incremental {
            g.slen(1.0, 10.0)
        } else {
            g.slen(0.0, 40.0)
        };
        let w = g.w(a1, v);
        g.line(w);
    }
    g.line("G80");
    g.feat("cycle: G80");
    if incremental && g.rng.chance(0.5) {
        g.line("G90");
        g.st.absolute = true;
    }
    g.forget_position();
}

/// Cutter radius compensation on a convex contour with lines and arcs.
pub fn cutter_comp(g: &mut Gen) {
    need_g94(g);
    if g.st.diameter {
        g.line("G8");
        g.st.diameter = false;
    }
    if g.st.plane != 17 {
        g.line("G17");
        g.st.plane = 17;
    }
    if !g.st.absolute {
        g.line("G90");
        g.st.absolute = true;
    }
    let side = if g.rng.chance(0.5) { "G41" } else { "G42" };
    let code = match g.rng.below(3) {
        0 => {
            let d = g.rlen(1.0, 6.0);
            g.feat("comp: G41.1/G42.1 D diameter");
            format!("{side}.1 {}", g.w('D', d))
        }
        1 => {
            let (t, _, _) = TOOLS[g.rng.below(2) as usize];
            g.feat("comp: G41/G42 D tool");
            format!("{side} D{t}")
        }
        _ => {
            // The tool in the spindle.
            if g.st.tool == 0 {
                g.line("T2 M6");
                g.st.tool = 2;
            }
            g.feat("comp: G41/G42 tool in spindle");
            side.to_string()
        }
    };
    g.feat(if side == "G41" {
        "comp: G41"
    } else {
        "comp: G42"
    });
    // A square of side s with one corner rounded by an arc, centred at (ox, oy).
    let s = g.rlen(30.0, 60.0);
    let (ox, oy) = (g.slen(0.0, 20.0), g.slen(0.0, 20.0));
    let z = g.rlen(-5.0, 5.0);
    let lead = g.rlen(15.0, 25.0);
    let (x0, y0) = (r4(ox - s / 2.0), r4(oy - s / 2.0));
    let (x1, y1) = (r4(ox + s / 2.0), r4(oy + s / 2.0));
    let rad = r4(s / 4.0);
    let (sx, sy, sz) = (
        g.w('X', r4(x0 - lead)),
        g.w('Y', r4(y0 - lead)),
        g.w('Z', z),
    );
    g.line(format!("G0 {sx} {sy} {sz}"));
    g.line(code);
    let ccw = g.rng.chance(0.5);
    let mut path: Vec<String> = Vec::new();
    let xw = |g: &mut Gen, v: f64| g.w('X', v);
    let yw = |g: &mut Gen, v: f64| g.w('Y', v);
    let entry = format!("G1 {} {}", xw(g, x0), yw(g, y0));
    path.push(entry);
    if ccw {
        path.push(format!("X{}", r4(x1 - rad)));
        path.push(format!("G3 X{} Y{} I0 J{}", x1, r4(y0 + rad), rad));
        path.push(format!("G1 Y{y1}"));
        path.push(format!("X{x0}"));
        path.push(format!("Y{y0}"));
    } else {
        path.push(format!("Y{}", r4(y1 - rad)));
        path.push(format!("G2 X{} Y{} I{} J0", r4(x0 + rad), y1, rad));
        path.push(format!("G1 X{x1}"));
        path.push(format!("Y{y0}"));
        path.push(format!("X{x0}"));
    }
    if g.rng.chance(0.3) {
        g.feat("comp: Z move under compensation");
        let dz = r4(z - g.rlen(0.5, 2.0));
        path.insert(2, format!("G1 Z{dz}"));
    }
    for l in path {
        g.line(l);
    }
    g.line("G40");
    g.feat("comp: G40");
    let (ex, ey) = (g.w('X', r4(x0 - lead)), g.w('Y', r4(y0 - lead)));
    g.line(format!("G1 {ex} {ey}"));
    g.forget_position();
}

/// G5 cubic, G5.1 quadratic, G5.2/G5.3 NURBS (XY plane).
pub fn splines(g: &mut Gen) {
    need_g94(g);
    if g.st.plane != 17 {
        g.line("G17");
        g.st.plane = 17;
    }
    if g.st.diameter {
        g.line("G8");
        g.st.diameter = false;
    }
    match g.rng.below(3) {
        0 => {
            g.feat("spline: G5 cubic");
            let n = 1 + g.rng.below(3);
            for k in 0..n {
                let (x, y) = (g.slen(1.0, 20.0), g.slen(1.0, 20.0));
                let (p, q) = (g.slen(1.0, 10.0), g.slen(1.0, 10.0));
                let (xw, yw, pw, qw) = (g.w('X', x), g.w('Y', y), g.w('P', p), g.w('Q', q));
                if k == 0 || g.rng.chance(0.5) {
                    let (i, j) = (g.slen(1.0, 10.0), g.slen(1.0, 10.0));
                    let (iw, jw) = (g.w('I', i), g.w('J', j));
                    g.line(format!("G5 {iw} {jw} {pw} {qw} {xw} {yw}"));
                } else {
                    // Later pieces may leave I/J out: tangent continuity with the previous one.
                    g.line(format!("G5 {pw} {qw} {xw} {yw}"));
                }
            }
        }
        1 => {
            g.feat("spline: G5.1 quadratic");
            let (x, y) = (g.slen(1.0, 20.0), g.slen(1.0, 20.0));
            let (i, j) = (g.slen(1.0, 10.0), g.slen(1.0, 10.0));
            let (xw, yw, iw, jw) = (g.w('X', x), g.w('Y', y), g.w('I', i), g.w('J', j));
            g.line(format!("G5.1 {xw} {yw} {iw} {jw}"));
        }
        _ => {
            g.feat("spline: G5.2/G5.3 NURBS");
            let n = 4 + g.rng.below(3);
            for k in 0..n {
                let (x, y) = (g.slen(0.0, 20.0), g.slen(0.0, 20.0));
                let p = g.rng.value(0.5, 2.0);
                let (xw, yw, pw) = (g.w('X', x), g.w('Y', y), g.w('P', p));
                if k == 0 {
                    g.line(format!("G5.2 {xw} {yw} {pw} L3"));
                } else {
                    g.line(format!("{xw} {yw} {pw}"));
                }
            }
            g.line("G5.3");
        }
    }
    g.forget_position();
}

/// G33 spindle-synchronised motion, G33.1 rigid tapping, G76 threading (XZ plane).
pub fn threading(g: &mut Gen) {
    need_g94(g);
    need_spindle(g);
    if !g.st.absolute {
        g.line("G90");
        g.st.absolute = true;
    }
    match g.rng.below(3) {
        0 => {
            g.feat("thread: G33");
            let z = g.slen(1.0, 20.0);
            let k = g.rlen(0.5, 3.0);
            let (zw, kw) = (g.w('Z', z), g.w('K', k));
            g.line(format!("G33 {zw} {kw}"));
        }
        1 => {
            g.feat("thread: G33.1 rigid tap");
            g.line("G0 X0 Y0 Z5");
            let z = g.rlen(-15.0, -1.0);
            let k = g.rlen(0.5, 2.0);
            let (zw, kw) = (g.w('Z', z), g.w('K', k));
            g.line(format!("G33.1 {zw} {kw}"));
        }
        _ => {
            g.feat("thread: G76");
            g.line("G18");
            g.st.plane = 18;
            let x = g.rlen(5.0, 20.0);
            let (xw, zw) = (g.w('X', x), g.w('Z', g.len(2.0)));
            g.line(format!("G0 {xw} {zw}"));
            let p = g.rlen(0.8, 2.5);
            let z = g.rlen(-30.0, -10.0);
            let i = -g.rlen(0.2, 1.0);
            let j = g.rlen(0.05, 0.2);
            let k = g.rlen(0.6, 1.5);
            let mut words = vec![
                "G76".to_string(),
                g.w('P', p),
                g.w('Z', z),
                g.w('I', i),
                g.w('J', j),
                g.w('K', k),
            ];
            if g.rng.chance(0.5) {
                let r = g.rng.value(1.0, 2.5);
                words.push(g.w('R', r));
            }
            if g.rng.chance(0.5) {
                words.push(format!("Q{}", g.rng.int(0, 30)));
            }
            if g.rng.chance(0.5) {
                words.push(format!("H{}", g.rng.int(0, 2)));
            }
            if g.rng.chance(0.3) {
                let e = g.rlen(0.2, 1.0);
                words.push(g.w('E', e));
                words.push(format!("L{}", g.rng.int(0, 3)));
            }
            g.line(words.join(" "));
        }
    }
    g.forget_position();
}

/// G70/G71/G72 (and .1/.2) with a type-1 profile subroutine, in G18.
pub fn lathe(g: &mut Gen) {
    need_g94(g);
    if !g.st.absolute {
        g.line("G90");
        g.st.absolute = true;
    }
    g.line("G18");
    g.st.plane = 18;
    let diameter = g.rng.chance(0.2);
    if diameter {
        g.feat("lathe: G7 diameter mode");
        g.line("G7");
    }
    let q = g.label();
    // A monotonic profile: X grows, Z falls, steps and a fillet arc.
    let x0 = g.rlen(8.0, 12.0);
    let z1 = -g.rlen(5.0, 10.0);
    let x1 = r4(x0 + g.rlen(2.0, 4.0));
    let z2 = r4(z1 - g.rlen(5.0, 10.0));
    let x2 = r4(x1 + g.rlen(1.0, 3.0));
    let z3 = r4(z2 - g.rlen(3.0, 6.0));
    let mut body = vec![
        format!("O{q} SUB"),
        format!("G0 X{x0} Z0"),
        format!("G1 Z{z1}"),
        format!("G1 X{x1}"),
        format!("G1 Z{z2}"),
    ];
    if g.rng.chance(0.4) {
        g.feat("lathe: profile arc");
        // A quarter circle from (x1, z2) to (x2, z2 − r). Under G7 the X words are diameters
        // and I is still a radius: r is half the X step, else the arc is off its radius (which
        // LinuxCNC 2.9's G7x reader does not check and cuts as garbage).
        let (r, x2) = if diameter {
            let r = r4((x2 - x1) / 2.0);
            (r, r4(x1 + 2.0 * r))
        } else {
            (r4(x2 - x1), x2)
        };
        body.push(format!("G2 X{x2} Z{} I{r} K0", r4(z2 - r)));
        body.push(format!("G1 Z{}", r4(z3 - r)));
    } else {
        body.push(format!("G1 X{x2} Z{z3}"));
    }
    body.push(format!("O{q} ENDSUB"));
    for l in body {
        g.line(l);
    }
    let (sx, sz) = (r4(x2 + g.rlen(2.0, 6.0)), g.rlen(2.0, 6.0));
    let (xw, zw) = (g.w('X', sx), g.w('Z', sz));
    g.line(format!("G0 {xw} {zw}"));
    let code = *g
        .rng
        .pick(&["G70", "G71", "G71.1", "G71.2", "G72", "G72.1", "G72.2"]);
    g.feat(match code {
        "G70" => "lathe: G70",
        "G71" | "G71.1" | "G71.2" => "lathe: G71 family",
        _ => "lathe: G72 family",
    });
    let mut words = vec![code.to_string(), format!("Q{q}"), xw, zw];
    if code == "G70" {
        if g.rng.chance(0.5) {
            let d = g.rlen(0.2, 1.0);
            words.push(g.w('D', d));
            words.push(format!("P{}", g.rng.int(1, 3)));
        }
    } else {
        let i = g.rlen(0.5, 2.0);
        words.push(g.w('I', i));
        if g.rng.chance(0.5) {
            let d = g.rlen(0.1, 0.5);
            words.push(g.w('D', d));
        }
        if g.rng.chance(0.3) {
            let r = g.rlen(0.1, 1.0);
            words.push(g.w('R', r));
        }
    }
    if g.rng.chance(0.3) {
        let f = feed_word(g);
        words.push(f);
    }
    g.line(words.join(" "));
    if diameter {
        g.line("G8");
    }
    g.forget_position();
}
