//! AxiOMA 3D tool radius compensation CUT3DC, CUT3DCC, CUT3DCCD, CUT3DF, CUT3DFS, CUT3DFF
//! (manual §13, spec axioma-4 §7): the state machine between the blocks. The geometry is in
//! `stanok_geom::offset3d` (offsets, corner types, crossings), the look-ahead in `engine.rs`,
//! the output fitting in `fit.rs`.
//!
//! ```text
//!  mode word (CUT2DF | CUT3D*): selects, acts at the next G41/G42 (§13.2.2)
//!            Off ──G41/G42 with a 3D mode (TRAORI on if the machine has it)──▶ Armed
//!          Armed ──first block moving X/Y/Z (G00/G01 only): the entry──────────▶ Active
//!         Active ──G40──▶ Exiting ──next block moving X/Y/Z (G00/G01 only): the exit──▶ Off
//! ```
//!
//! How the blocks reach the engine: a block runs as if uncompensated (its motions are Canon in
//! machine coordinates, so every frame and plane is already applied); at its end `after_block`
//! takes its motion commands out of the staged output (and, in the contour, the spline pieces the
//! spline look-ahead finished) and hands them to the engine with their slots. The programmed
//! position (`ModalState::position`) stays the uncompensated point; only the output changes.
//!
//! Rules enforced here: a mode change while 3D compensation is armed/active, or a 3D mode while 2D
//! compensation is active (§13.2.2); G41 ↔ G42 while active; the calls of §13.2.3 (M functions,
//! G153–G159, G17–G19, G43–G49, TRAORI/TRAFOOF/ORI*, SPLBREAK) from the entry to the exit, and a
//! change of the orientation programming method (direct axes ↔ angles/vector) inside the
//! contour; TRAORI before a 3D mode on a machine that has it (§13.2.4). The normals A4/B4/C4
//! (start) and A5/B5/C5 (end) carry over from block to block even while compensation is off;
//! ISD is ignored outside the contour and reset at activation and exit.

pub mod engine;
mod fit;

use crate::ctx::Ctx;
use crate::words::Val;
use engine::{Elem, Engine, Geometry, Kind, Mode3, ToolAxis};
use stanok_canon::setup::CutterShape;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_geom::offset3d::{Curve3, Cutter};
use stanok_geom::{cross, dot, normalize, sub, Vec3};
use stanok_syntax::{ColSpan, Keyword};

/// Where the 3D compensation is between the blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Phase {
    /// Not compensating.
    #[default]
    Off,
    /// G41/G42 programmed, the entry block not yet run.
    Armed,
    /// In the contour.
    Active,
    /// G40 programmed, the exit block not yet run.
    Exiting,
}

/// How a block inside the contour programs the orientation (§13.2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OriMethod {
    /// Rotary axes directly.
    Direct,
    /// Angles A2/B2/C2 or a vector A3/B3/C3.
    Generalized,
}

/// The 3D compensation state (part of `Extension`, restored on a failing block).
#[derive(Debug, Clone)]
pub struct Comp3d {
    /// The selected mode (G vector); None = CUT2DF.
    pub selected: Option<Mode3>,
    /// The phase.
    pub phase: Phase,
    mode: Mode3,
    side: f64,
    /// The current surface normal (end normal of the last block), machine coordinates.
    pub normal: Vec3,
    /// The current insertion depth, mm.
    pub isd: f64,
    method: Option<OriMethod>,
    engine: Option<Box<Engine>>,
    ready: Vec<(u64, Spanned<Canon>)>,
    /// This block's normals (start, end) and ISD (old, new), set before its motion.
    block: Option<([Vec3; 2], [f64; 2])>,
    /// The block of the last element given to the engine: where a fragment that ends without
    /// M30 is reported (the end of the text has no block of its own).
    pub last_span: stanok_canon::Span,
}

impl Default for Comp3d {
    fn default() -> Self {
        Comp3d {
            selected: None,
            phase: Phase::Off,
            mode: Mode3::C,
            side: 1.0,
            normal: [0.0, 0.0, 1.0],
            isd: 0.0,
            method: None,
            engine: None,
            ready: Vec::new(),
            block: None,
            last_span: stanok_canon::Span::default(),
        }
    }
}

/// The 3D words of one block: normals and ISD.
#[derive(Debug, Clone, Copy, Default)]
pub struct Words3 {
    start: [Option<Val>; 3],
    end: [Option<Val>; 3],
    /// ISD=.
    pub isd: Option<Val>,
}

impl Words3 {
    /// Takes `A4=` … `C5=`; false for other indexed words.
    pub fn take(&mut self, letter: u8, index: u8, val: Val) -> bool {
        let k = match letter {
            b'A' => 0,
            b'B' => 1,
            b'C' => 2,
            _ => return false,
        };
        match index {
            4 => self.start[k] = Some(val),
            5 => self.end[k] = Some(val),
            _ => return false,
        }
        true
    }
}

fn mode_of(kw: Keyword) -> Option<Option<Mode3>> {
    Some(match kw {
        Keyword::Cut2df => None,
        Keyword::Cut3dc => Some(Mode3::C),
        Keyword::Cut3dcc => Some(Mode3::Cc),
        Keyword::Cut3dccd => Some(Mode3::Ccd),
        Keyword::Cut3df => Some(Mode3::F),
        Keyword::Cut3dfs => Some(Mode3::Fs),
        Keyword::Cut3dff => Some(Mode3::Ff),
        _ => return None,
    })
}

fn name(m: Option<Mode3>) -> &'static str {
    m.map_or("CUT2DF", Mode3::name)
}

impl Comp3d {
    /// From the entry to the exit (the §13.2.3 prohibitions apply).
    pub fn in_contour(&self) -> bool {
        matches!(self.phase, Phase::Active | Phase::Exiting)
    }

    /// G40/G41/G42 belong to 3D compensation (a 3D mode is selected or it is on).
    pub fn claims(&self, code: u32) -> bool {
        matches!(code, 400 | 410 | 420) && (self.selected.is_some() || self.phase != Phase::Off)
    }

    /// Slot of the first motion the look-ahead still holds.
    pub fn first_unresolved_slot(&self) -> Option<u64> {
        self.engine.as_ref().and_then(|e| e.first_unresolved_slot())
    }

    /// Takes the finished motions.
    pub fn take_ready(&mut self) -> Vec<(u64, Spanned<Canon>)> {
        std::mem::take(&mut self.ready)
    }

    fn collect(&mut self) {
        if let Some(e) = self.engine.as_mut() {
            self.ready.append(&mut e.ready);
        }
    }

    /// End of the program text: the spline pieces the spline look-ahead finished last join the
    /// contour, then the look-ahead ends its path.
    pub fn flush_spline_and_end(
        &mut self,
        spline: &mut crate::splines::SplineState,
        warnings: &mut Vec<Diagnostic>,
        span: stanok_canon::Span,
    ) -> Result<(), Diagnostic> {
        if self.in_contour() {
            for (slot, c) in spline.take_ready() {
                let span = c.span;
                let curve = curve_of(&c.value).map_err(|what| {
                    Diagnostic::error(
                        "axioma::cut3d-unsupported-motion",
                        format!("{what} cannot be 3D-compensated"),
                        span,
                    )
                })?;
                let Some(m) = c.value.motion() else { continue };
                let (start, end) = (m.start(), m.end());
                let feed = match &c.value {
                    Canon::SplineFeed(sp) => sp.feed,
                    _ => 0.0,
                };
                let elem = Elem {
                    kind: Kind::Contour,
                    curve,
                    start,
                    end,
                    n0: self.normal,
                    n1: self.normal,
                    isd0: self.isd,
                    isd1: self.isd,
                    from: 0.0,
                    tmpl: c,
                    slot,
                    rapid: false,
                    feed,
                };
                if let Some(e) = self.engine.as_mut() {
                    e.push(elem).map_err(|f| engine::diagnostic(f, span))?;
                    self.last_span = span;
                }
            }
        }
        self.flush(warnings, span)
    }

    /// End of the program text or M02/M30: the last element runs to its end.
    pub fn flush(
        &mut self,
        warnings: &mut Vec<Diagnostic>,
        span: stanok_canon::Span,
    ) -> Result<(), Diagnostic> {
        if let Some(mut e) = self.engine.take() {
            if self.phase != Phase::Off {
                warnings.push(
                    Diagnostic::warning(
                        "axioma::cut3d-active-at-end",
                        "the program ends with 3D radius compensation active",
                        span,
                    )
                    .with_note(
                        "program G40 with a linear exit block before the end (manual §13.2.1)",
                    ),
                );
            }
            e.flush().map_err(|f| engine::diagnostic(f, span))?;
            self.ready.append(&mut e.ready);
        }
        self.phase = Phase::Off;
        Ok(())
    }
}

/// CUT2DF or a CUT3D* keyword (§13.2.2).
pub fn mode_word(cx: &mut Ctx<'_>, kw: Keyword, span: ColSpan) -> Result<bool, Diagnostic> {
    let Some(new) = mode_of(kw) else {
        return Ok(false);
    };
    let c = &cx.fe.ext.comp3d;
    if c.phase != Phase::Off {
        if new != Some(c.mode) {
            return Err(cx
                .err(
                    "axioma::cut3d-mode-switch",
                    format!(
                        "{} while 3D compensation {} is active: the mode cannot be switched",
                        name(new),
                        c.mode.name()
                    ),
                    span,
                )
                .with_note(
                    "switch compensation off with G40 and its exit block first (manual §13.2.2)",
                ));
        }
        return Ok(true);
    }
    if new.is_some() && cx.fe.ext.comp.is_active() {
        return Err(cx
            .err(
                "axioma::cut3d-mode-switch",
                format!("{} while 2D radius compensation is active", name(new)),
                span,
            )
            .with_note(
                "switch 2D compensation off with G40 and its exit block first (manual §13.2.2)",
            ));
    }
    cx.fe.ext.comp3d.selected = new;
    Ok(true)
}

/// A call §13.2.3 forbids between the entry and the exit.
pub fn forbidden(cx: &Ctx<'_>, what: &str, at: ColSpan) -> Result<(), Diagnostic> {
    if !cx.fe.ext.comp3d.in_contour() {
        return Ok(());
    }
    Err(cx
        .err(
            "axioma::cut3d-forbidden",
            format!("{what} is not allowed while 3D radius compensation is active"),
            at,
        )
        .with_note("forbidden from the entry into the contour to the exit (manual §13.2.3)"))
}

/// G40 / G41 / G42 under a 3D mode.
pub fn select(cx: &mut Ctx<'_>, code: u32, at: ColSpan) -> Result<(), Diagnostic> {
    let phase = cx.fe.ext.comp3d.phase;
    match code {
        400 => {
            let c = &mut cx.fe.ext.comp3d;
            c.phase = match phase {
                Phase::Off | Phase::Armed => Phase::Off,
                Phase::Active | Phase::Exiting => Phase::Exiting,
            };
        }
        _ => {
            let side = if code == 410 { 1.0 } else { -1.0 };
            if phase != Phase::Off {
                if side != cx.fe.ext.comp3d.side || phase == Phase::Exiting {
                    return Err(cx
                        .err(
                            "axioma::cut3d-side-change",
                            "G41 and G42 cannot be switched while 3D compensation is active",
                            at,
                        )
                        .with_note("cancel with G40 and its exit block first"));
                }
                return Ok(());
            }
            if cx.opts.five_axis.is_some() && !cx.fe.ext.ori.traori {
                return Err(cx
                    .err(
                        "axioma::cut3d-no-traori",
                        format!(
                            "{} needs TRAORI on this machine: its kinematics support the orientation transformation",
                            name(cx.fe.ext.comp3d.selected)
                        ),
                        at,
                    )
                    .with_note("program TRAORI before G41/G42 (manual §13.2.4)"));
            }
            let c = &mut cx.fe.ext.comp3d;
            c.mode = c.selected.unwrap_or(Mode3::C);
            c.side = side;
            c.phase = Phase::Armed;
            c.isd = 0.0;
            c.method = None;
        }
    }
    Ok(())
}

/// Before the block's motion: the normals (always), ISD (in the contour), the orientation method.
pub fn before_motion(
    cx: &mut Ctx<'_>,
    words: &Words3,
    generalized: bool,
) -> Result<(), Diagnostic> {
    // Normals (§13.4): missing components 0, carried over, normalised, WCS or MCS.
    let vec = |v: &[Option<Val>; 3]| v.map(|x| x.map_or(0.0, |x| x.v));
    let first_span = |v: &[Option<Val>; 3]| v.iter().flatten().map(|x| x.span).next();
    let programmed = |v: &[Option<Val>; 3]| -> Result<Option<Vec3>, Diagnostic> {
        let Some(at) = first_span(v) else {
            return Ok(None);
        };
        let n = normalize(vec(v)).ok_or_else(|| {
            cx.err(
                "axioma::cut3d-zero-normal",
                "the surface normal A4=/B4=/C4= (or A5=/B5=/C5=) is the zero vector",
                at,
            )
        })?;
        Ok(Some(if cx.fe.ext.ori.machine_base {
            n
        } else {
            crate::frame::mul_vec(cx.st.frame.rotation(), n)
        }))
    };
    let prev = cx.fe.ext.comp3d.normal;
    let ns = programmed(&words.start)?;
    let ne = programmed(&words.end)?;
    let n_s = ns.unwrap_or(prev);
    let n_e = ne.unwrap_or(n_s);
    if dot(n_s, n_e) < -1.0 + 1e-12 {
        return Err(cx.err(
            "axioma::cut3d-normals-opposite",
            "the start and end normals of the block are opposite: the rotation between them is undefined",
            first_span(&words.end).unwrap_or_else(|| cx.whole()),
        ));
    }
    let phase = cx.fe.ext.comp3d.phase;
    let isd_old = cx.fe.ext.comp3d.isd;
    let isd_new = match (phase, words.isd) {
        (Phase::Off, _) | (_, None) => isd_old,
        (_, Some(v)) => cx.mm(v.v),
    };
    // §13.2.3: one orientation method along the whole contour.
    if cx.fe.ext.comp3d.in_contour() && !cx.fe.params.cut3d_mixed_orientation {
        let direct = cx.opts.five_axis.as_ref().and_then(|k| {
            k.rotary_axes()
                .map(|a| a.name.to_ascii_uppercase() as u8)
                .find(|&l| cx.words.has(l))
        });
        let method = match (generalized, direct) {
            (true, _) => Some(OriMethod::Generalized),
            (false, Some(_)) => Some(OriMethod::Direct),
            _ => None,
        };
        if let Some(m) = method {
            match cx.fe.ext.comp3d.method {
                Some(old) if old != m => {
                    return Err(cx
                        .err(
                            "axioma::cut3d-ori-method-change",
                            "the orientation programming method changes inside the 3D-compensated contour",
                            cx.whole(),
                        )
                        .with_note("use either rotary axis positions or angles/vectors along the whole contour (manual §13.2.3)"))
                }
                _ => cx.fe.ext.comp3d.method = Some(m),
            }
        }
    }
    let c = &mut cx.fe.ext.comp3d;
    c.normal = n_e;
    c.isd = isd_new;
    c.block = Some(([n_s, n_e], [isd_old, isd_new]));
    Ok(())
}

/// The cutter of the active tool and edge: R and r (§13.2.5: CUT3DCCD takes the corrections).
fn cutter(cx: &Ctx<'_>, mode: Mode3) -> Result<Cutter, Diagnostic> {
    let (t, e) = (cx.st.current_tool, cx.fe.modes.edge);
    if t == 0 || e == 0 {
        return Ok(Cutter::default());
    }
    let (Some(tool), Some(edge)) = (
        cx.opts.control.tools.get(t),
        cx.opts.control.tools.edge(t, e as u32),
    ) else {
        return Ok(Cutter::default());
    };
    let differential = mode == Mode3::Ccd;
    let radius = if differential {
        edge.radius_wear
    } else {
        edge.radius + edge.radius_wear
    };
    let corner = match tool.body.cutter {
        Some(CutterShape::Ball) => radius,
        Some(CutterShape::Bull) => {
            if differential {
                0.0
            } else {
                tool.body.corner_radius.unwrap_or(0.0).min(radius)
            }
        }
        _ => 0.0,
    };
    if !(radius.is_finite() && radius >= 0.0 && corner >= 0.0) {
        return Err(cx.err(
            "axioma::cut3d-negative-radius",
            format!("T{t} D{e}: 3D compensation needs a radius ≥ 0 (got {radius} mm)"),
            cx.whole(),
        ));
    }
    Ok(Cutter { radius, corner })
}

/// The tool vector's source for the contour being entered.
fn tool_axis(cx: &Ctx<'_>, mode: Mode3) -> ToolAxis {
    let plane_axis = match cx.st.plane {
        stanok_canon::Plane::XY => [0.0, 0.0, 1.0],
        stanok_canon::Plane::ZX => [0.0, 1.0, 0.0],
        _ => [1.0, 0.0, 0.0],
    };
    match mode {
        Mode3::Fs => ToolAxis::Fixed(plane_axis),
        Mode3::Ff => ToolAxis::Fixed(crate::frame::mul_vec(cx.st.frame.rotation(), plane_axis)),
        _ => match (&cx.opts.five_axis, cx.fe.ext.ori.traori) {
            (Some(kin), true) => ToolAxis::Kinematic {
                kin: Box::new(kin.clone()),
                vector: cx.fe.ext.ori.vector,
            },
            // A 3-axis machine: the base orientation (§13.2.4).
            _ => ToolAxis::Fixed([0.0, 0.0, 1.0]),
        },
    }
}

fn moves_xyz(c: &Canon) -> bool {
    match c.motion() {
        Some(m) => {
            let (a, b) = (m.start().xyz(), m.end().xyz());
            stanok_geom::norm(sub(a, b)) > 1e-9 || matches!(c, Canon::ArcFeed(_))
        }
        None => false,
    }
}

/// The programmed path of a motion command, or why it cannot be compensated.
fn curve_of(c: &Canon) -> Result<Curve3, &'static str> {
    match c {
        Canon::StraightFeed(m) | Canon::StraightTraverse(m) => Ok(Curve3::Line {
            a: m.start.xyz(),
            b: m.end.xyz(),
        }),
        Canon::ArcFeed(a) => {
            let axis = normalize(a.axis).ok_or("an arc without an axis")?;
            let (s, e) = (a.start.xyz(), a.end.xyz());
            let r0 = sub(s, a.centre);
            let r0 = sub(r0, stanok_geom::scale(axis, dot(r0, axis)));
            let r1 = sub(e, a.centre);
            let rise = dot(sub(e, s), axis);
            let r1 = sub(r1, stanok_geom::scale(axis, dot(r1, axis)));
            let mut sweep = dot(axis, cross(r0, r1)).atan2(dot(r0, r1));
            if sweep <= 1e-12 {
                sweep += std::f64::consts::TAU;
            }
            sweep += std::f64::consts::TAU * (a.turns.max(1) - 1) as f64;
            Ok(Curve3::Arc {
                centre: stanok_geom::add(
                    a.centre,
                    stanok_geom::scale(axis, dot(sub(s, a.centre), axis)),
                ),
                axis,
                start: s,
                sweep,
                rise,
            })
        }
        Canon::SplineFeed(sp) => {
            let unit = sp.weights.iter().all(|w| (w - sp.weights[0]).abs() < 1e-12);
            if sp.degree == 3 && sp.control_points.len() == 4 && unit {
                let p = &sp.control_points;
                Ok(Curve3::Bezier {
                    p: [p[0], p[1], p[2], p[3]],
                })
            } else {
                Err("a BSPLINE (rational or of another degree than 3)")
            }
        }
        _ => Err("a probe or tapping move"),
    }
}

/// After the block's motion: its motions (and the spline pieces finished meanwhile) go to the
/// engine. `block_start` is the staged output's length when the block began.
pub fn after_block(cx: &mut Ctx<'_>, block_start: usize) -> Result<(), Diagnostic> {
    let block = cx.fe.ext.comp3d.block.take();
    if cx.fe.ext.comp3d.phase == Phase::Off {
        return Ok(());
    }
    let ([n_s, n_e], [isd_old, isd_new]) =
        block.unwrap_or(([cx.fe.ext.comp3d.normal; 2], [cx.fe.ext.comp3d.isd; 2]));
    let mut items: Vec<(u64, Spanned<Canon>, bool)> = Vec::new();
    if cx.fe.ext.comp3d.in_contour() {
        for (slot, c) in cx.fe.ext.spline.take_ready() {
            items.push((slot, c, false));
        }
    }
    let mut i = block_start;
    while i < cx.out.queue.len() {
        let c = &cx.out.queue[i];
        let take = c.value.motion().is_some()
            && (cx.fe.ext.comp3d.phase != Phase::Armed || moves_xyz(&c.value));
        if take {
            let slot = cx.fe.ext.held_base + i as u64;
            if let Some(c) = cx.out.queue.remove(i) {
                items.push((slot, c, true));
            }
        } else {
            i += 1;
        }
    }
    for (slot, c, own) in items {
        let (n, isd) = if own {
            ([n_s, n_e], [isd_old, isd_new])
        } else {
            ([n_s, n_s], [isd_old, isd_old])
        };
        hand_over(cx, slot, c, n, isd, !own)?;
    }
    cx.fe.ext.comp3d.collect();
    Ok(())
}

fn hand_over(
    cx: &mut Ctx<'_>,
    slot: u64,
    c: Spanned<Canon>,
    [n0, n1]: [Vec3; 2],
    [isd0, isd1]: [f64; 2],
    spline_piece: bool,
) -> Result<(), Diagnostic> {
    let span = cx.block.span();
    let geometric = moves_xyz(&c.value);
    let linear = matches!(c.value, Canon::StraightFeed(_) | Canon::StraightTraverse(_));
    let phase = cx.fe.ext.comp3d.phase;
    let kind = match phase {
        Phase::Off => return Ok(()),
        // Pieces of a spline programmed inside the contour (finished by a later block).
        _ if spline_piece => Kind::Contour,
        Phase::Armed => Kind::Entry,
        Phase::Active if geometric => Kind::Contour,
        Phase::Active => Kind::Reorient,
        Phase::Exiting if geometric => Kind::Exit,
        Phase::Exiting => Kind::Reorient,
    };
    if matches!(kind, Kind::Entry | Kind::Exit) && !linear {
        return Err(Diagnostic::error(
            "axioma::cut3d-entry-exit-not-linear",
            format!(
                "the {} block of 3D compensation must be linear (G00/G01)",
                if kind == Kind::Entry { "entry" } else { "exit" }
            ),
            span,
        )
        .with_note("entry and exit always follow the shortest line (manual §13.2.1)"));
    }
    let curve = curve_of(&c.value).map_err(|what| {
        Diagnostic::error(
            "axioma::cut3d-unsupported-motion",
            format!("{what} cannot be 3D-compensated"),
            span,
        )
    })?;
    let m = c.value.motion().expect("a motion");
    let (start, end) = (m.start(), m.end());
    let (rapid, feed) = match &c.value {
        Canon::StraightTraverse(_) => (true, cx.st.feed),
        Canon::StraightFeed(l) => (false, l.feed),
        Canon::ArcFeed(a) => (false, a.feed),
        Canon::SplineFeed(s) => (false, s.feed),
        _ => (false, cx.st.feed),
    };
    if kind == Kind::Entry {
        let mode = cx.fe.ext.comp3d.mode;
        let geo = Geometry {
            mode,
            side: cx.fe.ext.comp3d.side,
            cutter: cutter(cx, mode)?,
            axis: tool_axis(cx, mode),
        };
        cx.fe.ext.comp3d.engine = Some(Box::new(Engine::new(geo)));
        cx.fe.ext.comp3d.phase = Phase::Active;
    }
    let elem = Elem {
        kind,
        curve,
        start,
        end,
        n0,
        n1,
        isd0,
        isd1,
        from: 0.0,
        tmpl: c,
        slot,
        rapid,
        feed,
    };
    let c3 = &mut cx.fe.ext.comp3d;
    if let Some(e) = c3.engine.as_mut() {
        e.push(elem).map_err(|f| engine::diagnostic(f, span))?;
        c3.last_span = span;
    }
    if kind == Kind::Exit {
        c3.collect();
        c3.engine = None;
        c3.phase = Phase::Off;
        c3.isd = 0.0;
        c3.method = None;
    }
    Ok(())
}
