//! Issue 17: every verb's library path — check, run, canon, plot, convert — on mutated programs of
//! all eight dialects (byte flips, line duplication and deletion, huge and tiny numbers, long
//! lines, deep and long expressions, runaway loops, feeds and dwells). Asserted: no panic (and, on
//! the test thread's 2 MiB stack, no stack overflow), the run ends within the bounds, every
//! diagnostic names a line and column of the program. Seeds: the examples and
//! `../shared/corpus`, read in place. `scripts/mutation-campaign.py` does the same to the release
//! binary, with time and memory limits per run.

use proptest::prelude::*;
use stanok_canon::linuxcnc::LinuxCncPrinter;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_machine::{MachineData, SimMachine, SimOptions};
use stanok_syntax::Dialect;
use std::sync::OnceLock;

const DIALECTS: [Dialect; 8] = [
    Dialect::Axioma,
    Dialect::Rs274ngc,
    Dialect::Nc31,
    Dialect::P2p32,
    Dialect::Mc2101,
    Dialect::Gost20999,
    Dialect::Mazatrol,
    Dialect::Balt,
];

/// The seed programs with their dialects (at most 32 KiB each, to keep cases quick).
fn seeds() -> &'static [(Dialect, Vec<u8>)] {
    static SEEDS: OnceLock<Vec<(Dialect, Vec<u8>)>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mut files = Vec::new();
        let mut walk = vec![root.join("examples"), root.join("../shared/corpus")];
        while let Some(dir) = walk.pop() {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for e in entries.flatten() {
                let p = e.path();
                if p.is_dir() {
                    walk.push(p);
                } else if matches!(p.extension().and_then(|e| e.to_str()), Some("nc" | "ngc")) {
                    files.push(p);
                }
            }
        }
        files.sort();
        let mut out = Vec::new();
        for p in files {
            let Ok(data) = std::fs::read(&p) else {
                continue;
            };
            if data.len() > 32 * 1024 {
                continue;
            }
            let s = p.to_string_lossy();
            let dialect = if s.contains("/cvu/") {
                Dialect::Balt
            } else if s.contains("/mazatrol/") {
                Dialect::Mazatrol
            } else {
                Dialect::from_path(&p)
            };
            out.push((dialect, data));
        }
        // Without the shared corpus, the examples and a few lines of each dialect.
        out.push((
            Dialect::Rs274ngc,
            b"G21 G90\nG1 X10 Y5 F300\nG2 X20 Y5 R5\nM2\n".to_vec(),
        ));
        out.push((
            Dialect::Axioma,
            b"G71 G90\nG1 X10 F300\nint i;\nfor (i=0;i<3;i++) {\nG91 X1\n}\nM30\n".to_vec(),
        ));
        out
    })
}

/// One mutation (the kinds of the issue).
#[derive(Debug, Clone)]
enum Mutation {
    FlipByte {
        at: usize,
        to: u8,
    },
    DuplicateLine {
        at: usize,
        times: usize,
    },
    DeleteLines {
        at: usize,
        count: usize,
    },
    Number {
        at: usize,
        value: &'static str,
    },
    LongLine {
        at: usize,
        piece: &'static str,
        times: usize,
    },
    LongExpression {
        at: usize,
        terms: usize,
        op: usize,
    },
    DeepExpression {
        at: usize,
        depth: usize,
    },
    RunawayLoop {
        at: usize,
        kind: usize,
    },
    RunawayFeed {
        at: usize,
        block: &'static str,
    },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = any::<usize>();
    prop_oneof![
        (at, any::<u8>()).prop_map(|(at, to)| Mutation::FlipByte { at, to }),
        (at, prop_oneof![Just(1usize), Just(10), Just(300)])
            .prop_map(|(at, times)| Mutation::DuplicateLine { at, times }),
        (at, 1usize..5).prop_map(|(at, count)| Mutation::DeleteLines { at, count }),
        (
            at,
            prop::sample::select(vec![
                "1e308",
                "99999999999999999999",
                "0.0000001",
                "1e-300",
                "-0",
                "4294967296",
                "65536",
                "999999999"
            ])
        )
            .prop_map(|(at, value)| Mutation::Number { at, value }),
        (
            at,
            prop::sample::select(vec![" ", "X1 ", "G1 X1 ", "(", "a"]),
            prop_oneof![Just(100usize), Just(70_000)]
        )
            .prop_map(|(at, piece, times)| Mutation::LongLine { at, piece, times }),
        (at, prop_oneof![Just(100usize), Just(5_000)], 0usize..3)
            .prop_map(|(at, terms, op)| Mutation::LongExpression { at, terms, op }),
        (at, prop_oneof![Just(10usize), Just(70), Just(2_000)])
            .prop_map(|(at, depth)| Mutation::DeepExpression { at, depth }),
        (at, 0usize..3).prop_map(|(at, kind)| Mutation::RunawayLoop { at, kind }),
        (
            at,
            prop::sample::select(vec![
                "G1 X100 F0.0000001",
                "G4 P1000000000",
                "G4 P300000",
                "G1 X50 F0.01",
                "G1 X10 F1"
            ])
        )
            .prop_map(|(at, block)| Mutation::RunawayFeed { at, block }),
    ]
}

fn apply(data: &[u8], dialect: Dialect, m: &Mutation) -> Vec<u8> {
    let mut lines: Vec<Vec<u8>> = data.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    let n = lines.len().max(1);
    let iso = matches!(dialect, Dialect::Rs274ngc | Dialect::Mazatrol);
    match m {
        Mutation::FlipByte { at, to } => {
            let mut b = data.to_vec();
            if !b.is_empty() {
                let i = at % b.len();
                b[i] = *to;
            }
            return b;
        }
        Mutation::DuplicateLine { at, times } => {
            let l = lines[at % n].clone();
            for _ in 0..*times {
                lines.insert(at % n, l.clone());
            }
        }
        Mutation::DeleteLines { at, count } => {
            let i = at % n;
            let end = (i + count).min(lines.len());
            lines.drain(i..end);
        }
        Mutation::Number { at, value } => {
            let l = &mut lines[at % n];
            if let Some(i) = l.iter().position(u8::is_ascii_digit) {
                let j = l[i..]
                    .iter()
                    .position(|c| !c.is_ascii_digit())
                    .map_or(l.len(), |k| i + k);
                l.splice(i..j, value.bytes());
            }
        }
        Mutation::LongLine { at, piece, times } => {
            let l = &mut lines[at % n];
            l.extend(piece.repeat(*times).bytes());
            l.extend(b"G999");
        }
        Mutation::LongExpression { at, terms, op } => {
            let ops = if iso {
                ["+", " AND ", "*"]
            } else {
                ["+", "&&", "*"]
            };
            let chain = vec!["1"; *terms].join(ops[*op]);
            let line = if iso {
                format!("G1 X[{chain}] F100")
            } else {
                format!("double aa = {chain};")
            };
            lines.insert(at % n, line.into_bytes());
        }
        Mutation::DeepExpression { at, depth } => {
            let line = if iso {
                format!("G1 X{}1{} F100", "[".repeat(*depth), "]".repeat(*depth))
            } else {
                format!("double d = {}1{};", "(".repeat(*depth), ")".repeat(*depth))
            };
            lines.insert(at % n, line.into_bytes());
        }
        Mutation::RunawayLoop { at, kind } => {
            let body = match (iso, kind) {
                (true, 0) => "#1=0\no1 repeat [1000]\no2 repeat [1000]\no3 repeat [1000]\n#1=[#1+1]\no3 endrepeat\no2 endrepeat\no1 endrepeat".to_string(),
                (true, _) => "o9 while [1]\nG1 X1 F100\no9 endwhile".to_string(),
                (false, 0) => "int i; int j;\nfor (i = 0; i < 100000; i++) {\nfor (j = 0; j < 100000; j++) {\nG1 X1 F100\n}\n}".to_string(),
                (false, 1) => format!("{}{}", "if(1){\n".repeat(3_000), "}\n".repeat(3_000)),
                (false, _) => "while (true) { }".to_string(),
            };
            lines.insert(at % n, body.into_bytes());
        }
        Mutation::RunawayFeed { at, block } => lines.insert(at % n, block.as_bytes().to_vec()),
    }
    lines.join(&b'\n')
}

/// Bounds for the test: the defaults, with the work bounds lowered so a debug case stays quick.
fn options(dialect: Dialect, check: bool) -> InterpOptions {
    let mut o = InterpOptions::new(dialect);
    o.continue_after_error = check;
    o.max_blocks = 200_000;
    o.max_total_loop_iterations = 20_000;
    o
}

fn located(d: &Diagnostic, program: &[u8]) {
    let lines = program.iter().filter(|&&b| b == b'\n').count() as u64 + 1;
    assert!(
        d.span.line >= 1 && u64::from(d.span.line) <= lines && d.span.column >= 1,
        "a diagnostic without a place in the program ({lines} lines): {d:?}"
    );
}

/// Interprets to the end (check: past errors); asserts every diagnostic is located.
fn interpret(dialect: Dialect, check: bool, program: &[u8]) -> Vec<Spanned<Canon>> {
    let opts = options(dialect, check);
    let max_blocks = opts.max_blocks;
    let mut interp = Interpreter::new(std::io::Cursor::new(program), opts);
    let mut commands = Vec::new();
    for item in interp.by_ref() {
        match item {
            Ok(c) => commands.push(c),
            Err(d) => {
                located(&d, program);
                if !check {
                    break;
                }
            }
        }
    }
    for w in interp.take_warnings() {
        located(&w, program);
    }
    assert!(interp.stats().lines_read <= max_blocks + 1);
    commands
}

/// All five verbs on one program.
fn every_verb(dialect: Dialect, program: &[u8]) {
    // check
    let _ = interpret(dialect, true, program);
    // canon
    let commands = interpret(dialect, false, program);
    let mut printer = LinuxCncPrinter::new();
    for c in &commands {
        let _ = printer.print(c);
    }
    let _ = printer.finish();
    // run (default bound on machine time; steady stretches skipped as in `stanok run`)
    let mut sim = SimMachine::with_options(MachineData::default_mill(), SimOptions::default());
    sim.set_progress_sink(Box::new(|_| {}));
    for c in &commands {
        if let Err(d) = sim.apply(c) {
            located(&d, program);
            break;
        }
    }
    let report = sim.finish();
    assert!(report.cycle_time_s <= SimOptions::default().max_machine_time_s + 1.0);
    for w in sim.take_warnings() {
        located(&w, program);
    }
    // plot
    let svg = stanok_plot::render_svg(&commands, &stanok_plot::PlotOptions::default());
    assert!(svg.len() < 64 << 20);
    // convert
    for target in [
        stanok_convert::Target::Rs274ngc,
        stanok_convert::Target::Axioma,
    ] {
        let options = stanok_convert::ConvertOptions::new(target, "prop", dialect.id());
        let _ = stanok_convert::convert(&commands, options);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn every_verb_survives_mutated_programs(
        seed in any::<prop::sample::Index>(),
        other_dialect in prop::option::weighted(0.1, 0usize..8),
        mutations in prop::collection::vec(mutation(), 1..4),
    ) {
        let (dialect, data) = seed.get(seeds());
        let dialect = other_dialect.map_or(*dialect, |i| DIALECTS[i]);
        let mut program = data.clone();
        for m in &mutations {
            program = apply(&program, dialect, m);
        }
        let started = std::time::Instant::now();
        every_verb(dialect, &program);
        // Generous for a debug build on a shared machine; a hang would never get here.
        prop_assert!(started.elapsed().as_secs() < 120, "took {:?}", started.elapsed());
    }
}
