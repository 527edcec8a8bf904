//! O-word control flow: subroutines with arguments and return values (in the program, after its
//! end, and in files on the subroutine path), if/elseif/else, while, do-while, repeat, break,
//! continue.
//!
//! The generator knows every condition's value (expressions are evaluated in `expr.rs`), so it
//! knows which branch runs: a branch's body is written from a copy of the state, and the state
//! after the construct is the copy of the branch that ran. Loop bodies only move and print, so
//! that the state after a loop is the state before it with the position forgotten and the
//! counter at its final value.

use crate::sections::{debug_line, feed_word};
use crate::Gen;

/// An O label: numbered (`o123`) or named (`o<name123>`).
fn o_label(g: &mut Gen) -> String {
    let n = g.label();
    if g.rng.chance(0.3) {
        g.feat("flow: named O-word");
        format!("o<l{n}>")
    } else {
        format!("o{n}")
    }
}

/// A few moves and prints: the body of a loop or branch (keeps the modal state).
fn body(g: &mut Gen, indent: &str) {
    let n = 1 + g.rng.below(3);
    for _ in 0..n {
        match g.rng.below(4) {
            0 => debug_line(g),
            1 => {
                let v = g.slen(0.0, 30.0);
                let w = g.w('X', v);
                g.line(format!("{indent}G0 {w}"));
            }
            _ => {
                let v = g.slen(0.0, 30.0);
                let a = *g.rng.pick(&['X', 'Y', 'Z']);
                let w = g.w(a, v);
                let f = if g.st.feed_mode == 93 {
                    format!(" {}", feed_word(g))
                } else {
                    String::new()
                };
                g.line(format!("{indent}G1 {w}{f}"));
            }
        }
    }
    g.forget_position();
}

/// A condition with a known truth value.
fn condition(g: &mut Gen) -> (String, bool) {
    match g.expr_value() {
        Some((t, v)) => (t, v != 0.0),
        None => ("[1 GT 0]".into(), true),
    }
}

/// One control-flow construct.
pub fn control_flow(g: &mut Gen) {
    let label = o_label(g);
    match g.rng.below(6) {
        0 => {
            g.feat("flow: if/elseif/else");
            let (c1, t1) = condition(g);
            g.line(format!("{label} if {c1}"));
            body(g, "  ");
            if g.rng.chance(0.6) {
                let (c2, _) = condition(g);
                g.feat("flow: elseif");
                g.line(format!("{label} elseif {c2}"));
                body(g, "  ");
            }
            if g.rng.chance(0.6) {
                g.feat("flow: else");
                g.line(format!("{label} else"));
                body(g, "  ");
            }
            g.line(format!("{label} endif"));
            let _ = t1;
        }
        1 => {
            g.feat("flow: while");
            let k = g.rng.int(1, 30);
            let n = g.rng.int(1, 3);
            g.line(format!("#{k} = 0"));
            g.line(format!("{label} while [#{k} LT {n}]"));
            body(g, "  ");
            g.line(format!("  #{k} = [#{k} + 1]"));
            g.line(format!("{label} endwhile"));
            g.set_param(format!("#{k}"), n as f64);
        }
        2 => {
            g.feat("flow: do-while");
            let k = g.rng.int(1, 30);
            let n = g.rng.int(1, 3);
            g.line(format!("#{k} = 0"));
            g.line(format!("{label} do"));
            body(g, "  ");
            g.line(format!("  #{k} = [#{k} + 1]"));
            g.line(format!("{label} while [#{k} LT {n}]"));
            // A break that left a while loop earlier ends a do-loop after one pass (LinuxCNC's
            // pending `doing_break`): the count is not known.
            g.forget_param(&format!("#{k}"));
        }
        3 => {
            g.feat("flow: repeat");
            let n = g.rng.int(0, 3);
            g.line(format!("{label} repeat [{n}]"));
            body(g, "  ");
            g.line(format!("{label} endrepeat"));
        }
        4 => {
            g.feat("flow: break");
            let k = g.rng.int(1, 30);
            let inner = o_label(g);
            let n = g.rng.int(1, 3);
            let in_do = g.rng.chance(0.3);
            g.line(format!("#{k} = 0"));
            if in_do {
                g.feat("flow: break in a do-loop");
                g.line(format!("{label} do"));
            } else {
                g.line(format!("{label} while [1]"));
            }
            g.line(format!("  #{k} = [#{k} + 1]"));
            g.line(format!("  {inner} if [#{k} GT {n}]"));
            g.line(format!("    {label} break"));
            g.line(format!("  {inner} endif"));
            body(g, "  ");
            if in_do {
                g.line(format!("{label} while [1]"));
                g.forget_param(&format!("#{k}"));
            } else {
                g.line(format!("{label} endwhile"));
                g.set_param(format!("#{k}"), (n + 1) as f64);
            }
        }
        _ => {
            g.feat("flow: continue");
            let k = g.rng.int(1, 30);
            let inner = o_label(g);
            let n = g.rng.int(2, 4);
            let in_do = g.rng.chance(0.3);
            g.line(format!("#{k} = 0"));
            if in_do {
                g.feat("flow: continue in a do-loop");
                g.line(format!("{label} do"));
            } else {
                g.line(format!("{label} while [#{k} LT {n}]"));
            }
            g.line(format!("  #{k} = [#{k} + 1]"));
            g.line(format!("  {inner} if [#{k} EQ 2]"));
            g.line(format!("    {label} continue"));
            g.line(format!("  {inner} endif"));
            body(g, "  ");
            if in_do {
                g.line(format!("{label} while [#{k} LT {n}]"));
                g.forget_param(&format!("#{k}"));
            } else {
                g.line(format!("{label} endwhile"));
                g.set_param(format!("#{k}"), n as f64);
            }
        }
    }
    g.forget_position();
}

/// The body text of a subroutine over arguments #1…#n: moves with argument expressions, a
/// local named parameter, and a return value.
fn sub_body(g: &mut Gen, name: &str, args: u32) -> Vec<String> {
    let mut lines = Vec::new();
    let a = |g: &mut Gen| format!("#{}", g.rng.int(1, i64::from(args)));
    lines.push(format!("#<tmp> = [{} * 2]", a(g)));
    for _ in 0..1 + g.rng.below(3) {
        let (x, y) = (a(g), a(g));
        let code = if g.rng.chance(0.7) { "G1" } else { "G0" };
        lines.push(format!("{code} X{x} Y[{y} + #<tmp> / 4]"));
    }
    match g.rng.below(3) {
        0 => {
            g.feat("flow: return with value");
            let v = a(g);
            lines.push(format!("{name} return [{v} + 1]"));
        }
        1 => {
            g.feat("flow: endsub with value");
        }
        _ => {}
    }
    lines
}

/// Defines a subroutine (in the program or in a file) and calls it with arguments.
pub fn call_sub(g: &mut Gen) {
    if g.st.feed_mode == 93 {
        return;
    }
    let args = g.rng.int(1, 3) as u32;
    let n = g.label();
    let in_file = g.rng.chance(0.2);
    let name = if in_file || g.rng.chance(0.4) {
        format!("o<s{n}>")
    } else {
        format!("o{n}")
    };
    let mut body = sub_body(g, &name, args);
    let value = if g.rng.chance(0.4) {
        let v = g.rng.int(1, i64::from(args));
        format!(" [#{v}]")
    } else {
        String::new()
    };
    if !value.is_empty() {
        g.feat("flow: endsub with value");
    }
    let mut def = vec![format!("{name} sub")];
    def.append(&mut body);
    def.push(format!("{name} endsub{value}"));
    if in_file {
        g.feat("flow: subroutine file");
        def.push("M2".into());
        g.subfiles
            .push((format!("s{n}.ngc"), def.join("\n") + "\n"));
    } else if g.rng.chance(0.3) {
        g.feat("flow: sub defined after the end");
        g.subs.push(def.join("\n"));
    } else {
        g.feat("flow: sub defined before its call");
        for l in def {
            g.line(l);
        }
    }
    let mut call = format!("{name} call");
    for _ in 0..args {
        let v = g.slen(0.0, 30.0);
        let t = g.rng.number_text(v);
        call.push_str(&format!(" [{t}]"));
    }
    g.feat("flow: call with arguments");
    g.line(call);
    if g.rng.chance(0.5) {
        g.feat("param: #<_value> after a call");
        g.line("(DEBUG, value #<_value> #<_value_returned>)");
    }
    g.forget_position();
}

/// The subroutines written after the program's end.
pub fn late_subs(g: &mut Gen) {
    let subs = std::mem::take(&mut g.subs);
    for s in subs {
        for l in s.lines() {
            g.line(l.to_string());
        }
    }
}
