//! RS274/NGC parameters and expression evaluation.
//!
//! Storage follows LinuxCNC: numbered parameters `#1…#5601` live in one array (the work-offset
//! tables `#5221…#5390` and the G92 offsets `#5211…#5219` are *stored* there, in mm, and are the
//! source of truth the interpreter reads when it selects a coordinate system); a few numbers are
//! computed on read from the live state (`#5220` active system, `#5400` tool in spindle,
//! `#5420…#5428` current position in program units). Named parameters are local to the subroutine
//! call level that created them (`#<name>`) or global (`#<_name>`); names ignore case and spaces.
//!
//! Evaluation is a recursive walk of the block's expression arena. Its depth is bounded by the
//! parser's bracket-nesting limit, so it cannot overflow the stack. Every domain error (division by
//! zero, `sqrt` of a negative, `acos` outside [−1, 1], unknown parameter …) is a diagnostic at the
//! offending sub-expression, with LinuxCNC's wording.

use crate::state::ModalState;
use stanok_canon::{Diagnostic, Span};
use stanok_syntax::{BinOp, Block, ExprId, ExprNode, ParamRef, UnaryFn};
use std::collections::HashMap;

/// Highest numbered parameter + 1 (LinuxCNC's RS274NGC_MAX_PARAMETERS).
pub const MAX_PARAMETERS: usize = 5602;

/// LinuxCNC's tolerance for `EQ`/`NE`.
const TOLERANCE_EQUAL: f64 = 0.0001;

/// Parameter storage.
#[derive(Debug, Clone)]
pub struct Parameters {
    numbered: Vec<f64>,
    globals: HashMap<String, f64>,
    /// One map per subroutine call level; index 0 is the main program.
    locals: Vec<HashMap<String, f64>>,
}

impl Default for Parameters {
    fn default() -> Self {
        let mut numbered = vec![0.0; MAX_PARAMETERS];
        numbered[5220] = 1.0;
        Parameters {
            numbered,
            globals: HashMap::new(),
            locals: vec![HashMap::new()],
        }
    }
}

/// A parameter resolved to its storage slot, ready to be written.
#[derive(Debug, Clone, PartialEq)]
pub enum Slot {
    /// `#n`.
    Numbered(usize),
    /// `#<name>` (normalised), global or local.
    Named {
        /// Lower case, no spaces.
        name: String,
        /// `#<_name>`.
        global: bool,
    },
}

/// Lower case, spaces removed: LinuxCNC's name normalisation.
pub fn normalise_name(raw: &str) -> String {
    raw.chars()
        .filter(|c| !c.is_whitespace())
        .flat_map(|c| c.to_lowercase())
        .collect()
}

impl Parameters {
    /// Loads the stored control data into the numbered parameters, as LinuxCNC reads its `.var`
    /// file: G28 5161…, G30 5181…, G92 5210…5219, active system 5220, G54…G59.3 5221…5390 (page 1,
    /// with the rotation in the tenth slot), then the preset parameters.
    pub fn preset_from(&mut self, c: &stanok_canon::setup::ControlData) {
        let o = &c.offsets;
        for (k, v) in o.g28.to_array().into_iter().enumerate() {
            self.set(5161 + k, v);
        }
        for (k, v) in o.g30.to_array().into_iter().enumerate() {
            self.set(5181 + k, v);
        }
        self.set(5210, if o.g92_applied { 1.0 } else { 0.0 });
        for (k, v) in o.g92.to_array().into_iter().enumerate() {
            self.set(5211 + k, v);
        }
        self.set(5220, o.active_system.clamp(1, 9) as f64);
        for system in 1..=9u8 {
            if let Some(z) = o.zero_offset(system, 1) {
                let base = 5201 + 20 * system as usize;
                for (k, v) in z.offset.to_array().into_iter().enumerate() {
                    self.set(base + k, v);
                }
                self.set(base + 9, z.rotation_xy);
            }
        }
        for (&n, &v) in &c.parameters {
            self.set(n as usize, v);
        }
    }

    /// Raw numbered value (no live binding).
    pub fn get(&self, n: usize) -> f64 {
        self.numbered.get(n).copied().unwrap_or(0.0)
    }

    /// Sets a numbered value.
    pub fn set(&mut self, n: usize, v: f64) {
        if let Some(slot) = self.numbered.get_mut(n) {
            *slot = v;
        }
    }

    /// Enters a subroutine: a fresh local scope.
    pub fn push_scope(&mut self) {
        self.locals.push(HashMap::new());
    }

    /// Leaves a subroutine.
    pub fn pop_scope(&mut self) {
        if self.locals.len() > 1 {
            self.locals.pop();
        }
    }

    /// Writes a resolved slot.
    pub fn write(&mut self, slot: &Slot, v: f64) {
        match slot {
            Slot::Numbered(n) => self.set(*n, v),
            Slot::Named { name, global: true } => {
                self.globals.insert(name.clone(), v);
            }
            Slot::Named {
                name,
                global: false,
            } => {
                if let Some(scope) = self.locals.last_mut() {
                    scope.insert(name.clone(), v);
                }
            }
        }
    }

    fn named(&self, name: &str, global: bool) -> Option<f64> {
        if global {
            self.globals.get(name).copied()
        } else {
            self.locals.last().and_then(|s| s.get(name).copied())
        }
    }
}

/// Evaluates expressions of one block against the parameters and the live state.
pub struct Evaluator<'a> {
    /// The block whose arena holds the expressions.
    pub block: &'a Block,
    /// Parameter storage (read only: assignments are applied after the whole line is read).
    pub params: &'a Parameters,
    /// Live state for the bound parameters.
    pub state: &'a ModalState,
}

impl Evaluator<'_> {
    fn span(&self, id: ExprId) -> Span {
        self.block.span_of(self.block.expr_span(id))
    }

    /// Resolves a parameter reference to a writable slot.
    pub fn slot(&self, p: &ParamRef, at: ExprId) -> Result<Slot, Diagnostic> {
        match p {
            ParamRef::Numbered(e) => {
                let v = self.eval(*e)?;
                let n = v.round();
                if (v - n).abs() > 1e-6 || n < 1.0 || n >= MAX_PARAMETERS as f64 {
                    return Err(Diagnostic::error(
                        "rs274::parameter-number-out-of-range",
                        format!("Parameter number out of range: #{v}"),
                        self.span(at),
                    )
                    .with_note(format!(
                        "numbered parameters are #1 … #{}",
                        MAX_PARAMETERS - 1
                    )));
                }
                Ok(Slot::Numbered(n as usize))
            }
            ParamRef::Named { name, global } => Ok(Slot::Named {
                name: normalise_name(self.block.slice(*name)),
                global: *global,
            }),
        }
    }

    /// Reads a parameter (with live bindings).
    pub fn read(&self, p: &ParamRef, at: ExprId) -> Result<f64, Diagnostic> {
        match self.slot(p, at)? {
            Slot::Numbered(n) => Ok(self.read_numbered(n)),
            Slot::Named { name, global } => self.params.named(&name, global).ok_or_else(|| {
                Diagnostic::error(
                    "rs274::named-parameter-undefined",
                    format!("Named parameter #<{name}> not defined"),
                    self.span(at),
                )
            }),
        }
    }

    /// A named parameter's value, if defined.
    pub fn params_named(&self, name: &str, global: bool) -> Option<f64> {
        self.params.named(name, global)
    }

    /// A numbered parameter's value with live bindings (0 outside the range).
    pub fn numbered(&self, n: usize) -> f64 {
        if n == 0 || n >= MAX_PARAMETERS {
            return 0.0;
        }
        self.read_numbered(n)
    }

    fn read_numbered(&self, n: usize) -> f64 {
        let st = self.state;
        let units = st.units.mm_per_unit();
        match n {
            5220 => st.g5x_index.max(1) as f64,
            5400 => st.current_tool as f64,
            5420..=5428 => {
                let p = st.program_position().to_array();
                let i = n - 5420;
                if matches!(i, 3..=5) {
                    p[i]
                } else {
                    p[i] / units
                }
            }
            _ => self.params.get(n),
        }
    }

    /// Evaluates an expression node.
    pub fn eval(&self, id: ExprId) -> Result<f64, Diagnostic> {
        match *self.block.expr(id) {
            ExprNode::Number(v) => Ok(v),
            ExprNode::Param(ref p) => self.read(p, id),
            ExprNode::Exists(ref p) => match p {
                ParamRef::Named { name, global } => {
                    let name = normalise_name(self.block.slice(*name));
                    Ok(if self.params.named(&name, *global).is_some() {
                        1.0
                    } else {
                        0.0
                    })
                }
                ParamRef::Numbered(_) => Ok(1.0),
            },
            ExprNode::Unary(f, arg) => {
                let x = self.eval(arg)?;
                self.unary(f, x, id)
            }
            ExprNode::Atan(y, x) => {
                let (y, x) = (self.eval(y)?, self.eval(x)?);
                Ok(y.atan2(x).to_degrees())
            }
            ExprNode::Binary(op, l, r) => {
                let a = self.eval(l)?;
                let b = self.eval(r)?;
                self.binary(op, a, b, id)
            }
        }
    }

    fn domain(&self, id: ExprId, msg: &str) -> Diagnostic {
        Diagnostic::error("rs274::expression-domain", msg.to_string(), self.span(id))
    }

    fn unary(&self, f: UnaryFn, x: f64, id: ExprId) -> Result<f64, Diagnostic> {
        Ok(match f {
            UnaryFn::Abs => x.abs(),
            UnaryFn::Acos => {
                if !(-1.0..=1.0).contains(&x) {
                    return Err(self.domain(id, "Argument to acos out of range"));
                }
                x.acos().to_degrees()
            }
            UnaryFn::Asin => {
                if !(-1.0..=1.0).contains(&x) {
                    return Err(self.domain(id, "Argument to asin out of range"));
                }
                x.asin().to_degrees()
            }
            UnaryFn::Cos => x.to_radians().cos(),
            UnaryFn::Sin => x.to_radians().sin(),
            UnaryFn::Tan => x.to_radians().tan(),
            UnaryFn::Exp => x.exp(),
            UnaryFn::Fix => x.floor(),
            UnaryFn::Fup => x.ceil(),
            UnaryFn::Round => x.round(),
            UnaryFn::Ln => {
                if x <= 0.0 {
                    return Err(self.domain(id, "Zero or negative argument to ln"));
                }
                x.ln()
            }
            UnaryFn::Sqrt => {
                if x < 0.0 {
                    return Err(self.domain(id, "Negative argument to sqrt"));
                }
                x.sqrt()
            }
            UnaryFn::Neg => -x,
            UnaryFn::Plus => x,
        })
    }

    fn binary(&self, op: BinOp, a: f64, b: f64, id: ExprId) -> Result<f64, Diagnostic> {
        let truth = |c: bool| if c { 1.0 } else { 0.0 };
        Ok(match op {
            BinOp::Pow => {
                if a < 0.0 && b.fract() != 0.0 {
                    return Err(self.domain(id, "Attempt to raise negative to non-integer power"));
                }
                a.powf(b)
            }
            BinOp::Mul => a * b,
            BinOp::Div => {
                if b == 0.0 {
                    return Err(self.domain(id, "Attempt to divide by zero"));
                }
                a / b
            }
            BinOp::Mod => {
                if b == 0.0 {
                    return Err(self.domain(id, "Attempt to divide by zero"));
                }
                let r = a % b;
                if r < 0.0 {
                    r + b.abs()
                } else {
                    r
                }
            }
            BinOp::Add => a + b,
            BinOp::Sub => a - b,
            BinOp::Eq => truth((a - b).abs() < TOLERANCE_EQUAL),
            BinOp::Ne => truth((a - b).abs() >= TOLERANCE_EQUAL),
            BinOp::Gt => truth(a > b),
            BinOp::Ge => truth(a >= b),
            BinOp::Lt => truth(a < b),
            BinOp::Le => truth(a <= b),
            BinOp::And => truth(a != 0.0 && b != 0.0),
            BinOp::Or => truth(a != 0.0 || b != 0.0),
            BinOp::Xor => truth((a != 0.0) != (b != 0.0)),
        })
    }
}
