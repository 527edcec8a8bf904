//! End points (`docs/dialects/mazatrol-eia.md` §4.3, §12.3): a block's axis words to a program
//! position — G90/G91, U V W as the T-series' X Y Z increments, G122 polar input (radius and
//! angle about the work origin).

use crate::ctx::Ctx;
use stanok_canon::{Diagnostic, Pose};
use stanok_interp_core::{is_linear, DistanceMode};

pub(crate) const AXES: [u8; 6] = [b'X', b'Y', b'Z', b'A', b'B', b'C'];

/// The end point of the block's axis words (program coordinates, mm/deg) and which axes were
/// given: G90/G91, U V W as X Y Z increments on the T-series, G122 polar input.
pub(crate) fn end_point(cx: &mut Ctx<'_>) -> Result<(Pose, [bool; 9]), Diagnostic> {
    let mut p = cx.st.program_position().to_array();
    if let Some(q) = crate::compensate::programmed_point(cx) {
        let (a, b, _) = cx.st.plane.axes();
        p[a] = q[0];
        p[b] = q[1];
    }
    let inc = cx.st.distance == DistanceMode::Incremental;
    let mut given = [false; 9];
    // The plane's two words G122 read as radius and angle (`Words::take` marks a word used but
    // keeps it, so the loop below must not read them again as positions).
    let mut polar_words = [false; 6];
    if cx.fe.m.polar_input && cx.fe.m.t() {
        polar_words = polar_input(cx, &mut p, &mut given, inc)?;
    }
    for (i, &l) in AXES.iter().enumerate() {
        if polar_words[i] {
            continue;
        }
        let Some(val) = cx.words.take(l) else {
            continue;
        };
        if !cx.opts.axes[i] {
            return Err(cx.err(
                "interp::axis-not-configured",
                format!("{} axis is not configured on this machine", l as char),
                val.span,
            ));
        }
        let v = if is_linear(i) { cx.mm(val.v) } else { val.v };
        p[i] = if inc { p[i] + v } else { v };
        given[i] = true;
    }
    let incs: [u8; 3] = [b'U', b'V', b'W'];
    for (i, &l) in incs.iter().enumerate() {
        let Some(val) = cx.words.peek(l) else {
            continue;
        };
        if cx.fe.m.t() {
            cx.words.take(l);
            if given[i] {
                return Err(cx.err(
                    "mazatrol::repeated-word",
                    format!(
                        "{} and {} both command {}",
                        AXES[i] as char, l as char, AXES[i] as char
                    ),
                    val.span,
                ));
            }
            p[i] += cx.mm(val.v);
            given[i] = true;
        } else if cx.opts.axes[6 + i] {
            cx.words.take(l);
            let v = cx.mm(val.v);
            p[6 + i] = if inc { p[6 + i] + v } else { v };
            given[6 + i] = true;
        }
    }
    Ok((Pose::from_array(p), given))
}

/// G122 (T): the plane's first axis word is a radius, the second an angle (degrees). Returns the
/// axis words it read.
fn polar_input(
    cx: &mut Ctx<'_>,
    p: &mut [f64; 9],
    given: &mut [bool; 9],
    inc: bool,
) -> Result<[bool; 6], Diagnostic> {
    let (a, b, _) = cx.st.plane.axes();
    let (la, lb) = (AXES[a], AXES[b]);
    let r = cx.words.take(la);
    let t = cx.words.take(lb);
    if r.is_none() && t.is_none() {
        return Ok([false; 6]);
    }
    // An X word arrives halved when X is programmed as a diameter; neither G122's radius nor
    // its angle is a diameter.
    let diameter = cx.fe.m.t() && !cx.fe.m.x_radius;
    let t = t.map(|mut v| {
        if lb == b'X' && diameter {
            v.v *= 2.0;
        }
        v
    });
    let (r0, t0) = (p[a].hypot(p[b]), p[b].atan2(p[a]).to_degrees());
    // The radius word is on the radius (not a diameter), in program units.
    let rw = r.map(|v| {
        let mut x = cx.mm(v.v);
        if la == b'X' && diameter {
            x *= 2.0;
        }
        x
    });
    let (rr, tt) = if inc {
        (r0 + rw.unwrap_or(0.0), t0 + t.map_or(0.0, |v| v.v))
    } else {
        (rw.unwrap_or(r0), t.map_or(t0, |v| v.v))
    };
    p[a] = rr * tt.to_radians().cos();
    p[b] = rr * tt.to_radians().sin();
    given[a] = true;
    given[b] = true;
    let mut read = [false; 6];
    read[a] = true;
    read[b] = true;
    Ok(read)
}
