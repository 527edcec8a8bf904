//! AxiOMA 5-axis machining: TRAORI / TRAFOOF and the programming of the tool orientation
//! (spec axioma-4 §3–§6).
//!
//! # What TRAORI changes in the stream
//!
//! TRAORI emits `Canon::SetToolCentrePoint { active: true, tool_offset: c0 }` and from then on the
//! positions of the motion commands are the **tool tip** (the frame's tool length offset is set to
//! zero: the kinematics apply the length along the tool vector) plus the rotary axis values; the
//! motion stage's kin stage turns them into machine axes every servo cycle. TRAORI and TRAFOOF
//! move nothing (spec §4.6 [P]); the position is re-expressed: after TRAORI the tip is the
//! forward kinematics of where the axes are; after TRAFOOF the axes are the inverse kinematics of
//! the tip and the program position is the axes minus the fixed length compensation c0
//! (Example 12.3: (70.7107, 0, −29.2893)).
//!
//! # Orientation words (checked in this order)
//!
//! 1. Words: A2/B2/C2 (angles), A3/B3/C3 (vector), and the machine's rotary orientation axes
//!    given directly. Angles with vector components, or either with a direct orientation axis,
//!    is **error 653**; C2 with a vector is the roll angle (ignored on a 5-axis machine).
//! 2. Any change of the orientation while 2D radius compensation is on: **error 656**.
//! 3. Generalized orientation (angles, vector) needs a machine with orientation axes (without
//!    TRAORI the axes go to the solution and the tip is not held, spec A-7 [P]) and a base
//!    orientation of (0,0,1) (G17 with G43, or no length compensation; spec §3.2 [D]).
//! 4. The tool vector: ORIEULER t = Rz(A2)·Ry(B2)·Rz(C2)·ez, ORIRPY t = Rz(C2)·Ry(B2)·Rx(A2)·ez
//!    (angles reduced into [−180, 180], missing ones 0), or the normalised vector (missing
//!    components 0, a zero vector is an error); ORIWKS turns it by the G154–G159 rotation, ORIMKS
//!    does not.
//! 5. Rotary values: `FiveAxis::orient` (both solutions, limits, least time, continuity; the free
//!    axis keeps its value at a singular pose). None reachable: `axioma::orientation-unreachable`.
//! 6. ORIAXES moves the rotary values linearly; ORIVECT (`SetOrientationInterpolation`) makes the
//!    kin stage follow the great circle.

use super::motion::feed_check;
use crate::ctx::Ctx;
use crate::modes::LengthComp;
use crate::state::MotionMode;
use crate::words::Val;
use stanok_canon::{Canon, Diagnostic, LineMove, OrientationInterpolation, Plane, Pose};
use stanok_kin::orientation::{euler_zyz, normalised, reduce_180, rpy_zyx, tool_vector_of};
use stanok_kin::{FiveAxis, KinError, Kinematics};
use stanok_syntax::{ColSpan, Keyword};

/// The orientation modes of the channel (G vector, spec axioma-4 §2).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OriState {
    /// TRAORI is on.
    pub traori: bool,
    /// ORIRPY (true) or ORIEULER (false, default).
    pub rpy: bool,
    /// ORIMKS (true) or ORIWKS (false, default).
    pub machine_base: bool,
    /// ORIVECT (true) or ORIAXES (false, default).
    pub vector: bool,
    /// The tool offset c0 the kinematics use while TRAORI is on, mm.
    pub c0: [f64; 3],
}

/// The orientation words of one block: A2/B2/C2 and A3/B3/C3.
#[derive(Debug, Clone, Copy, Default)]
pub struct OriWords {
    /// A2, B2, C2.
    pub angles: [Option<Val>; 3],
    /// A3, B3, C3.
    pub vector: [Option<Val>; 3],
}

impl OriWords {
    /// Takes `A2=`… `C3=`; false for any other indexed word.
    pub fn take(&mut self, letter: u8, index: u8, val: Val) -> bool {
        let k = match letter {
            b'A' => 0,
            b'B' => 1,
            b'C' => 2,
            _ => return false,
        };
        match index {
            2 => self.angles[k] = Some(val),
            3 => self.vector[k] = Some(val),
            _ => return false,
        }
        true
    }

    fn any_angle(&self) -> bool {
        self.angles.iter().any(Option::is_some)
    }

    fn any_vector(&self) -> bool {
        self.vector.iter().any(Option::is_some)
    }

    /// Any orientation word at all.
    pub fn any(&self) -> bool {
        self.any_angle() || self.any_vector()
    }

    fn first_span(&self) -> Option<ColSpan> {
        self.angles
            .iter()
            .chain(self.vector.iter())
            .flatten()
            .map(|v| v.span)
            .next()
    }
}

fn kinematics<'a>(cx: &'a Ctx<'_>, at: ColSpan) -> Result<&'a FiveAxis, Diagnostic> {
    cx.opts.five_axis.as_ref().ok_or_else(|| {
        cx.manual(
            654,
            "TRAORI is not allowed by the kinematic scheme of this channel",
            at,
        )
        .with_note("choose a 5-axis machine, e.g. --machine 5axis-bc-head")
    })
}

/// c0 for the active tool, G43/G44/G45 and plane (spec axioma-4 §3.3): σ·V of the length
/// compensation, in machine X Y Z.
fn tool_offset(cx: &Ctx<'_>) -> [f64; 3] {
    super::tools::length_offset(cx).xyz()
}

/// TRAORI, TRAFOOF, ORIEULER/ORIRPY, ORIWKS/ORIMKS, ORIAXES/ORIVECT.
pub(super) fn keyword(cx: &mut Ctx<'_>, kw: Keyword, span: ColSpan) -> Result<(), Diagnostic> {
    match kw {
        Keyword::Traori => {
            let kin = kinematics(cx, span)?.clone();
            if cx.fe.ext.ori.traori {
                return Ok(());
            }
            let c0 = tool_offset(cx);
            // The axes stay; the position becomes the tip they hold (spec §4.6 [P]).
            cx.apply_pending_tlo();
            let joints = cx.st.position.to_array();
            let tip = kin
                .with_tool_offset(c0)
                .forward(&joints)
                .map_err(|e| kin_error(cx, e, span))?;
            cx.st.frame.set_tlo(Pose::ZERO);
            cx.fe.modes.pending_tlo = None;
            cx.st.position = tip;
            cx.fe.ext.ori.traori = true;
            cx.fe.ext.ori.c0 = c0;
            cx.out.push(Canon::SetToolCentrePoint {
                active: true,
                tool_offset: c0,
            });
        }
        Keyword::TrafOff => {
            if !cx.fe.ext.ori.traori {
                return Ok(());
            }
            let kin = kinematics(cx, span)?
                .clone()
                .with_tool_offset(cx.fe.ext.ori.c0);
            let joints = kin
                .inverse(&cx.st.position)
                .map_err(|e| kin_error(cx, e, span))?;
            cx.st.position = Pose::from_array(joints);
            let tlo = super::tools::length_offset(cx);
            cx.st.frame.set_tlo(tlo);
            cx.fe.modes.pending_tlo = None;
            cx.fe.ext.ori.traori = false;
            cx.out.push(Canon::SetToolCentrePoint {
                active: false,
                tool_offset: [0.0; 3],
            });
        }
        Keyword::OriEuler => cx.fe.ext.ori.rpy = false,
        Keyword::OriRpy => cx.fe.ext.ori.rpy = true,
        Keyword::OriWks => cx.fe.ext.ori.machine_base = false,
        Keyword::OriMks => cx.fe.ext.ori.machine_base = true,
        Keyword::OriAxes | Keyword::OriVect => {
            let vector = kw == Keyword::OriVect;
            if vector != cx.fe.ext.ori.vector {
                cx.fe.ext.ori.vector = vector;
                cx.out.push(Canon::SetOrientationInterpolation {
                    mode: if vector {
                        OrientationInterpolation::Vector
                    } else {
                        OrientationInterpolation::Axes
                    },
                });
            }
        }
        _ => {}
    }
    Ok(())
}

/// Under TRAORI a changed c0 (another tool, edge, G43/G44/G45/G49) goes to the kinematics, not to
/// the frame: the next motion brings the tip to the programmed point with the new length
/// (spec §4.6 [P]). Returns true when TRAORI is on (the caller then skips the frame's update).
pub(super) fn update_tool(cx: &mut Ctx<'_>) -> bool {
    if !cx.fe.ext.ori.traori {
        return false;
    }
    cx.fe.modes.pending_tlo = None;
    let c0 = tool_offset(cx);
    if c0 != cx.fe.ext.ori.c0 {
        cx.fe.ext.ori.c0 = c0;
        cx.out.push(Canon::SetToolCentrePoint {
            active: true,
            tool_offset: c0,
        });
    }
    true
}

fn kin_error(cx: &Ctx<'_>, e: KinError, at: ColSpan) -> Diagnostic {
    cx.err(
        "axioma::orientation-unreachable",
        format!("the tool orientation cannot be reached by this machine: {e}"),
        at,
    )
}

/// Rules 1–3 of the module doc for a block; true when the block sets the orientation by
/// angles or a vector (then [`motion`] must run it).
pub(super) fn check(cx: &Ctx<'_>, words: &OriWords) -> Result<bool, Diagnostic> {
    let direct: Vec<u8> = cx
        .opts
        .five_axis
        .as_ref()
        .map(|k| {
            k.rotary_axes()
                .map(|a| a.name.to_ascii_uppercase() as u8)
                .collect()
        })
        .unwrap_or_default();
    let direct_word = direct.iter().find(|&&l| cx.words.has(l)).copied();
    // Rule 1: 653. C2 with a vector is the roll (allowed).
    let angles_besides_roll = words.angles[0].is_some() || words.angles[1].is_some();
    if words.any_vector() && angles_besides_roll {
        return Err(cx.manual(
            653,
            "orientation angles (A2=, B2=, C2=) and vector components (A3=, B3=, C3=) in one block",
            words.first_span().unwrap_or_else(|| cx.whole()),
        ));
    }
    if let (true, Some(l)) = (words.any(), direct_word) {
        return Err(cx
            .manual(
                653,
                format!(
                    "the orientation is given twice: by {} and by orientation angles or vector",
                    l as char
                ),
                words.first_span().unwrap_or_else(|| cx.whole()),
            )
            .with_note(
                "program the orientation axes directly or in generalized coordinates, not both",
            ));
    }
    // Rule 2: 656.
    let changes_direct = direct_word.is_some_and(|l| {
        let i = crate::ctx::AXIS_WORDS
            .iter()
            .position(|&w| w == l)
            .unwrap_or(0);
        let now = cx.st.program_position().to_array()[i];
        cx.words.peek(l).is_some_and(|v| {
            v.v != now || cx.st.distance == crate::state::DistanceMode::Incremental && v.v != 0.0
        })
    });
    if cx.fe.ext.comp.is_active() && (words.any() || changes_direct) {
        return Err(cx.manual(
            656,
            "the tool orientation may not change while 2D radius compensation is active",
            words.first_span().unwrap_or_else(|| cx.whole()),
        ));
    }
    if !words.any() {
        return Ok(false);
    }
    // Rule 3.
    let at = words.first_span().unwrap_or_else(|| cx.whole());
    // Spec A-7 [P]: without TRAORI the words are accepted on a machine with orientation axes
    // (converted to axis positions as under ORIAXES, the tip not held).
    if cx.opts.five_axis.is_none() {
        return Err(cx
            .err(
                "axioma::no-orientation-axes",
                "orientation angles or vectors need a machine with rotary orientation axes",
                at,
            )
            .with_note("choose a 5-axis machine, e.g. --machine 5axis-bc-head"));
    }
    let base_is_z = match cx.fe.modes.length_comp {
        LengthComp::Off => true,
        LengthComp::Plus => cx.st.plane == Plane::XY,
        LengthComp::Minus => false,
        LengthComp::Fixed { plane, sign } => plane == Plane::XY && sign > 0.0,
    };
    if !base_is_z {
        return Err(cx
            .err(
                "axioma::orientation-base",
                "generalized orientation is not allowed for this base orientation",
                at,
            )
            .with_note("angles and vectors need the tool along +Z at zero axes (G17 with G43); program the rotary axes directly"));
    }
    Ok(true)
}

/// The tool vector a block asks for, in the machine (table-fixed) frame (rule 4).
fn tool_vector(cx: &Ctx<'_>, words: &OriWords) -> Result<[f64; 3], Diagnostic> {
    let at = words.first_span().unwrap_or_else(|| cx.whole());
    let t = if words.any_vector() {
        let c = words.vector.map(|v| v.map_or(0.0, |v| v.v));
        normalised(c).ok_or_else(|| {
            cx.err(
                "axioma::zero-orientation-vector",
                "the orientation vector A3= B3= C3= is zero",
                at,
            )
        })?
    } else {
        let [a, b, c] = words.angles.map(|v| reduce_180(v.map_or(0.0, |v| v.v)));
        let frame = if cx.fe.ext.ori.rpy {
            rpy_zyx(a, b, c)
        } else {
            euler_zyz(a, b, c)
        };
        tool_vector_of(&frame)
    };
    let t: [f64; 3] = t.into();
    Ok(if cx.fe.ext.ori.machine_base {
        t
    } else {
        crate::frame::mul_vec(cx.st.frame.rotation(), t)
    })
}

/// A G00/G01 block with orientation angles or a vector under TRAORI (rules 4–6): the tip goes
/// to the programmed point (or stays), the rotary axes to the orientation's solution.
pub(super) fn motion(cx: &mut Ctx<'_>, span: ColSpan, words: &OriWords) -> Result<(), Diagnostic> {
    let mode = cx.st.motion;
    if !matches!(mode, MotionMode::Rapid | MotionMode::Linear) {
        return Err(cx.err(
            "axioma::orientation-on-arc",
            "orientation angles or vectors are supported with G00/G01 only",
            span,
        ));
    }
    let t = tool_vector(cx, words)?;
    let kin = kinematics(cx, span)?
        .clone()
        .with_tool_offset(cx.fe.ext.ori.c0);
    let at = words.first_span().unwrap_or(span);
    let oriented = kin
        .orient(t, &cx.st.position)
        .map_err(|e| kin_error(cx, e, at))?;
    let (end, _) = cx.end_point()?;
    let mut end_m = cx.st.frame.to_machine(&end).to_array();
    end_m[3..6].copy_from_slice(&oriented.to_array()[3..6]);
    let end_m = Pose::from_array(end_m);
    let start = cx.st.position;
    let rapid = mode == MotionMode::Rapid;
    let feed = if rapid {
        0.0
    } else {
        let length = super::technology::feed_length(&start.to_array(), &end_m.to_array());
        feed_check(cx, span, length)?
    };
    let m = LineMove {
        start,
        end: end_m,
        feed,
    };
    cx.out.push(if rapid {
        Canon::StraightTraverse(m)
    } else {
        Canon::StraightFeed(m)
    });
    cx.st.position = end_m;
    Ok(())
}
