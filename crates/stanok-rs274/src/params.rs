//! RS274/NGC parameters and expression evaluation.
//!
//! Storage follows LinuxCNC: numbered parameters `#1…#5601` live in one array, and the numbers
//! LinuxCNC gives a meaning (spec rs274ngc §3.2) are *stored* there exactly as LinuxCNC stores them,
//! lengths in the machine's length unit (LinuxCNC's "user units", [`Parameters::set_machine_units`]):
//! G28/G30 positions `#5161…#5189`, the G92 flag and offsets `#5210…#5219`, the active system
//! `#5220`, the G54…G59.3 table `#5221…#5390`, the loaded tool `#5400…#5413`. The interpreter writes
//! them when the event happens (G28.1, G92, G5x selection, M6, G10 …) and reads them when it needs
//! them (a G5x selection loads the table *then*, so a program's `#5221 = …` takes effect at the next
//! selection, as in LinuxCNC). `#5400…#5413` and `#5420…#5428` are read-only to programs, and
//! `#5420…#5428` (current position, program units) are computed on read from the live state.
//! Named parameters are local to the subroutine call level that created them (`#<name>`) or global
//! (`#<_name>`); names ignore case and spaces.
//!
//! The tool table lives here too: LinuxCNC's interpreter keeps it as data beside its parameters
//! (G10 L1 writes it, G43 and M6 read it). Both change only when a block commits: a block's writes
//! go through an undo journal ([`Parameters::begin_block`], `rollback`, `commit`).
//!
//! Evaluation is a recursive walk of the block's expression arena. Its depth is bounded by the
//! parser's bracket-nesting limit, so it cannot overflow the stack. Every domain error (division by
//! zero, `sqrt` of a negative, `acos` outside [−1, 1], unknown parameter …) is a diagnostic at the
//! offending sub-expression, with LinuxCNC's wording.

use crate::modal_context::SavedContext;
use crate::state::ModalState;
use crate::Rs274State;
use stanok_canon::setup::{ControlData, Tool, ToolTable};
use stanok_canon::{Diagnostic, LengthUnits, Pose, Span};
use stanok_interp_core::WordValues;
use stanok_syntax::{BinOp, Block, ColSpan, ExprId, ExprNode, ParamRef, UnaryFn};
use std::collections::HashMap;

/// Highest numbered parameter + 1 (LinuxCNC's RS274NGC_MAX_PARAMETERS).
pub const MAX_PARAMETERS: usize = 5602;

/// LinuxCNC's tolerance for `EQ`/`NE`.
const TOLERANCE_EQUAL: f64 = 0.0001;

/// Parameter storage and the tool table.
#[derive(Debug, Clone)]
pub struct Parameters {
    numbered: Vec<f64>,
    globals: HashMap<String, f64>,
    /// One map per subroutine call level; index 0 is the main program.
    locals: Vec<HashMap<String, f64>>,
    /// mm per machine length unit: the unit length parameters are stored in.
    unit_mm: f64,
    /// Inside a block: numbered writes are journalled (number, old value) for `rollback`.
    in_block: bool,
    journal: Vec<(usize, f64)>,
    tools: ToolTable,
    /// Old entries of the tools the block changed.
    tool_journal: Vec<(u32, Option<Tool>)>,
    /// G5.2 control points collected so far (program X Y Z mm, weight), with the order.
    nurbs: NurbsBuffer,
    /// The buffer as it was before the block first changed it (for `rollback`).
    nurbs_backup: Option<NurbsBuffer>,
    /// M70/M73 saved modal states, one slot per call level (parallel to `locals`).
    contexts: Vec<Option<SavedContext>>,
    /// `contexts` as it was before the block first changed it (for `rollback`).
    contexts_backup: Option<Vec<Option<SavedContext>>>,
}

/// The control points of an open G5.2 block.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NurbsBuffer {
    /// Order k = degree + 1.
    pub order: u32,
    /// Points (program coordinates, mm) and weights.
    pub points: Vec<([f64; 3], f64)>,
}

impl Default for Parameters {
    fn default() -> Self {
        let mut numbered = vec![0.0; MAX_PARAMETERS];
        numbered[5220] = 1.0;
        // (DEBUG,…) messages on (LinuxCNC).
        numbered[5599] = 1.0;
        Parameters {
            numbered,
            globals: HashMap::new(),
            locals: vec![HashMap::new()],
            unit_mm: 1.0,
            in_block: false,
            journal: Vec::new(),
            tools: ToolTable::default(),
            tool_journal: Vec::new(),
            nurbs: NurbsBuffer::default(),
            nurbs_backup: None,
            contexts: vec![None],
            contexts_backup: None,
        }
    }
}

/// Parameters read-only to programs (LinuxCNC: "Parameter is readonly"): the loaded tool
/// `#5400…#5413` and the current position `#5420…#5428`.
pub fn is_read_only(n: usize) -> bool {
    matches!(n, 5400..=5413 | 5420..=5428)
}

/// The axis index (X = 0 … W = 8) of a numbered parameter that holds a length or angle of an axis
/// in LinuxCNC's tables, if it is one: G28 `#5161…`, G30 `#5181…`, G92 `#5211…`, the G54…G59.3
/// systems, the loaded tool's offsets `#5401…`. (The probe result `#5061…` is in program units:
/// the probing issue writes it.)
fn axis_of(n: usize) -> Option<usize> {
    match n {
        5161..=5169 => Some(n - 5161),
        5181..=5189 => Some(n - 5181),
        5211..=5219 => Some(n - 5211),
        5221..=5390 => Some((n - 5221) % 20).filter(|&k| k < 9),
        5401..=5409 => Some(n - 5401),
        _ => None,
    }
}

/// True if parameter `n` holds a length (stored in machine units): the linear axes of the tables
/// above and the tool diameter `#5410`.
fn is_length(n: usize) -> bool {
    n == 5410 || axis_of(n).is_some_and(crate::ctx::is_linear)
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
    /// Also copies the tool table.
    pub fn preset_from(&mut self, c: &ControlData) {
        let o = &c.offsets;
        self.set_pose_mm(5161, &o.g28);
        self.set_pose_mm(5181, &o.g30);
        self.set(5210, if o.g92_applied { 1.0 } else { 0.0 });
        self.set_pose_mm(5211, &o.g92);
        self.set(5220, o.active_system.clamp(1, 9) as f64);
        for system in 1..=9u8 {
            if let Some(z) = o.zero_offset(system, 1) {
                let base = 5201 + 20 * system as usize;
                self.set_pose_mm(base, &z.offset);
                self.set(base + 9, z.rotation_xy);
            }
        }
        for (&n, &v) in &c.parameters {
            self.set(n as usize, v);
        }
        self.tools = c.tools.clone();
    }

    /// The stored control data as the run left it — what LinuxCNC writes back to its `.var` file
    /// and tool table: `template` (the data the run started from) with the G28/G30 positions, the
    /// G92 offsets and flag, the active system, page 1 of the G54…G59.3 table and the tool table
    /// replaced by their current values, and each of `template.parameters` by its current value.
    pub fn to_control(&self, template: &ControlData) -> ControlData {
        let mut c = template.clone();
        let o = &mut c.offsets;
        o.g28 = self.pose_mm(5161);
        o.g30 = self.pose_mm(5181);
        o.g92_applied = self.get(5210) != 0.0;
        o.g92 = self.pose_mm(5211);
        o.active_system = (self.get(5220).round() as u8).clamp(1, 9);
        for (s, pages) in o.zero.iter_mut().enumerate() {
            if let Some(z) = pages.first_mut() {
                let base = 5221 + 20 * s;
                z.offset = self.pose_mm(base);
                z.rotation_xy = self.get(base + 9);
            }
        }
        for (&n, v) in c.parameters.iter_mut() {
            *v = self.get(n as usize);
        }
        c.tools = self.tools.clone();
        c
    }

    /// The machine's length unit, in which length parameters are stored (LinuxCNC's user units,
    /// `[TRAJ]LINEAR_UNITS`). Set it before [`Parameters::preset_from`].
    pub fn set_machine_units(&mut self, units: LengthUnits) {
        self.unit_mm = units.mm_per_unit();
    }

    /// mm per machine length unit.
    pub fn machine_unit_mm(&self) -> f64 {
        self.unit_mm
    }

    /// Parameter `n` in mm (lengths) or degrees/as stored (everything else).
    pub fn get_mm(&self, n: usize) -> f64 {
        let v = self.get(n);
        if is_length(n) {
            v * self.unit_mm
        } else {
            v
        }
    }

    /// Stores `v` (mm for a length parameter) in parameter `n`.
    pub fn set_mm(&mut self, n: usize, v: f64) {
        let v = if is_length(n) { v / self.unit_mm } else { v };
        self.set(n, v);
    }

    /// Nine consecutive axis parameters from `base` (X at `base`) as a pose in mm/deg.
    pub fn pose_mm(&self, base: usize) -> Pose {
        let mut v = [0.0; 9];
        for (k, x) in v.iter_mut().enumerate() {
            *x = self.get_mm(base + k);
        }
        Pose::from_array(v)
    }

    /// Stores a pose (mm/deg) in the nine axis parameters from `base`.
    pub fn set_pose_mm(&mut self, base: usize, p: &Pose) {
        for (k, v) in p.to_array().into_iter().enumerate() {
            self.set_mm(base + k, v);
        }
    }

    /// The tool table.
    pub fn tools(&self) -> &ToolTable {
        &self.tools
    }

    /// Replaces (or adds) a tool's entry; undone by `rollback` inside a block.
    pub fn set_tool(&mut self, tool: Tool) {
        let old = self.tools.tools.insert(tool.number, tool.clone());
        if self.in_block {
            self.tool_journal.push((tool.number, old));
        }
    }

    /// LinuxCNC's slot of a tool: its 1-based position in the table (ordered by tool number).
    pub fn tool_slot(&self, number: u32) -> Option<u32> {
        self.tools
            .tools
            .keys()
            .position(|&t| t == number)
            .map(|i| i as u32 + 1)
    }

    /// Starts a block: from here numbered and tool-table writes can be undone.
    pub fn begin_block(&mut self) {
        self.in_block = true;
        self.journal.clear();
        self.tool_journal.clear();
    }

    /// The open G5.2 block's control points.
    pub fn nurbs(&self) -> &NurbsBuffer {
        &self.nurbs
    }

    /// The open G5.2 block's control points, to change (undone by `rollback`).
    pub fn nurbs_mut(&mut self) -> &mut NurbsBuffer {
        if self.in_block && self.nurbs_backup.is_none() {
            self.nurbs_backup = Some(self.nurbs.clone());
        }
        &mut self.nurbs
    }

    /// The block succeeded: keep its writes.
    pub fn commit(&mut self) {
        self.nurbs_backup = None;
        self.contexts_backup = None;
        self.in_block = false;
        self.journal.clear();
        self.tool_journal.clear();
    }

    /// The block failed: undo its writes.
    pub fn rollback(&mut self) {
        if let Some(b) = self.nurbs_backup.take() {
            self.nurbs = b;
        }
        if let Some(c) = self.contexts_backup.take() {
            self.contexts = c;
        }
        self.in_block = false;
        while let Some((n, v)) = self.journal.pop() {
            self.numbered[n] = v;
        }
        while let Some((number, old)) = self.tool_journal.pop() {
            match old {
                Some(t) => self.tools.tools.insert(number, t),
                None => self.tools.tools.remove(&number),
            };
        }
    }

    /// Raw numbered value (no live binding).
    pub fn get(&self, n: usize) -> f64 {
        self.numbered.get(n).copied().unwrap_or(0.0)
    }

    /// Sets a numbered value.
    pub fn set(&mut self, n: usize, v: f64) {
        if let Some(slot) = self.numbered.get_mut(n) {
            if self.in_block {
                self.journal.push((n, *slot));
            }
            *slot = v;
        }
    }

    /// Enters a subroutine: a fresh local scope.
    pub fn push_scope(&mut self) {
        self.locals.push(HashMap::new());
        self.contexts.push(None);
    }

    /// Leaves a subroutine; returns the modal state M73 asked to restore, if any.
    pub fn pop_scope(&mut self) -> Option<SavedContext> {
        if self.locals.len() > 1 {
            self.locals.pop();
            return self.contexts.pop().flatten().filter(|c| c.auto_restore);
        }
        None
    }

    /// The modal state M70/M73 saved at the current call level.
    pub fn context(&self) -> Option<SavedContext> {
        self.contexts.last().copied().flatten()
    }

    /// Saves (or with None forgets) the current level's modal state (undone by `rollback`).
    pub fn set_context(&mut self, c: Option<SavedContext>) {
        if self.in_block && self.contexts_backup.is_none() {
            self.contexts_backup = Some(self.contexts.clone());
        }
        if let Some(slot) = self.contexts.last_mut() {
            *slot = c;
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
            // LinuxCNC defines the return value of a subroutine, 0, before any call.
            self.globals
                .get(name)
                .copied()
                .or_else(|| matches!(name, "_value" | "_value_returned").then_some(0.0))
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
    /// RS274/NGC's own modes (named parameters `#<_…>` read them).
    pub modes: &'a Rs274State,
}

impl WordValues for Evaluator<'_> {
    #[inline(always)]
    fn expr(&self, _block: &Block, e: ExprId, _at: ColSpan) -> Result<f64, Diagnostic> {
        self.eval(e)
    }
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

    /// Resolves the target of an assignment `#n = …`: like [`Evaluator::slot`], and refuses the
    /// parameters LinuxCNC keeps read-only.
    pub fn assignment_slot(&self, p: &ParamRef, at: ExprId) -> Result<Slot, Diagnostic> {
        let slot = self.slot(p, at)?;
        if let Slot::Numbered(n) = slot {
            if is_read_only(n) {
                return Err(Diagnostic::error(
                    "rs274::parameter-read-only",
                    "Parameter is readonly",
                    self.span(at),
                )
                .with_note(format!(
                    "#{n} reflects the interpreter's state: {}",
                    if n < 5420 {
                        "the loaded tool (M6, G10 L1 change it)"
                    } else {
                        "the current position"
                    }
                )));
            }
        }
        Ok(slot)
    }

    /// Reads a parameter (with live bindings).
    pub fn read(&self, p: &ParamRef, at: ExprId) -> Result<f64, Diagnostic> {
        match self.slot(p, at)? {
            Slot::Numbered(n) => Ok(self.read_numbered(n)),
            Slot::Named { name, global } => match self.params_named(&name, global) {
                Some(v) => Ok(v),
                None if self.created_earlier_in_line(&name, global, at) => Ok(0.0),
                None => Err(Diagnostic::error(
                    "rs274::named-parameter-undefined",
                    format!("Named parameter #<{name}> not defined"),
                    self.span(at),
                )),
            },
        }
    }

    /// LinuxCNC creates a named parameter (unset, reading 0) as soon as it reads the name on the
    /// left of an assignment, before it reads the value: so `#<a> = [#<a> + 1]` with `#<a>`
    /// undefined gives 1, and a later reference in the same line reads 0 too; a reference before
    /// the assignment in the line is still an error.
    #[cold]
    fn created_earlier_in_line(&self, name: &str, global: bool, at: ExprId) -> bool {
        let here = self.block.expr_span(at).start;
        self.block.assignments.iter().any(|a| match a.target {
            ParamRef::Named { name: n, global: g } => {
                g == global && n.start < here && normalise_name(self.block.slice(n)) == name
            }
            ParamRef::Numbered(_) => false,
        })
    }

    /// A named parameter's value, if defined.
    pub fn params_named(&self, name: &str, global: bool) -> Option<f64> {
        if global && name.starts_with('_') {
            if let Some(v) = crate::predefined::predefined(
                name,
                self.state,
                self.modes,
                self.params,
                self.block.line,
            ) {
                return Some(v);
            }
        }
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
                Ok(crate::degrees::to_degrees(y.atan2(x)))
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
                crate::degrees::to_degrees(x.acos())
            }
            UnaryFn::Asin => {
                if !(-1.0..=1.0).contains(&x) {
                    return Err(self.domain(id, "Argument to asin out of range"));
                }
                crate::degrees::to_degrees(x.asin())
            }
            UnaryFn::Cos => crate::degrees::cos_deg(x),
            UnaryFn::Sin => crate::degrees::sin_deg(x),
            UnaryFn::Tan => crate::degrees::tan_deg(x),
            UnaryFn::Exp => x.exp(),
            UnaryFn::Fix => x.floor(),
            UnaryFn::Fup => x.ceil(),
            // LinuxCNC's `(int)(x ± 0.5)`: truncation after adding a half (0.49999999999999994
            // rounds to 1), and x86's 0x80000000 for what an int cannot hold.
            UnaryFn::Round => {
                let t = x + if x < 0.0 { -0.5 } else { 0.5 };
                if t > -2_147_483_649.0 && t < 2_147_483_648.0 {
                    t.trunc()
                } else {
                    -2_147_483_648.0
                }
            }
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
                    return Err(self.domain(id, "Attempt to raise negative to non integer power"));
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
                // LinuxCNC computes fmod(a, 0) = NaN and then refuses the NaN.
                if b == 0.0 {
                    return Err(self.domain(id, "Calculation resulted in 'not a number'"));
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
