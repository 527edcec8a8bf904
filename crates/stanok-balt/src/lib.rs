//! # stanok-balt: the Balt-System CVU front end
//!
//! Balt-System NC: continuous 5-axis machining CVU=1 / CVU=0 (cvu-five-axis.md §3, §6).
//!
//! Built: `CVU=1` / `CVU=0`, G0/G1, G90/G91 (G91 moves X Y Z only; A B C are always absolute in
//! CVU=1, §6.3), X Y Z + A B C (rotary angles) and X Y Z + I J K (surface normal = tool axis from
//! the tip toward the spindle, normalised; rejected below length 1e-6), F, S, `T t.c` with M6, M3/
//! M4/M5, M0/M1/M2/M30, `(DIS,"text")`. The machine is the `[kinematics]` of the machine data —
//! with `fat = "…"` the manual's characterization line (`stanok_kin::from_fat`).
//!
//! * `CVU=1` (precondition: the tool along Z, §3) emits `SetToolCentrePoint` with c0 = L·e_z, L =
//!   the length of corrector c of the last `T t.c` (tool table entry c, its first edge; AMB-6), and
//!   re-expresses the position as the tip the axes hold: nothing moves (§6.1).
//! * In CVU=1 the tip follows the programmed line in part coordinates while the rotary axes move
//!   linearly (the kin stage turns every servo setpoint into machine axes); an IJK block's angles
//!   come from `FiveAxis::orient_least_travel` (both solutions, travel limits, least
//!   |Δθo| + |Δθi|; a singular pose keeps the free axis, §5.7–§5.8).
//! * `CVU=0` (the tool along Z again, AMB-11) switches back: the position is the machine axes
//!   again; nothing moves. Outside CVU the corrector's length is a 3-axis length offset along Z
//!   (§5.1), so a programmed Z means the tip before, during and after CVU=1.
//!
//! * `CVU=3` (positional machining in a tilted plane, §5.10, §6.8): tool-centre-point control as
//!   in CVU=1, and X Y Z are coordinates of the local frame `(LCS,1,X…,Y…,Z…,A…,B…,C…)`: part
//!   point P = o + R_L·p_local, with R_L the rotation the machine's rotary axes at the LCS angles
//!   give the tool (`FiveAxis::orientation_frame`, so local +Z is the tool axis once the axes stand
//!   at those angles). Omitted words and G91 act on the local coordinates. A block that moves
//!   rotary axes only follows `MOVST`: 1 (the default, decision) keeps the tip on the part as in
//!   CVU=1; 2 keeps the linear axes still (TCP is switched off for the block, so the machine axes
//!   move exactly as programmed) and the tip is then where forward kinematics puts it.
//!   `(LCS,0)` cancels the frame. Decision (the spec proposes otherwise): the frame maps X Y Z
//!   only while CVU=3 is on; under CVU=0 the words are the machine's linear axes.
//!
//! * The G and M codes, their groups and handlers (an M code's with its phase: before or after
//!   the block's motion): codes.rs (`code_table!`).
//!
//! * G02/G03 with R in the `(DPI,…)` plane: arc.rs.
//!
//! * Splines `(BSP …)`, G06 nodes, `(ESP)`: spline.rs.
//!
//! * The front end the driver calls (`stanok_interp_core::FrontEnd`): front.rs.
//!
//! Not built (refused with a diagnostic): E parameters. The codes the manual prohibits under CVU=1 (§3.3.1: G40–G42,
//! G60–G62, G20/G21, G72–G74, G81–G86, G89) are `balt::prohibited-in-cvu`.

mod arc;
pub mod codes;
mod front;
mod spline;

/// The core's pieces under the names the front end's files use.
mod ctx {
    /// A block's context with the Balt-System part.
    pub type Ctx<'a> = stanok_interp_core::Ctx<'a, crate::front::BaltPart>;
}
use stanok_interp_core::state;

pub use front::{Balt, BaltPart};
pub use spline::SplineBuffer;

use crate::codes::{Handler, MHandler, Phase};
use crate::ctx::Ctx;
use crate::state::{DistanceMode, MotionMode};
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_interp_core::words::Val;
use stanok_interp_core::Outcome;
use stanok_kin::{FiveAxis, Kinematics};
use stanok_syntax::{ColSpan, CommentKind, Keyword};

/// The Balt-System modal state (Copy: journalled with the block, restored when it fails).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BaltState {
    /// CVU=1 or CVU=3 is on (tool-centre-point control).
    pub cvu: bool,
    /// CVU=3: X Y Z are local-frame coordinates.
    pub cvu3: bool,
    /// MOVST=1 or 2; 0 = never set, which acts as 1.
    pub movst: u8,
    /// The local frame of `(LCS,1,…)`, until `(LCS,0)`.
    pub lcs: Option<Lcs>,
    /// CVU=3: the last programmed local X Y Z. Omitted words keep these, not the tip's actual
    /// local coordinates: after a MOVST=2 rotation the tip has left the programmed point, and the
    /// manual's square (§6.8, O5) goes on from the programmed corner. None = take the tip's.
    pub local: Option<[f64; 3]>,
    /// Tool length of the active corrector, mm.
    pub length: f64,
    /// `(DPI,…)` names the plane's axes in the reverse of Canon's order (arc.rs).
    pub plane_reversed: bool,
    /// G06 (spline nodes, spline.rs) until G00–G03.
    pub spline: bool,
}

/// A CVU=3 local frame: part point = origin + rotation·local (rotation row-major).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lcs {
    /// o, part coordinates, mm.
    pub origin: [f64; 3],
    /// R_L.
    pub rotation: [[f64; 3]; 3],
}

impl Lcs {
    /// o + R_L·p.
    pub fn part_point(&self, p: [f64; 3]) -> [f64; 3] {
        let r = &self.rotation;
        std::array::from_fn(|i| self.origin[i] + (0..3).map(|j| r[i][j] * p[j]).sum::<f64>())
    }

    /// R_Lᵀ·(P − o).
    pub fn local_point(&self, p: [f64; 3]) -> [f64; 3] {
        let r = &self.rotation;
        let d: [f64; 3] = std::array::from_fn(|i| p[i] - self.origin[i]);
        std::array::from_fn(|j| (0..3).map(|i| r[i][j] * d[i]).sum::<f64>())
    }
}

/// `(LCS,1,X xo,Y yo,Z zo,A a,B b,C c)` / `(LCS,0)` (§5.10). A field is a letter and a number
/// (an empty number is 0, §2); an angle of a rotary axis the machine lacks must be 0.
fn lcs(cx: &mut Ctx<'_>, text: &str, at: ColSpan) -> Result<(), Diagnostic> {
    let bad = |cx: &Ctx<'_>, why: String| {
        cx.err("balt::lcs", format!("(LCS …): {why}"), at)
            .with_note("the form is (LCS,1,X…,Y…,Z…,A…,B…,C…) or (LCS,0)")
    };
    let mut fields = text.split(',').skip(1).map(str::trim);
    match fields.next() {
        Some("0") => {
            cx.fe.modes.lcs = None;
            cx.fe.modes.local = None;
            return Ok(());
        }
        Some("1") => {}
        other => return Err(bad(cx, format!("the frame number {other:?} is not 0 or 1"))),
    }
    let mut v = [0.0; 9];
    for f in fields.filter(|f| !f.is_empty()) {
        let letter = f.as_bytes()[0].to_ascii_uppercase();
        let Some(slot) = b"XYZABC".iter().position(|&c| c == letter) else {
            return Err(bad(cx, format!("unknown field {f:?}")));
        };
        let num = f[1..].trim();
        v[slot] = if num.is_empty() {
            0.0
        } else {
            num.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(cx, format!("{f:?} is not a number")))?
        };
    }
    let kin = kinematics(cx, at)?;
    for (k, name) in ['A', 'B', 'C'].iter().enumerate() {
        if v[3 + k] != 0.0 && !kin.rotary_axes().any(|a| a.name.eq_ignore_ascii_case(name)) {
            return Err(bad(cx, format!("the machine has no {name} axis")));
        }
    }
    cx.fe.modes.local = None;
    cx.fe.modes.lcs = Some(Lcs {
        origin: [v[0], v[1], v[2]],
        rotation: kin.orientation_frame(&Pose::from_array(v)),
    });
    Ok(())
}

fn kinematics(cx: &Ctx<'_>, at: ColSpan) -> Result<FiveAxis, Diagnostic> {
    cx.opts.five_axis.clone().ok_or_else(|| {
        cx.err(
            "balt::no-five-axis-kinematics",
            "CVU needs a machine with 5-axis kinematics (a [kinematics] section, e.g. fat = \"C,0,0,0,A,0,0,0\")",
            at,
        )
        .with_note("choose e.g. --machine 5axis-cvu-tt")
    })
}

/// One block.
pub(crate) fn execute(cx: &mut Ctx<'_>) -> Result<Outcome, Diagnostic> {
    // Mnemonic blocks.
    for c in cx.block.comments.clone() {
        if c.kind != CommentKind::Paren {
            continue;
        }
        let text = cx.block.slice(c.text).to_string();
        let name: String = text
            .split(',')
            .next()
            .unwrap_or("")
            .trim()
            .to_ascii_uppercase();
        match name.as_str() {
            "DIS" => {
                let msg = text
                    .split_once(',')
                    .map(|x| x.1.trim().trim_matches('"').to_string())
                    .unwrap_or_default();
                cx.out.push(Canon::Message { text: msg });
            }
            "LCS" => lcs(cx, &text, c.text)?,
            "DPI" => crate::arc::dpi(cx, &text, c.text)?,
            "BSP" => crate::spline::begin(cx, &text, c.text)?,
            "ESP" => crate::spline::end(cx, c.text)?,
            // Display settings of the control's screen: no effect on motion.
            "UCG" | "UAV" | "UAO" => {}
            _ => {
                return Err(cx.err(
                    "interp::unsupported",
                    format!(
                        "({} …) is not supported by the Balt-System front end",
                        clipped(&name, 32)
                    ),
                    c.text,
                ))
            }
        }
    }
    let mut cvu_word = None;
    for &(kw, _, val, span) in &cx.words.keywords {
        match kw {
            Keyword::Cvu => cvu_word = Some((val.map_or(-1.0, |v| v.v), span)),
            Keyword::Movst => match val.map(|v| v.v) {
                Some(m) if m == 1.0 || m == 2.0 => cx.fe.modes.movst = m as u8,
                _ => {
                    return Err(cx.err(
                        "balt::movst",
                        format!("{} is not MOVST=1 or MOVST=2", cx.block.slice(span)),
                        span,
                    ))
                }
            },
            _ => {
                return Err(cx.err(
                    "interp::unsupported",
                    format!("{} is not supported", clipped(cx.block.slice(span), 32)),
                    span,
                ))
            }
        }
    }
    // G codes through the table (codes.rs), in written order.
    let gs = cx.words.g.clone();
    for &(code, span) in &gs {
        match codes::g_code(code).map(|c| c.handler) {
            Some(Handler::SetMotion(mode)) => {
                cx.fe.modes.spline = false;
                cx.st.motion = mode;
            }
            Some(Handler::SplineNodes) => cx.fe.modes.spline = true,
            Some(Handler::SetDistance(mode)) => cx.st.distance = mode,
            Some(Handler::NoEffect) => {}
            Some(Handler::ProhibitedInCvu) if cx.fe.modes.cvu => {
                return Err(cx.err(
                    "balt::prohibited-in-cvu",
                    format!("G{} is prohibited while CVU=1 is active", code / 10),
                    span,
                ))
            }
            Some(Handler::ProhibitedInCvu) | None => {
                return Err(cx.err(
                    "interp::unsupported",
                    format!(
                        "G{} is not supported by the Balt-System front end",
                        code as f64 / 10.0
                    ),
                    span,
                ))
            }
        }
    }
    if let Some(f) = cx.words.take(b'F') {
        cx.st.feed = cx.mm(f.v);
        cx.out.push(Canon::SetFeedRate { feed: cx.st.feed });
    }
    if let Some(s) = cx.words.take(b'S') {
        cx.out.push(Canon::SetSpindleSpeed {
            spindle: 0,
            rpm: s.v,
        });
    }
    // M codes through the table (codes.rs), in written order: a code the table lacks is refused
    // where it stands, the spindle and tool rows run before the motion, stop and end after it.
    // T t.c: tool t, corrector c (AMB-6: the corrector is the tool table entry of the length).
    let tool = cx.words.take(b'T');
    let ms = cx.words.m.clone();
    let mut rows = Vec::with_capacity(ms.len());
    for &(m, span) in &ms {
        let Some(row) = codes::m_code(m) else {
            return Err(cx.err(
                "interp::unsupported",
                format!("M{m} is not supported by the Balt-System front end"),
                span,
            ));
        };
        if row.handler.phase() == Phase::BeforeMotion {
            m_function(cx, row.handler, tool, span)?;
        }
        rows.push((row.handler, span));
    }
    if let Some((v, span)) = cvu_word {
        switch(cx, v, span)?;
    } else if cx.has_axis_words() || cx.words.any(b"IJK") {
        motion(cx)?;
    }
    let mut outcome = Outcome::Continue;
    for &(handler, span) in &rows {
        if handler.phase() == Phase::AfterMotion && m_function(cx, handler, tool, span)? {
            outcome = Outcome::End;
        }
    }
    cx.check_all_used()?;
    Ok(outcome)
}

/// Runs one M function's row (codes.rs); true when it ends the program.
fn m_function(
    cx: &mut Ctx<'_>,
    handler: MHandler,
    tool: Option<Val>,
    span: ColSpan,
) -> Result<bool, Diagnostic> {
    match handler {
        MHandler::ToolChange => {
            let Some(t) = tool else {
                return Err(cx.err("balt::m6-without-t", "M6 needs T<tool>.<corrector>", span));
            };
            let number = t.v.trunc() as u32;
            let corrector = ((t.v.fract() * 10.0).round()) as u32;
            cx.out.push(Canon::ChangeTool {
                tool: number,
                slot: number,
            });
            cx.st.current_tool = number;
            cx.fe.modes.length = cx
                .opts
                .control
                .tools
                .get(corrector)
                .and_then(|t| t.edges.first())
                .map_or(0.0, |e| e.length[0] + e.length_wear[0]);
            if !cx.fe.modes.cvu {
                set_length_offset(cx, cx.fe.modes.length);
            }
        }
        MHandler::StartSpindle(direction) => cx.out.push(Canon::StartSpindle {
            spindle: 0,
            direction,
        }),
        MHandler::StopSpindle => cx.out.push(Canon::StopSpindle { spindle: 0 }),
        MHandler::Stop { optional } => cx.out.push(Canon::ProgramStop { optional }),
        MHandler::End => {
            cx.out.push(Canon::ProgramEnd);
            return Ok(true);
        }
    }
    Ok(false)
}

/// 3-axis tool length compensation along Z (§5.1): with the rotary axes at 0 the tip is the gauge
/// point − L·e_z, so the programmed Z is the tip under CVU=0 as under CVU=1. The machine
/// position stays; the program position follows the new offset.
fn set_length_offset(cx: &mut Ctx<'_>, length: f64) {
    let offset = Pose {
        z: length,
        ..Pose::ZERO
    };
    if *cx.st.frame.tlo() != offset {
        cx.st.frame.set_tlo(offset);
        cx.out.push(Canon::UseToolLengthOffset { offset });
    }
}

/// CVU=1 / CVU=0 (§6.1): nothing moves, the position changes meaning.
fn switch(cx: &mut Ctx<'_>, v: f64, span: ColSpan) -> Result<(), Diagnostic> {
    let base = kinematics(cx, span)?;
    let c0 = [0.0, 0.0, cx.fe.modes.length];
    match v as i64 {
        1 | 3 if v == 1.0 || v == 3.0 => {
            cx.fe.modes.cvu3 = v == 3.0;
            cx.fe.modes.local = None;
            if cx.fe.modes.cvu {
                return Ok(());
            }
            let t = base.tool_vector(&cx.st.position);
            // The manual states the precondition for CVU=1 (§3); CVU=3 positions the axes itself.
            if v == 1.0 && (t[2] - 1.0).abs() > 1e-9 {
                return Err(cx
                    .err(
                        "balt::cvu-precondition",
                        "CVU=1 needs the tool along Z, pointing to −Z",
                        span,
                    )
                    .with_note("turn the rotary axes to the tool's zero orientation first"));
            }
            let tip = base
                .with_tool_offset(c0)
                .forward(&cx.st.position.to_array())
                .map_err(|e| cx.err("balt::kinematics", e.to_string(), span))?;
            cx.out.push(Canon::SetToolCentrePoint {
                active: true,
                tool_offset: c0,
            });
            // TCP takes the length over from the 3-axis offset (c0): the tip stays where the
            // program had it, so nothing jumps (§5.1, issue 22 item 15).
            set_length_offset(cx, 0.0);
            cx.st.position = tip;
            cx.fe.modes.cvu = true;
        }
        0 if v == 0.0 => {
            if !cx.fe.modes.cvu {
                return Ok(());
            }
            let joints = base
                .clone()
                .with_tool_offset(c0)
                .inverse(&cx.st.position)
                .map_err(|e| cx.err("balt::kinematics", e.to_string(), span))?;
            // §6.1 [PROPOSED], AMB-11 (issue 22 item 13): CVU=0 needs the tool along Z, as CVU=1
            // does; else "Format error" — the 3-axis position would not be the programmed tip.
            if (base.tool_vector(&Pose::from_array(joints))[2] - 1.0).abs() > 1e-9 {
                return Err(cx
                    .err(
                        "balt::cvu-precondition",
                        "Format error: CVU=0 needs the tool along Z, pointing to −Z",
                        span,
                    )
                    .with_note(
                        "turn the rotary axes back to the tool's zero orientation before CVU=0",
                    ));
            }
            cx.out.push(Canon::SetToolCentrePoint {
                active: false,
                tool_offset: [0.0; 3],
            });
            // Back to 3-axis length compensation (§5.1): the programmed Z is the tip again.
            set_length_offset(cx, cx.fe.modes.length);
            cx.st.position = Pose::from_array(joints);
            cx.fe.modes.cvu = false;
            cx.fe.modes.cvu3 = false;
        }
        _ => {
            return Err(cx.err(
                "interp::unsupported",
                format!("CVU={v} is not supported (CVU=0, CVU=1 and CVU=3 are built)"),
                span,
            ))
        }
    }
    Ok(())
}

/// At most `max` characters of `text` (with `…` when cut): a message names what it refuses, and
/// a 1 MB comment must not become a 1 MB message.
fn clipped(text: &str, max: usize) -> std::borrow::Cow<'_, str> {
    match text.char_indices().nth(max) {
        Some((i, _)) => format!("{}…", &text[..i]).into(),
        None => text.into(),
    }
}

/// A G0/G1 block: X Y Z (G91: incremental, XYZ only in CVU=1) with A B C or I J K.
fn motion(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    let at = cx.whole();
    let ijk = [b'I', b'J', b'K'].map(|l| cx.words.take(l));
    let rotary_words = [b'A', b'B', b'C'].map(|l| cx.words.peek(l));
    let linear_words = cx.words.any(b"XYZ");
    let lcs = cx.fe.modes.lcs.filter(|_| cx.fe.modes.cvu3);
    let (end, _) = match lcs {
        // CVU=3: the words (and G91, and omitted words) act on the local coordinates.
        Some(l) => {
            let part = cx.st.position;
            let mut local = part.to_array();
            let p = cx
                .fe
                .modes
                .local
                .unwrap_or_else(|| l.local_point([local[0], local[1], local[2]]));
            local[..3].copy_from_slice(&p);
            cx.st.position = Pose::from_array(local);
            let r = cx.end_point();
            cx.st.position = part;
            let (end, given) = r?;
            let mut e = end.to_array();
            cx.fe.modes.local = Some([e[0], e[1], e[2]]);
            let p = l.part_point([e[0], e[1], e[2]]);
            e[..3].copy_from_slice(&p);
            (Pose::from_array(e), given)
        }
        None => cx.end_point()?,
    };
    let mut e = end.to_array();
    if cx.fe.modes.cvu && cx.st.distance == DistanceMode::Incremental {
        // §6.3: G91 applies to X Y Z only; angles are absolute.
        for (k, w) in rotary_words.iter().enumerate() {
            if let Some(w) = w {
                e[3 + k] = w.v;
            }
        }
    }
    if ijk.iter().any(Option::is_some) {
        if rotary_words.iter().any(Option::is_some) {
            return Err(cx.err(
                "balt::angles-and-normal",
                "give the tool axis either by the rotary angles or by I J K, not both",
                at,
            ));
        }
        let v = ijk.map(|w| w.map_or(0.0, |w| w.v));
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if len < 1e-6 {
            return Err(cx.err("balt::zero-normal", "the normal I J K is zero", at));
        }
        let kin = kinematics(cx, at)?;
        let oriented = kin
            .orient_least_travel([v[0] / len, v[1] / len, v[2] / len], &cx.st.position)
            .map_err(|err| {
                cx.err(
                    "balt::orientation-unreachable",
                    format!("the tool axis I J K cannot be reached: {err}"),
                    at,
                )
            })?;
        e[3..6].copy_from_slice(&oriented.to_array()[3..6]);
    }
    let rapid = cx.st.motion == MotionMode::Rapid && !cx.fe.modes.spline;
    let feed = cx.st.feed;
    if !rapid && feed <= 0.0 {
        let e = cx.err("balt::feed-missing", "feed move without F", at);
        return Err(if cx.fe.modes.cvu {
            e.with_note("the first motion block after CVU=1 must program F (§6.1)")
        } else {
            e.with_note("program F in this block or before it")
        });
    }
    if cx.fe.modes.spline {
        return crate::spline::node(cx, Pose::from_array(e), feed, at);
    }
    if matches!(cx.st.motion, MotionMode::ArcCw | MotionMode::ArcCcw) {
        if cx.fe.spline.open {
            return Err(cx.manual(
                477,
                "Incongruent profile: G02/G03 inside a spline definition (BSP … ESP)",
                at,
            ));
        }
        return crate::arc::arc(cx, e, feed, at);
    }
    let here = cx.st.position.xyz();
    crate::spline::straight_block(cx, here, [e[0], e[1], e[2]], at)?;
    let feed = if rapid { 0.0 } else { feed };
    if cx.fe.modes.cvu3 && cx.fe.modes.movst == 2 && !linear_words {
        return rotate_with_linear_axes_still(cx, e, rapid, feed, at);
    }
    cx.straight(rapid, Pose::from_array(e), feed);
    Ok(())
}

/// CVU=3, MOVST=2, a block without X Y Z (§6.8): the linear axes stay where they are while the
/// rotary axes turn. TCP is switched off for the block (the kin stage re-expresses the position
/// as machine axes and back, nothing moves at the switches), the block moves the rotary axes in
/// machine coordinates, and the tip afterwards is forward(Q, new angles).
fn rotate_with_linear_axes_still(
    cx: &mut Ctx<'_>,
    end: [f64; 9],
    rapid: bool,
    feed: f64,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let c0 = [0.0, 0.0, cx.fe.modes.length];
    let kin = kinematics(cx, at)?.with_tool_offset(c0);
    let mut joints = kin
        .inverse(&cx.st.position)
        .map_err(|e| cx.err("balt::kinematics", e.to_string(), at))?;
    cx.out.push(Canon::SetToolCentrePoint {
        active: false,
        tool_offset: [0.0; 3],
    });
    cx.st.position = Pose::from_array(joints);
    joints[3..].copy_from_slice(&end[3..]);
    cx.straight(rapid, Pose::from_array(joints), feed);
    let tip = kin
        .forward(&joints)
        .map_err(|e| cx.err("balt::kinematics", e.to_string(), at))?;
    cx.out.push(Canon::SetToolCentrePoint {
        active: true,
        tool_offset: c0,
    });
    cx.st.position = tip;
    Ok(())
}
