//! Column [1] of tables 12.1 and 12.2, code by code: every code of every row runs in a block of
//! its own outside tool tip point control (or is refused as not simulated), and inside it runs
//! when the row says ○ and is refused with the table's alarm when it says ×. The rows come from
//! `codes::TABLE_T` / `TABLE_M`, which `ttpc_tables.rs` checks against the seed.

mod common;
use common::*;
use stanok_mazatrol::codes::{g_name, ttpc_table, Code, Mark, Series};

/// A block that exercises `code` (G × 10 or M), valid outside TTPC.
fn sample(series: Series, code: Code) -> String {
    let t = series == Series::T;
    let s = match code {
        Code::M(98) => "M98 P9000",
        Code::M(99) => "M98 P9001",
        Code::M(_) => "M05",
        Code::G(g) => match g {
            0 => "G00 X10.",
            10 => "G01 X10. F500.",
            11 => "G01.1 Z-10.",
            20 if t => "G02 X10. Z-5. R5. F500.",
            20 => "G02 X10. Y0 R5. F500.",
            30 if t => "G03 X10. Z-5. R5. F500.",
            30 => "G03 X10. Y0 R5. F500.",
            21 if t => "G02.1 X10. Z0 I0 K5. F500.",
            21 => "G02.1 X10. Y0 I5. J0 F500.",
            31 if t => "G03.1 X10. Z0 I0 K5. F500.",
            31 => "G03.1 X10. Y0 I5. J0 F500.",
            40 => "G04 P100",
            50 => "G05 P2",
            61 => "G06.1 X1.",
            62 => "G06.2 X1.",
            70 => "G07 X1.",
            71 => "G07.1 C20.\nG07.1 C0",
            90 => "G09 G01 X10. F500.",
            100 if t => "G10 L10 P5 X0 Z10.",
            100 => "G10 L2 P2 X1.",
            110 => "G11",
            121 => "G12.1\nG13.1",
            131 => "G13.1",
            160 => "G16",
            170 => "G17",
            180 => "G18",
            190 => "G19",
            200 => "G20\nG21",
            210 => "G21",
            220 => "G22 X-900. Y-900. Z-900. I-800. J-800. K-800.",
            230 => "G23",
            // Machine Z 0 (the reference point) is program Z 200 (M) / −200 (T).
            270 if t => "G27 Z-200.",
            270 => "G27 Z200.",
            280 => "G28 Z0",
            290 => "G28 Z0\nG29 Z0",
            300 => "G30 P2 Z0",
            301 => "G30.1 Z0",
            310 => "G31 X1. F100.",
            311 => "G31.1 X1. F100.",
            312 => "G31.2 X1. F100.",
            313 => "G31.3 X1. F100.",
            320 => "G97 S500 M03\nG32 Z-10. F1.5",
            330 if t => "G97 S500 M03\nG33 Z-10. F1.5",
            330 => "S500 M03\nG33 Z-10. F1.5",
            340 => "G97 S500 M03\nG34 Z-10. F1.5 K0.1",
            360 | 370 | 365 | 375 => "G37 Z0",
            380 | 390 => "G38",
            400 => "G40",
            410 if t => "T0101\nG41",
            420 if t => "T0101\nG42",
            460 if t => "T0101\nG46",
            410 => "G41 D3",
            420 => "G42 D3",
            430 => "G43 H2",
            440 => "G44 H2",
            490 => "G49",
            450 => "G45 X1. D3",
            460 => "G46 X1. D3",
            470 => "G47 X1. D3",
            480 => "G48 X1. D3",
            500 if t => "G50 S2000",
            500 => "G50",
            510 => "G51 X0 Y0 P2.",
            501 => "G50.1 X0",
            511 => "G51.1 X0",
            502 | 512 => "G51.2 P1 Q1",
            520 => "G52 X1.",
            530 => "G53 Z0",
            525 => "G52.5",
            535 => "G53.5",
            540 => "G54",
            550 => "G55",
            560 => "G56",
            570 => "G57",
            580 => "G58",
            590 => "G59",
            541 => "G54.1 P2",
            600 => "G60 X10.",
            610 => "G61",
            611 => "G61.1",
            620 => "G62",
            630 => "G63",
            640 => "G64",
            650 => "G65 P9000 A1.",
            660 => "G66 P9000 A1.",
            661 => "G66.1 P9000 A1.",
            670 => "G67",
            680 if t => "G68",
            680 => "G68 X0 Y0 R30.",
            690 => "G69",
            685 => "G68.5 X0 Y0 Z0 I0 J0 K1 R30.",
            695 => "G69.5",
            700 => "G00 X30. Z2.\nG70 P10 Q12\nG00 X40.\nN10 G00 X20.\nN11 G01 Z-10. F0.1\nN12 X30.",
            710 => "G00 X30. Z2.\nG71 U1. R0.5\nG71 P10 Q12 U0.2 W0.1 F0.2\nN10 G00 X20.\nN11 G01 Z-10.\nN12 X30.",
            720 => "G00 X30. Z2.\nG72 W1. R0.5\nG72 P10 Q12 U0.2 W0.1 F0.2\nN10 G00 Z-5.\nN11 G01 X20.\nN12 Z2.",
            730 if t => "G00 X30. Z2.\nG73 U2. W1. R2\nG73 P10 Q12 U0.2 W0.1 F0.2\nN10 G00 X20.\nN11 G01 Z-10.\nN12 X30.",
            740 if t => "G74 R0.5\nG74 X0 Z-5. Q2000 F0.1",
            750 => "G00 X20. Z0\nG75 R0.5\nG75 X10. Z-2. P1000 Q1000 F0.1",
            760 if t => "G97 S500 M03\nG00 X20. Z5.\nG76 P010060 Q100 R0.05\nG76 X17. Z-10. P1000 Q300 F1.5",
            770 => "G77 X20. Z-10. F0.1",
            780 => "G97 S500 M03\nG00 X20. Z5.\nG78 X18. Z-10. F1.5",
            790 => "G00 X20. Z2.\nG79 X10. Z-1. F0.1",
            800 => "G80",
            830 if t => "G97 S500 M03\nG83 X0 C0 Z-5. R-1. Q2000 F0.1\nG80",
            840 if t => "G97 S500 M03\nG84 X0 C0 Z-5. R-1. F0.1\nG80",
            850 if t => "G97 S500 M03\nG85 X0 C0 Z-5. R-1. F0.1\nG80",
            870 if t => "G97 S500 M03\nG00 X40. Z-5.\nG87 Z-5. C0 X10. R-1. Q2000 F0.1\nG80",
            880 if t => "G97 S500 M03\nG00 X40. Z-5.\nG88 Z-5. C0 X10. R-1. F0.1\nG80",
            890 if t => "G97 S500 M03\nG00 X40. Z-5.\nG89 Z-5. C0 X10. R-1. P500 F0.1\nG80",
            870 => "S500 M03\nG98 G87 X10. Y10. Z-5. R-10. Q0.5 F100.\nG80",
            730 => "S500 M03\nG73 X10. Y10. Z-5. R2. Q1. F100.\nG80",
            740 => "S500 M04\nG74 X10. Y10. Z-5. R2. F100.\nG80",
            760 => "S500 M03\nG76 X10. Y10. Z-5. R2. Q0.2 F100.\nG80",
            810 => "S500 M03\nG81 X10. Y10. Z-5. R2. F100.\nG80",
            820 => "S500 M03\nG82 X10. Y10. Z-5. R2. P500 F100.\nG80",
            830 => "S500 M03\nG83 X10. Y10. Z-5. R2. Q1. F100.\nG80",
            840 => "S500 M03\nG84 X10. Y10. Z-5. R2. F100.\nG80",
            850 => "S500 M03\nG85 X10. Y10. Z-5. R2. F100.\nG80",
            860 => "S500 M03\nG86 X10. Y10. Z-5. R2. F100.\nG80",
            880 => "S500 M03\nG88 X10. Y10. Z-5. R2. P500 F100.\nG80",
            890 => "S500 M03\nG89 X10. Y10. Z-5. R2. P500 F100.\nG80",
            900 => "G90",
            910 => "G91",
            920 => "G92 X0 Y0 Z0",
            925 => "G92.5 R10.",
            930 => "G93",
            940 => "G94",
            950 => "G95",
            960 => "G96 S100",
            970 => "G97 S100",
            980 => "G98",
            990 => "G99",
            1090 => "G109 L1",
            1100 => "G110",
            1110 => "G111",
            1120 => "G112 M03",
            1130 => "G113",
            1143 => "G114.3",
            1200 => "G120",
            1210 => "G121",
            1220 => "G122",
            1230 => "G123",
            1221 => "G122.1",
            1231 => "G123.1",
            _ => panic!("no sample for {}", g_name(g)),
        },
    };
    s.to_string()
}

/// The block that uses `code` inside TTPC (the code itself, with words valid there).
fn in_ttpc(series: Series, code: Code) -> String {
    match code {
        Code::G(20) | Code::G(30) => sample(series, code),
        Code::G(90) => "G09 G01 X12. F500.".into(),
        Code::G(0) => "G00 X12.".into(),
        Code::G(10) => "G01 X12. F500.".into(),
        Code::G(930) => "G93 G01 X12. F2.".into(),
        Code::G(910) => "G91".into(),
        Code::G(410) if series == Series::T => "G41".into(),
        Code::G(420) if series == Series::T => "G42".into(),
        Code::G(460) if series == Series::T => "G46".into(),
        _ => sample(series, code),
    }
}

fn subprograms() -> &'static str {
    "M30\nO9000\nM99\nO9001\nM99\n"
}

fn machine(series: Series) -> Machine {
    match series {
        Series::M => mazak_m(),
        Series::T => mazak_t(),
    }
}

fn ttpc_start(series: Series) -> &'static str {
    match series {
        Series::M => "G90 G01 F1000.\nG43.4 X0 Y0 Z50. B0 H2\n",
        Series::T => "G90 G94 G01 F1000.\nG43.4 X100. Y0 Z50. B0 H2\n",
    }
}

#[test]
fn column_one_code_by_code() {
    for series in [Series::M, Series::T] {
        for row in ttpc_table(series) {
            for &code in row.codes {
                let name = match code {
                    Code::G(g) => g_name(g),
                    Code::M(m) => format!("M{m:02}"),
                };
                // Outside TTPC: runs, or is refused as not simulated.
                let home = match series {
                    Series::M => "G00 X0 Y0 Z0\n",
                    Series::T => "G00 X0 Z0\n",
                };
                let prog = format!("{home}{}\n{}", sample(series, code), subprograms());
                let r = run(&prog, &machine(series));
                if let Some(e) = &r.error {
                    assert_eq!(
                        e.code.to_string(),
                        "mazatrol::not-simulated",
                        "{} {} outside TTPC: {e:?}",
                        series.name(),
                        name
                    );
                }
                // Inside TTPC.
                let block = if row.function == "helical interpolation" {
                    match series {
                        Series::M => "G02 X10. Y0 Z5. R5.".to_string(),
                        Series::T => "G02 X10. Z-5. Y1. R5.".to_string(),
                    }
                } else {
                    in_ttpc(series, code)
                };
                let prog = format!("{}{}\n{}", ttpc_start(series), block, subprograms());
                let r = run(&prog, &machine(series));
                let refused = r
                    .error
                    .as_ref()
                    .filter(|e| e.code.to_string() == "mazatrol::code-not-allowed-in-ttpc");
                match row.in_ttpc {
                    Mark::Yes => assert!(
                        r.error.is_none(),
                        "{} {name} ({}) must run in TTPC: {:?}",
                        series.name(),
                        row.function,
                        r.error
                    ),
                    Mark::No => {
                        let e = refused.unwrap_or_else(|| {
                            panic!(
                                "{} {name} ({}) must be refused in TTPC: {:?}",
                                series.name(),
                                row.function,
                                r.error
                            )
                        });
                        assert!(
                            e.message.contains(&format!("table {}", series.table())),
                            "{}",
                            e.message
                        );
                        assert!(e.message.contains(series.name()), "{}", e.message);
                    }
                    Mark::Note(3) => {
                        // Table frame: refused naming note 3.
                        let e = refused.expect("note 3 under the table frame");
                        assert!(e.message.contains("note 3"), "{}", e.message);
                    }
                    Mark::Note(_) | Mark::NonModal => {
                        assert!(r.error.is_none(), "{} {name}: {:?}", series.name(), r.error)
                    }
                }
            }
        }
    }
}
