//! Mazatrol circles in tool tip point control (M-series, spec mazatrol §7.4, table 2 note 3):
//! G02/G03 are accepted only under G43.4 (type 1) with the workpiece programming frame (F85 bit
//! 2 = 1, `[kinematics] ttpc_frame = "workpiece"`); otherwise they stay
//! `mazatrol::code-not-allowed-in-ttpc` (mazatrol.rs). No rotary word may ride on the arc
//! (`mazatrol::rotary-word-in-arc`): the table pose r is constant through the block.
//!
//! Geometry: start S (the tip's current W position), end E (X Y Z after G90/G91) and centre
//! C = S + (I, J, K) in the G17/G18/G19 plane, all in W; |S − C| and |E − C| must agree within
//! 0.01 mm (`mazatrol::arc-radius`). With r constant, W → table frame is the rigid map
//! x ↦ G(r)⁻¹·(x + w) − w, so the arc stays an arc: its start, end and centre map as points and
//! its axis (± the plane normal, + for G03) by the rotation alone. Canon gets that arc in machine
//! coordinates of the table frame, which is what the kin stage follows under TCP.

use crate::ctx::Ctx;
use stanok_canon::{ArcMove, Canon, Diagnostic, Pose};
use stanok_kin::FiveAxis;
use stanok_syntax::ColSpan;

/// Start/end radius agreement, mm.
const RADIUS_TOLERANCE: f64 = 0.01;

/// A G02/G03 block in TTPC type 1 with the workpiece frame.
pub(crate) fn arc(
    cx: &mut Ctx<'_>,
    base: &FiveAxis,
    ccw: bool,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    for l in [b'A', b'B', b'C'] {
        if let Some(w) = cx.words.peek(l) {
            return Err(cx.err(
                "mazatrol::rotary-word-in-arc",
                format!(
                    "{} cannot be commanded in circular interpolation under tool tip point control",
                    l as char
                ),
                w.span,
            ));
        }
    }
    let offsets = [b'I', b'J', b'K'].map(|l| cx.words.take(l).map_or(0.0, |w| cx.mm(w.v)));
    let table = cx.st.position;
    // The tip's current W position in machine coordinates (x + w), and the program's.
    let start_m = base.table_at(&table, table.xyz());
    cx.st.position = table.with_xyz(start_m);
    let start_p = cx.st.program_position();
    let r = cx.end_point();
    cx.st.position = table;
    let (end_p, _) = r?;
    let plane = cx.st.plane;
    let (a, b, n) = plane.axes();
    let s = start_p.xyz();
    let e = end_p.xyz();
    let mut c = s;
    for i in 0..3 {
        c[i] += offsets[i];
    }
    let r1 = ((s[a] - c[a]).powi(2) + (s[b] - c[b]).powi(2)).sqrt();
    let r2 = ((e[a] - c[a]).powi(2) + (e[b] - c[b]).powi(2)).sqrt();
    if r1 < 1e-9 || (r1 - r2).abs() > RADIUS_TOLERANCE {
        return Err(cx.err(
            "mazatrol::arc-radius",
            format!("the start radius {r1:.4} and the end radius {r2:.4} differ"),
            at,
        ));
    }
    let feed = cx.st.feed;
    if feed <= 0.0 {
        return Err(cx.err("mazatrol::feed-missing", "feed move with F = 0", at));
    }
    // W (program) → machine W → table frame (machine coordinates at zero table pose).
    let end_pose = Pose::from_array({
        let mut v = end_p.to_array();
        v[3..6].copy_from_slice(&table.to_array()[3..6]);
        v
    });
    let to_table = |p: Pose| {
        let m = cx.st.frame.to_machine(&p);
        m.with_xyz(base.table_home(&table, m.xyz()))
    };
    let end_t = to_table(end_pose);
    let centre_t = to_table(end_pose.with_xyz(c)).xyz();
    let mut normal = [0.0; 3];
    normal[n] = if ccw { 1.0 } else { -1.0 };
    let o = base.table_home(&table, [0.0; 3]);
    let h = base.table_home(&table, normal);
    let axis = [h[0] - o[0], h[1] - o[1], h[2] - o[2]];
    cx.out.push(Canon::ArcFeed(ArcMove {
        start: table,
        end: end_t,
        centre: centre_t,
        axis,
        turns: 1,
        plane,
        feed,
    }));
    cx.st.position = end_t;
    Ok(())
}
