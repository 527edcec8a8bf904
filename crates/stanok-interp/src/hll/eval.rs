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

use super::format::sprintf;
use super::value::{binary, finite, unary, HVal, MAX_STRING};
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
enum Undo {
    Var { var: usize, elem: usize, old: HVal },
    IPerm(u32, Option<i64>),
    DPerm(u32, Option<f64>),
    Zero(usize, usize, ZeroOffset),
    Wcs(usize, usize, WorkpieceFrame),
}

/// The variables, their scopes, and the journal.
#[derive(Debug, Clone, Default)]
pub struct Vars {
    list: Vec<Var>,
    scopes: Vec<usize>,
    journal: Vec<Undo>,
    /// Variables alive when the journal began (declarations are undone by truncation).
    journal_vars: usize,
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

    fn find(&self, name: &str) -> Option<usize> {
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
enum Place {
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
    fn err(&self, code: &'static str, msg: impl Into<String>, at: ColSpan) -> Diagnostic {
        Diagnostic::error(code, msg, self.block.span_of(at))
    }

    fn span(&self, e: HExprId) -> ColSpan {
        self.block.hll.expr_span(e)
    }

    fn name(&self, c: ColSpan) -> &str {
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
        match self.block.hll.expr(e) {
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

    fn arith_err(&self, m: String, at: ColSpan) -> Diagnostic {
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
    fn place(&mut self, e: HExprId) -> R<Place> {
        let at = self.span(e);
        match self.block.hll.expr(e) {
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
                match self.block.hll.expr(base) {
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

    fn read(&self, p: &Place) -> HVal {
        match *p {
            Place::Var(v, i) => self.vars.list[v].data[i].clone(),
            Place::IPerm(i) => HVal::Int(self.control.perm_int.get(&i).copied().unwrap_or(0)),
            Place::DPerm(i) => {
                HVal::Double(self.control.perm_double.get(&i).copied().unwrap_or(0.0))
            }
        }
    }

    /// Stores `v` (converted to the place's type) and returns what was stored.
    fn write(&mut self, p: &Place, v: HVal, at: ColSpan) -> R<HVal> {
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

    fn numbers(&mut self, args: &[HExprId], at: ColSpan, name: &str) -> R<Vec<f64>> {
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

    /// A built-in function. Names are matched without regard to case (`FTABLE`, `ftable`).
    fn call(&mut self, name: ColSpan, args: &[HExprId], at: ColSpan) -> R<HVal> {
        let fname = self.name(name).to_ascii_lowercase();
        let shown = self.name(name).to_string();
        let block = self.block;
        let arity = |n: std::ops::RangeInclusive<usize>| -> R<()> {
            if n.contains(&args.len()) {
                Ok(())
            } else {
                Err(Diagnostic::error(
                    "hll::arguments",
                    format!(
                        "`{}` takes {} argument{}, not {}",
                        shown,
                        if n.start() == n.end() {
                            n.start().to_string()
                        } else {
                            format!("{} … {}", n.start(), n.end())
                        },
                        if *n.end() == 1 { "" } else { "s" },
                        args.len()
                    ),
                    block.span_of(at),
                ))
            }
        };
        let domain = |env: &Self, ok: bool, what: &str| -> R<()> {
            if ok {
                Ok(())
            } else {
                Err(env.err("hll::domain", format!("`{fname}`: {what}"), at))
            }
        };
        let one = |env: &mut Self| -> R<f64> {
            arity(1..=1)?;
            Ok(env.numbers(args, at, &fname)?[0])
        };
        let v = match fname.as_str() {
            "sin" => one(self)?.to_radians().sin(),
            "cos" => one(self)?.to_radians().cos(),
            "tan" => {
                let x = one(self)?;
                domain(
                    self,
                    (x / 90.0 - 1.0).rem_euclid(2.0) != 0.0,
                    "tan(90° + k·180°) is infinite",
                )?;
                x.to_radians().tan()
            }
            "asin" | "acos" => {
                let x = one(self)?;
                domain(
                    self,
                    (-1.0..=1.0).contains(&x),
                    "the argument must be in −1 … 1",
                )?;
                if fname == "asin" {
                    x.asin().to_degrees()
                } else {
                    x.acos().to_degrees()
                }
            }
            "atan" => one(self)?.atan().to_degrees(),
            "atan2" => {
                arity(2..=2)?;
                let v = self.numbers(args, at, &fname)?;
                v[0].atan2(v[1]).to_degrees()
            }
            "sqrt" => {
                let x = one(self)?;
                domain(self, x >= 0.0, "negative argument")?;
                x.sqrt()
            }
            "exp" => one(self)?.exp(),
            "log" | "log10" => {
                let x = one(self)?;
                domain(self, x > 0.0, "the argument must be positive")?;
                if fname == "log" {
                    x.ln()
                } else {
                    x.log10()
                }
            }
            "pow" => {
                arity(2..=2)?;
                let v = self.numbers(args, at, &fname)?;
                v[0].powf(v[1])
            }
            "floor" => one(self)?.floor(),
            "ceil" => one(self)?.ceil(),
            // C's round: halves away from zero.
            "round" => one(self)?.round(),
            "trunc" => one(self)?.trunc(),
            "fabs" => one(self)?.abs(),
            "abs" => {
                arity(1..=1)?;
                let v = self.eval(args[0])?;
                return match v {
                    HVal::Int(i) => i
                        .checked_abs()
                        .map(HVal::Int)
                        .ok_or_else(|| self.err("hll::arithmetic", "integer overflow", at)),
                    HVal::Bool(b) => Ok(HVal::Int(b as i64)),
                    HVal::Double(d) => Ok(HVal::Double(d.abs())),
                    HVal::Str(_) => Err(self.err("hll::type-mismatch", "`abs` of a string", at)),
                };
            }
            "min" | "max" => {
                arity(2..=2)?;
                let a = self.eval(args[0])?;
                let b = self.eval(args[1])?;
                let less =
                    binary(HBinOp::Lt, a.clone(), b.clone()).map_err(|m| self.arith_err(m, at))?;
                let a_first = (less == HVal::Bool(true)) == (fname == "min");
                let (pick, other) = if a_first { (a, b) } else { (b, a) };
                // Mixed int/double: the result is double, as C's usual conversions.
                return Ok(match (pick, other) {
                    (HVal::Int(i), HVal::Double(_)) => HVal::Double(i as f64),
                    (p, _) => p,
                });
            }
            "ftable" | "stable" => {
                arity(1..=1)?;
                let i = self.eval(args[0])?;
                let table = if fname == "ftable" {
                    &self.machine.feed_table
                } else {
                    &self.machine.speed_table
                };
                return match i {
                    HVal::Int(i) if (0..128).contains(&i) && (i as usize) < table.len() => {
                        Ok(HVal::Double(table[i as usize]))
                    }
                    other => Err(self.err(
                        "axioma::table-index",
                        format!(
                            "{}({}): the table index is an integer 0 … 127",
                            fname.to_ascii_uppercase(),
                            match other {
                                HVal::Str(s) => format!("\"{s}\""),
                                v => v.number().unwrap_or(0.0).to_string(),
                            }
                        ),
                        at,
                    )),
                };
            }
            "strlen" => {
                arity(1..=1)?;
                return match self.eval(args[0])? {
                    HVal::Str(s) => Ok(HVal::Int(s.chars().count() as i64)),
                    v => Err(self.err(
                        "hll::type-mismatch",
                        format!("`strlen` of a {}", v.kind()),
                        at,
                    )),
                };
            }
            "sprintf" => return self.sprintf(args, at),
            "settable_zs" => return self.settable(args, at, true),
            "settable_wcs" => return self.settable(args, at, false),
            _ => {
                return Err(self.err(
                    "hll::unknown-function",
                    format!("unknown function `{}`", self.name(name)),
                    name,
                ))
            }
        };
        finite(v).map_err(|m| self.err("hll::domain", m, at))
    }

    /// `sprintf(str, format, args…)`: formats into the string variable `str`; returns the length.
    fn sprintf(&mut self, args: &[HExprId], at: ColSpan) -> R<HVal> {
        if args.len() < 2 {
            return Err(self.err(
                "hll::arguments",
                "`sprintf` takes a string variable, a format and its arguments",
                at,
            ));
        }
        let place = self.place(args[0])?;
        let fmt = match self.eval(args[1])? {
            HVal::Str(s) => s,
            v => {
                return Err(self.err(
                    "hll::type-mismatch",
                    format!("the format must be a string, not a {}", v.kind()),
                    self.span(args[1]),
                ))
            }
        };
        let mut values = Vec::with_capacity(args.len() - 2);
        for &a in &args[2..] {
            values.push(self.eval(a)?);
        }
        let text = sprintf(&fmt, &values).map_err(|m| self.err("hll::format", m, at))?;
        if text.chars().count() > MAX_STRING {
            return Err(self.err(
                "hll::string-length",
                format!("the result is longer than {MAX_STRING} characters"),
                at,
            ));
        }
        let len = text.chars().count() as i64;
        if !matches!(self.read(&place), HVal::Str(_)) {
            return Err(self.err(
                "hll::type-mismatch",
                "sprintf writes into a string variable",
                self.span(args[0]),
            ));
        }
        self.write(&place, HVal::Str(text), at)?;
        Ok(HVal::Int(len))
    }

    /// `settable_zs(g, page, x, y, z [, a, b, c])`: zero offset G54…G59 (`g` = 54…59) page 1…32;
    /// `settable_wcs(g, page, x, y, z, phi, theta, psi)`: workpiece system G154…G159 (`g` =
    /// 154…159), origin in machine mm and Euler angles ZY'Z'' in degrees. Values in mm/deg, not
    /// affected by G70/G71 (spec §9 [D]). The new values are read the next time the table entry
    /// is selected (G54…/G154… in a later block), like Sinumerik's settable frames.
    fn settable(&mut self, args: &[HExprId], at: ColSpan, zero: bool) -> R<HVal> {
        let (name, first, range) = if zero {
            ("settable_zs", 54.0, 5..=8)
        } else {
            ("settable_wcs", 154.0, 8..=8)
        };
        if !range.contains(&args.len()) {
            return Err(self.err(
                "hll::arguments",
                if zero {
                    "`settable_zs(g, page, x, y, z [, a, b, c])` takes 5 … 8 arguments"
                } else {
                    "`settable_wcs(g, page, x, y, z, phi, theta, psi)` takes 8 arguments"
                },
                at,
            ));
        }
        let v = self.numbers(args, at, name)?;
        let system = v[0] - first;
        if system.fract() != 0.0 || !(0.0..=5.0).contains(&system) {
            return Err(self.err(
                "hll::domain",
                format!(
                    "`{name}`: the table is G{} … G{}, not {}",
                    first,
                    first + 5.0,
                    v[0]
                ),
                self.span(args[0]),
            ));
        }
        if v[1].fract() != 0.0 || !(1.0..=32.0).contains(&v[1]) {
            return Err(self.err(
                "axioma::page-range",
                format!(
                    "`{name}`: page {} out of range: the tables have pages 1 to 32",
                    v[1]
                ),
                self.span(args[1]),
            ));
        }
        let (s, p) = (system as usize, v[1] as usize - 1);
        if zero {
            let old = self.control.offsets.zero[s][p];
            // X Y Z, then A B C when given (spec §9 [D]: one value per programmable coordinate).
            let mut axes = [0.0; 9];
            axes[..v.len() - 2].copy_from_slice(&v[2..]);
            let new = ZeroOffset {
                offset: stanok_canon::Pose::from_array(axes),
                rotation_xy: 0.0,
            };
            self.control.offsets.zero[s][p] = new;
            self.vars.journal.push(Undo::Zero(s, p, old));
        } else {
            let old = self.control.offsets.workpiece[s][p];
            self.control.offsets.workpiece[s][p] = WorkpieceFrame {
                origin: [v[2], v[3], v[4]],
                euler: [v[5], v[6], v[7]],
            };
            self.vars.journal.push(Undo::Wcs(s, p, old));
        }
        Ok(HVal::Int(0))
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
