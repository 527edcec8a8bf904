//! AxiOMA G75 probe moves and M910/M911 batch mode (spec axioma-2 §2.5) on the s5_5 fixtures:
//! the probe moves as Canon `StraightProbe`, trip points from the configured probe surfaces, the
//! latch and the next block starting from it, error 617. Positions to 1e-9 mm.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::setup::ProbeSurface;
use stanok_canon::{Canon, Spanned};
use stanok_interp::{InterpOptions, Interpreter, ProbeLatch};
use stanok_syntax::Dialect;

fn program(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// (N, kind, end XYZ, contact XYZ, feed) of every motion.
type Mv = (Option<u32>, &'static str, [f64; 3], Option<[f64; 3]>, f64);

fn motions(cmds: &[Spanned<Canon>]) -> Vec<Mv> {
    cmds.iter()
        .filter_map(|c| {
            let n = c.block_number;
            Some(match &c.value {
                Canon::StraightTraverse(m) => (n, "rapid", m.end.xyz(), None, m.feed),
                Canon::StraightFeed(m) => (n, "feed", m.end.xyz(), None, m.feed),
                Canon::StraightProbe {
                    motion, contact, ..
                } => (
                    n,
                    "probe",
                    motion.end.xyz(),
                    contact.as_ref().map(|p| p.xyz()),
                    motion.feed,
                ),
                _ => return None,
            })
        })
        .collect()
}

struct Done {
    latch: Option<ProbeLatch>,
    m_vector: Vec<(String, u32)>,
}

impl Done {
    fn axioma_probe_latch(&self) -> Option<ProbeLatch> {
        self.latch
    }
    fn axioma_m_vector(&self) -> Vec<(String, u32)> {
        self.m_vector.clone()
    }
}

fn run_ok(text: &str, o: InterpOptions) -> (Vec<Spanned<Canon>>, Done) {
    let mut it = Interpreter::from_text(text, o);
    let cmds: Vec<_> = it.by_ref().map(|c| c.unwrap()).collect();
    let done = Done {
        latch: it.axioma_probe_latch(),
        m_vector: it.axioma_m_vector(),
    };
    (cmds, done)
}

#[test]
fn s5_5_example_5_19_without_a_trigger() {
    let (cmds, it) = run_ok(
        &program("s5_5-probe-g75-example-5_19.nc"),
        options(Dialect::Axioma),
    );
    assert_eq!(
        motions(&cmds),
        [
            (Some(10), "rapid", [0.0, 20.0, 0.0], None, 0.0),
            (Some(20), "probe", [200.0, 20.0, 0.0], None, 100.0),
            // G75 is modal: N30 is a probe move too.
            (Some(30), "probe", [250.0, 50.0, 0.0], None, 100.0),
            (Some(40), "feed", [300.0, 100.0, 0.0], None, 1000.0),
        ]
    );
    let latch = it.axioma_probe_latch().unwrap();
    assert!(!latch.triggered);
    assert_eq!(latch.position.xyz(), [250.0, 50.0, 0.0]);
}

#[test]
fn s5_5_example_5_19_with_a_workpiece_edge() {
    // A wall at X = 120: N20 trips there; N30 starts from the latch (already in contact, it
    // does not trip again) and N40 runs from N30's end.
    let mut o = options(Dialect::Axioma);
    o.control.probe_surfaces = vec![ProbeSurface {
        axis: 0,
        at_or_below: false,
        value: 120.0,
    }];
    let (cmds, it) = run_ok(&program("s5_5-probe-g75-example-5_19.nc"), o);
    let m = motions(&cmds);
    assert_eq!(
        m[1],
        (
            Some(20),
            "probe",
            [200.0, 20.0, 0.0],
            Some([120.0, 20.0, 0.0]),
            100.0
        )
    );
    let n30 = cmds
        .iter()
        .find_map(|c| match &c.value {
            Canon::StraightProbe { motion, .. } if c.block_number == Some(30) => {
                Some(motion.start.xyz())
            }
            _ => None,
        })
        .unwrap();
    assert_eq!(n30, [120.0, 20.0, 0.0]);
    assert_eq!(m[3].2, [300.0, 100.0, 0.0]);
    let latch = it.axioma_probe_latch().unwrap();
    assert!(
        !latch.triggered,
        "N30 starts in contact and never changes state"
    );
}

#[test]
fn s5_5_latch_is_in_machine_coordinates_without_offsets() {
    // Under a G54 offset of X+10 the probe surface at machine X = 50 latches machine X 50, and the
    // program continues from program X 40.
    let mut o = options(Dialect::Axioma);
    o.control.probe_surfaces = vec![ProbeSurface {
        axis: 0,
        at_or_below: false,
        value: 50.0,
    }];
    o.control.offsets.zero[0][0].offset.x = 10.0;
    let (cmds, it) = run_ok("G54 G90 F100\nG75 X100\nG91 G01 X5\n", o);
    let latch = it.axioma_probe_latch().unwrap();
    assert!(latch.triggered);
    assert_eq!(latch.position.xyz(), [50.0, 0.0, 0.0]);
    let last = motions(&cmds).last().copied().unwrap();
    assert_eq!(last.2, [55.0, 0.0, 0.0]);
}

#[test]
fn s5_5_batch_mode_monitors_feed_moves_between_m910_and_m911() {
    let (cmds, it) = run_ok(
        &program("s5_5-probe-batch-m910-m911-example-5_20.nc"),
        options(Dialect::Axioma),
    );
    let m = motions(&cmds);
    let kinds: Vec<(Option<u32>, &str, [f64; 3])> = m.iter().map(|v| (v.0, v.1, v.2)).collect();
    assert_eq!(
        kinds,
        [
            (Some(10), "rapid", [0.0, 0.0, 0.0]),
            // The M910 block is a rapid: not monitored (A19).
            (Some(10), "rapid", [0.0, 0.0, 20.0]),
            (Some(20), "probe", [10.0, 0.0, 20.0]),
            (Some(30), "probe", [-10.0, 0.0, 20.0]),
            (Some(40), "probe", [-10.0, 10.0, 20.0]),
            // M911 is postfix: N50's motion is still monitored.
            (Some(50), "probe", [-10.0, 10.0, 0.0]),
        ]
    );
    assert!(m[2..].iter().all(|v| v.4 == 300.0));
    assert_eq!(
        it.axioma_m_vector()
            .iter()
            .find(|(g, _)| g == "M_BatchProbe")
            .map(|v| v.1),
        Some(911)
    );
    // After M911 a G01 is a plain feed again.
    let (cmds, _) = run_ok("F100 M910\nG01 X1\nX2 M911\nX3\n", options(Dialect::Axioma));
    let kinds: Vec<&str> = motions(&cmds).iter().map(|v| v.1).collect();
    assert_eq!(kinds, ["probe", "probe", "feed"]);
}

#[test]
fn s5_5_fragments_and_errors() {
    let (cmds, _) = run_ok(
        &program("s5_5-probe-g75-fragment.nc"),
        options(Dialect::Axioma),
    );
    assert_eq!(
        motions(&cmds),
        [(Some(20), "probe", [150.0, 200.0, 0.0], None, 1000.0)]
    );
    // The syntax line has no feed: refused like a G01 without F; with F it runs, I/J kept.
    let text = program("s5_5-probe-g75-syntax-example.nc");
    let (_, err) = run(&text, Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "axioma::feed-missing");
    let (cmds, it) = run_ok(&format!("F50\n{text}"), options(Dialect::Axioma));
    assert_eq!(motions(&cmds)[0].2, [-1.0, -1.0, 0.0]);
    assert_eq!(
        it.axioma_probe_latch().unwrap().ijk,
        [Some(5.0), Some(5.0), None]
    );
    // G93 with G75: error 617.
    let (_, err) = run("G93 F2\nG75 X10\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "E617");
}
