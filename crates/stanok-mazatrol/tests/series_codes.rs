//! Codes of one series with hand-computed numbers (`docs/dialects/mazatrol-eia.md` §4.3, §6.1,
//! §7.8, §7.9, §7.11, §12.3): W/U incremental on the T-series, the T-series G68 facing-turret
//! mirror, G92.5 work-system rotation (M), G53.5/G52.5 (T), G122/G123 polar input, G16 (T).
//!
//! `mazak_t()`: G54 = machine Z200, X on the radius in the machine, a diameter in the program
//! (G123.1 at power-on); `mill()`: no offsets.

mod common;
use common::*;
use stanok_canon::Canon;

fn xyz_c(r: &Run) -> Vec<[f64; 4]> {
    r.ends().iter().map(|p| [p.x, p.y, p.z, p.c]).collect()
}

fn close(got: &[[f64; 4]], want: &[[f64; 4]]) {
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            g.iter().zip(w).all(|(a, b)| (a - b).abs() < 1e-9),
            "got {got:?}, want {want:?}"
        );
    }
}

#[test]
fn u_and_w_are_increments_on_the_t_series() {
    // X40 (diameter) → radius 20; W−5: Z 10 − 5 = 5 → machine 205; U10 (diameter) → radius 25.
    let r = run("G94 G00 X40. Z10.\nW-5.\nU10.\n", &mazak_t());
    r.ok();
    close(
        &xyz_c(&r),
        &[
            [20.0, 0.0, 210.0, 0.0],
            [20.0, 0.0, 205.0, 0.0],
            [25.0, 0.0, 205.0, 0.0],
        ],
    );
}

#[test]
fn g68_on_the_t_series_mirrors_x_and_exchanges_g02_and_g03() {
    let r = run("G94 G68\nG00 X40. Z10.\nG69\nG00 X40.\n", &mazak_t());
    r.ok();
    close(
        &xyz_c(&r),
        &[[-20.0, 0.0, 210.0, 0.0], [20.0, 0.0, 210.0, 0.0]],
    );
    // The same G02 in G18 turns the other way under G68: its axis flips.
    let r = run(
        "G94 G00 X0 Z0\nG02 X20. Z-10. R10. F100.\nG68\nG00 X0 Z0\nG02 X20. Z-10. R10.\n",
        &mazak_t(),
    );
    r.ok();
    let axes: Vec<[f64; 3]> = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(a.axis),
            _ => None,
        })
        .collect();
    assert_eq!(axes.len(), 2);
    assert!(
        (axes[0][1] + 1.0).abs() < 1e-12 && (axes[1][1] - 1.0).abs() < 1e-12,
        "{axes:?}"
    );
}

#[test]
fn g92_5_rotates_the_work_system_on_the_m_series() {
    // R90 about the origin: X10 Y0 → (0, 10); G92.5 R0 cancels.
    let r = run(
        "G92.5 X0 Y0 R90.\nG00 X10. Y0\nG92.5 R0\nG00 X10. Y0\n",
        &mill(),
    );
    r.ok();
    close(&xyz_c(&r), &[[0.0, 10.0, 0.0, 0.0], [10.0, 0.0, 0.0, 0.0]]);
}

#[test]
fn g53_5_and_g52_5_switch_to_the_mazatrol_origin_and_back() {
    let mut t = mazak_t();
    t.params.mazatrol_wpc = Some([0.0, 0.0, 300.0]);
    let r = run("G53.5\nG00 Z10.\nG52.5\nG00 Z10.\n", &t);
    r.ok();
    close(
        &xyz_c(&r),
        &[[0.0, 0.0, 310.0, 0.0], [0.0, 0.0, 210.0, 0.0]],
    );
}

/// Regression: G122's radius and angle words were read a second time as positions, so polar
/// input did nothing (the X word of a G18 angle also arrived halved as a diameter).
#[test]
fn g122_polar_input_reads_radius_and_angle() {
    let t = mazak_t();
    // G17: X radius 20, Y angle 90 → X 0, Y 20; after G123, X20 is a diameter again → radius 10.
    let r = run("G94 G17 G122\nG00 X20. Y90.\nG123\nG00 X20. Y0\n", &t);
    r.ok();
    close(&xyz_c(&r), &[[0.0, 20.0, 0.0, 0.0], [10.0, 0.0, 0.0, 0.0]]);
    // G18 (power-on on T): Z radius 10, X angle 90 → Z 0 (machine 200), X radius 10.
    let r = run("G122\nG00 Z10. X90.\n", &t);
    r.ok();
    close(&xyz_c(&r), &[[10.0, 0.0, 200.0, 0.0]]);
    // G91: the radius and angle add to the current ones: (r 10, 90°) + (r 5, −90°) → X 15, Y 0.
    let r = run("G94 G17 G122\nG00 X10. Y90.\nG91 G00 X5. Y-90.\n", &t);
    r.ok();
    close(&xyz_c(&r), &[[0.0, 10.0, 0.0, 0.0], [15.0, 0.0, 0.0, 0.0]]);
    // The M-series has no G122.
    let e = run("G122\n", &mill()).error.unwrap();
    assert_eq!(
        e.message,
        "G122 is not a G code of the M-series (table 12.2)"
    );
}

#[test]
fn g16_selects_the_z_c_plane_on_the_t_series() {
    // #4002 reads the plane code: 16.
    let r = run(
        "G94 G16\nG00 Z10. C90.\n#1 = #4002\nG18\nG00 Z#1\n",
        &mazak_t(),
    );
    r.ok();
    close(
        &xyz_c(&r),
        &[[0.0, 0.0, 210.0, 90.0], [0.0, 0.0, 216.0, 90.0]],
    );
}
