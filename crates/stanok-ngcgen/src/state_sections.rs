//! The generator's sections that change the machine's state: offsets (G10, G52, G92, G5x), tools
//! and length offsets, feed modes, units, modal codes, M codes, probing and home positions.

use crate::sections::*;
use crate::{Gen, TOOLS};

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
                // LinuxCNC takes the spindle for stopped after M19 (threads and tapping need M3).
                g.st.spindle = false;
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
