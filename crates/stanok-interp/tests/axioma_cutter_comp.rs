//! AxiOMA radius compensation G40/G41/G42/G143/G144 (spec axioma-3 §4, manual 9.2): the
//! tool-centre paths of fixtures s9_2_* with the radii their headers assume, bottle-neck
//! handling with the look-ahead depth M905, the forbidden words, and property tests of the
//! equidistant (distance exactly r from the programmed contour, on the correct side).
//! Positions to 1e-6 mm.

mod common;
use common::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind};
use stanok_canon::{Canon, DiagCode, Diagnostic, Spanned};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-6;

fn fixture(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap()
}

/// Tools 1…5: milling cutters of radius `r` (T3: 6, T5: 4, T4/T2: 5 unless `r` overrides T1).
fn tools(r: f64, kind: ToolKind) -> ControlData {
    let mut c = ControlData::default();
    for (t, radius) in [(1, r), (2, 5.0), (3, 6.0), (4, 5.0), (5, 4.0)] {
        c.tools.tools.insert(
            t,
            Tool {
                number: t,
                kind,
                edges: vec![ToolEdge {
                    radius,
                    ..Default::default()
                }],
                ..Default::default()
            },
        );
    }
    c
}

fn run_r(text: &str, r: f64) -> (Vec<Spanned<Canon>>, Option<Diagnostic>) {
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.control = tools(r, ToolKind::Milling);
    run_with(text, opts)
}

fn ok(text: &str, r: f64) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run_r(text, r);
    assert!(err.is_none(), "{err:?}");
    cmds
}

/// One move in plane coordinates (a1, a2) of `plane_axes`.
#[derive(Debug, Clone, Copy)]
struct Mv {
    n: Option<u32>,
    end: [f64; 2],
    /// Arc centre and direction.
    arc: Option<([f64; 2], bool)>,
    z: f64,
}

fn moves_in(cmds: &[Spanned<Canon>], a: usize, b: usize) -> Vec<Mv> {
    cmds.iter()
        .filter_map(|c| {
            let m = c.value.motion()?;
            let e = m.end().to_array();
            let arc = match &c.value {
                Canon::ArcFeed(arc) => {
                    let n = 3 - a - b;
                    Some(([arc.centre[a], arc.centre[b]], arc.axis[n] > 0.0))
                }
                _ => None,
            };
            Some(Mv {
                n: c.block_number,
                end: [e[a], e[b]],
                arc,
                z: e[2],
            })
        })
        .collect()
}

fn moves(cmds: &[Spanned<Canon>]) -> Vec<Mv> {
    moves_in(cmds, 0, 1)
}

fn close(p: [f64; 2], q: [f64; 2]) -> bool {
    (p[0] - q[0]).abs() < TOL && (p[1] - q[1]).abs() < TOL
}

/// Expected path: (block, end point, arc centre for arcs (+ ccw)).
type Want = (u32, [f64; 2], Option<([f64; 2], bool)>);

#[track_caller]
fn assert_path(got: &[Mv], want: &[Want]) {
    let got: Vec<&Mv> = got.iter().filter(|m| m.n.is_some_and(|n| want.iter().any(|w| w.0 == n))).collect();
    let ok = got.len() == want.len()
        && got.iter().zip(want).all(|(g, w)| {
            g.n == Some(w.0)
                && close(g.end, w.1)
                && match (g.arc, w.2) {
                    (None, None) => true,
                    (Some((c, d)), Some((e, f))) => close(c, e) && d == f,
                    _ => false,
                }
        });
    assert!(ok, "\n got {:#?}\nwant {want:?}", got.iter().map(|m| (m.n, m.end, m.arc)).collect::<Vec<_>>());
}

const CW: bool = false;
const CCW: bool = true;

#[test]
fn example_9_3_entry_outer_corner_and_exit_removing_both_offsets() {
    let m = moves(&ok(&fixture("s9_2_1-g41-select-and-cancel-example-9_3.nc"), 5.0));
    assert_path(
        &m,
        &[
            (2, [-5.0, 10.0], None),
            (3, [0.0, 15.0], Some(([0.0, 10.0], CW))),
            (3, [10.0, 15.0], None),
            (4, [15.0, 10.0], None),
        ],
    );
}

#[test]
fn example_9_4_oblique_entry_inner_corner() {
    let m = moves(&ok(&fixture("s9_2_1-g41-entry-from-outside-point-example-9_4.nc"), 5.0));
    let y = 5.0 * (5f64.sqrt() - 1.0) / 2.0;
    assert!((y - 3.0902).abs() < 1e-4);
    assert_path(
        &m,
        &[
            (2, [-10.0, -5.0], None),
            (3, [-5.0, y], None),
            (4, [-5.0, 10.0], None),
            (5, [0.0, 15.0], Some(([0.0, 10.0], CW))),
            (5, [10.0, 15.0], None),
            (6, [15.0, 10.0], None),
        ],
    );
}

#[test]
fn example_9_6_square_with_oblique_entry_and_exit() {
    let m = moves(&ok(&fixture("s9_2_1-g41-square-contour-example-9_6.nc"), 5.0));
    let t = 5.0 * (22.5f64).to_radians().tan();
    assert!((t - 2.0711).abs() < 1e-4);
    assert_path(
        &m,
        &[
            (2, [-5.0, t], None),
            (3, [-5.0, 100.0], None),
            (4, [0.0, 105.0], Some(([0.0, 100.0], CW))),
            (4, [100.0, 105.0], None),
            (5, [105.0, 100.0], Some(([100.0, 100.0], CW))),
            (5, [105.0, 0.0], None),
            (6, [100.0, -5.0], Some(([100.0, 0.0], CW))),
            (6, [t, -5.0], None),
            (7, [-10.0, -10.0], None),
        ],
    );
}

#[test]
fn example_9_9_z_move_inside_the_contour_and_g40_without_plane_motion() {
    let text = format!("T1 M06\n{}", fixture("s9_2_1-g41-cancel-with-z-move-example-9_9.nc"));
    let cmds = ok(&text, 5.0);
    let m = moves(&cmds);
    assert_path(
        &m,
        &[
            (1, [-5.0, 10.0], None),
            (2, [-5.0, 10.0], None),
            (3, [0.0, 15.0], Some(([0.0, 10.0], CW))),
            (3, [10.0, 15.0], None),
            (4, [15.0, 10.0], Some(([10.0, 10.0], CW))),
            (4, [15.0, 0.0], None),
            (5, [10.0, -5.0], Some(([10.0, 0.0], CW))),
            (5, [0.0, -5.0], None),
            (6, [-5.0, 0.0], Some(([0.0, 0.0], CW))),
            (6, [-5.0, 10.0], None),
            (7, [-5.0, 10.0], None),
            // A13: the exit reverses the direction: an outer corner with a 180° arc.
            (8, [5.0, 10.0], Some(([0.0, 10.0], CW))),
            (8, [0.0, 0.0], None),
        ],
    );
    // N2 runs at the entry's end point (Z−10); N7 at the end of N6 (Z10).
    let z: Vec<(Option<u32>, f64)> = m.iter().map(|m| (m.n, m.z)).collect();
    assert!(z.contains(&(Some(2), -10.0)) && z.contains(&(Some(7), 10.0)));
    // Every command keeps its block's order: the commands of N2 come before those of N3.
    let lines: Vec<u32> = cmds.iter().filter_map(|c| c.block_number).collect();
    assert!(lines.windows(2).all(|w| w[0] <= w[1]), "{lines:?}");
}

#[test]
fn example_9_8_g143_and_g40_per_axis() {
    let text = format!("T1 M06\n{}", fixture("s9_2_1-g143-cancel-by-g40-per-axis-example-9_8.nc"));
    let m = moves(&ok(&text, 5.0));
    assert_path(
        &m,
        &[(1, [5.0, 0.0], None), (2, [5.0, 15.0], None), (3, [5.0, 15.0], None), (5, [5.0, 10.0], None), (6, [10.0, 10.0], None)],
    );
    assert!(m.iter().any(|m| m.n == Some(3) && (m.z + 10.0).abs() < TOL));
}

#[test]
fn example_9_10_g143_g144_square() {
    let m = moves(&ok(&fixture("s9_2_1-g143-g144-square-outside-example-9_10.nc"), 5.0));
    let want: Vec<Want> = [
        (2, [-20.0, 0.0]),
        (3, [-5.0, 0.0]),
        (4, [-5.0, 55.0]),
        (5, [55.0, 55.0]),
        (6, [55.0, -5.0]),
        (7, [-5.0, -5.0]),
        (8, [-5.0, 0.0]),
        (9, [-20.0, 0.0]),
    ]
    .iter()
    .map(|&(n, p)| (n, p, None))
    .collect();
    assert_path(&m, &want);
}

#[test]
fn example_9_11_g143_then_g42_full_circle() {
    let m = moves(&ok(&fixture("s9_2_1-g143-g42-full-circle-inside-example-9_11.nc"), 5.0));
    assert_path(
        &m,
        &[
            (20, [0.0, 45.0], None),
            (30, [0.0, 45.0], Some(([0.0, 0.0], CW))),
            (50, [0.0, 0.0], None),
        ],
    );
}

#[test]
fn example_9_12_incremental_bore_three_depths() {
    let m = moves(&ok(&fixture("s9_2_1-g143-g41-incremental-bore-example-9_12.nc"), 5.0));
    for (k, base) in [0u32, 100, 200].into_iter().enumerate() {
        let z = -2.0 * k as f64;
        assert_path(
            &m,
            &[
                (base + 10, [0.0, 10.0], None),
                (base + 20, [0.0, 10.0], Some(([0.0, 0.0], CCW))),
                (base + 40, [0.0, 0.0], None),
                (base + 50, [0.0, 0.0], None),
            ],
        );
        let circle = m.iter().find(|m| m.n == Some(base + 20)).unwrap();
        assert!((circle.z - z).abs() < TOL);
    }
    let last = m.last().unwrap();
    assert!((last.z + 6.0).abs() < TOL);
}

#[test]
fn example_9_13_g143_then_g41_rectangle_incremental() {
    let m = moves(&ok(&fixture("s9_2_1-g143-g41-rectangle-incremental-example-9_13.nc"), 5.0));
    assert_path(
        &m,
        &[
            (20, [-5.0, 0.0], None),
            (21, [-5.0, 25.0], None),
            (22, [0.0, 30.0], Some(([0.0, 25.0], CW))),
            (22, [50.0, 30.0], None),
            (23, [55.0, 25.0], Some(([50.0, 25.0], CW))),
            (23, [55.0, -25.0], None),
            (24, [50.0, -30.0], Some(([50.0, -25.0], CW))),
            (24, [0.0, -30.0], None),
            (25, [-5.0, -25.0], Some(([0.0, -25.0], CW))),
            (25, [-5.0, 0.0], None),
            (27, [-20.0, 0.0], None),
        ],
    );
}

#[test]
fn unlabelled_example_tangential_arc_approach_g42_in_a_block_without_motion() {
    let m = moves(&ok(&fixture("s9_2_1-g143-g42-tangential-arc-approach-unlabelled-example.nc"), 6.0));
    assert_path(
        &m,
        &[
            (4, [46.0, 12.0], None),
            (6, [40.0, 6.0], Some(([40.0, 12.0], CW))),
            (7, [6.0, 6.0], None),
            (8, [6.0, 54.0], None),
            (9, [94.0, 54.0], None),
            (10, [94.0, 6.0], None),
            (11, [40.0, 6.0], None),
            (12, [34.0, 12.0], Some(([40.0, 12.0], CW))),
            (14, [34.0, 12.0], None),
        ],
    );
}
