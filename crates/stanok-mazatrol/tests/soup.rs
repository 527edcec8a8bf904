//! Random programs from the language's pieces (`docs/dialects/mazatrol-eia.md` §2–§16): whatever
//! the text, the front end neither panics nor runs forever, an error ends the stream, and every
//! command carries a span inside the program.

mod common;
use common::*;
use proptest::prelude::*;

/// Words and statements the soup is made of: every G code of both tables, axis and argument
/// words, macro statements, variables, calls and returns.
fn piece() -> impl Strategy<Value = String> {
    let g = prop::sample::select(vec![
        "G00", "G01", "G02", "G03", "G02.1", "G04", "G09", "G10", "G11", "G12.1", "G13.1", "G07.1",
        "G17", "G18", "G19", "G20", "G21", "G22", "G23", "G27", "G28", "G29", "G30", "G31", "G32",
        "G33", "G34", "G40", "G41", "G42", "G43", "G43.4", "G43.5", "G44", "G45", "G46", "G49",
        "G50", "G51", "G50.1", "G51.1", "G52", "G53", "G54", "G54.1", "G55", "G60", "G61", "G64",
        "G65", "G66", "G66.1", "G67", "G68", "G69", "G68.5", "G69.5", "G70", "G71", "G72", "G73",
        "G74", "G75", "G76", "G77", "G78", "G79", "G80", "G81", "G82", "G83", "G84", "G85", "G86",
        "G87", "G88", "G89", "G90", "G91", "G92", "G93", "G94", "G95", "G96", "G97", "G98", "G99",
        "G109", "G122", "G123", "M03", "M04", "M05", "M06", "M08", "M19", "M29", "M98", "M99",
        "M30", "M02",
    ]);
    let letter = prop::sample::select(vec![
        'X', 'Y', 'Z', 'U', 'W', 'B', 'C', 'I', 'J', 'K', 'R', 'F', 'S', 'T', 'H', 'D', 'P', 'Q',
        'L', 'A', 'E',
    ]);
    let number = prop_oneof![
        (-500i32..500).prop_map(|v| format!("{v}")),
        (-5000i32..5000).prop_map(|v| format!("{}.", f64::from(v) / 10.0)),
        Just("0".to_string()),
        Just("#1".to_string()),
        Just("#100".to_string()),
        Just("#0".to_string()),
        Just("[#1+2.]".to_string()),
        Just("[1/0]".to_string()),
        Just("[SQRT[-1]]".to_string()),
    ];
    prop_oneof![
        4 => g.prop_map(|s| s.to_string()),
        6 => (letter, number).prop_map(|(l, v)| format!("{l}{v}")),
        1 => (1u32..200, -50i32..50).prop_map(|(n, v)| format!("#{n}={v}")),
        1 => (1u32..40).prop_map(|n| format!("N{n}")),
        1 => (1u32..40).prop_map(|n| format!("GOTO{n}")),
        1 => (1u32..4).prop_map(|n| format!("WHILE[#1LT3]DO{n}")),
        1 => (1u32..4).prop_map(|n| format!("END{n}")),
        1 => (1u32..40).prop_map(|n| format!("IF[#1GT0]GOTO{n}")),
        1 => Just("#1=#1+1".to_string()),
        1 => Just("O10".to_string()),
        1 => Just("(A COMMENT)".to_string()),
        1 => Just("/".to_string()),
    ]
}

fn program() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::collection::vec(piece(), 1..6), 1..25).prop_map(|lines| {
        let mut s = String::new();
        for (i, l) in lines.iter().enumerate() {
            s.push_str(&format!("N{} ", i + 1));
            s.push_str(&l.join(" "));
            s.push('\n');
        }
        s
    })
}

fn bounded(mut m: Machine) -> Machine {
    m.opts.max_blocks = 5_000;
    m.opts.max_loop_iterations = 500;
    m
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn soup_never_panics_and_ends(text in program()) {
        let lines = text.lines().count() as u32;
        for m in [bounded(mazak_m()), bounded(mazak_t()), bounded(mill())] {
            let r = run(&text, &m);
            for c in &r.canon {
                prop_assert!(c.span.line <= lines + 1, "{:?} in\n{text}", c.span);
            }
        }
    }
}
