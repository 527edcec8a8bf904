//! The converter's state and the non-motion commands (`motion.rs` writes the moves).
//!
//! One `Canon` in → zero or more program lines out, in stream order. State kept between commands:
//! the start frame to fold out (`Fold`), the last written position (so A–W are written only when
//! they move), the spindle-sync pitch, the coolant pair (M9 stops both), a pending pallet shuttle
//! (M30 = shuttle + end), and whether the program has ended (LinuxCNC's resets after M2 are not
//! program text).

use crate::format::{axioma_text, num, rs274_comment_text};
use crate::{ConvertOptions, Target, Warning};
use stanok_canon::{AccelerationProfile, Canon, LogAction, PathMode, Pose, Spanned};

/// The work frame of the source's start, folded out of every position:
/// work = Rot(−R)·(machine − g5x) − g92 (LinuxCNC's order; rotation about Z on X, Y only).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fold {
    g5x: Pose,
    g92: Pose,
    rotation_deg: f64,
}

impl Fold {
    const IDENTITY: Fold = Fold {
        g5x: Pose::ZERO,
        g92: Pose::ZERO,
        rotation_deg: 0.0,
    };

    /// A machine pose in the output's program coordinates.
    pub(crate) fn pose(&self, p: &Pose) -> Pose {
        let m = p.to_array();
        let g5x = self.g5x.to_array();
        let g92 = self.g92.to_array();
        let mut w = [0.0; 9];
        for i in 0..9 {
            w[i] = m[i] - g5x[i];
        }
        let [x, y, z] = self.point([m[0], m[1], m[2]]);
        w[0] = x;
        w[1] = y;
        w[2] = z;
        for i in 3..9 {
            w[i] -= g92[i];
        }
        Pose::from_array(w)
    }

    /// A machine X Y Z point in program coordinates.
    pub(crate) fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let d = [p[0] - self.g5x.x, p[1] - self.g5x.y, p[2] - self.g5x.z];
        let (s, c) = (-self.rotation_deg).to_radians().sin_cos();
        [
            c * d[0] - s * d[1] - self.g92.x,
            s * d[0] + c * d[1] - self.g92.y,
            d[2] - self.g92.z,
        ]
    }

    /// A machine direction in program coordinates (rotation only).
    pub(crate) fn direction(&self, v: [f64; 3]) -> [f64; 3] {
        let (s, c) = (-self.rotation_deg).to_radians().sin_cos();
        [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
    }
}

/// Writes a program of the target dialect from a Canon stream, one command at a time
/// (streaming: [`Converter::take_text`] hands out what is written so far).
pub struct Converter {
    pub(crate) opts: ConvertOptions,
    pub(crate) fold: Fold,
    /// Last written position, program coordinates (None before `Init`).
    pub(crate) last: Option<Pose>,
    /// Source line of the last line-number comment.
    last_line: u32,
    /// Pitch of the spindle-synchronised motion in force (StartSpindleSync … StopSpindleSync).
    pub(crate) sync_pitch: Option<f64>,
    /// Plane code last written by an arc.
    pub(crate) plane_code: Option<&'static str>,
    /// Main spindle speed last commanded, rpm (a rigid tap's feed where the target has no tapping).
    pub(crate) spindle_rpm: f64,
    /// Feed of the last feed move, mm/min (for moves the target cannot synchronise).
    pub(crate) last_feed: f64,
    /// Source line of the last "offset change" note.
    offset_note_line: u32,
    mist: bool,
    flood: bool,
    pending_pallet: bool,
    ended: bool,
    started: bool,
    out: String,
    warnings: Vec<Warning>,
}

impl Converter {
    /// A converter writing `opts.target`.
    pub fn new(opts: ConvertOptions) -> Self {
        Converter {
            opts,
            fold: Fold::IDENTITY,
            last: None,
            last_line: 0,
            sync_pitch: None,
            plane_code: None,
            last_feed: 0.0,
            spindle_rpm: 0.0,
            offset_note_line: 0,
            mist: false,
            flood: false,
            pending_pallet: false,
            ended: false,
            started: false,
            out: String::new(),
            warnings: Vec::new(),
        }
    }

    pub(crate) fn rs274(&self) -> bool {
        self.opts.target == Target::Rs274ngc
    }

    /// The text written since the last call.
    pub fn take_text(&mut self) -> String {
        std::mem::take(&mut self.out)
    }

    /// Everything that could not be expressed exactly, in stream order.
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// A program line; the first line written for a new source line carries its number.
    pub(crate) fn line(&mut self, src: u32, body: &str) {
        self.out.push_str(body);
        if src != 0 && src != self.last_line {
            self.last_line = src;
            if self.rs274() {
                self.out.push_str(&format!(" (line {src})"));
            } else {
                self.out.push_str(&format!(" ; line {src}"));
            }
        }
        self.out.push('\n');
    }

    /// A comment line of the target (never carries the line number: an RS274/NGC line keeps only
    /// its last comment).
    pub(crate) fn comment(&mut self, text: &str) {
        if self.rs274() {
            self.out
                .push_str(&format!("({})\n", rs274_comment_text(text)));
        } else {
            self.out.push_str(&format!("; {}\n", axioma_text(text)));
        }
    }

    /// Something the target cannot say: a comment in the program and a warning.
    pub(crate) fn cannot(&mut self, src: u32, what: &str) {
        self.comment(&format!("stanok: line {src}: {what}"));
        self.warnings.push(Warning {
            line: src,
            message: what.to_string(),
        });
    }

    /// Converts one command.
    pub fn push(&mut self, cmd: &Spanned<Canon>) {
        if self.ended {
            return;
        }
        let src = cmd.span.line;
        if !self.started {
            let init = match &cmd.value {
                Canon::Init { .. } => cmd.value.clone(),
                // A stream without Init (hand-made): start from machine zero.
                _ => Canon::Init {
                    position: Pose::ZERO,
                    units: stanok_canon::LengthUnits::Millimetres,
                    g5x_index: 1,
                    g5x_offset: Pose::ZERO,
                    g92_offset: Pose::ZERO,
                    xy_rotation: 0.0,
                },
            };
            self.header(&init);
            if matches!(cmd.value, Canon::Init { .. }) {
                return;
            }
        }
        if self.pending_pallet && !matches!(cmd.value, Canon::ProgramEnd) {
            self.pending_pallet = false;
            if self.rs274() {
                self.line(src, "M60");
            } else {
                self.cannot(src, "pallet shuttle (LinuxCNC M60) has no AxiOMA form");
            }
        }
        if cmd.value.motion().is_some() {
            self.motion(src, &cmd.value);
            return;
        }
        self.technology(src, &cmd.value);
    }

    fn header(&mut self, init: &Canon) {
        self.started = true;
        let Canon::Init {
            position,
            g5x_index,
            g5x_offset,
            g92_offset,
            xy_rotation,
            ..
        } = init
        else {
            return;
        };
        let o = self.opts.clone();
        let source = format!(
            "converted by Stanok from {} ({}) to {}",
            o.source_name,
            o.source_dialect,
            o.target.id()
        );
        if self.rs274() {
            self.fold = Fold {
                g5x: *g5x_offset,
                g92: *g92_offset,
                rotation_deg: *xy_rotation,
            };
            let code = match g5x_index {
                2 => "G55",
                3 => "G56",
                4 => "G57",
                5 => "G58",
                6 => "G59",
                7 => "G59.1",
                8 => "G59.2",
                9 => "G59.3",
                _ => "G54",
            };
            self.comment(&source);
            self.comment(&format!(
                "positions: absolute, mm, in the work frame the source started in ({code}; offsets X{} Y{} Z{}, G92 X{} Y{} Z{}, rotation {} deg); no tool length offset, no cutter compensation",
                num(g5x_offset.x), num(g5x_offset.y), num(g5x_offset.z),
                num(g92_offset.x), num(g92_offset.y), num(g92_offset.z),
                num(*xy_rotation)
            ));
            self.comment("run it from the same start state: cycles, subprograms, loops and compensation are already expanded");
            self.comment("feeds: G94 mm/min whatever the source's feed mode; comments (line N) name the source line");
            self.line(0, &format!("G21 G17 G90 G91.1 G94 G40 G49 G80 {code}"));
            self.plane_code = Some("G17");
        } else {
            self.fold = Fold::IDENTITY;
            self.out.push_str("% STANOK-CONVERTED\n");
            self.comment(&source);
            self.comment("positions: absolute machine coordinates, mm (G53 G153 G193: no zero offset, no workpiece frame, no programmed shift); no tool length offset (G49), no cutter compensation (G40)");
            self.comment("cycles, subprograms, loops and compensation are already expanded; feeds: G94 mm/min");
            self.comment("comments ; line N name the source line");
            self.line(
                0,
                "G17 G90 G15 G191 G71 G72 G172 G272 G94 G97 G49 G40 G00 G80 G98",
            );
            self.line(0, "G53 G153 G193");
            self.plane_code = Some("G17");
        }
        self.last = Some(self.fold.pose(position));
    }

    /// Ends the program: a program that ended with `%` (Canon `Finish`) or without anything gets
    /// the target's end code so that it is a complete program.
    pub fn finish(&mut self) {
        if !self.started {
            self.header(&Canon::Init {
                position: Pose::ZERO,
                units: stanok_canon::LengthUnits::Millimetres,
                g5x_index: 1,
                g5x_offset: Pose::ZERO,
                g92_offset: Pose::ZERO,
                xy_rotation: 0.0,
            });
        }
        if !self.ended {
            self.comment("stanok: the source has no program end here; the target needs one");
            let end = if self.rs274() { "M2" } else { "M30" };
            self.line(0, end);
            self.ended = true;
        }
    }

    /// Every command that does not move: spindle, coolant, tools, stops, messages, modes.
    fn technology(&mut self, src: u32, c: &Canon) {
        let rs = self.rs274();
        let on_off = |b: bool| if b { 1 } else { 0 };
        match c {
            Canon::Init { .. } => {}
            // Motion is handled before this match.
            Canon::StraightTraverse(_)
            | Canon::StraightFeed(_)
            | Canon::ArcFeed(_)
            | Canon::SplineFeed(_)
            | Canon::StraightProbe { .. }
            | Canon::RigidTap { .. } => {}
            Canon::StartSpindleSync { pitch, .. } => self.sync_pitch = Some(*pitch),
            Canon::StopSpindleSync => self.sync_pitch = None,
            Canon::SetPathMode {
                mode,
                naive_cam_tolerance,
            } => match (rs, mode) {
                (true, PathMode::ExactStop) => self.line(src, "G61.1"),
                (true, PathMode::ExactPath) => self.line(src, "G61"),
                (true, PathMode::Continuous { tolerance }) => {
                    let mut s = "G64".to_string();
                    if *tolerance > 0.0 {
                        s += &format!(" P{}", num(*tolerance));
                        if let Some(q) = naive_cam_tolerance {
                            s += &format!(" Q{}", num(*q));
                        }
                    }
                    self.line(src, &s)
                }
                (false, PathMode::ExactStop) => self.line(src, "G60"),
                (false, PathMode::ExactPath) => {
                    self.line(src, "G60");
                    self.cannot(
                        src,
                        "exact path without stops (LinuxCNC G61) has no AxiOMA form: G60 (exact stop) written",
                    )
                }
                (false, PathMode::Continuous { tolerance }) => {
                    self.line(src, "G64");
                    if *tolerance > 0.0 {
                        self.cannot(
                            src,
                            &format!(
                                "AxiOMA G64 takes no path tolerance: P{} dropped",
                                num(*tolerance)
                            ),
                        )
                    }
                }
            },
            Canon::SetAccelerationProfile { profile } => {
                let word = match profile {
                    AccelerationProfile::Brisk => "BRISK",
                    AccelerationProfile::Soft => "SOFT",
                };
                if rs {
                    self.cannot(src, &format!("{word} (acceleration profile) has no RS274/NGC form"))
                } else {
                    self.line(src, word)
                }
            }
            Canon::SetFeedOverrideEnabled { enabled } => {
                if rs {
                    self.line(src, &format!("M50 P{}", on_off(*enabled)))
                } else {
                    self.cannot(src, "feed override switch (LinuxCNC M48-M50) has no AxiOMA form")
                }
            }
            Canon::SetSpindleOverrideEnabled { spindle, enabled } => {
                if rs && *spindle == 0 {
                    self.line(src, &format!("M51 P{}", on_off(*enabled)))
                } else if rs {
                    self.cannot(src, &format!("spindle override switch of spindle {spindle}: only the main spindle is converted"))
                } else {
                    self.cannot(src, "spindle override switch (LinuxCNC M51) has no AxiOMA form")
                }
            }
            Canon::SetAdaptiveFeed { enabled } => {
                if rs {
                    self.line(src, &format!("M52 P{}", on_off(*enabled)))
                } else {
                    self.cannot(src, "adaptive feed (LinuxCNC M52) has no AxiOMA form")
                }
            }
            Canon::SetFeedHoldEnabled { enabled } => {
                if rs {
                    self.line(src, &format!("M53 P{}", on_off(*enabled)))
                } else {
                    self.cannot(src, "feed stop control (LinuxCNC M53) has no AxiOMA form")
                }
            }
            Canon::OrientSpindle {
                spindle,
                degrees,
                direction,
                timeout,
            } => {
                if rs {
                    let mut s = format!("M19 R{} P{}", num(*degrees), direction);
                    if let Some(q) = timeout {
                        s += &format!(" Q{}", num(*q));
                    }
                    self.line(src, &s);
                    if *spindle != 0 {
                        self.cannot(src, &format!("M19 of spindle {spindle} written for the main spindle"))
                    }
                } else {
                    self.line(src, &format!("M19 S{}", num(*degrees)));
                    if *direction != 0 || timeout.is_some() || *spindle != 0 {
                        self.cannot(src, "M19 direction, timeout or spindle number dropped (AxiOMA M19 S<angle>)")
                    }
                }
            }
            Canon::WaitSpindleOrient { spindle, timeout } => {
                if rs {
                    self.line(src, &format!("M19 Q{}", num(*timeout)));
                    if *spindle != 0 {
                        self.cannot(src, &format!("M19 of spindle {spindle} written for the main spindle"))
                    }
                } else {
                    self.cannot(src, "a wait for a spindle orientation (LinuxCNC M19 Q) has no AxiOMA form")
                }
            }
            Canon::SetCurrentTool { tool, .. } => {
                if rs {
                    self.line(src, &format!("M61 Q{tool}"))
                } else {
                    self.cannot(src, &format!("tool {tool} declared loaded (LinuxCNC M61) has no AxiOMA form"))
                }
            }
            Canon::DigitalOutput {
                index,
                on,
                synchronised,
            } => {
                if rs {
                    let m = match (synchronised, on) {
                        (true, true) => 62,
                        (true, false) => 63,
                        (false, true) => 64,
                        (false, false) => 65,
                    };
                    self.line(src, &format!("M{m} P{index}"))
                } else {
                    self.cannot(
                        src,
                        &format!("digital output {index} {} not written (no AxiOMA G110/G111 address mapping)", if *on { "on" } else { "off" }),
                    )
                }
            }
            Canon::WaitInput {
                index,
                analog,
                mode,
                timeout,
            } => {
                if rs {
                    let port = if *analog { 'E' } else { 'P' };
                    self.line(src, &format!("M66 {port}{index} L{mode} Q{}", num(*timeout)))
                } else {
                    self.cannot(src, &format!("wait for input {index} (LinuxCNC M66) has no AxiOMA form"))
                }
            }
            Canon::Dwell { seconds } => {
                if rs {
                    self.line(src, &format!("G4 P{}", num(*seconds)))
                } else {
                    self.line(src, &format!("G04 X{}", num(*seconds)))
                }
            }
            // Feeds are written with every feed move (mm/min, G94); planes with every arc; units are mm.
            Canon::SetFeedRate { .. }
            | Canon::SetFeedMode { .. }
            | Canon::SelectPlane { .. }
            | Canon::UseLengthUnits { .. }
            | Canon::StartToolChange => {}
            Canon::SetG5xOffset { .. }
            | Canon::SetG92Offset { .. }
            | Canon::SetXyRotation { .. }
            | Canon::UseToolLengthOffset { .. } => {
                // Positions are machine positions already: the change is in every later
                // coordinate. One note per source line.
                if self.offset_note_line != src {
                    self.offset_note_line = src;
                    self.comment(&format!(
                        "line {src}: offset change of the source (already in the positions)"
                    ));
                }
            }
            Canon::SetToolTableEntry { tool, .. } => self.comment(&format!(
                "line {src}: the source writes tool table entry {tool} (not needed: positions include offsets)"
            )),
            Canon::ReloadToolTable => {
                self.comment(&format!("line {src}: the source reloads the tool table"))
            }
            Canon::SetSpindleSpeed { spindle, rpm } => {
                if *spindle == 0 {
                    self.spindle_rpm = *rpm;
                    self.line(src, &format!("S{}", num(*rpm)))
                } else if rs {
                    self.cannot(src, &format!("S{} of spindle {spindle}: only the main spindle is converted for RS274/NGC", num(*rpm)))
                } else {
                    self.line(src, &format!("S{}={}", spindle + 1, num(*rpm)))
                }
            }
            Canon::StartSpindle { spindle, direction } => {
                let m = match direction {
                    stanok_canon::SpindleDirection::Clockwise => "M3",
                    stanok_canon::SpindleDirection::CounterClockwise => "M4",
                };
                if *spindle == 0 {
                    self.line(src, m)
                } else {
                    self.cannot(src, &format!("{m} of spindle {spindle}: only the main spindle is converted"))
                }
            }
            Canon::StopSpindle { spindle } => {
                if *spindle == 0 {
                    self.line(src, "M5")
                } else {
                    self.cannot(src, &format!("M5 of spindle {spindle}: only the main spindle is converted"))
                }
            }
            Canon::SetSpindleMode {
                spindle,
                constant_surface_speed,
                max_rpm,
            } => {
                if *spindle != 0 {
                    self.cannot(src, &format!("spindle mode of spindle {spindle}: only the main spindle is converted"))
                } else if rs {
                    if *constant_surface_speed {
                        let d = if *max_rpm > 0.0 {
                            format!(" D{}", num(*max_rpm))
                        } else {
                            String::new()
                        };
                        self.line(src, &format!("G96{d}"))
                    } else {
                        self.line(src, "G97")
                    }
                } else if *constant_surface_speed {
                    self.cannot(src, "constant surface speed (G96) not converted for AxiOMA: the following S words are surface speeds, not rpm")
                } else {
                    self.line(src, "G97")
                }
            }
            // The machine's continuous G96 law; the program words that state it came as
            // SetSpindleMode/SetSpindleSpeed above (RS274/NGC) or as the speeds an AxiOMA control
            // shows at block ends, which is what a converted program can say.
            Canon::SetSurfaceSpeedLaw { .. } => {}
            // Tool-centre-point control: the positions that follow are tool-tip positions with
            // rotary angles. AxiOMA says so with TRAORI (its tool length must be the source's: it
            // comes from the tool, which this writer selects but does not offset); RS274/NGC has
            // no G-code for it (LinuxCNC does it in its kinematics module), so it is a warning.
            Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } => {
                if rs {
                    let what = if *active { "on" } else { "off" };
                    self.cannot(src, &format!("tool-centre-point control {what} has no RS274/NGC form: the following positions are the tool tip's"))
                } else if *active {
                    self.line(src, "TRAORI");
                    let l = tool_offset.iter().map(|v| v * v).sum::<f64>().sqrt();
                    self.cannot(src, &format!("TRAORI needs the source's tool length ({}) active on the target", num(l)))
                } else {
                    self.line(src, "TRAFOOF")
                }
            }
            Canon::SetOrientationInterpolation { mode } => {
                let word = match mode {
                    stanok_canon::OrientationInterpolation::Axes => "ORIAXES",
                    stanok_canon::OrientationInterpolation::Vector => "ORIVECT",
                };
                if rs {
                    self.cannot(src, &format!("{word} (orientation interpolation) has no RS274/NGC form"))
                } else {
                    self.line(src, word)
                }
            }
            Canon::Mist { on } => self.coolant(src, Some(*on), None),
            Canon::Flood { on } => self.coolant(src, None, Some(*on)),
            Canon::SelectTool { tool } => self.line(src, &format!("T{tool}")),
            Canon::ChangeTool { tool, .. } => {
                let m = if rs { "M6" } else { "M06" };
                self.line(src, &format!("T{tool} {m}"))
            }
            Canon::ChangeSpindleTool { spindle, tool } => self.cannot(
                src,
                &format!("tool {tool} into spindle {spindle}: not converted"),
            ),
            Canon::AuxiliaryFunction { number, .. } => {
                if !rs && self.opts.source_dialect.eq_ignore_ascii_case("axioma") {
                    self.line(src, &format!("M{number}"))
                } else if !rs {
                    // Another control's machine function means nothing to an AxiOMA machine (and
                    // the generic profile refuses numbers outside its M-function table).
                    self.cannot(src, &format!("M{number} (a machine function of the {} control) has no AxiOMA meaning", self.opts.source_dialect))
                } else if (100..=199).contains(number) {
                    self.line(src, &format!("M{number}"));
                    self.cannot(src, &format!("M{number} needs LinuxCNC's user M-code program M{number} on the target"))
                } else {
                    self.cannot(src, &format!("M{number} (machine-specific function) has no RS274/NGC meaning"))
                }
            }
            Canon::Message { text } => {
                if rs {
                    self.out
                        .push_str(&format!("(MSG,{})\n", rs274_comment_text(text)));
                } else {
                    self.line(src, &format!("MSG(\"{}\")", axioma_text(text)))
                }
            }
            Canon::Log { action, text } => {
                if rs {
                    let t = rs274_comment_text(text);
                    let s = match action {
                        LogAction::Open => format!("(LOGOPEN,{t})"),
                        LogAction::Append => format!("(LOGAPPEND,{t})"),
                        LogAction::Close => "(LOGCLOSE)".into(),
                        LogAction::Write => format!("(LOG,{t})"),
                    };
                    self.out.push_str(&s);
                    self.out.push('\n');
                } else {
                    self.cannot(src, &format!("program log ({action:?} {text}) has no AxiOMA form"))
                }
            }
            // LinuxCNC's interpreter reports its own mode changes as comments: the target's
            // interpreter makes its own, so they are not program text.
            Canon::Comment { text } if text.starts_with("interpreter: ") => {}
            Canon::Comment { text } => self.comment(text),
            Canon::ProgramStop { optional } => {
                let m = match (rs, optional) {
                    (true, false) => "M0",
                    (true, true) => "M1",
                    (false, false) => "M00",
                    (false, true) => "M01",
                };
                self.line(src, m)
            }
            Canon::PalletShuttle => self.pending_pallet = true,
            Canon::ProgramEnd => {
                let m = match (rs, self.pending_pallet) {
                    (true, true) => "M30",
                    (true, false) => "M2",
                    (false, true) => "M30",
                    (false, false) => "M02",
                };
                self.pending_pallet = false;
                self.line(src, m);
                self.ended = true;
            }
            // `%` at the end: the converted program gets an explicit end in `finish`.
            Canon::Finish => {}
        }
    }

    /// M7/M8/M9: M9 stops both, so a single stop re-starts the other.
    fn coolant(&mut self, src: u32, mist: Option<bool>, flood: Option<bool>) {
        let (m0, f0) = (self.mist, self.flood);
        let m1 = mist.unwrap_or(m0);
        let f1 = flood.unwrap_or(f0);
        self.mist = m1;
        self.flood = f1;
        if m1 && !m0 {
            self.line(src, if self.rs274() { "M7" } else { "M07" });
        }
        if f1 && !f0 {
            self.line(src, if self.rs274() { "M8" } else { "M08" });
        }
        if (m0 && !m1) || (f0 && !f1) {
            self.line(src, if self.rs274() { "M9" } else { "M09" });
            if m1 {
                self.line(src, if self.rs274() { "M7" } else { "M07" });
            }
            if f1 {
                self.line(src, if self.rs274() { "M8" } else { "M08" });
            }
        }
    }
}
