//! The sections of a program: short passages, each exercising one area of the language from the
//! tracked state and leaving the state valid for the next (see lib.rs). Canned cycles, cutter
//! compensation, splines, threading and lathe cycles are in `cycles.rs`, O-word control flow in
//! `flow.rs`.

use crate::{cycles, flow, Gen};

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

// The machine-state sections live in `state_sections.rs`.
pub use crate::state_sections::{feeds, homes, mcodes, modes, offsets, probe, tools, units};
