//! AxiOMA high-level language (docs/axioma.md, "The high-level language"): every construct, its
//! numbers asserted (end points to 1e-9 mm, messages exactly), and every kind of bad input as a
//! diagnostic with its code and line, with nothing of the bad line executed.

use stanok_canon::setup::ControlData;
use stanok_canon::{Canon, DiagCode, Spanned};
use stanok_interp::{HVal, InterpOptions, Interpreter};
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn opts() -> InterpOptions {
    InterpOptions::new(Dialect::Axioma)
}

/// Runs to the end or the first error; returns the commands, the error, and the interpreter.
fn exec(text: &str, o: InterpOptions) -> (Vec<Spanned<Canon>>, Option<stanok_canon::Diagnostic>) {
    let mut out = Vec::new();
    for item in Interpreter::from_text(text, o) {
        match item {
            Ok(c) => out.push(c),
            Err(d) => return (out, Some(d)),
        }
    }
    (out, None)
}

fn ok(text: &str) -> Vec<Spanned<Canon>> {
    let (cmds, err) = exec(text, opts());
    assert!(err.is_none(), "{text}\n{}", err.unwrap());
    cmds
}

/// End points (x, y, z) of the moves, in order.
fn ends(cmds: &[Spanned<Canon>]) -> Vec<[f64; 3]> {
    cmds.iter()
        .filter_map(|c| c.value.motion().map(|m| m.end().xyz()))
        .collect()
}

fn messages(cmds: &[Spanned<Canon>]) -> Vec<String> {
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::Message { text } => Some(text.clone()),
            _ => None,
        })
        .collect()
}

fn assert_points(got: &[[f64; 3]], want: &[[f64; 3]]) {
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        for k in 0..3 {
            assert!((g[k] - w[k]).abs() < TOL, "{got:?} != {want:?}");
        }
    }
}

fn fails(text: &str, code: &str, line: u32) -> Vec<Spanned<Canon>> {
    let (cmds, err) = exec(text, opts());
    let err = err.unwrap_or_else(|| panic!("{text}: no error"));
    assert_eq!(err.code, DiagCode::Stanok(leak(code)), "{text}: {err}");
    assert_eq!(err.span.line, line, "{text}: {err}");
    cmds
}

fn leak(s: &str) -> &'static str {
    Box::leak(s.to_string().into_boxed_str())
}

#[test]
fn for_loop_runs_its_iso_blocks_once_per_pass_with_current_values() {
    let cmds = ok("int i;\n\
                   for (i = 1; i <= 3; i++)\n\
                   {\n\
                   G01 X=i*10 Y=-i F100\n\
                   }\n\
                   G00 X=i Y0\n\
                   M30\n");
    assert_points(
        &ends(&cmds),
        &[
            [10.0, -1.0, 0.0],
            [20.0, -2.0, 0.0],
            [30.0, -3.0, 0.0],
            [4.0, 0.0, 0.0],
        ],
    );
    // The ISO block of every pass carries its own line (4).
    let lines: Vec<u32> = cmds
        .iter()
        .filter(|c| c.value.motion().is_some())
        .map(|c| c.span.line)
        .collect();
    assert_eq!(lines, [4, 4, 4, 6]);
}

#[test]
fn nested_loops_around_iso_blocks() {
    let cmds = ok("for (int row = 0; row < 2; row++) {\n\
                     for (int col = 0; col < 3; col++) {\n\
                       G00 X=col*5 Y=row*7\n\
                     }\n\
                   }\n\
                   M30\n");
    let want: Vec<[f64; 3]> = (0..2)
        .flat_map(|r| (0..3).map(move |c| [c as f64 * 5.0, r as f64 * 7.0, 0.0]))
        .collect();
    assert_points(&ends(&cmds), &want);
}

#[test]
fn while_do_while_break_continue_and_braceless_bodies() {
    let cmds = ok("int n = 0;\n\
                   while (n < 10) {\n\
                     n++;\n\
                     if (n % 2 == 0) continue;\n\
                     if (n > 7) break;\n\
                     G00 X=n\n\
                   }\n\
                   int k = 0;\n\
                   do { k += 3; } while (k < 10);\n\
                   G00 Y=k\n\
                   while (k > 0) k -= 4;\n\
                   G00 Z=k\n\
                   for (int j = 0; j < 2; j++)\n\
                     G00 X=100+j\n\
                   M30\n");
    assert_points(
        &ends(&cmds),
        &[
            [1.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [5.0, 0.0, 0.0],
            [7.0, 0.0, 0.0],
            [7.0, 12.0, 0.0],
            [7.0, 12.0, 0.0],
            [100.0, 12.0, 0.0],
            [101.0, 12.0, 0.0],
        ],
    );
}

#[test]
fn if_else_chains_and_scopes() {
    let cmds = ok("double a = 2.5;\n\
                   string word;\n\
                   if (a > 3) { word = \"big\"; }\n\
                   else if (a > 2)\n\
                   {\n\
                     string t = \"mid\";\n\
                     word = t + \"dle\";\n\
                   }\n\
                   else { word = \"small\"; }\n\
                   MSG(word)\n\
                   { int a = 7;\n\
                   G00 X=a\n\
                   }\n\
                   G00 Y=a\n\
                   if (a < 0)\n\
                     G00 Z50\n\
                   else\n\
                     G00 Z=-a\n\
                   M30\n");
    assert_eq!(messages(&cmds), ["middle"]);
    assert_points(
        &ends(&cmds),
        &[[7.0, 0.0, 0.0], [7.0, 2.5, 0.0], [7.0, 2.5, -2.5]],
    );
}

#[test]
fn c_arithmetic_types_and_operators() {
    let text = "int i = 7 / 2;\n\
                double d = 7 / 2.0;\n\
                int r = -7 % 3;\n\
                long big = 1 << 40;\n\
                bool b = 3 > 2 && !(1 == 2);\n\
                int c = 5; c += 3; c *= 2; c -= 1; c /= 3; c %= 4;\n\
                int post = c++; int pre = ++c;\n\
                double t = i > 2 ? 1.5 : -1.5;\n\
                int trunc = 2.9;\n\
                int arr[4] = {1, 2, 3};\n\
                arr[3] = arr[0] + arr[2];\n\
                int last = arr[3];\n\
                int bits = (6 & 3) | (1 ^ 4);\n\
                M30\n";
    let mut it = Interpreter::from_text(text, opts());
    for c in it.by_ref() {
        c.unwrap();
    }
    let v = |n: &str| it.hll_variable(n).unwrap();
    assert_eq!(v("i"), HVal::Int(3));
    assert_eq!(v("d"), HVal::Double(3.5));
    assert_eq!(v("r"), HVal::Int(-1));
    assert_eq!(v("big"), HVal::Int(1 << 40));
    assert_eq!(v("b"), HVal::Bool(true));
    // ((5 + 3) * 2 - 1) / 3 = 5, 5 % 4 = 1; post reads 1, pre reads 3.
    assert_eq!(v("post"), HVal::Int(1));
    assert_eq!(v("pre"), HVal::Int(3));
    assert_eq!(v("c"), HVal::Int(3));
    assert_eq!(v("t"), HVal::Double(1.5));
    assert_eq!(v("trunc"), HVal::Int(2));
    assert_eq!(v("last"), HVal::Int(4));
    assert_eq!(v("bits"), HVal::Int(7));
}

#[test]
fn math_library_in_degrees() {
    let cmds = ok("double a = atan2(1, 1);\n\
                   G00 X=sin(30)*2 Y=cos(60)*4 Z=tan(45)\n\
                   G00 X=a Y=asin(0.5) Z=acos(0)\n\
                   G00 X=atan(1) Y=sqrt(16) Z=pow(2, 10)\n\
                   G00 X=abs(-3) Y=floor(-2.5) Z=ceil(-2.5)\n\
                   G00 X=round(2.5) Y=round(-2.5) Z=min(3, max(1, 2.5))\n\
                   M30\n");
    assert_points(
        &ends(&cmds),
        &[
            [1.0, 2.0, 1.0],
            [45.0, 30.0, 90.0],
            [45.0, 4.0, 1024.0],
            [3.0, -3.0, -2.0],
            [3.0, -3.0, 2.5],
        ],
    );
}

#[test]
fn sprintf_formats_and_msg() {
    let cmds = ok("string s;\n\
                   int n = sprintf(s, \"%d|%i|%5.2f|%e|%g|%s|%%|%-4d|\", 42, -7, 3.14359, 1234.5, 0.0001, \"ok\", 5);\n\
                   MSG(s)\n\
                   sprintf(s, \"len %d\", n);\n\
                   N20 MSG(s + \"!\")\n\
                   MSG()\n\
                   M30\n");
    assert_eq!(
        messages(&cmds),
        ["42|-7| 3.14|1.234500e+03|0.0001|ok|%|5   |", "len 42!", ""]
    );
}

#[test]
fn expressions_in_feed_speed_and_q_words_and_tables() {
    let mut o = opts();
    o.control.perm_int.insert(1, 1500);
    o.control.perm_double.insert(2, 0.5);
    let text = "int f = 2;\n\
                N10 G01 X10 F=$iPerm[1]\n\
                N20 S=$iPerm[1]*2 M3\n\
                N30 G01 X20 F=FTABLE(f+1)\n\
                N40 S2=STABLE(1) \n\
                N50 G91 G273 Q=90*$dPerm[2] G90\n\
                $iPerm[3] = $iPerm[1] + 1;\n\
                $dPerm[4] = 2.25;\n\
                M30\n";
    let mut it = Interpreter::from_text(text, o);
    let mut cmds = Vec::new();
    for c in it.by_ref() {
        cmds.push(c.unwrap());
    }
    let feeds: Vec<f64> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some(m.feed),
            _ => None,
        })
        .collect();
    let ftable = stanok_interp::AxiomaMachineParams::default().feed_table;
    assert_eq!(feeds, [1500.0, ftable[3]]);
    let speeds: Vec<(usize, f64)> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::SetSpindleSpeed { spindle, rpm } => Some((*spindle as usize, *rpm)),
            _ => None,
        })
        .collect();
    let stable = stanok_interp::AxiomaMachineParams::default().speed_table;
    assert!(speeds.contains(&(0, 3000.0)), "{speeds:?}");
    assert!(speeds.contains(&(1, stable[1])), "{speeds:?}");
    // Q=90*0.5: a 45° rotation is active at the end.
    assert!((it.axioma_chain().unwrap().rotation_deg - 45.0).abs() < TOL);
    // Permanent parameters written by the program come back in the control data.
    let data = it.control_data();
    assert_eq!(data.perm_int.get(&3), Some(&1501));
    assert_eq!(data.perm_double.get(&4), Some(&2.25));
}

#[test]
fn settable_writes_the_zero_offset_and_workpiece_tables() {
    let cmds = ok("settable_zs(55, 3, 100, 50, -10);\n\
                   settable_wcs(154, 1, 10, 20, 0, 90, 0, 0);\n\
                   N10 G55 P3 G00 X0 Y0\n\
                   N20 G53 G154 X1 Y0\n\
                   M30\n");
    // G55 page 3 = (100, 50, −10): X0 Y0 is there (Z not programmed, stays 0).
    // G154 page 1: origin (10, 20, 0) rotated 90° about Z: (1, 0) → (10, 21).
    assert_points(&ends(&cmds), &[[100.0, 50.0, 0.0], [10.0, 21.0, 0.0]]);
    fails("settable_zs(60, 1, 0, 0, 0);\nM30\n", "hll::domain", 1);
    fails(
        "settable_zs(54, 33, 0, 0, 0);\nM30\n",
        "axioma::page-range",
        1,
    );
    fails("settable_wcs(154, 1, 0, 0);\nM30\n", "hll::arguments", 1);
}

#[test]
fn bad_input_gives_diagnostics_at_the_statement() {
    fails("int a = b + 1;\nM30\n", "hll::undeclared", 1);
    fails("int a;\nint a = 2;\nM30\n", "hll::redeclared", 2);
    fails("string s = 5;\nM30\n", "hll::type-mismatch", 1);
    fails("int a = 1 + \"x\";\nM30\n", "hll::type-mismatch", 1);
    fails(
        "int z = 0;\nint a = 5 / z;\nM30\n",
        "hll::division-by-zero",
        2,
    );
    fails(
        "double z = 0;\nG01 X=1/z F100\nM30\n",
        "hll::division-by-zero",
        2,
    );
    fails("int p[3];\np[3] = 1;\nM30\n", "hll::index-range", 2);
    fails("int p[3];\nG00 X=p[-1]\nM30\n", "hll::index-range", 2);
    fails("G00 X=$iPerm[1000]\nM30\n", "hll::index-range", 1);
    fails(
        "for (int i = 0; i < 3; i++) {\nG00 X=i\n",
        "hll::unclosed-brace",
        1,
    );
    fails("int a = 1;\n}\nM30\n", "hll::unmatched-brace", 2);
    fails("string s = \"open;\nM30\n", "syntax::unclosed-string", 1);
    fails("int i = sqrt(-1);\nM30\n", "hll::domain", 1);
    fails("int i = 3000000000;\nM30\n", "hll::type-mismatch", 1);
    fails("break;\nM30\n", "hll::outside-loop", 1);
    fails("else { }\nM30\n", "hll::else-without-if", 1);
    fails("if (1) for (;;) { }\nM30\n", "hll::body", 1);
    fails("do { }\nG00 X1\nM30\n", "hll::expected-while", 2);
    fails("int a = foo(1);\nM30\n", "hll::unknown-function", 1);
    fails("string s;\nG00 X=s\nM30\n", "hll::type-mismatch", 2);
    fails("int n = 5;\nMSG(n)\nM30\n", "hll::type-mismatch", 2);
    fails(
        "string s;\nsprintf(s, \"%d\", 1.5);\nM30\n",
        "hll::format",
        2,
    );
    fails("G01 X=FTABLE(128) F100\nM30\n", "axioma::table-index", 1);
}

#[test]
fn a_failing_statement_leaves_nothing_executed() {
    // `a = 5` happens before the division fails on the same line: it is undone.
    let text = "int aa = 1;\nint z = 0;\naa = 5; aa = aa / z;\nM30\n";
    let mut it = Interpreter::from_text(text, opts());
    let mut err = None;
    for c in it.by_ref() {
        if let Err(d) = c {
            err = Some(d);
        }
    }
    assert_eq!(err.unwrap().span.line, 3);
    assert_eq!(it.hll_variable("aa"), Some(HVal::Int(1)));
    // A failing ISO block undoes its word expressions' writes (`X=i++`) and moves nothing.
    let text = "int i = 1;\nG01 X=i++ F=0\nM30\n";
    let mut it = Interpreter::from_text(text, opts());
    let mut cmds = Vec::new();
    for c in it.by_ref() {
        match c {
            Ok(c) => cmds.push(c),
            Err(d) => assert_eq!(d.span.line, 2),
        }
    }
    assert!(ends(&cmds).is_empty());
    assert_eq!(it.hll_variable("i"), Some(HVal::Int(1)));
}

#[test]
fn endless_loops_stop_at_the_iteration_limit() {
    let mut o = opts();
    o.max_loop_iterations = 1000;
    for text in [
        "while (true) { }\nM30\n",
        "for (;;) {\nG00 X1\n}\nM30\n",
        "int k = 0;\ndo { k = 0; } while (k == 0);\nM30\n",
        "while (1);\nM30\n",
    ] {
        let (cmds, err) = exec(text, o.clone());
        let err = err.unwrap_or_else(|| panic!("{text}"));
        assert_eq!(
            err.code,
            DiagCode::Stanok("hll::loop-limit"),
            "{text}: {err}"
        );
        // At most 1000 passes: the G00 of the `for (;;)` ran exactly 1000 times.
        let moves = ends(&cmds).len();
        assert!(moves == 0 || moves == 1000, "{text}: {moves}");
    }
}

#[test]
fn permanent_parameters_default_to_zero_and_control_data_is_unchanged_without_hll() {
    let mut o = opts();
    o.control = ControlData::default();
    o.control.perm_int.insert(7, 3);
    let (cmds, err) = exec("G01 X=$iPerm[7]+$iPerm[8] F100\nM30\n", o);
    assert!(err.is_none());
    assert_points(&ends(&cmds), &[[3.0, 0.0, 0.0]]);
}

fn fixture(name: &str) -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus/axioma/"
    );
    std::fs::read_to_string(format!("{path}{name}")).unwrap()
}

fn spindle_speeds(cmds: &[Spanned<Canon>]) -> Vec<f64> {
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::SetSpindleSpeed { rpm, .. } => Some(*rpm),
            _ => None,
        })
        .collect()
}

#[test]
fn s6_fixtures_read_feed_and_speed_from_iperm() {
    // `$iPerm[n]` comes from the machine data; the fixtures say "value defined elsewhere".
    let mut o = opts();
    o.control.perm_int.insert(1, 1500);
    o.control.perm_int.insert(5, 2400);
    // s6_1 example 2: `N10 G90 G01 X50 F=$iPerm[1]` — a feed move to X50 at 1500 mm/min.
    let (cmds, err) = exec(
        &fixture("s6_1-feed-system-variable-fragment-2.nc"),
        o.clone(),
    );
    assert!(err.is_none(), "{err:?}");
    let feeds: Vec<(f64, f64)> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some((m.end.x, m.feed)),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, [(50.0, 1500.0)]);
    // s6_1 word forms: `F1000`, then `F=$iPerm[1]`: stored (modal, 1500 at the end), no motion.
    let forms = fixture("s6_1-feed-word-forms-fragment.nc");
    let mut it = Interpreter::from_text(&forms, o.clone());
    let mut cmds = Vec::new();
    for c in it.by_ref() {
        cmds.push(c.unwrap());
    }
    assert!(ends(&cmds).is_empty());
    assert_eq!(it.state().feed, 1500.0);
    // …and a following move runs at it.
    let text = format!("{}\nG01 X5\n", fixture("s6_1-feed-word-forms-fragment.nc"));
    let (cmds, err) = exec(&text, o.clone());
    assert!(err.is_none(), "{err:?}");
    let feeds: Vec<f64> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some(m.feed),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, [1500.0]);
    // s6_8 example 2: `N10 S=$iPerm[5]` — 2400 rpm stored.
    let (cmds, err) = exec(
        &fixture("s6_8-spindle-speed-system-variable-fragment-2.nc"),
        o.clone(),
    );
    assert!(err.is_none(), "{err:?}");
    assert_eq!(spindle_speeds(&cmds), [2400.0]);
    // s6_8 word forms: `S1000`, then `S=$iPerm[1]` = 1500.
    let (cmds, err) = exec(&fixture("s6_8-spindle-speed-word-forms-fragment.nc"), o);
    assert!(err.is_none(), "{err:?}");
    assert_eq!(spindle_speeds(&cmds), [1000.0, 1500.0]);
}

/// The diagnostic of `text`: its code, line, column and the text its span covers.
fn located(text: &str) -> (String, u32, u32, String) {
    let (_, err) = exec(text, opts());
    let err = err.unwrap_or_else(|| panic!("{text}: no error"));
    let covered = text
        .get(err.span.start as usize..err.span.end as usize)
        .unwrap_or("<outside>")
        .to_string();
    (
        err.code.to_string(),
        err.span.line,
        err.span.column,
        covered,
    )
}

#[test]
fn diagnostics_point_at_the_offending_text() {
    for (text, want) in [
        ("int a = b + 1;\nM30\n", ("hll::undeclared", 1, 9, "b")),
        ("int a;\nint a = 2;\nM30\n", ("hll::redeclared", 2, 5, "a")),
        (
            "int z = 0;\nint a = 5 / z;\nM30\n",
            ("hll::division-by-zero", 2, 9, "5 / z"),
        ),
        (
            "double z = 0;\nG01 X=1/z F100\nM30\n",
            ("hll::division-by-zero", 2, 7, "1/z"),
        ),
        (
            "int p[3];\np[3] = 1;\nM30\n",
            ("hll::index-range", 2, 1, "p[3]"),
        ),
        (
            "string s = \"open;\nM30\n",
            ("syntax::unclosed-string", 1, 12, "\"open;"),
        ),
        (
            "int n = 5;\nMSG(n)\nM30\n",
            ("hll::type-mismatch", 2, 5, "n"),
        ),
        (
            "G01 X=FTABLE(128) F100\nM30\n",
            ("axioma::table-index", 1, 7, "FTABLE(128)"),
        ),
    ] {
        let got = located(text);
        assert_eq!(
            (got.0.as_str(), got.1, got.2, got.3.as_str()),
            want,
            "{text}"
        );
    }
}

#[test]
fn decrements_precision_formats_and_loops_counting_down() {
    // `--` both ways, `%.Nf` and `%.Ne`, and a loop counting down around an ISO block.
    let text = "int dec = 5; dec--; --dec;\n\
                int pd = dec--;\n\
                string s;\n\
                sprintf(s, \"%.3f|%.0f|%.2e|%05d|%s\", 3.14159, 2.5, 12345.678, 42, \"end\");\n\
                MSG(s)\n\
                for (int k = 3; k > 0; k--)\n\
                  G00 X=k*1.5\n\
                M30\n";
    let mut it = Interpreter::from_text(text, opts());
    let mut cmds = Vec::new();
    for c in it.by_ref() {
        cmds.push(c.unwrap());
    }
    assert_eq!(it.hll_variable("pd"), Some(HVal::Int(3)));
    assert_eq!(it.hll_variable("dec"), Some(HVal::Int(2)));
    // C rounds 2.5 with %.0f to even: "2".
    assert_eq!(messages(&cmds), ["3.142|2|1.23e+04|00042|end"]);
    assert_points(
        &ends(&cmds),
        &[[4.5, 0.0, 0.0], [3.0, 0.0, 0.0], [1.5, 0.0, 0.0]],
    );
}
