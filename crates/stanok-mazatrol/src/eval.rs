//! Reading and writing macro variables from a block (`docs/dialects/mazatrol-eia.md` §15): the
//! user variables of `vars.rs` and the system variables of `rules::sys_var`, and the values of a
//! block's words (a vacant word is dropped).

use crate::macro_b::{self, EvalError, MVal, ReadVariable};
use crate::modes::Modes;
use crate::rules::{sys_var, SysVar};
use crate::tables::Tables;
use crate::vars::{kind, Kind, Variables};
use crate::{MazatrolState, TtpcMode};
use stanok_canon::{Diagnostic, LengthUnits, Pose};
use stanok_interp_core::{ModalState, MotionMode, WordValues};
use stanok_syntax::{Block, ColSpan, ExprId};
use std::cell::RefCell;

/// Everything a variable read may look at.
pub struct Env<'a> {
    /// User variables.
    pub vars: &'a Variables,
    /// The dialect's modes.
    pub modes: &'a Modes,
    /// Tool tip control and length offset.
    pub ttpc: &'a MazatrolState,
    /// The common state.
    pub st: &'a ModalState,
    /// Tools and offsets.
    pub tables: &'a Tables,
    /// Scratch for the evaluator.
    pub scratch: &'a RefCell<Vec<MVal>>,
}

impl Env<'_> {
    /// mm → program units.
    fn units(&self, mm: f64) -> f64 {
        match self.st.units {
            LengthUnits::Inches => mm / 25.4,
            LengthUnits::Millimetres => mm,
        }
    }

    /// A position in program units (linear axes; X on the diameter on the T-series under G123.1).
    fn pos(&self, p: &Pose, axis: usize) -> f64 {
        let v = p.to_array()[axis];
        if (3..=5).contains(&axis) {
            return v;
        }
        let v = self.units(v);
        if axis == 0 && self.modes.t() && !self.modes.x_radius {
            2.0 * v
        } else {
            v
        }
    }

    /// The value of the expression `e` of `block`.
    pub fn value(&self, block: &Block, e: ExprId) -> Result<MVal, Diagnostic> {
        let mut scratch = self.scratch.borrow_mut();
        macro_b::eval(block, e, self, &mut scratch).map_err(|err| diag(block, err))
    }

    fn modal_g(&self, group: u32) -> MVal {
        let m = self.modes;
        let st = self.st;
        let v = match group {
            1 => match (m.cycle, st.motion) {
                (Some(c), _) => f64::from(c.code) / 10.0,
                (None, MotionMode::Linear) => 1.0,
                (None, MotionMode::ArcCw) => 2.0,
                (None, MotionMode::ArcCcw) => 3.0,
                _ => 0.0,
            },
            2 => match st.plane {
                _ if m.plane_zc => 16.0,
                stanok_canon::Plane::XY => 17.0,
                stanok_canon::Plane::ZX => 18.0,
                stanok_canon::Plane::YZ => 19.0,
            },
            3 => match st.distance {
                stanok_interp_core::DistanceMode::Absolute => 90.0,
                stanok_interp_core::DistanceMode::Incremental => 91.0,
            },
            4 => {
                if m.stroke_on {
                    22.0
                } else {
                    23.0
                }
            }
            5 => match st.feed_mode {
                stanok_canon::FeedMode::InverseTime => 93.0,
                stanok_canon::FeedMode::UnitsPerMinute => 94.0,
                stanok_canon::FeedMode::UnitsPerRevolution => 95.0,
            },
            6 => match st.units {
                LengthUnits::Inches => 20.0,
                LengthUnits::Millimetres => 21.0,
            },
            7 => match m.comp {
                crate::modes::CompMode::Off => 40.0,
                crate::modes::CompMode::Left => 41.0,
                crate::modes::CompMode::Right => 42.0,
                crate::modes::CompMode::Auto => 46.0,
            },
            8 => match (self.ttpc.mode, self.ttpc.offset) {
                (TtpcMode::Type1, _) => 43.4,
                (TtpcMode::Type2, _) => 43.5,
                (_, crate::tlo::LengthOffset::Plus) => 43.0,
                (_, crate::tlo::LengthOffset::Minus) => 44.0,
                _ => 49.0,
            },
            9 => {
                if m.cycle.is_some() {
                    f64::from(m.cycle.map_or(800, |c| c.code)) / 10.0
                } else {
                    80.0
                }
            }
            10 => {
                if m.return_initial {
                    98.0
                } else {
                    99.0
                }
            }
            11 => {
                if m.scaling.is_some() {
                    51.0
                } else {
                    50.0
                }
            }
            12 => match m.modal_call {
                Some(c) if c.every_block => 66.1,
                Some(_) => 66.0,
                None => 67.0,
            },
            13 => f64::from(m.path) / 10.0,
            14 => match m.work {
                crate::modes::WorkSystem::Standard(n) => 53.0 + f64::from(n),
                crate::modes::WorkSystem::Extra(_) => 54.1,
            },
            16 => {
                if m.rotation.is_some() || m.turret_mirror {
                    68.0
                } else {
                    69.0
                }
            }
            _ => return None,
        };
        Some(v)
    }
}

/// An evaluation error as a diagnostic of the block.
pub fn diag(block: &Block, e: EvalError) -> Diagnostic {
    Diagnostic::error(e.code, e.message, block.span_of(e.span))
}

impl ReadVariable for Env<'_> {
    fn read(&self, n: u32, at: ColSpan) -> Result<MVal, EvalError> {
        if let Some(k) = kind(n) {
            return Ok(self.vars.get(k));
        }
        let t = self.modes.t();
        let Some(sv) = sys_var(n, t) else {
            return Err(EvalError::new(
                "mazatrol::variable-range",
                format!("#{n} is not a variable of this control"),
                at,
            ));
        };
        let tools = &self.tables.data.tools;
        let edge = |tool: u32| tools.get(tool).and_then(|t| t.edges.first());
        let turning = |tool: u32| {
            tools.get(tool).is_some_and(|t| {
                matches!(
                    t.kind,
                    stanok_canon::setup::ToolKind::Turning
                        | stanok_canon::setup::ToolKind::Grinding
                )
            })
        };
        let st = self.st;
        Ok(match sv {
            SysVar::LengthWear(t) => Some(self.units(edge(t).map_or(0.0, |e| e.length_wear[0]))),
            SysVar::LengthGeometry(t) => Some(self.units(edge(t).map_or(0.0, |e| e.length[0]))),
            SysVar::RadiusWear(t) => Some(self.units(edge(t).map_or(0.0, |e| e.radius_wear))),
            SysVar::RadiusGeometry(t) => Some(self.units(edge(t).map_or(0.0, |e| e.radius))),
            SysVar::TurnWear(o, a) | SysVar::TurnGeometry(o, a) => {
                let wear = matches!(sv, SysVar::TurnWear(..));
                let Some(e) = edge(o) else {
                    return Ok(Some(0.0));
                };
                let (lx, lz) = if turning(o) { (0, 1) } else { (usize::MAX, 0) };
                let len = |i: usize| {
                    if i == usize::MAX {
                        0.0
                    } else if wear {
                        e.length_wear[i]
                    } else {
                        e.length[i]
                    }
                };
                Some(match a {
                    // X offsets are shown on the diameter, like X.
                    0 => 2.0 * self.units(len(lx)),
                    1 => self.units(len(lz)),
                    2 => self.units(if wear { e.radius_wear } else { e.radius }),
                    _ => f64::from(e.orientation),
                })
            }
            SysVar::Alarm | SysVar::Message | SysVar::SingleBlock | SysVar::FeedControl => {
                Some(0.0)
            }
            SysVar::Clock => {
                return Err(EvalError::new(
                    "mazatrol::not-simulated",
                    format!("#{n} (a clock) is not simulated: the interpreter has no time"),
                    at,
                ))
            }
            SysVar::ModalG(g) => self.modal_g(g),
            SysVar::Address(l) => {
                let i = b"BDFHMNOST".iter().position(|&c| c == l).unwrap_or(0);
                self.modes.last_address[i]
            }
            SysVar::BlockEnd(i) | SysVar::Current(i) => {
                let p = st.program_position();
                Some(self.pos(&p, i))
            }
            SysVar::Machine(i) => Some(self.pos(&st.position, i)),
            SysVar::Skip(i) => Some(self.modes.skip[i]),
            SysVar::ToolOffset(i) => Some(self.units(st.frame.tlo().to_array()[i])),
            SysVar::WorkOffset(s, i) => {
                let o = if s == 0 {
                    self.tables.external
                } else {
                    self.tables.work_offset(s, 1)
                };
                Some(if (3..=5).contains(&i) {
                    o[i]
                } else {
                    self.units(o[i])
                })
            }
            SysVar::ExtraOffset(p, i) => {
                let o = self.tables.extra_offset(p as u8);
                Some(if (3..=5).contains(&i) {
                    o[i]
                } else {
                    self.units(o[i])
                })
            }
        })
    }
}

impl WordValues for Env<'_> {
    fn expr(&self, block: &Block, e: ExprId, _at: ColSpan) -> Result<f64, Diagnostic> {
        Ok(self.value(block, e)?.unwrap_or(0.0))
    }

    fn expr_or_vacant(
        &self,
        block: &Block,
        e: ExprId,
        _at: ColSpan,
    ) -> Result<Option<f64>, Diagnostic> {
        self.value(block, e)
    }
}

/// Which user variable number `n` is, for a write: #0 and unknown numbers are refused.
pub fn writable(block: &Block, n: u32, at: ColSpan) -> Result<Option<Kind>, Diagnostic> {
    match kind(n) {
        Some(Kind::Vacant) => Err(Diagnostic::error(
            "mazatrol::read-only-variable",
            "#0 is always vacant and cannot be assigned",
            block.span_of(at),
        )),
        Some(k) => Ok(Some(k)),
        None => Ok(None),
    }
}
