//! The two example jobs of `examples/`, run end to end through the core driver, against the
//! hand-computed numbers in their headers.

mod common;
use common::*;

const M_JOB: &str = include_str!("/work/mazatrol/examples/mazak-m-job.eia");
const T_JOB: &str = include_str!("/work/mazatrol/examples/mazak-t-job.eia");

fn line_of(text: &str, prefix: &str) -> u32 {
    text.lines()
        .position(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("{prefix}")) as u32
        + 1
}

#[test]
fn the_m_series_job() {
    let r = run(M_JOB, &mazak_m());
    r.ok();
    let kin = mazak_m().opts.five_axis.unwrap();
    let at = |p: &str| {
        r.joints_at_line(line_of(M_JOB, p), &kin)
            .unwrap_or_else(|| panic!("{p}"))
    };
    near(at("N14 "), [105.0, 70.0, -30.0, 0.0, 0.0]);
    // G28 moves Z only: X Y stay over the last bolt-circle hole (112.990381, 42.5).
    near(at("N22 "), [212.990381, 92.5, 0.0, 0.0, 0.0]);
    near(at("N25 "), [100.0, 50.0, 0.0, 0.0, 0.0]);
    near(at("N31 "), [100.0, 50.0, -50.0, 0.0, 0.0]);
    near(at("N32 "), [100.0, 50.0, -75.0, 0.0, 0.0]);
    near(at("N33 "), [275.0, 50.0, -111.173141, 30.0, 0.0]);
    near(at("N34 "), [315.0, 50.0, -111.173141, 30.0, 0.0]);
    near(at("N35 "), [180.0, 50.0, -75.0, 0.0, 0.0]);
    near(at("N36 "), [180.0, 50.0, 70.0, 0.0, 0.0]);
    near(at("N37 "), [180.0, 50.0, -50.0, 0.0, 0.0]);
    // N33 halfway: the tip at work X20 Z5 with B15 (the kin stage interpolates the tip linearly).
    {
        use stanok_kin::Kinematics;
        let mid = stanok_canon::Pose {
            x: 120.0,
            y: 50.0,
            z: -195.0,
            b: 15.0,
            ..stanok_canon::Pose::ZERO
        };
        let j = kin
            .clone()
            .with_tool_offset([0.0, 0.0, 120.0])
            .inverse(&mid)
            .unwrap();
        near(
            stanok_canon::Pose::from_array(j),
            [189.881142, 50.0, -84.200027, 15.0, 0.0],
        );
    }
    // The holes: every feed move down to machine Z -60 (work Z -10) ends at a hole's bottom.
    let bottoms: Vec<(f64, f64)> = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            stanok_canon::Canon::StraightFeed(m) if (m.end.z + 60.0).abs() < 1e-9 => {
                Some((m.end.x - 100.0, m.end.y - 50.0))
            }
            _ => None,
        })
        .collect();
    let mut want: Vec<(f64, f64)> = Vec::new();
    for y in [20.0, 35.0, 50.0] {
        for x in [20.0, 35.0, 50.0, 65.0] {
            want.push((x, y));
        }
    }
    for (x, y) in [
        (100.0, 50.0),
        (87.009619, 42.5),
        (87.009619, 27.5),
        (100.0, 20.0),
        (112.990381, 27.5),
        (112.990381, 42.5),
    ] {
        want.push((x, y));
    }
    assert_eq!(bottoms.len(), 18, "{bottoms:?}");
    for (g, w) in bottoms.iter().zip(&want) {
        assert!(
            (g.0 - w.0).abs() < 1e-6 && (g.1 - w.1).abs() < 1e-6,
            "{g:?} {w:?}"
        );
    }
    // Each hole is 13 mm of feed from R3 to Z-10.
    let drilling: f64 = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            stanok_canon::Canon::StraightFeed(m) if (m.end.z + 60.0).abs() < 1e-9 => {
                Some(m.start.z - m.end.z)
            }
            _ => None,
        })
        .sum();
    assert!((drilling - 18.0 * 13.0).abs() < 1e-9, "{drilling}");
    // Spindle and coolant.
    use stanok_canon::Canon;
    let speeds: Vec<f64> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::SetSpindleSpeed { rpm, .. } => Some(rpm),
            _ => None,
        })
        .collect();
    assert_eq!(speeds, vec![2000.0, 6000.0]);
    assert!(r.canon.iter().any(|c| c.value == Canon::Flood { on: true }));
    assert!(matches!(r.canon.last().unwrap().value, Canon::ProgramEnd));
}

#[test]
fn the_t_series_job() {
    let r = run(T_JOB, &mazak_t());
    r.ok();
    let kin = mazak_t().opts.five_axis.unwrap();
    let line = |p: &str| line_of(T_JOB, p);
    let at = |p: &str| {
        r.joints_at_line(line(p), &kin)
            .unwrap_or_else(|| panic!("{p}"))
    };
    use stanok_canon::Canon;
    // N13: A = R31 Z2 → machine X = 31 + 20 (offset X), Z = 2 + 200 + 80.
    near(at("N13 "), [51.0, 0.0, 282.0, 0.0, 0.0]);
    // G71: the seven level cuts (feed along -Z at the level), machine X = level + 20.
    let n15 = line("N15 ");
    let cuts: Vec<(f64, f64)> = r
        .canon
        .iter()
        .filter(|c| c.span.line == n15)
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m)
                if (m.start.x - m.end.x).abs() < 1e-12 && m.end.z < m.start.z =>
            {
                Some((m.end.x - 20.0, m.end.z - 280.0))
            }
            _ => None,
        })
        .collect();
    let want = [
        (29.0, -44.9),
        (27.0, -44.9),
        (25.0, -44.895998),
        (23.0, -44.389989),
        (21.0, -42.612932),
        (19.0, -23.7),
        (17.0, -21.7),
    ];
    assert!(cuts.len() >= 7, "{cuts:?}");
    for (g, w) in cuts.iter().zip(want) {
        assert!(
            (g.0 - w.0).abs() < 1e-6 && (g.1 - w.1).abs() < 1e-6,
            "{g:?} {w:?}"
        );
    }
    // G71's feed: 281.098919 + 4.949747 + 70.925049.
    let feed_of = |line: u32| -> f64 {
        let mut t = 0.0;
        for c in r.canon.iter().filter(|c| c.span.line == line) {
            match &c.value {
                Canon::StraightFeed(m) => {
                    t += ((m.end.x - m.start.x).powi(2) + (m.end.z - m.start.z).powi(2)).sqrt()
                }
                Canon::ArcFeed(a) => {
                    t += stanok_geom::Helix {
                        start: a.start.xyz(),
                        end: a.end.xyz(),
                        centre: a.centre,
                        axis: a.axis,
                        turns: a.turns,
                    }
                    .length()
                }
                _ => {}
            }
        }
        t
    };
    let g71 = feed_of(n15);
    assert!(
        (g71 - (281.098919 + 4.949747 + 70.925049)).abs() < 1e-5,
        "{g71}"
    );
    // G70: the profile blocks run (their own lines), then back to A.
    let g70: f64 = (line("N20 ")..=line("N26 ")).map(feed_of).sum();
    assert!((g70 - 70.925049).abs() < 1e-5, "{g70}");
    near(at("N30 "), [51.0, 0.0, 282.0, 0.0, 0.0]);
    // G96 S200 at X62: 1026.806 rpm.
    let rpm = r.canon.iter().find_map(|c| match c.value {
        Canon::SetSpindleSpeed { spindle: 0, rpm } if c.span.line == line("N13 ") => Some(rpm),
        _ => None,
    });
    assert!(rpm.is_some_and(|v| (v - 1026.806).abs() < 1e-3), "{rpm:?}");
    // G12.1: the square's corner X20 C10 = R14.142136 C45; the last block ends at C360.
    near(at("N46 "), [200f64.sqrt(), 0.0, 300.0 - 2.0, 0.0, 45.0]);
    near(at("N50 "), [10.0, 0.0, 298.0, 0.0, 360.0]);
    // TTPC.
    near(at("N63 "), [272.132034, 0.0, 222.132034, 45.0, 0.0]);
    near(at("N64 "), [272.132034, 0.0, 202.132034, 45.0, 0.0]);
    near(at("N65 "), [212.132034, 60.0, 202.132034, 45.0, 90.0]);
    near(at("N66 "), [212.132034, 60.0, 262.132034, 45.0, 90.0]);
    near(at("N67 "), [141.421356, 60.0, 191.421356, 45.0, 90.0]);
}
