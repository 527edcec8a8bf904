//! Metamorphic laws of AxiOMA (issue 22): with no reference implementation to diff against, one
//! path written in different notations must give the same motion, and a frame function wrapped
//! around a program must move its whole motion by exactly that transform. Generated programs
//! (`metamorphic/mod.rs`: lines, rapid moves, arcs in the three forms, polar lines, G70/G71, G10)
//! on a grid where every form is exact, compared motion by motion (ends, arc centres, arc sense)
//! to 1e-9 mm. 500 programs per law by default; `STANOK_METAMORPHIC_CASES=10000` for a local run.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
mod metamorphic;

use metamorphic::*;
use proptest::prelude::*;

fn base(segs: &[Seg]) -> Result<Vec<Mv>, TestCaseError> {
    let want = motions(&program(segs, Form::BASE, ""), options())
        .map_err(|d| TestCaseError::fail(format!("base program refused: {d}")))?;
    // The stream compared is the path itself, not an empty one.
    prop_assert_eq!(want.len(), segs.len(), "one motion per segment");
    Ok(want)
}

fn run(segs: &[Seg], form: Form, header: &str) -> Result<Vec<Mv>, TestCaseError> {
    let text = program(segs, form, header);
    motions(&text, options()).map_err(|d| TestCaseError::fail(format!("{d}\nin:\n{text}")))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    /// G90 and G91 write the same path.
    #[test]
    fn absolute_and_incremental_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        let got = run(&segs, Form { incremental: true, ..Form::BASE }, "")?;
        same(&want, &got)?;
    }

    /// I J, R and CR= write the same arcs.
    #[test]
    fn ijk_r_and_cr_arcs_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        for arc in [1, 2] {
            same(&want, &run(&segs, Form { arc, ..Form::BASE }, "")?)?;
            same(&want, &run(&segs, Form { arc, incremental: true, ..Form::BASE }, "")?)?;
        }
    }

    /// G70 (inches) and G71 (mm) write the same path.
    #[test]
    fn inches_and_millimetres_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        for form in [
            Form { inches: true, ..Form::BASE },
            Form { inches: true, incremental: true, arc: 2, ..Form::BASE },
        ] {
            same(&want, &run(&segs, form, "")?)?;
        }
    }

    /// G10 X1 diameter programming equals its radius rewrite.
    #[test]
    fn diameter_programs_equal_their_radius_rewrite(segs in path()) {
        let want = base(&segs)?;
        for form in [
            Form { diameter: true, ..Form::BASE },
            Form { diameter: true, incremental: true, ..Form::BASE },
            Form { diameter: true, arc: 1, ..Form::BASE },
        ] {
            same(&want, &run(&segs, form, "")?)?;
        }
    }

    /// Lines in polar coordinates (pole at the origin) equal their Cartesian form.
    #[test]
    fn polar_and_cartesian_lines_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        same(&want, &run(&segs, Form { polar: true, ..Form::BASE }, "")?)?;
        same(&want, &run(&segs, Form { polar: true, arc: 2, inches: true, ..Form::BASE }, "")?)?;
    }

    /// A G54 page shifts the whole path by its offset.
    #[test]
    fn a_zero_offset_shifts_the_path(segs in path(), page in 1u8..=32,
                                     ox in -200i32..200, oy in -200i32..200, oz in -50i32..50) {
        let want = base(&segs)?;
        let mut opts = options();
        let off = [ox as f64 * 0.5, oy as f64 * 0.25, oz as f64];
        let e = &mut opts.control.offsets.zero[0][page as usize - 1].offset;
        (e.x, e.y, e.z) = (off[0], off[1], off[2]);
        let text = program(&segs, Form::BASE, &format!("G54 P{page}\n"));
        let got = motions(&text, opts).map_err(|d| TestCaseError::fail(format!("{d}\n{text}")))?;
        assert_transformed(&want, &got, &Transform {
            point: &|p| [p[0] + off[0], p[1] + off[1], p[2] + off[2]],
            flips: false,
        })?;
    }

    /// G273 rotates the whole path about the pole (the origin).
    #[test]
    fn a_rotation_rotates_the_path(segs in path(), tenths in -3600i32..3600) {
        let want = base(&segs)?;
        let q = tenths as f64 / 10.0;
        let got = run(&segs, Form::BASE, &format!("G273 Q{q} I0 J0\n"))?;
        let (s, c) = q.to_radians().sin_cos();
        assert_transformed(&want, &got, &Transform {
            point: &|p| [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]],
            flips: false,
        })?;
    }

    /// G173 P scales the whole path about the pole (the origin), Z included.
    #[test]
    fn a_scale_scales_the_path(segs in path(), k in 1u32..40) {
        let want = base(&segs)?;
        let f = k as f64 * 0.125;
        let got = run(&segs, Form::BASE, &format!("G173 P{f} I0 J0 K0\n"))?;
        assert_transformed(&want, &got, &Transform {
            point: &|p| [f * p[0], f * p[1], f * p[2]],
            flips: false,
        })?;
    }

    /// G73 mirrors the path about the pole and reverses the arcs' sense.
    #[test]
    fn a_mirror_mirrors_the_path_and_reverses_arcs(segs in path(), in_x in any::<bool>()) {
        let want = base(&segs)?;
        let (word, sx, sy) = if in_x { ("X-1", -1.0, 1.0) } else { ("Y-1", 1.0, -1.0) };
        let got = run(&segs, Form::BASE, &format!("G73 {word} I0 J0\n"))?;
        assert_transformed(&want, &got, &Transform {
            point: &|p| [sx * p[0], sy * p[1], p[2]],
            flips: true,
        })?;
    }
}
