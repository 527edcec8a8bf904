//! AxiOMA high-level language under random input: token soup of the language's own vocabulary
//! (keywords, braces, operators, names, numbers, strings, ISO words) — mostly ill-formed — must
//! never make the parser or the interpreter panic or hang: every run ends (an error is fine),
//! within the loop and block bounds, and every emitted coordinate is finite.

use proptest::prelude::*;
use stanok_canon::Canon;
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::{parse, Dialect};

const TOKENS: &[&str] = &[
    "int",
    "long",
    "double",
    "bool",
    "string",
    "for",
    "while",
    "do",
    "if",
    "else",
    "break",
    "continue",
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    ";",
    ",",
    "=",
    "+=",
    "-=",
    "*=",
    "/=",
    "%=",
    "++",
    "--",
    "+",
    "-",
    "*",
    "/",
    "%",
    "<",
    "<=",
    ">",
    ">=",
    "==",
    "!=",
    "&&",
    "||",
    "!",
    "?",
    ":",
    "ii",
    "kk",
    "arr",
    "str",
    "0",
    "1",
    "2",
    "7",
    "0.5",
    "-3",
    "1e300",
    "\"a%d\"",
    "\"x",
    "sprintf",
    "sin",
    "atan2",
    "sqrt",
    "FTABLE",
    "STABLE",
    "MSG",
    "$iPerm",
    "$dPerm",
    "settable_zs",
    "true",
    "G01",
    "X=",
    "Y10",
    "F=",
    "N10",
    "M30",
    "//",
    "/*",
    "*/",
    "\n",
    "\n",
    "\n",
];

fn soup() -> impl Strategy<Value = String> {
    prop::collection::vec(0usize..TOKENS.len(), 0..80).prop_map(|idx| {
        let mut text = String::new();
        for i in idx {
            text.push_str(TOKENS[i]);
            text.push(' ');
        }
        text
    })
}

/// A well-formed skeleton with random bounds and bodies: loops that really run.
fn loops() -> impl Strategy<Value = String> {
    (0i32..6, 0i32..6, 0usize..4, -5i32..5).prop_map(|(a, b, body, step)| {
        let inner = match body {
            0 => "G01 X=ii Y=kk F100".to_string(),
            1 => "if (ii > kk) break;\nG00 X=ii*2".to_string(),
            2 => "kk += 1;\nif (kk % 2) continue;\nG00 Y=kk".to_string(),
            _ => "do { kk++; } while (kk < 3);\nG00 Z=kk".to_string(),
        };
        format!(
            "int kk = {b};\nfor (int ii = 0; ii < {a}; ii += {}) {{\n{inner}\n}}\nwhile (kk > {step}) kk--;\nM30\n",
            if step == 0 { 1 } else { step.abs() }
        )
    })
}

fn run(text: &str) {
    let _ = parse(text, Dialect::Axioma);
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.max_loop_iterations = 500;
    opts.max_blocks = 20_000;
    for item in Interpreter::from_text(text, opts) {
        match item {
            Ok(c) => {
                if let Some(m) = c.value.motion() {
                    assert!(m.end().to_array().iter().all(|v| v.is_finite()));
                }
                if let Canon::Message { text } = &c.value {
                    assert!(text.chars().count() <= 256);
                }
            }
            Err(_) => break,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn token_soup_never_panics_or_hangs(text in soup()) {
        run(&text);
    }

    #[test]
    fn random_loops_end_without_error(text in loops()) {
        let mut opts = InterpOptions::new(Dialect::Axioma);
        opts.max_loop_iterations = 500;
        for item in Interpreter::from_text(&text, opts) {
            if let Err(d) = item {
                panic!("{text}\n{d}");
            }
        }
    }
}
