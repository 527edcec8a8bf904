//! Expressions: a random tree over every operator and function of RS274/NGC, printed with the
//! brackets the precedence needs (and sometimes more), and evaluated here by LinuxCNC's rules so
//! that the generator keeps every value inside its function's domain and every coordinate finite
//! and bounded.
//!
//! ## Invariants
//! * [`Expr::value`] follows LinuxCNC 2.9's `execute_binary`/`execute_unary`: angles in degrees,
//!   `EQ`/`NE` with the tolerance 1e-6 … 1e-4 avoided (operands of a comparison are never that
//!   close unless equal), `MOD` as `fmod` made non-negative, `ROUND` half away from zero, `FIX`
//!   floor, `FUP` ceiling.
//! * A tree is only printed if every node's value is finite and inside `±1e6`, no division or
//!   `MOD` by (nearly) zero, no `SQRT`/`LN`/`ASIN`/`ACOS`/`**` outside its domain
//!   ([`Expr::valid`]); the generator draws again otherwise (a bounded number of times).

use crate::rng::Rng;

/// A binary operator, in LinuxCNC's precedence classes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

impl Op {
    const ALL: [Op; 15] = [
        Op::Pow,
        Op::Mul,
        Op::Div,
        Op::Mod,
        Op::Add,
        Op::Sub,
        Op::Eq,
        Op::Ne,
        Op::Gt,
        Op::Ge,
        Op::Lt,
        Op::Le,
        Op::And,
        Op::Or,
        Op::Xor,
    ];

    fn precedence(self) -> u8 {
        match self {
            Op::Pow => 4,
            Op::Mul | Op::Div | Op::Mod => 3,
            Op::Add | Op::Sub => 2,
            Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 1,
            Op::And | Op::Or | Op::Xor => 0,
        }
    }

    fn text(self) -> &'static str {
        match self {
            Op::Pow => "**",
            Op::Mul => "*",
            Op::Div => "/",
            Op::Mod => "MOD",
            Op::Add => "+",
            Op::Sub => "-",
            Op::Eq => "EQ",
            Op::Ne => "NE",
            Op::Gt => "GT",
            Op::Ge => "GE",
            Op::Lt => "LT",
            Op::Le => "LE",
            Op::And => "AND",
            Op::Or => "OR",
            Op::Xor => "XOR",
        }
    }
}

/// A unary function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Func {
    Abs,
    Acos,
    Asin,
    Cos,
    Exp,
    Fix,
    Fup,
    Round,
    Ln,
    Sin,
    Sqrt,
    Tan,
}

impl Func {
    const ALL: [Func; 12] = [
        Func::Abs,
        Func::Acos,
        Func::Asin,
        Func::Cos,
        Func::Exp,
        Func::Fix,
        Func::Fup,
        Func::Round,
        Func::Ln,
        Func::Sin,
        Func::Sqrt,
        Func::Tan,
    ];

    fn text(self) -> &'static str {
        match self {
            Func::Abs => "ABS",
            Func::Acos => "ACOS",
            Func::Asin => "ASIN",
            Func::Cos => "COS",
            Func::Exp => "EXP",
            Func::Fix => "FIX",
            Func::Fup => "FUP",
            Func::Round => "ROUND",
            Func::Ln => "LN",
            Func::Sin => "SIN",
            Func::Sqrt => "SQRT",
            Func::Tan => "TAN",
        }
    }
}

/// An expression tree.
#[derive(Clone, Debug)]
pub enum Expr {
    /// A number, printed as given.
    Num(f64, String),
    /// A parameter reference (`#1`, `#<name>`, `#<_x>`) with its known value.
    Param(String, f64),
    /// `#[expr]`: a numbered parameter chosen by an expression, with the parameter's value.
    Indirect(Box<Expr>, f64),
    Bin(Op, Box<Expr>, Box<Expr>),
    Call(Func, Box<Expr>),
    /// `ATAN[a]/[b]`.
    Atan(Box<Expr>, Box<Expr>),
    /// `EXISTS[#<name>]`, with whether it does.
    Exists(String, bool),
}

const LIMIT: f64 = 1e6;

impl Expr {
    /// The value by LinuxCNC's rules; None where LinuxCNC would stop with an error.
    pub fn value(&self) -> Option<f64> {
        let v = match self {
            Expr::Num(v, _) | Expr::Param(_, v) | Expr::Indirect(_, v) => *v,
            Expr::Exists(_, e) => f64::from(u8::from(*e)),
            Expr::Atan(a, b) => a.value()?.atan2(b.value()?).to_degrees(),
            Expr::Call(f, a) => {
                let a = a.value()?;
                match f {
                    Func::Abs => a.abs(),
                    Func::Acos if (-1.0..=1.0).contains(&a) => a.acos().to_degrees(),
                    Func::Asin if (-1.0..=1.0).contains(&a) => a.asin().to_degrees(),
                    Func::Acos | Func::Asin => return None,
                    Func::Cos => a.to_radians().cos(),
                    Func::Sin => a.to_radians().sin(),
                    Func::Tan => {
                        // Keep away from the poles, where the two sides' rounding could differ.
                        let c = a.to_radians().cos();
                        if c.abs() < 1e-3 {
                            return None;
                        }
                        a.to_radians().tan()
                    }
                    Func::Exp if a < 30.0 => a.exp(),
                    Func::Exp => return None,
                    Func::Fix => a.floor(),
                    Func::Fup => a.ceil(),
                    Func::Round => (a + if a < 0.0 { -0.5 } else { 0.5 }).trunc(),
                    Func::Ln if a > 1e-6 => a.ln(),
                    Func::Ln => return None,
                    Func::Sqrt if a >= 0.0 => a.sqrt(),
                    Func::Sqrt => return None,
                }
            }
            Expr::Bin(op, a, b) => {
                let (a, b) = (a.value()?, b.value()?);
                let close = (a - b).abs();
                if matches!(op, Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le)
                    && close > 0.0
                    && close < 1e-3
                {
                    // Too near the comparison's tolerance to be sure of LinuxCNC's answer.
                    return None;
                }
                let truth = |t: bool| f64::from(u8::from(t));
                match op {
                    Op::Pow => {
                        if (a < 0.0 && b.fract() != 0.0) || (a == 0.0 && b <= 0.0) {
                            return None;
                        }
                        a.powf(b)
                    }
                    Op::Mul => a * b,
                    Op::Div if b.abs() > 1e-3 => a / b,
                    Op::Mod if b.abs() > 1e-3 => {
                        let r = a % b;
                        if r < 0.0 {
                            r + b.abs()
                        } else {
                            r
                        }
                    }
                    Op::Div | Op::Mod => return None,
                    Op::Add => a + b,
                    Op::Sub => a - b,
                    Op::Eq => truth(a == b),
                    Op::Ne => truth(a != b),
                    Op::Gt => truth(a > b),
                    Op::Ge => truth(a >= b),
                    Op::Lt => truth(a < b),
                    Op::Le => truth(a <= b),
                    Op::And => truth(a != 0.0 && b != 0.0),
                    Op::Or => truth(a != 0.0 || b != 0.0),
                    Op::Xor => truth((a != 0.0) != (b != 0.0)),
                }
            }
        };
        (v.is_finite() && v.abs() < LIMIT).then_some(v)
    }

    /// True if LinuxCNC evaluates it without error and every intermediate value is bounded.
    pub fn valid(&self) -> bool {
        self.value().is_some()
    }

    fn precedence(&self) -> u8 {
        match self {
            Expr::Bin(op, ..) => op.precedence(),
            _ => 9,
        }
    }

    /// The text inside a word: numbers and parameters as they are, anything else in brackets.
    pub fn word_text(&self, rng: &mut Rng) -> String {
        match self {
            Expr::Num(_, t) => t.clone(),
            Expr::Param(p, _) => p.clone(),
            Expr::Bin(..) => format!("[{}]", self.inner(rng)),
            _ if rng.chance(0.5) => self.inner(rng),
            _ => format!("[{}]", self.inner(rng)),
        }
    }

    /// The text of the expression where a bracketed expression's inside is expected.
    pub fn inner(&self, rng: &mut Rng) -> String {
        match self {
            Expr::Num(_, t) => t.clone(),
            Expr::Param(p, _) => p.clone(),
            Expr::Indirect(e, _) => format!("#[{}]", e.inner(rng)),
            Expr::Exists(n, _) => format!("{}[{n}]", rng.case("EXISTS")),
            Expr::Atan(a, b) => {
                format!("{}[{}]/[{}]", rng.case("ATAN"), a.inner(rng), b.inner(rng))
            }
            Expr::Call(f, a) => format!("{}[{}]", rng.case(f.text()), a.inner(rng)),
            Expr::Bin(op, a, b) => {
                let p = op.precedence();
                // Left-associative: a left operand of the same class needs no brackets, a right
                // one does. Brackets are sometimes added where none are needed.
                let left = if a.precedence() < p || rng.chance(0.15) {
                    format!("[{}]", a.inner(rng))
                } else {
                    a.inner(rng)
                };
                let right = if b.precedence() <= p || rng.chance(0.15) {
                    format!("[{}]", b.inner(rng))
                } else {
                    b.inner(rng)
                };
                let sp = if rng.chance(0.8) { " " } else { "" };
                let op_text = rng.case(op.text());
                // Word operators need no space before a bracket, but do before a digit.
                let sp = if sp.is_empty() && op_text.chars().all(|c| c.is_ascii_alphabetic()) {
                    " "
                } else {
                    sp
                };
                format!("{left}{sp}{op_text}{sp}{right}")
            }
        }
    }
}

/// What an expression may refer to: parameters with their known values.
pub struct Scope<'a> {
    /// Readable parameters (`#1`, `#<name>`, `#<_x>` …) and their values.
    pub params: &'a [(String, f64)],
    /// Numbered parameters 1…30 that are set, with values (for `#[…]`).
    pub numbered: &'a [(u32, f64)],
    /// Named parameters whose existence `EXISTS` may test.
    pub names: &'a [String],
}

/// Draws an expression of at most `depth` levels (a leaf at depth 0); features used are noted.
pub fn random_expr(rng: &mut Rng, depth: u32, scope: &Scope, used: &mut Vec<&'static str>) -> Expr {
    if depth == 0 || rng.chance(0.25) {
        return leaf(rng, scope, used);
    }
    match rng.below(10) {
        0..=4 => {
            let op = *rng.pick(&Op::ALL);
            used.push(op_feature(op));
            let a = random_expr(rng, depth - 1, scope, used);
            let b = random_expr(rng, depth - 1, scope, used);
            Expr::Bin(op, Box::new(a), Box::new(b))
        }
        5..=7 => {
            let f = *rng.pick(&Func::ALL);
            used.push("expr: function");
            let a = random_expr(rng, depth - 1, scope, used);
            // Help the domain along: most arguments of ASIN/ACOS/LN/SQRT would be refused.
            let a = match f {
                Func::Asin | Func::Acos => Expr::Call(Func::Sin, Box::new(a)),
                Func::Ln | Func::Sqrt => Expr::Bin(
                    Op::Add,
                    Box::new(Expr::Call(Func::Abs, Box::new(a))),
                    Box::new(Expr::Num(1.0, "1".into())),
                ),
                _ => a,
            };
            Expr::Call(f, Box::new(a))
        }
        8 => {
            used.push("expr: ATAN[]/[]");
            let a = random_expr(rng, depth - 1, scope, used);
            let b = random_expr(rng, depth - 1, scope, used);
            Expr::Atan(Box::new(a), Box::new(b))
        }
        _ => {
            if !scope.names.is_empty() && rng.chance(0.5) {
                used.push("expr: EXISTS");
                let (n, e) = if rng.chance(0.7) {
                    (rng.pick(scope.names).clone(), true)
                } else {
                    ("#<nosuch>".to_string(), false)
                };
                Expr::Exists(n, e)
            } else if !scope.numbered.is_empty() {
                used.push("param: indirect #[]");
                let (n, v) = *rng.pick(scope.numbered);
                // #[a + b] with a + b = n.
                let k = rng.below(n as u64) as f64;
                let e = Expr::Bin(
                    Op::Add,
                    Box::new(Expr::Num(k, format!("{k}"))),
                    Box::new(Expr::Num(n as f64 - k, format!("{}", n as f64 - k))),
                );
                Expr::Indirect(Box::new(e), v)
            } else {
                leaf(rng, scope, used)
            }
        }
    }
}

fn leaf(rng: &mut Rng, scope: &Scope, used: &mut Vec<&'static str>) -> Expr {
    if !scope.params.is_empty() && rng.chance(0.4) {
        let (p, v) = rng.pick(scope.params).clone();
        used.push(if p.starts_with("#<_") {
            "param: read global/predefined"
        } else if p.starts_with("#<") {
            "param: read named local"
        } else {
            "param: read numbered"
        });
        return Expr::Param(p, v);
    }
    let v = rng.value(-20.0, 20.0);
    Expr::Num(v, rng.number_text(v))
}

fn op_feature(op: Op) -> &'static str {
    match op {
        Op::Pow => "expr: **",
        Op::Mul | Op::Div => "expr: * /",
        Op::Mod => "expr: MOD",
        Op::Add | Op::Sub => "expr: + -",
        Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => "expr: comparison",
        Op::And | Op::Or | Op::Xor => "expr: AND OR XOR",
    }
}
