//! Variables and expression evaluation of the AxiOMA high-level language.
//!
//! Variables live in one vector in declaration order; `scopes` holds the vector's length at each
//! open `{` (and `for`), so leaving a scope truncates it, and lookup searches from the end (the
//! innermost declaration wins, C's shadowing). A redeclaration in the same scope is an error.
//!
//! Every write — variables, `$iPerm`/`$dPerm`, `settable_zs`/`settable_wcs` — is journalled
//! (old value first) while a statement line or ISO block runs; if it fails the journal is undone,
//! so a failing statement leaves nothing executed (the same contract as RS274/NGC parameters).
//!
//! Unit convention of the math library: angles in degrees (sin, cos, tan take degrees; asin,
//! acos, atan, atan2 return degrees), as everywhere else in a part program.

use super::value::{binary, unary, HVal};
use crate::AxiomaMachineParams;
use stanok_canon::setup::{ControlData, WorkpieceFrame, ZeroOffset};
use stanok_canon::Diagnostic;
use stanok_syntax::hll::{HBinOp, HExpr, HExprId, HType};
use stanok_syntax::{Block, ColSpan};

/// Highest index of `$iPerm[n]` / `$dPerm[n]` (Stanok's choice: 0 … 999).
pub const PERM_LAST: i64 = 999;
/// Largest array a declaration may make.
pub const MAX_ARRAY: i64 = 100_000;
/// Most variables alive at once (bounds memory against a declaration inside a long loop).
pub const MAX_VARIABLES: usize = 100_000;

/// A declared variable.
#[derive(Debug, Clone)]
pub struct Var {
    name: String,
    ty: HType,
    array: bool,
    data: Vec<HVal>,
}

/// One undo record of the journal.
#[derive(Debug, Clone)]
pub(super) enum Undo {
    Var { var: usize, elem: usize, old: HVal },
    IPerm(u32, Option<i64>),
    DPerm(u32, Option<f64>),
    Zero(usize, usize, ZeroOffset),
    Wcs(usize, usize, WorkpieceFrame),
}

/// The variables, their scopes, and the journal.
#[derive(Clone, Default)]
pub struct Vars {
    list: Vec<Var>,
    scopes: Vec<usize>,
    pub(super) journal: Vec<Undo>,
    /// Variables alive when the journal began (declarations are undone by truncation).
    journal_vars: usize,
}

/// The variables and their scopes (the journal is the undo of the line being executed, not state).
impl std::fmt::Debug for Vars {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Vars")
            .field("list", &self.list)
            .field("scopes", &self.scopes)
            .finish()
    }
}

impl Vars {
    /// Opens a scope.
    pub fn push_scope(&mut self) {
        self.scopes.push(self.list.len());
    }

    /// Closes the innermost scope, dropping its variables.
    pub fn pop_scope(&mut self) {
        if let Some(n) = self.scopes.pop() {
            self.list.truncate(n);
        }
    }

    /// Starts journalling a statement line or block.
    pub fn begin(&mut self) {
        self.journal.clear();
        self.journal_vars = self.list.len();
    }

    /// Undoes everything since `begin` (variables, permanent parameters, tables).
    pub fn rollback(&mut self, control: &mut ControlData) {
        while let Some(u) = self.journal.pop() {
            match u {
                Undo::Var { var, elem, old } => {
                    if let Some(slot) = self.list.get_mut(var).and_then(|v| v.data.get_mut(elem)) {
                        *slot = old;
                    }
                }
                Undo::IPerm(i, old) => restore(&mut control.perm_int, i, old),
                Undo::DPerm(i, old) => restore(&mut control.perm_double, i, old),
                Undo::Zero(s, p, old) => control.offsets.zero[s][p] = old,
                Undo::Wcs(s, p, old) => control.offsets.workpiece[s][p] = old,
            }
        }
        self.list.truncate(self.journal_vars.min(self.list.len()));
    }

    /// Scope stack and variable count, to restore after a failing line (with `rollback`).
    pub fn scopes_snapshot(&self) -> Vec<usize> {
        self.scopes.clone()
    }

    /// Restores the scope stack of `scopes_snapshot`.
    pub fn restore_scopes(&mut self, scopes: Vec<usize>) {
        self.scopes = scopes;
    }

    pub(super) fn find(&self, name: &str) -> Option<usize> {
        self.list.iter().rposition(|v| v.name == name)
    }

    /// The value of a scalar variable (tests, reports).
    pub fn get(&self, name: &str) -> Option<&HVal> {
        let v = &self.list[self.find(name)?];
        if v.array {
            None
        } else {
            v.data.first()
        }
    }
}

fn restore<T>(map: &mut std::collections::BTreeMap<u32, T>, i: u32, old: Option<T>) {
    match old {
        Some(v) => {
            map.insert(i, v);
        }
        None => {
            map.remove(&i);
        }
    }
}

/// Where an assignment writes.
pub(super) enum Place {
    Var(usize, usize),
    IPerm(u32),
    DPerm(u32),
}

/// What an expression evaluates in: the line, the variables and the machine data.
pub struct Env<'a> {
    /// The line the expressions belong to.
    pub block: &'a Block,
    /// The variables.
    pub vars: &'a mut Vars,
    /// Stored control data ($iPerm, zero-offset and workpiece tables).
    pub control: &'a mut ControlData,
    /// FTABLE/STABLE.
    pub machine: &'a AxiomaMachineParams,
}

type R<T> = Result<T, Diagnostic>;

impl Env<'_> {
    pub(super) fn err(
        &self,
        code: &'static str,
        msg: impl Into<String>,
        at: ColSpan,
    ) -> Diagnostic {
        Diagnostic::error(code, msg, self.block.span_of(at))
    }

    pub(super) fn span(&self, e: HExprId) -> ColSpan {
        self.block.hll().expr_span(e)
    }

    pub(super) fn name(&self, c: ColSpan) -> &str {
        self.block.slice(c)
    }

    /// Declares a variable in the innermost scope.
    pub fn declare(&mut self, ty: HType, decl: &stanok_syntax::hll::HDecl) -> R<()> {
        use stanok_syntax::hll::HInit;
        let name = self.name(decl.name).to_string();
        let from = self.vars.scopes.last().copied().unwrap_or(0);
        if self.vars.list[from..].iter().any(|v| v.name == name) {
            return Err(self.err(
                "hll::redeclared",
                format!("`{name}` is already declared in this scope"),
                decl.name,
            ));
        }
        if self.vars.list.len() >= MAX_VARIABLES {
            return Err(self.err(
                "hll::too-many-variables",
                format!("more than {MAX_VARIABLES} variables alive"),
                decl.span,
            ));
        }
        let len = match decl.len {
            None => None,
            Some(e) => {
                let n = match self.eval(e)? {
                    HVal::Int(n) => n,
                    v => {
                        return Err(self.err(
                            "hll::type-mismatch",
                            format!("an array size must be an integer, not a {}", v.kind()),
                            self.span(e),
                        ))
                    }
                };
                if !(1..=MAX_ARRAY).contains(&n) {
                    return Err(self.err(
                        "hll::array-size",
                        format!("array size {n}: it must be 1 … {MAX_ARRAY}"),
                        self.span(e),
                    ));
                }
                Some(n as usize)
            }
        };
        let mut data = vec![HVal::zero(ty); len.unwrap_or(1)];
        match (&decl.init, len) {
            (HInit::None, _) => {}
            (HInit::Expr(e), None) => {
                let v = self.eval(*e)?;
                data[0] = v
                    .convert(ty)
                    .map_err(|m| self.err("hll::type-mismatch", m, self.span(*e)))?;
            }
            (HInit::List(list), Some(n)) if list.len() <= n => {
                for (slot, &e) in data.iter_mut().zip(list) {
                    let v = self.eval(e)?;
                    *slot = v
                        .convert(ty)
                        .map_err(|m| self.err("hll::type-mismatch", m, self.span(e)))?;
                }
            }
            (HInit::List(list), Some(n)) => {
                return Err(self.err(
                    "hll::index-range",
                    format!("{} initialisers for an array of {n}", list.len()),
                    decl.span,
                ))
            }
            _ => {
                return Err(self.err(
                    "hll::type-mismatch",
                    "an array is initialised with `{ … }`, a single variable with a value",
                    decl.span,
                ))
            }
        }
        self.vars.list.push(Var {
            name,
            ty,
            array: len.is_some(),
            data,
        });
        Ok(())
    }

    /// The value of a word (`X=<expr>`): a finite number.
    pub fn number(&mut self, e: HExprId) -> R<f64> {
        let v = self.eval(e)?;
        match v.number() {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(
                "hll::type-mismatch",
                format!("a word value must be a number, not a {}", v.kind()),
                self.span(e),
            )),
        }
    }

    /// A condition: a number or bool.
    pub fn truth(&mut self, e: HExprId) -> R<bool> {
        let v = self.eval(e)?;
        v.truth().ok_or_else(|| {
            self.err(
                "hll::type-mismatch",
                "a condition must be a number or a bool, not a string",
                self.span(e),
            )
        })
    }

    /// Evaluates an expression.
    pub fn eval(&mut self, e: HExprId) -> R<HVal> {
        let at = self.span(e);
        match self.block.hll().expr(e) {
            HExpr::Int(i) => Ok(HVal::Int(*i)),
            HExpr::Float(f) => Ok(HVal::Double(*f)),
            HExpr::Bool(b) => Ok(HVal::Bool(*b)),
            HExpr::Str(s) => Ok(HVal::Str(unescape(self.block.slice(*s)))),
            HExpr::Var(_) | HExpr::Index(..) | HExpr::System(_) => {
                let place = self.place(e)?;
                Ok(self.read(&place))
            }
            &HExpr::Unary(op, a) => {
                let v = self.eval(a)?;
                unary(op, v).map_err(|m| self.err("hll::type-mismatch", m, at))
            }
            &HExpr::Binary(op @ (HBinOp::And | HBinOp::Or), a, b) => {
                let x = self.truth(a)?;
                if x == (op == HBinOp::Or) {
                    return Ok(HVal::Bool(x));
                }
                Ok(HVal::Bool(self.truth(b)?))
            }
            &HExpr::Binary(op, a, b) => {
                let x = self.eval(a)?;
                let y = self.eval(b)?;
                binary(op, x, y).map_err(|m| self.arith_err(m, at))
            }
            &HExpr::Assign(op, target, value) => {
                let place = self.place(target)?;
                let v = self.eval(value)?;
                let v = match op {
                    None => v,
                    Some(op) => {
                        let old = self.read(&place);
                        binary(op, old, v).map_err(|m| self.arith_err(m, at))?
                    }
                };
                self.write(&place, v, at)
            }
            &HExpr::IncDec {
                inc,
                prefix,
                target,
            } => {
                let place = self.place(target)?;
                let old = self.read(&place);
                let step = if inc { HBinOp::Add } else { HBinOp::Sub };
                let new =
                    binary(step, old.clone(), HVal::Int(1)).map_err(|m| self.arith_err(m, at))?;
                let stored = self.write(&place, new, at)?;
                Ok(if prefix { stored } else { old })
            }
            &HExpr::Cond(c, a, b) => {
                if self.truth(c)? {
                    self.eval(a)
                } else {
                    self.eval(b)
                }
            }
            HExpr::Call(name, args) => {
                let name = *name;
                let args = args.clone();
                self.call(name, &args, at)
            }
        }
    }

    pub(super) fn arith_err(&self, m: String, at: ColSpan) -> Diagnostic {
        let code = if m.contains("division by zero") {
            "hll::division-by-zero"
        } else if m.contains("type mismatch") || m.contains("needs") || m.contains("string") {
            "hll::type-mismatch"
        } else {
            "hll::arithmetic"
        };
        self.err(code, m, at)
    }

    /// Resolves a variable, element or system variable.
    pub(super) fn place(&mut self, e: HExprId) -> R<Place> {
        let at = self.span(e);
        match self.block.hll().expr(e) {
            HExpr::Var(n) => {
                let name = self.name(*n);
                let Some(i) = self.vars.find(name) else {
                    return Err(self.err(
                        "hll::undeclared",
                        format!("`{name}` is not declared"),
                        at,
                    ));
                };
                if self.vars.list[i].array {
                    return Err(self.err(
                        "hll::type-mismatch",
                        format!("`{name}` is an array: index it, `{name}[i]`"),
                        at,
                    ));
                }
                Ok(Place::Var(i, 0))
            }
            &HExpr::Index(base, index) => {
                let i = self.eval(index)?;
                let HVal::Int(i) = i else {
                    return Err(self.err(
                        "hll::type-mismatch",
                        format!("an index must be an integer, not a {}", i.kind()),
                        self.span(index),
                    ));
                };
                match self.block.hll().expr(base) {
                    HExpr::Var(n) => {
                        let name = self.name(*n);
                        let Some(v) = self.vars.find(name) else {
                            return Err(self.err(
                                "hll::undeclared",
                                format!("`{name}` is not declared"),
                                self.span(base),
                            ));
                        };
                        let var = &self.vars.list[v];
                        if !var.array {
                            return Err(self.err(
                                "hll::type-mismatch",
                                format!("`{name}` is not an array"),
                                at,
                            ));
                        }
                        if i < 0 || i as usize >= var.data.len() {
                            return Err(self.err(
                                "hll::index-range",
                                format!(
                                    "index {i} out of range: `{name}` has {} elements (0 … {})",
                                    var.data.len(),
                                    var.data.len() - 1
                                ),
                                at,
                            ));
                        }
                        Ok(Place::Var(v, i as usize))
                    }
                    HExpr::System(n) => {
                        let name = self.name(*n);
                        let int = if name.eq_ignore_ascii_case("iPerm") {
                            true
                        } else if name.eq_ignore_ascii_case("dPerm") {
                            false
                        } else {
                            return Err(self.err(
                                "hll::undeclared",
                                format!(
                                    "unknown system variable `${name}` (known: $iPerm, $dPerm)"
                                ),
                                self.span(base),
                            ));
                        };
                        if !(0..=PERM_LAST).contains(&i) {
                            return Err(self.err(
                                "hll::index-range",
                                format!("`${name}[{i}]`: the index is 0 … {PERM_LAST}"),
                                at,
                            ));
                        }
                        Ok(if int {
                            Place::IPerm(i as u32)
                        } else {
                            Place::DPerm(i as u32)
                        })
                    }
                    _ => Err(self.err("hll::type-mismatch", "only arrays can be indexed", at)),
                }
            }
            HExpr::System(n) => Err(self.err(
                "hll::type-mismatch",
                format!("`${}` is an array: index it", self.name(*n)),
                at,
            )),
            _ => Err(self.err(
                "hll::not-assignable",
                "only a variable or an array element can be assigned to",
                at,
            )),
        }
    }

    pub(super) fn read(&self, p: &Place) -> HVal {
        match *p {
            Place::Var(v, i) => self.vars.list[v].data[i].clone(),
            Place::IPerm(i) => HVal::Int(self.control.perm_int.get(&i).copied().unwrap_or(0)),
            Place::DPerm(i) => {
                HVal::Double(self.control.perm_double.get(&i).copied().unwrap_or(0.0))
            }
        }
    }

    /// Stores `v` (converted to the place's type) and returns what was stored.
    pub(super) fn write(&mut self, p: &Place, v: HVal, at: ColSpan) -> R<HVal> {
        let ty = match *p {
            Place::Var(var, _) => self.vars.list[var].ty,
            Place::IPerm(_) => HType::Long,
            Place::DPerm(_) => HType::Double,
        };
        let v = v
            .convert(ty)
            .map_err(|m| self.err("hll::type-mismatch", m, at))?;
        match *p {
            Place::Var(var, elem) => {
                let slot = &mut self.vars.list[var].data[elem];
                let old = std::mem::replace(slot, v.clone());
                self.vars.journal.push(Undo::Var { var, elem, old });
            }
            Place::IPerm(i) => {
                let x = match v {
                    HVal::Int(x) => x,
                    _ => 0,
                };
                let old = self.control.perm_int.insert(i, x);
                self.vars.journal.push(Undo::IPerm(i, old));
            }
            Place::DPerm(i) => {
                let x = v.number().unwrap_or(0.0);
                let old = self.control.perm_double.insert(i, x);
                self.vars.journal.push(Undo::DPerm(i, old));
            }
        }
        Ok(v)
    }

    pub(super) fn numbers(&mut self, args: &[HExprId], at: ColSpan, name: &str) -> R<Vec<f64>> {
        let mut out = Vec::with_capacity(args.len());
        for &a in args {
            let v = self.eval(a)?;
            match v.number() {
                Some(x) => out.push(x),
                None => {
                    return Err(self.err(
                        "hll::type-mismatch",
                        format!("`{name}` takes numbers, not a string"),
                        self.span(a),
                    ))
                }
            }
        }
        let _ = at;
        Ok(out)
    }
}

/// Resolves C escapes of a string literal: `\"` `\\` `\n` `\t` `\r` `\0`; others keep the char.
fn unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some('0') => out.push('\0'),
            Some(o) => out.push(o),
            None => out.push('\\'),
        }
    }
    out
}
