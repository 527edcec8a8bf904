//! The sections of a program: short passages, each exercising one area of the language from the
//! tracked state and leaving the state valid for the next (see lib.rs). Canned cycles, cutter
//! compensation, splines, threading and lathe cycles are in `cycles.rs`, O-word control flow in
//! `flow.rs`.

use crate::{cycles, flow, Gen, TOOLS};

/// Rounds to 4 decimals (coordinates computed from angles).
pub fn r4(v: f64) -> f64 {
    let r = (v * 10000.0).round() / 10000.0;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// Units, distance mode, plane, feed; sometimes spindle and a tool.
pub fn prelude(g: &mut Gen) {
    if g.rng.chance(0.3) {
        g.line("(generated program)");
        g.feat("surface: comment line");
    }
    let mut words = Vec::new();
    if g.rng.chance(0.85) {
        g.st.metric = g.rng.chance(0.7);
        words.push(if g.st.metric { "G21" } else { "G20" }.to_string());
    }
    if g.rng.chance(0.7) {
        words.push("G90".into());
    }
    if g.rng.chance(0.5) {
        words.push("G17".into());
    }
    if g.rng.chance(0.3) {
        words.push("G40 G49 G80".into());
    }
    if g.rng.chance(0.3) {
        words.push("G94".into());
    }
    let f = g.rlen(50.0, 2000.0);
    words.push(g.w('F', f));
    g.line(words.join(" "));
    if g.rng.chance(0.6) {
        let s = g.rng.int(100, 3000) as f64;
        let m = if g.rng.chance(0.8) { "M3" } else { "M4" };
        let sw = g.w('S', s);
        g.line(format!("{sw} {m}"));
        g.st.spindle = true;
        g.feat("spindle: S M3/M4");
    }
    if g.rng.chance(0.3) {
        tools(g);
    }
}

/// One random section.
pub fn section(g: &mut Gen) {
    match g.rng.below(26) {
        0..=3 => moves(g),
        4..=6 => arcs(g),
        7 | 8 => params(g),
        9 | 10 => flow::control_flow(g),
        11 => offsets(g),
        12 => tools(g),
        13 | 14 => cycles::canned(g),
        15 => cycles::cutter_comp(g),
        16 => cycles::splines(g),
        17 => cycles::threading(g),
        18 => cycles::lathe(g),
        19 => feeds(g),
        20 => units(g),
        21 => modes(g),
        22 => mcodes(g),
        23 => probe(g),
        24 => homes(g),
        _ => flow::call_sub(g),
    }
}

/// Cancels what must not be open at the end and ends the program.
pub fn ending(g: &mut Gen) {
    if g.rng.chance(0.3) {
        g.line("G80 G40");
    }
    let end = if g.rng.chance(0.75) { "M2" } else { "M30" };
    g.line(end);
    g.feat(if end == "M2" { "end: M2" } else { "end: M30" });
    // Subroutines written after the end (LinuxCNC finds them by searching forward).
    flow::late_subs(g);
}

/// The letters of extra axes a move may carry.
const ROTARY: [char; 3] = ['A', 'B', 'C'];

/// G0/G1 moves with some axes, modal continuation blocks, G91 deltas.
pub fn moves(g: &mut Gen) {
    g.feat("motion: G0/G1");
    let n = 2 + g.rng.below(5);
    let mut modal: Option<&str> = None;
    for _ in 0..n {
        let rapid = g.rng.chance(0.35);
        let code = if rapid { "G0" } else { "G1" };
        let mut words = Vec::new();
        if modal != Some(code) || g.rng.chance(0.5) {
            words.push(code.to_string());
        } else {
            g.feat("motion: modal block (axis words only)");
        }
        let mut any = false;
        let mut delta = [0.0; 3];
        let mut target = g.st.pos;
        for (i, letter) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            if g.rng.chance(0.6) {
                let v = if g.st.absolute {
                    let v = g.slen(0.0, 60.0);
                    if let Some(t) = target.as_mut() {
                        t[i] = v;
                    }
                    v
                } else {
                    let d = g.slen(0.0, 20.0);
                    delta[i] = d;
                    d
                };
                words.push(g.wx(letter, v));
                any = true;
            }
        }
        if g.rng.chance(0.15) {
            let a = *g.rng.pick(&ROTARY);
            let v = g.rng.signed(0.0, 360.0);
            words.push(g.w(a, v));
            g.feat("motion: rotary axis A/B/C");
            any = true;
        }
        if !any {
            let v = if g.st.absolute {
                g.slen(0.0, 50.0)
            } else {
                g.slen(0.0, 10.0)
            };
            if let Some(t) = target.as_mut() {
                if g.st.absolute {
                    t[0] = v;
                } else {
                    delta[0] = v;
                }
            }
            if !g.st.absolute {
                delta[0] = v;
            }
            words.push(g.w('X', v));
        }
        if !rapid && (g.st.feed_mode == 93 || g.rng.chance(0.15)) {
            let f = feed_word(g);
            words.push(f);
        }
        if g.rng.chance(0.1) {
            words.push("(move)".into());
            g.feat("surface: comment in a block");
        }
        if !g.st.absolute {
            target = target.map(|p| [p[0] + delta[0], p[1] + delta[1], p[2] + delta[2]]);
        }
        if g.rng.chance(0.3) {
            // Word order is free.
            let first = words.remove(0);
            let at = g.rng.below(words.len() as u64 + 1) as usize;
            words.insert(at, first);
            g.feat("surface: words in any order");
        }
        g.line(words.join(" "));
        g.st.pos = target;
        modal = Some(code);
    }
}

/// An F word right for the current feed mode.
pub fn feed_word(g: &mut Gen) -> String {
    let f = match g.st.feed_mode {
        93 => g.rng.value(1.0, 100.0),
        95 => g.rlen(0.05, 2.0),
        _ => g.rlen(50.0, 2000.0),
    };
    g.w('F', f)
}

/// G2/G3 in the current or a new plane: centre form (incremental or G90.1 absolute centre),
/// radius form (±R), full circles, P turns, helices, blocks with only centre words.
pub fn arcs(g: &mut Gen) {
    if g.rng.chance(0.5) && !g.st.diameter {
        let p = *g.rng.pick(&[17u8, 18, 19]);
        g.st.plane = p;
        g.line(format!("G{p}"));
    }
    if g.st.diameter {
        g.line("G8");
        g.st.diameter = false;
    }
    g.feat(match g.st.plane {
        17 => "arc: G17 plane",
        18 => "arc: G18 plane",
        _ => "arc: G19 plane",
    });
    let (a1, a2, an) = g.plane_axes();
    let (i1, i2) = match g.st.plane {
        18 => ('K', 'I'),
        19 => ('J', 'K'),
        _ => ('I', 'J'),
    };
    let n = 1 + g.rng.below(3);
    for _ in 0..n {
        let p = if g.st.absolute {
            g.known_position()
        } else {
            g.st.pos.unwrap_or([0.0; 3])
        };
        let (s1, s2) = (p[Gen::axis_index(a1)], p[Gen::axis_index(a2)]);
        let radius = g.rlen(2.0, 30.0);
        let start_angle = g.rng.value(0.0, 360.0).to_radians();
        let (c1, c2) = (
            r4(s1 - radius * start_angle.cos()),
            r4(s2 - radius * start_angle.sin()),
        );
        let code = if g.rng.chance(0.5) { "G2" } else { "G3" };
        let full = g.rng.chance(0.2);
        let sweep = if full {
            0.0
        } else {
            g.rng.value(10.0, 350.0).to_radians()
        };
        let rad = (s1 - c1).hypot(s2 - c2);
        let end_angle = (s2 - c2).atan2(s1 - c1) + if code == "G3" { sweep } else { -sweep };
        let (e1, e2) = if full {
            (s1, s2)
        } else {
            (
                r4(c1 + rad * end_angle.cos()),
                r4(c2 + rad * end_angle.sin()),
            )
        };
        let radius_form = !full && g.rng.chance(0.3);
        let mut words = vec![code.to_string()];
        let (v1, v2) = if g.st.absolute {
            (e1, e2)
        } else {
            (r4(e1 - s1), r4(e2 - s2))
        };
        if !full || g.rng.chance(0.5) {
            words.push(g.wx(a1, v1));
            words.push(g.wx(a2, v2));
        }
        let mut end = p;
        end[Gen::axis_index(a1)] = e1;
        end[Gen::axis_index(a2)] = e2;
        if radius_form {
            g.feat("arc: radius form R");
            // The sign picks the arc: negative for more than a half turn.
            let r = if sweep > std::f64::consts::PI {
                -rad
            } else {
                rad
            };
            let r = r4(r * 1.0001);
            words.push(g.w('R', r));
        } else {
            g.feat(if full {
                "arc: full circle"
            } else {
                "arc: centre form I/J/K"
            });
            let absolute_centre = g.st.absolute && g.rng.chance(0.15);
            let (o1, o2) = if absolute_centre {
                g.feat("arc: G90.1 absolute centre");
                g.line("G90.1");
                (c1, c2)
            } else {
                (r4(c1 - s1), r4(c2 - s2))
            };
            words.push(g.w(i1, o1));
            words.push(g.w(i2, o2));
            if absolute_centre {
                words.push("G91.1".into());
            }
        }
        if g.rng.chance(0.25) {
            g.feat("arc: helix");
            let d = g.slen(0.5, 10.0);
            let v = if g.st.absolute {
                r4(p[Gen::axis_index(an)] + d)
            } else {
                d
            };
            end[Gen::axis_index(an)] = r4(p[Gen::axis_index(an)] + d);
            words.push(g.w(an, v));
            if g.rng.chance(0.4) {
                g.feat("arc: P turns");
                let turns = g.rng.int(2, 3);
                words.push(format!("P{turns}"));
            }
        } else if full && g.rng.chance(0.3) {
            g.feat("arc: P turns");
            words.push("P2".into());
        }
        if g.st.feed_mode == 93 || g.rng.chance(0.1) {
            let f = feed_word(g);
            words.push(f);
        }
        // The centre-word block of a G90.1 arc carries G91.1 back: move it to its own line.
        if words.last().map(String::as_str) == Some("G91.1") {
            words.pop();
            g.line(words.join(" "));
            g.line("G91.1");
        } else {
            g.line(words.join(" "));
        }
        g.st.pos = Some(end);
        if full && !radius_form && g.rng.chance(0.5) {
            // Issue 21 reproduction 2: a block with only centre words under modal G2/G3.
            g.feat("arc: block with only centre words");
            let r2 = g.rlen(2.0, 20.0);
            let (o1, o2) = (g.w(i1, -r2), g.w(i2, 0.0));
            if g.st.feed_mode == 93 {
                let f = feed_word(g);
                g.line(format!("{o1} {o2} {f}"));
            } else {
                g.line(format!("{o1} {o2}"));
            }
        }
    }
}

/// Assignments to numbered, named local and named global parameters (several on a line), and
/// DEBUG/MSG comments that print values.
pub fn params(g: &mut Gen) {
    let n = 1 + g.rng.below(4);
    for _ in 0..n {
        let target = match g.rng.below(4) {
            0 => {
                g.feat("param: set numbered #1-#30");
                format!("#{}", g.rng.int(1, 30))
            }
            1 => {
                g.feat("param: set numbered #31-#5000");
                format!("#{}", g.rng.int(31, 4999))
            }
            2 => {
                g.feat("param: set named local");
                format!("#<{}>", g.rng.pick(&["a", "depth", "my_value", "k2"]))
            }
            _ => {
                g.feat("param: set named global");
                format!("#<_{}>", g.rng.pick(&["g", "offset", "count", "glob"]))
            }
        };
        let v = match g.expr_value() {
            Some((t, v)) => {
                let mut line = format!("{target} = {t}");
                if g.rng.chance(0.2) {
                    // A second assignment on the line reads the old values (all on a line are
                    // evaluated before any is set).
                    if let Some((t2, v2)) = g.expr_value() {
                        let k = g.rng.int(1, 30);
                        line.push_str(&format!(" #{k}={t2}"));
                        g.feat("param: two assignments on a line");
                        g.line(line);
                        g.set_param(target, v);
                        g.set_param(format!("#{k}"), v2);
                        continue;
                    }
                }
                g.line(line);
                v
            }
            None => {
                let v = g.rng.value(-50.0, 50.0);
                let t = g.rng.number_text(v);
                g.line(format!("{target}={t}"));
                v
            }
        };
        g.set_param(target, v);
    }
    if g.rng.chance(0.5) {
        debug_line(g);
    }
    if g.rng.chance(0.2) {
        g.feat("comment: MSG");
        g.line("(MSG, generated message)");
    }
}

/// A DEBUG comment printing parameters, among them read-only predefined ones.
pub fn debug_line(g: &mut Gen) {
    g.feat("comment: DEBUG with parameters");
    const PREDEFINED: [&str; 24] = [
        "#<_x>",
        "#<_y>",
        "#<_z>",
        "#<_a>",
        "#<_metric>",
        "#<_imperial>",
        "#<_absolute>",
        "#<_incremental>",
        "#<_feed>",
        "#<_rpm>",
        "#<_motion_mode>",
        "#<_plane>",
        "#<_ccomp>",
        "#<_current_tool>",
        "#<_current_pocket>",
        "#<_coord_system>",
        "#<_spindle_on>",
        "#<_tool_offset>",
        "#<_retract_r_plane>",
        "#<_value>",
        "#5220",
        "#5420",
        "#5422",
        "#5400",
    ];
    let mut parts = Vec::new();
    for _ in 0..1 + g.rng.below(3) {
        if !g.st.params.is_empty() && g.rng.chance(0.4) {
            let (p, _) = g.rng.pick(&g.st.params).clone();
            parts.push(p);
        } else {
            g.feat("param: read-only predefined");
            parts.push(g.rng.pick(&PREDEFINED).to_string());
        }
    }
    g.line(format!("(DEBUG, v={})", parts.join(" ")));
}

impl Gen {
    /// A random expression's text and value, if one in range was drawn.
    pub fn expr_value(&mut self) -> Option<(String, f64)> {
        let mut used = Vec::new();
        for _ in 0..8 {
            let params = self.st.params.clone();
            let numbered = self.st.numbered.clone();
            let names = self.st.names.clone();
            let scope = crate::expr::Scope {
                params: &params,
                numbered: &numbered,
                names: &names,
            };
            let depth = 1 + self.rng.below(3) as u32;
            let e = crate::expr::random_expr(&mut self.rng, depth, &scope, &mut used);
            if let Some(v) = e.value() {
                if v.abs() < 1e4 {
                    for f in used {
                        self.feat(f);
                    }
                    return Some((format!("[{}]", e.inner(&mut self.rng)), v));
                }
            }
            used.clear();
        }
        None
    }
}

/// G10 L2/L20, G54–G59.3, the G92 family, G52, G53.
pub fn offsets(g: &mut Gen) {
    let n = 1 + g.rng.below(3);
    for _ in 0..n {
        match g.rng.below(9) {
            0 => {
                g.feat("offsets: G10 L2");
                let p = g.rng.int(0, 9);
                let mut words = vec![format!("G10 L2 P{p}")];
                for a in ['X', 'Y', 'Z'] {
                    if g.rng.chance(0.6) {
                        let v = g.slen(0.0, 50.0);
                        words.push(g.w(a, v));
                    }
                }
                if g.rng.chance(0.2) {
                    g.feat("offsets: G10 L2 R rotation");
                    let r = g.rng.signed(0.0, 90.0);
                    words.push(g.w('R', r));
                }
                if words.len() == 1 {
                    words.push("X0".into());
                }
                g.line(words.join(" "));
            }
            1 => {
                g.feat("offsets: G10 L20");
                let p = g.rng.int(0, 9);
                let v = g.slen(0.0, 30.0);
                let w = g.w('X', v);
                let z = g.slen(0.0, 30.0);
                let wz = g.w('Z', z);
                g.line(format!("G10 L20 P{p} {w} {wz}"));
            }
            2 | 3 => {
                g.feat("offsets: G54-G59.3");
                let (code, n) = *g.rng.pick(&[
                    ("G54", 1),
                    ("G55", 2),
                    ("G56", 3),
                    ("G57", 4),
                    ("G58", 5),
                    ("G59", 6),
                    ("G59.1", 7),
                    ("G59.2", 8),
                    ("G59.3", 9),
                ]);
                g.st.system = n;
                g.line(code);
            }
            4 => {
                g.feat("offsets: G92");
                let v = g.slen(0.0, 30.0);
                let w = g.w('X', v);
                let y = g.slen(0.0, 30.0);
                let wy = g.w('Y', y);
                g.line(format!("G92 {w} {wy}"));
            }
            5 => {
                let code = *g.rng.pick(&["G92.1", "G92.2", "G92.3"]);
                g.feat("offsets: G92.1/G92.2/G92.3");
                g.line(code);
            }
            6 => {
                g.feat("offsets: G52");
                let v = g.slen(0.0, 20.0);
                let w = g.w('X', v);
                let z = g.slen(0.0, 5.0);
                let wz = g.w('Z', z);
                g.line(format!("G52 {w} {wz}"));
            }
            _ => {
                g.feat("offsets: G53 machine coordinates");
                let code = if g.rng.chance(0.7) { "G0" } else { "G1" };
                let z = g.slen(0.0, 20.0);
                let wz = g.w('Z', z);
                let g90 = if g.st.absolute { "" } else { "G90 " };
                let f = if code == "G1" && g.st.feed_mode == 93 {
                    format!(" {}", feed_word(g))
                } else {
                    String::new()
                };
                g.line(format!("{g90}G53 {code} {wz}{f}"));
                if !g.st.absolute {
                    g.line("G91");
                }
            }
        }
        g.forget_position();
    }
}

/// T, M6, M61, G43 (H, none), G43.1, G43.2, G49, G10 L1/L10/L11.
pub fn tools(g: &mut Gen) {
    let n = 1 + g.rng.below(3);
    for _ in 0..n {
        let t = TOOLS[g.rng.below(TOOLS.len() as u64) as usize].0;
        match g.rng.below(9) {
            0 | 1 => {
                g.feat("tools: T M6");
                let same_block = g.rng.chance(0.15);
                if same_block {
                    // rs274 and milltask differ here (docs/linuxcnc.md, known differences).
                    g.feat("tools: T M6 G43 in one block (known difference)");
                    g.line(format!("T{t} M6 G43"));
                } else {
                    g.line(format!("T{t} M6"));
                }
                g.st.tool = t;
            }
            2 => {
                g.feat("tools: M61");
                g.line(format!("M61 Q{t}"));
                g.st.tool = t;
            }
            3 => {
                g.feat("tools: T alone (prepare)");
                g.line(format!("T{t}"));
            }
            4 => {
                g.feat("tools: G43 H");
                g.line(format!("G43 H{t}"));
            }
            5 => {
                g.feat("tools: G43 / G49");
                let c = if g.rng.chance(0.5) { "G43" } else { "G49" };
                g.line(c);
            }
            6 => {
                g.feat("tools: G43.1");
                let z = g.slen(0.0, 10.0);
                let w = g.w('Z', z);
                g.line(format!("G43.1 {w}"));
            }
            7 => {
                g.feat("tools: G43.2 H");
                g.line(format!("G43.2 H{t}"));
            }
            _ => {
                let l = *g.rng.pick(&[1, 10, 11]);
                g.feat(match l {
                    1 => "tools: G10 L1",
                    10 => "tools: G10 L10",
                    _ => "tools: G10 L11",
                });
                let z = g.slen(0.0, 5.0);
                let w = g.w('Z', z);
                let r = if l == 1 && g.rng.chance(0.5) {
                    let r = g.rlen(0.5, 5.0);
                    format!(" {}", g.w('R', r))
                } else {
                    String::new()
                };
                g.line(format!("G10 L{l} P{t} {w}{r}"));
            }
        }
        g.forget_position();
    }
}

/// Feed modes G93/G94/G95, G96/G97, S, M3/M4/M5.
pub fn feeds(g: &mut Gen) {
    match g.rng.below(5) {
        0 => {
            g.feat("feed: G93 inverse time");
            g.st.feed_mode = 93;
            g.line("G93");
            moves(g);
            g.line("G94");
            let f = g.rlen(50.0, 2000.0);
            let fw = g.w('F', f);
            g.line(fw);
            g.st.feed_mode = 94;
        }
        1 => {
            g.feat("feed: G95 per revolution");
            if !g.st.spindle {
                g.line("S800 M3");
                g.st.spindle = true;
            }
            g.st.feed_mode = 95;
            let f = g.rlen(0.05, 1.0);
            let fw = g.w('F', f);
            g.line(format!("G95 {fw}"));
            moves(g);
            g.st.feed_mode = 94;
            let f = g.rlen(50.0, 2000.0);
            let fw = g.w('F', f);
            g.line(format!("G94 {fw}"));
        }
        2 => {
            g.feat("spindle: G96 constant surface speed");
            let s = g.rng.int(50, 300);
            let d = g.rng.int(1000, 4000);
            g.line(format!("G96 S{s} D{d} M3"));
            g.st.spindle = true;
            if g.rng.chance(0.5) {
                moves(g);
            }
            let s = g.rng.int(100, 2000);
            g.line(format!("G97 S{s}"));
        }
        3 => {
            g.feat("spindle: M5 and restart");
            g.line("M5");
            let s = g.rng.int(100, 3000);
            g.line(format!("M4 S{s}"));
            g.st.spindle = true;
        }
        _ => {
            g.feat("feed: F alone");
            let f = feed_word(g);
            g.line(f);
        }
    }
}

/// G20/G21 in the middle of a program.
pub fn units(g: &mut Gen) {
    g.feat("units: G20/G21 mid-program");
    g.st.metric = !g.st.metric;
    let f = g.rlen(50.0, 2000.0);
    let fw = if g.st.feed_mode == 94 {
        format!(" {}", g.w('F', f))
    } else {
        String::new()
    };
    g.line(format!("{}{fw}", if g.st.metric { "G21" } else { "G20" }));
    g.forget_position();
    // Known values of parameters stay, in the units they were set in.
}

/// Path modes, distance modes, planes, dwell.
pub fn modes(g: &mut Gen) {
    match g.rng.below(6) {
        0 => {
            g.feat("path: G61/G61.1");
            let c = if g.rng.chance(0.5) { "G61" } else { "G61.1" };
            g.line(c);
        }
        1 => {
            g.feat("path: G64 P Q");
            let p = g.rlen(0.01, 0.5);
            let pw = g.w('P', p);
            if g.rng.chance(0.5) {
                let q = g.rlen(0.01, 0.5);
                let qw = g.w('Q', q);
                g.line(format!("G64 {pw} {qw}"));
            } else {
                g.line(format!("G64 {pw}"));
            }
        }
        2 => {
            g.feat("path: G64");
            g.line("G64");
        }
        3 => {
            g.feat("distance: G90/G91 switch");
            g.st.absolute = !g.st.absolute;
            g.line(if g.st.absolute { "G90" } else { "G91" });
        }
        4 => {
            g.feat("dwell: G4");
            let p = g.rng.value(0.0, 3.0);
            let pw = g.w('P', p.abs());
            g.line(format!("G4 {pw}"));
        }
        _ => {
            g.feat("plane: G17/G18/G19");
            let p = *g.rng.pick(&[17u8, 18, 19]);
            g.st.plane = p;
            g.line(format!("G{p}"));
        }
    }
}

/// Coolant, overrides, digital/analog outputs, orientation, stops, modal state M70–M72.
pub fn mcodes(g: &mut Gen) {
    let n = 1 + g.rng.below(3);
    for _ in 0..n {
        let line = match g.rng.below(9) {
            0 => {
                g.feat("M: coolant M7/M8/M9");
                g.rng.pick(&["M7", "M8", "M9", "M7 M8"]).to_string()
            }
            1 => {
                g.feat("M: overrides M48-M53");
                g.rng
                    .pick(&[
                        "M48", "M49", "M50 P0", "M50 P1", "M51 P1", "M52 P1", "M53 P0",
                    ])
                    .to_string()
            }
            2 => {
                g.feat("M: outputs M62-M65");
                let p = g.rng.int(0, 3);
                format!("{} P{p}", g.rng.pick(&["M62", "M63", "M64", "M65"]))
            }
            3 => {
                g.feat("M: M66 wait");
                let p = g.rng.int(0, 3);
                format!("M66 P{p} L0")
            }
            4 => {
                g.feat("M: M19 orient");
                let r = g.rng.int(0, 359);
                format!("M19 R{r} Q2 P{}", g.rng.int(0, 2))
            }
            5 => {
                g.feat("M: M0/M1 stops");
                g.rng.pick(&["M0", "M1", "M60"]).to_string()
            }
            6 => {
                g.feat("M: M70/M72 modal state");
                // M72 restores what M70 saved.
                g.line("M70");
                g.line(if g.st.metric { "G20" } else { "G21" });
                g.line(if g.st.absolute { "G91" } else { "G90" });
                "M72".to_string()
            }
            7 => {
                g.feat("M: M3/M4 with S on the line");
                let s = g.rng.int(100, 3000);
                g.st.spindle = true;
                format!("{} S{s}", g.rng.pick(&["M3", "M4"]))
            }
            _ => {
                g.feat("M: M5 stop spindle");
                g.st.spindle = false;
                if g.st.feed_mode == 95 || g.st.css {
                    return;
                }
                "M5".to_string()
            }
        };
        g.line(line);
    }
}

/// G38.2–G38.5 straight probes.
pub fn probe(g: &mut Gen) {
    g.feat("probe: G38.x");
    if g.st.feed_mode == 93 {
        return;
    }
    let code = *g.rng.pick(&["G38.2", "G38.3", "G38.4", "G38.5"]);
    let d = g.slen(1.0, 20.0);
    let p = if g.st.absolute {
        Some(g.known_position())
    } else {
        None
    };
    let v = match p {
        Some(p) => r4(p[2] + d),
        None => d,
    };
    let w = g.w('Z', v);
    let f = g.rlen(50.0, 500.0);
    let fw = g.w('F', f);
    g.line(format!("{code} {w} {fw}"));
    g.forget_position();
    if g.rng.chance(0.5) {
        g.feat("param: probe result #5061-#5070");
        g.line("(DEBUG, probe #5070 #5061 #5062 #5063)");
    }
}

/// G28/G30 (with and without an intermediate point), G28.1/G30.1.
pub fn homes(g: &mut Gen) {
    g.feat("home: G28/G30/G28.1/G30.1");
    match g.rng.below(4) {
        0 => {
            let c = *g.rng.pick(&["G28.1", "G30.1"]);
            g.line(c);
        }
        1 => {
            let c = *g.rng.pick(&["G28", "G30"]);
            g.line(c);
        }
        _ => {
            let code = *g.rng.pick(&["G28", "G30"]);
            let v = if g.st.absolute {
                g.slen(0.0, 30.0)
            } else {
                g.slen(0.0, 10.0)
            };
            let w = g.w('Z', v);
            g.line(format!("{code} {w}"));
        }
    }
    g.forget_position();
}
