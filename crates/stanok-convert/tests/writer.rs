//! The writer on hand-made Canon streams: the exact text of the cases the round-trip table does
//! not reach (a rotated start frame folded out, an arc about a tilted axis as chords, M30 as
//! pallet shuttle + end, coolant pairs, spindle-synchronised moves, what each target cannot say).

use stanok_canon::{ArcMove, Canon, LengthUnits, LineMove, Plane, Pose, Span, Spanned};
use stanok_convert::{convert, ConvertOptions, Target};

fn at(line: u32, value: Canon) -> Spanned<Canon> {
    Spanned::new(Span::new(0, 1, line, 1), value)
}

fn p(x: f64, y: f64, z: f64) -> Pose {
    Pose {
        x,
        y,
        z,
        ..Pose::ZERO
    }
}

fn init(g5x: Pose, rotation: f64) -> Spanned<Canon> {
    at(
        0,
        Canon::Init {
            position: Pose::ZERO,
            units: LengthUnits::Millimetres,
            g5x_index: 2,
            g5x_offset: g5x,
            g92_offset: Pose::ZERO,
            xy_rotation: rotation,
        },
    )
}

/// Program lines without the header comments.
fn body(text: &str) -> Vec<&str> {
    text.lines()
        .filter(|l| !l.starts_with('(') && !l.starts_with(';') && !l.starts_with('%'))
        .collect()
}

#[test]
fn the_start_frame_is_folded_out_of_rs274ngc_positions() {
    // G55 at (100, 50, 0) rotated 90°: machine (100, 60) is work (10, 0).
    let cmds = [
        init(p(100.0, 50.0, 0.0), 90.0),
        at(
            3,
            Canon::StraightFeed(LineMove {
                start: Pose::ZERO,
                end: p(100.0, 60.0, -1.0),
                feed: 250.0,
                law: stanok_canon::FeedLaw::PerMinute,
            }),
        ),
        at(4, Canon::ProgramEnd),
    ];
    let (text, warnings) = convert(
        &cmds,
        ConvertOptions::new(Target::Rs274ngc, "t", "rs274ngc"),
    );
    assert_eq!(
        body(&text),
        [
            "G21 G17 G90 G91.1 G94 G40 G49 G80 G55",
            "G1 X10 Y0 Z-1 F250 (line 3)",
            "M2 (line 4)"
        ],
        "{text}"
    );
    assert!(warnings.is_empty());
    // AxiOMA: machine coordinates under G53 G153 G193.
    let (text, _) = convert(&cmds, ConvertOptions::new(Target::Axioma, "t", "rs274ngc"));
    assert!(text.contains("G01 X100 Y60 Z-1 F250 ; line 3"), "{text}");
    assert!(text.contains("G53 G153 G193"), "{text}");
}

#[test]
fn an_arc_about_a_tilted_axis_becomes_chords_within_the_tolerance() {
    let s = 0.5f64.sqrt();
    // A half circle of radius 10 about (0,0,0), axis (0, −√½, √½): from (10,0,0) to (−10,0,0).
    let arc = ArcMove {
        start: p(10.0, 0.0, 0.0),
        end: p(-10.0, 0.0, 0.0),
        centre: [0.0, 0.0, 0.0],
        axis: [0.0, -s, s],
        turns: 1,
        plane: Plane::XY,
        feed: 100.0,
        law: stanok_canon::FeedLaw::PerMinute,
    };
    let cmds = [
        init(Pose::ZERO, 0.0),
        at(
            2,
            Canon::StraightTraverse(LineMove {
                start: Pose::ZERO,
                end: arc.start,
                feed: 0.0,
                law: stanok_canon::FeedLaw::PerMinute,
            }),
        ),
        at(3, Canon::ArcFeed(arc)),
        at(4, Canon::ProgramEnd),
    ];
    let mut opts = ConvertOptions::new(Target::Rs274ngc, "t", "rs274ngc");
    opts.chord_tolerance_mm = 0.01;
    let (text, warnings) = convert(&cmds, opts);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(warnings[0].line, 3);
    let chords: Vec<[f64; 3]> = body(&text)
        .iter()
        .filter(|l| l.starts_with("G1 "))
        .map(|l| {
            let v = |c: char| {
                l.split_whitespace()
                    .find_map(|w| w.strip_prefix(c))
                    .unwrap()
                    .parse::<f64>()
                    .unwrap()
            };
            [v('X'), v('Y'), v('Z')]
        })
        .collect();
    // Sagitta 10·(1 − cos(π/2n)) ≤ 0.01 needs n ≥ 36 chords on the half circle (CCW about the
    // axis: through y = z > 0).
    assert!(
        chords.len() >= 36 && chords.len() < 400,
        "{}\n{text}",
        chords.len()
    );
    for c in &chords {
        let r = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        assert!((r - 10.0).abs() < 1e-6, "{c:?} off the circle");
        assert!(
            (c[1] - c[2]).abs() < 1e-6,
            "{c:?} off the arc's plane y = z"
        );
    }
    assert_eq!(chords.last().unwrap(), &[-10.0, 0.0, 0.0]);
    // Every chord (from the start (10, 0, 0) on) stays within the tolerance of the circle.
    let mut prev = [10.0, 0.0, 0.0];
    for c in &chords {
        let m = [
            0.5 * (prev[0] + c[0]),
            0.5 * (prev[1] + c[1]),
            0.5 * (prev[2] + c[2]),
        ];
        let r = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        assert!(
            10.0 - r <= 0.01 + 1e-9,
            "chord to {c:?}: sagitta {}",
            10.0 - r
        );
        assert!(c[1] > 0.0 || c[0] == -10.0, "{c:?} on the wrong side");
        prev = *c;
    }
}

#[test]
fn end_coolant_sync_and_what_a_target_cannot_say() {
    let line = |a: Pose, b: Pose| {
        Canon::StraightFeed(LineMove {
            start: a,
            end: b,
            feed: 300.0,
            law: stanok_canon::FeedLaw::PerMinute,
        })
    };
    let cmds = [
        init(Pose::ZERO, 0.0),
        at(2, Canon::Mist { on: true }),
        at(2, Canon::Flood { on: true }),
        at(3, Canon::Mist { on: false }),
        at(
            4,
            Canon::StartSpindleSync {
                pitch: 1.5,
                velocity_mode: false,
            },
        ),
        at(4, line(Pose::ZERO, p(0.0, 0.0, -15.0))),
        at(5, Canon::StopSpindleSync),
        at(
            6,
            Canon::SetAccelerationProfile {
                profile: stanok_canon::AccelerationProfile::Soft,
            },
        ),
        at(7, Canon::PalletShuttle),
        at(7, Canon::ProgramEnd),
        at(8, line(p(0.0, 0.0, -15.0), Pose::ZERO)),
    ];
    let (text, warnings) = convert(&cmds, ConvertOptions::new(Target::Rs274ngc, "t", "x"));
    assert_eq!(
        body(&text),
        [
            "G21 G17 G90 G91.1 G94 G40 G49 G80 G55",
            "M7 (line 2)",
            "M8",
            "M9 (line 3)",
            "M8",
            "G33 X0 Y0 Z-15 K1.5 (line 4)",
            "M30 (line 7)"
        ],
        "{text}"
    );
    // SOFT has no RS274/NGC form: a comment in the program and a warning; nothing after M30.
    assert!(text.contains("(stanok: line 6: SOFT [acceleration profile] has no RS274/NGC form)"));
    assert_eq!(warnings.len(), 1);
    let (text, warnings) = convert(&cmds, ConvertOptions::new(Target::Axioma, "t", "x"));
    assert!(text.contains("SOFT ; line 6"), "{text}");
    assert!(text.contains("G01 X0 Y0 Z-15 F300 ; line 4"), "{text}");
    assert!(text.contains("M30 ; line 7"), "{text}");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].message.contains("spindle-synchronised"));
}

#[test]
fn a_stream_without_program_end_gets_one() {
    let cmds = [init(Pose::ZERO, 0.0), at(1, Canon::Finish)];
    let (text, _) = convert(&cmds, ConvertOptions::new(Target::Axioma, "t", "x"));
    assert_eq!(body(&text).last(), Some(&"M30"), "{text}");
}
