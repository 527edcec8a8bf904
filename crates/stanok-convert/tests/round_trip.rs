//! Round trip: a program is interpreted, its Canon stream converted to each target dialect, the
//! converted text interpreted again by Stanok's own interpreter, and the two motion streams
//! compared. One row per (source dialect, file); the lab dialects' fixtures are added as rows.
//!
//! Compared, motion by motion: the kind (rapid, feed line, arc, spline, probe, rigid tap), the end
//! point of all nine axes, the feed (mm/min), and for arcs the centre, the axis and the number of
//! turns; for splines the control points, weights and the knot vector up to scale. Tolerance:
//! `TOL_MM` = 2e-6 mm on positions (the converter prints 6 decimals: each printed coordinate is
//! within 5e-7 mm, a re-derived centre within 1e-6 mm) and 1e-6 relative on feeds. Where the
//! converter writes chords for a curve the target cannot express (it warns), the chords replace
//! the curve: every chord end must lie on the source curve (within `TOL_MM`), every chord's
//! midpoint within the chord tolerance of it, and the last chord must end at the curve's end.

mod common;
use common::*;
use stanok_canon::Canon;
use stanok_convert::{convert, ConvertOptions, Target};
use stanok_syntax::Dialect;
use std::path::PathBuf;

/// The programs: lines, arcs in G17/G18/G19, helices with turns, full circles, splines (Bézier,
/// NURBS, Akima, cubic), canned cycles, cutter compensation, frames, polar moves, probing, dwell,
/// spindle, coolant, tool changes. Paths are relative to `../shared/corpus`, or to the repository's
/// `examples/` and this crate's `tests/programs/` (programs written for this test: what the corpus
/// fragments do not reach — G18/G19 arcs, helices with P in two planes, G5/G5.1/G5.2 in one
/// program, cycles, dynamic compensation, G92/G10 L2 rotation/G55 frames, G93/G95 feed modes, inch
/// moves, G33, probing) with those prefixes.
const ROWS: &[(Dialect, &str)] = &[
    (Dialect::Rs274ngc, "rs274ngc/g01-linear-example-1.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g02-arc-center-example-1.ngc"),
    (
        Dialect::Rs274ngc,
        "rs274ngc/g02-g03-arc-center-example-2.ngc",
    ),
    (Dialect::Rs274ngc, "rs274ngc/g02-helix-example-3.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g02-p-word-example-4.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/derived-g02-full-circle.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g05-cubic-spline-example-1.ngc"),
    (
        Dialect::Rs274ngc,
        "rs274ngc/g05.1-quadratic-spline-example-1.ngc",
    ),
    (Dialect::Rs274ngc, "rs274ngc/g05.2-nurbs-example-1.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g81-twelve-holes-example.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g40-example-1.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/derived-g10-l2-rotation.ngc"),
    (Dialect::Rs274ngc, "examples/demo-bolt-circle.ngc"),
    (Dialect::Rs274ngc, "programs/planes-helices-splines.ngc"),
    (Dialect::Rs274ngc, "programs/technology-frames-cycles.ngc"),
    (Dialect::Axioma, "examples/demo-plate.nc"),
    (
        Dialect::Axioma,
        "axioma/s5_3_1-arc-centre-ijk-absolute-milling-example-5_5.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_3_1-arc-centre-ijk-relative-turning-example-5_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_3_4-full-circle-ijk-only-example-5_12.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_3_6-helix-extra-turns-p-example-5_14.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_9_3-polar-arc-yz-example-4_25.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_3_3-rotation-loop-slots-example-4_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_4_1-aspline-akima-example-5_15.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_4_3-cspline-cubic-example-5_17.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_4_2-bspline-nurbs-circle-example-5_16.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s11_6_2-g83-peck-drilling-example-11_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s11_8_3-g389-circular-pocket-example-11_14.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s9_2_1-g41-square-contour-example-9_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s9_2_1-g42-turning-contour-example-9_7.nc",
    ),
    (Dialect::Axioma, "axioma/s5_5-probe-g75-example-5_19.nc"),
    (
        Dialect::Axioma,
        "axioma/s5_5-probe-batch-m910-m911-example-5_20.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s11_8_1-g387-rectangular-pocket-example-11_12.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_3_4-combined-transforms-pole-example-4_8.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_9_4-polar-absolute-keyhole-example-4_29.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s9_2_1-g143-g41-incremental-bore-example-9_12.nc",
    ),
    (Dialect::Axioma, "axioma/s5_4_4-splbreak-example-5_18.nc"),
    (
        Dialect::Axioma,
        "axioma/s4_8_1-absolute-centre-turning-example-4_18.nc",
    ),
];

#[test]
fn every_row_round_trips_to_the_same_tool_path_in_both_targets() {
    let mut failures = Vec::new();
    let mut tally = Tally::default();
    let files = ROWS.iter().map(|&(dialect, row)| {
        let path = path_of(row);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{row}: {e}"));
        (dialect, row, text, path.parent().unwrap().to_path_buf())
    });
    for (dialect, row, text, dir) in files {
        let dir = dir.as_path();
        let source = interpret_prefix(&text, dialect, dir);
        let moves = source.iter().filter(|c| c.value.motion().is_some()).count();
        if moves == 0 {
            failures.push(format!(
                "{row}: the source does not move before its first error"
            ));
        }
        for target in [Target::Rs274ngc, Target::Axioma] {
            let opts = ConvertOptions::new(target, row, &format!("{dialect:?}"));
            let (converted, _warnings) = convert(&source, opts);
            let again = match interpret(&converted, target_dialect(target), dir) {
                Ok(s) => s,
                Err(e) => {
                    failures.push(format!(
                        "{row} → {}: the converted program does not run: {e}\n{converted}",
                        target.id()
                    ));
                    continue;
                }
            };
            if let Err(e) = compare(&source, &again, &mut tally) {
                failures.push(format!("{row} → {}: {e}\n{converted}", target.id()));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    eprintln!("{tally:?}");
    // The table covers what it claims: arcs in all three planes, multi-turn helices, splines kept
    // exact (RS274/NGC G5.2, AxiOMA BSPLINE, whole or in pieces), probe moves.
    let t = &tally;
    assert!(t.motions > 500, "{t:?}");
    assert!(t.arcs_by_normal.iter().all(|&n| n >= 4), "{t:?}");
    assert!(t.multi_turn >= 8, "{t:?}");
    assert!(t.splines + t.spline_pieces >= 60, "{t:?}");
    assert!(t.probes >= 4, "{t:?}");
}

/// Beyond the table: every RS274/NGC and AxiOMA corpus program that moves before its first error
/// round-trips in both targets (the same comparison).
#[test]
fn every_corpus_program_that_moves_round_trips() {
    let mut failures = Vec::new();
    let mut tally = Tally::default();
    let mut programs = 0;
    let base = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus"
    ));
    for (sub, dialect) in [("rs274ngc", Dialect::Rs274ngc), ("axioma", Dialect::Axioma)] {
        let mut files: Vec<PathBuf> = std::fs::read_dir(base.join(sub))
            .unwrap_or_else(|e| panic!("{sub}: {e}"))
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "nc" || e == "ngc"))
            .collect();
        files.sort();
        for path in files {
            let Ok(text) = std::fs::read_to_string(&path) else {
                continue;
            };
            let dir = path.parent().unwrap();
            let source = interpret_prefix(&text, dialect, dir);
            if !source.iter().any(|c| c.value.motion().is_some()) {
                continue;
            }
            programs += 1;
            let row = format!("{sub}/{}", path.file_name().unwrap().to_string_lossy());
            for target in [Target::Rs274ngc, Target::Axioma] {
                let (converted, _) = convert(&source, ConvertOptions::new(target, &row, sub));
                match interpret(&converted, target_dialect(target), dir) {
                    Err(e) => failures.push(format!("{row} → {}: does not run: {e}", target.id())),
                    Ok(again) => {
                        if let Err(e) = compare(&source, &again, &mut tally) {
                            failures.push(format!("{row} → {}: {e}", target.id()));
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        programs >= 100 && tally.motions > 2000,
        "{programs} programs, {tally:?}"
    );
}

/// The lab dialects (NC-31, 2P32, MC2101, GOST 20999): every `corpus/labs` fixture that moves
/// before its first error round-trips in both targets (the same comparison). The fixtures'
/// annotations (`;` lines, `//` tails) are stripped first, as `--strip-fixture-comments` does;
/// the dialect comes from the file-name prefix, as on the command line.
#[test]
fn every_lab_program_that_moves_round_trips() {
    let mut failures = Vec::new();
    let mut tally = Tally::default();
    let mut programs = 0;
    let base = path_of("labs");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&base)
        .unwrap_or_else(|e| panic!("labs: {e}"))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "nc"))
        .collect();
    files.sort();
    let mut by_dialect = std::collections::BTreeMap::new();
    for path in files {
        let dialect = Dialect::from_path(&path);
        assert!(dialect.is_lab(), "{}", path.display());
        let text = std::fs::read_to_string(&path).unwrap();
        let text = stanok_syntax::labs::strip_fixture_comments(&text);
        let mut source = interpret_lab_prefix(&text, dialect, &base);
        // "No feed" (feed 0) runs the machine's maximum feed, which the converter writes.
        for c in &mut source {
            match &mut c.value {
                Canon::StraightFeed(m) if m.feed == 0.0 => m.feed = 5000.0,
                Canon::ArcFeed(a) if a.feed == 0.0 => a.feed = 5000.0,
                _ => {}
            }
        }
        if !source.iter().any(|c| c.value.motion().is_some()) {
            continue;
        }
        programs += 1;
        *by_dialect.entry(dialect.id()).or_insert(0) += 1;
        let row = format!("labs/{}", path.file_name().unwrap().to_string_lossy());
        for target in [Target::Rs274ngc, Target::Axioma] {
            let opts = ConvertOptions::new(target, &row, dialect.id());
            let (converted, _) = convert(&source, opts);
            match interpret(&converted, target_dialect(target), &base) {
                Err(e) => failures.push(format!(
                    "{row} → {}: does not run: {e}\n{converted}",
                    target.id()
                )),
                Ok(again) => {
                    if let Err(e) = compare(&source, &again, &mut tally) {
                        failures.push(format!("{row} → {}: {e}\n{converted}", target.id()));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    eprintln!("{programs} lab programs {by_dialect:?}, {tally:?}");
    // Every lab dialect is exercised, with arcs (NC-31 about Y, GOST 20999 in G17).
    assert_eq!(by_dialect.len(), 4, "{by_dialect:?}");
    assert!(programs >= 22, "{programs} programs");
    assert!(
        tally.arcs_by_normal.iter().sum::<usize>() >= 10,
        "{tally:?}"
    );
}
