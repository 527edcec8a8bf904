//! Fanuc custom macro B values and expressions (`docs/dialects/mazatrol-eia.md` §15).
//!
//! A value is `Option<f64>`: `None` is *vacant* (`#0`, a variable never assigned). Vacant follows
//! Fanuc's rules (§15.2): a plain reference keeps it vacant (`#2 = #1`), arithmetic and functions
//! count it as 0 (`#1 * 5` = 0, `-#1` = 0), `EQ`/`NE` tell vacant from 0, the other comparisons
//! count it as 0.
//!
//! Evaluation is one forward pass over the arena range of the expression: `stanok-syntax`'s
//! Mazatrol parser pushes every subtree as a contiguous range of the block's arena ending at its
//! root (children first), so `lowest(root)..=root` is exactly the expression and a node's children
//! are always evaluated before it. No recursion: an expression of any length evaluates in constant
//! stack.

use stanok_syntax::{BinOp, Block, ColSpan, ExprId, ExprNode, ParamRef, UnaryFn};

/// A macro value: a number or vacant.
pub type MVal = Option<f64>;

/// Largest magnitude a macro value may take (Fanuc: about 10^47); beyond it the calculation
/// overflows (`mazatrol::bad-argument`).
pub const MAX_MAGNITUDE: f64 = 1e47;

/// Why an expression could not be evaluated.
#[derive(Debug, Clone, PartialEq)]
pub struct EvalError {
    /// `mazatrol::…`.
    pub code: &'static str,
    /// What went wrong.
    pub message: String,
    /// Where in the block.
    pub span: ColSpan,
}

impl EvalError {
    /// An error at `span`.
    pub fn new(code: &'static str, message: impl Into<String>, span: ColSpan) -> Self {
        EvalError {
            code,
            message: message.into(),
            span,
        }
    }
}

/// Where variable values come from (the front end: locals, commons, system variables).
pub trait ReadVariable {
    /// The value of variable `number`; `at` is the reference's span (for errors).
    fn read(&self, number: u32, at: ColSpan) -> Result<MVal, EvalError>;
}

/// The lowest arena index of the expression rooted at `root` (following first children).
pub fn lowest(block: &Block, root: ExprId) -> usize {
    let mut id = root;
    loop {
        id = match *block.expr(id) {
            ExprNode::Unary(_, a) => a,
            ExprNode::Binary(_, l, _) | ExprNode::Atan(l, _) => l,
            ExprNode::Param(ParamRef::Numbered(i)) => i,
            _ => return id.0 as usize,
        };
    }
}

/// The variable number an index value designates: rounded to the nearest integer [F]; vacant,
/// negative or beyond `u32` is `mazatrol::variable-range`.
pub fn variable_number(v: MVal, at: ColSpan) -> Result<u32, EvalError> {
    match v {
        Some(x) if x.is_finite() && (-0.5..4_294_967_295.5).contains(&x) => Ok(x.round() as u32),
        Some(x) => Err(EvalError::new(
            "mazatrol::variable-range",
            format!("#{x} is not a variable of this control"),
            at,
        )),
        None => Err(EvalError::new(
            "mazatrol::variable-range",
            "the variable number is vacant",
            at,
        )),
    }
}

/// Evaluates the expression `root` of `block`. `scratch` is reused between calls.
pub fn eval(
    block: &Block,
    root: ExprId,
    vars: &dyn ReadVariable,
    scratch: &mut Vec<MVal>,
) -> Result<MVal, EvalError> {
    let lo = lowest(block, root);
    let hi = root.0 as usize;
    scratch.clear();
    for i in lo..=hi {
        let (node, span) = block.exprs[i];
        let get = |id: ExprId| scratch[id.0 as usize - lo];
        let v = match node {
            ExprNode::Number(v) => Some(v),
            ExprNode::Param(ParamRef::Numbered(index)) => {
                let n = variable_number(get(index), span)?;
                vars.read(n, span)?
            }
            ExprNode::Param(ParamRef::Named { .. }) | ExprNode::Exists(_) => {
                return Err(EvalError::new(
                    "mazatrol::variable-range",
                    "named parameters are not part of this language",
                    span,
                ))
            }
            ExprNode::Unary(f, a) => Some(unary(f, get(a).unwrap_or(0.0), span)?),
            ExprNode::Binary(op, l, r) => binary(op, get(l), get(r), span)?,
            ExprNode::Atan(y, x) => Some(atan(get(y).unwrap_or(0.0), get(x).unwrap_or(0.0), span)?),
        };
        if let Some(x) = v {
            check_magnitude(x, span)?;
        }
        scratch.push(v);
    }
    Ok(scratch[hi - lo])
}

fn check_magnitude(x: f64, span: ColSpan) -> Result<(), EvalError> {
    if !x.is_finite() || x.abs() > MAX_MAGNITUDE {
        return Err(EvalError::new(
            "mazatrol::bad-argument",
            "the calculation overflows (a value beyond 10^47)",
            span,
        ));
    }
    Ok(())
}

fn bad(message: String, span: ColSpan) -> EvalError {
    EvalError::new("mazatrol::bad-argument", message, span)
}

/// A function or sign of a number (vacant already counted as 0). Angles in degrees.
pub fn unary(f: UnaryFn, x: f64, span: ColSpan) -> Result<f64, EvalError> {
    let deg = |r: f64| r.to_degrees();
    Ok(match f {
        UnaryFn::Neg => -x,
        UnaryFn::Plus => x,
        UnaryFn::Sin => x.to_radians().sin(),
        UnaryFn::Cos => x.to_radians().cos(),
        UnaryFn::Tan => x.to_radians().tan(),
        UnaryFn::Asin | UnaryFn::Acos => {
            // A rounding hair outside ±1 is ±1.
            if x.abs() > 1.0 + 1e-12 {
                let name = if f == UnaryFn::Asin { "ASIN" } else { "ACOS" };
                return Err(bad(
                    format!("{name} of {x}: the argument is outside -1…1"),
                    span,
                ));
            }
            let x = x.clamp(-1.0, 1.0);
            if f == UnaryFn::Asin {
                deg(x.asin())
            } else {
                deg(x.acos())
            }
        }
        UnaryFn::Sqrt => {
            if x < 0.0 {
                return Err(bad(format!("SQRT of {x}: the argument is negative"), span));
            }
            x.sqrt()
        }
        UnaryFn::Abs => x.abs(),
        UnaryFn::Round => x.round(),
        UnaryFn::Fix => x.trunc(),
        UnaryFn::Fup => {
            if x.fract() == 0.0 {
                x
            } else {
                x.trunc() + x.signum()
            }
        }
        UnaryFn::Ln => {
            if x <= 0.0 {
                return Err(bad(
                    format!("LN of {x}: the argument is not positive"),
                    span,
                ));
            }
            x.ln()
        }
        UnaryFn::Exp => x.exp(),
    })
}

/// `ATAN[y]/[x]` in degrees, 0 ≤ angle < 360 [F].
pub fn atan(y: f64, x: f64, span: ColSpan) -> Result<f64, EvalError> {
    if y == 0.0 && x == 0.0 {
        return Err(bad("ATAN[0]/[0] has no angle".into(), span));
    }
    let a = y.atan2(x).to_degrees();
    Ok(if a < 0.0 { a + 360.0 } else { a })
}

/// Equality of two numbers, relative 1e-12 (printed decimals that are equal compare equal).
fn equal(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

/// The integer operand of AND / OR / XOR: a whole number 0 … 2³¹ − 1.
fn bits(v: f64, name: &str, span: ColSpan) -> Result<u32, EvalError> {
    if v.fract() != 0.0 || !(0.0..=2_147_483_647.0).contains(&v) {
        return Err(bad(
            format!("{name} needs whole numbers from 0 to 2147483647, not {v}"),
            span,
        ));
    }
    Ok(v as u32)
}

/// A binary operation with Fanuc's vacant rules.
pub fn binary(op: BinOp, l: MVal, r: MVal, span: ColSpan) -> Result<MVal, EvalError> {
    let truth = |b: bool| Some(if b { 1.0 } else { 0.0 });
    // EQ and NE see vacant; everything else counts it as 0.
    match op {
        BinOp::Eq | BinOp::Ne => {
            let same = match (l, r) {
                (None, None) => true,
                (Some(a), Some(b)) => equal(a, b),
                _ => false,
            };
            return Ok(truth(same == (op == BinOp::Eq)));
        }
        _ => {}
    }
    let (a, b) = (l.unwrap_or(0.0), r.unwrap_or(0.0));
    Ok(match op {
        BinOp::Add => Some(a + b),
        BinOp::Sub => Some(a - b),
        BinOp::Mul => Some(a * b),
        BinOp::Div | BinOp::Mod => {
            if b == 0.0 {
                return Err(EvalError::new(
                    "mazatrol::division-by-zero",
                    if op == BinOp::Div {
                        "division by zero".to_string()
                    } else {
                        "MOD by zero".to_string()
                    },
                    span,
                ));
            }
            if op == BinOp::Div {
                Some(a / b)
            } else {
                Some(a - b * (a / b).trunc())
            }
        }
        BinOp::Pow => Some(a.powf(b)),
        BinOp::Gt => truth(a > b && !equal(a, b)),
        BinOp::Ge => truth(a > b || equal(a, b)),
        BinOp::Lt => truth(a < b && !equal(a, b)),
        BinOp::Le => truth(a < b || equal(a, b)),
        BinOp::And | BinOp::Or | BinOp::Xor => {
            let name = match op {
                BinOp::And => "AND",
                BinOp::Or => "OR",
                _ => "XOR",
            };
            let (x, y) = (bits(a, name, span)?, bits(b, name, span)?);
            Some(f64::from(match op {
                BinOp::And => x & y,
                BinOp::Or => x | y,
                _ => x ^ y,
            }))
        }
        // Answered above with the vacant rule; numbers compare alike here.
        BinOp::Eq | BinOp::Ne => truth(equal(a, b) == (op == BinOp::Eq)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_syntax::{BlockParser, Dialect};

    /// Variables #1 = 2, #2 = vacant, #3 = 0, #10 = 10, everything else vacant.
    struct Vars;
    impl ReadVariable for Vars {
        fn read(&self, n: u32, _: ColSpan) -> Result<MVal, EvalError> {
            Ok(match n {
                1 => Some(2.0),
                3 => Some(0.0),
                10 => Some(10.0),
                _ => None,
            })
        }
    }

    /// The value of the right side of `#100 = <text>`.
    fn value(text: &str) -> Result<MVal, EvalError> {
        let mut p = BlockParser::new(Dialect::Mazatrol);
        let mut b = Block::default();
        let mut d = Vec::new();
        p.parse_line(&format!("#100 = {text}"), 1, 0, &mut b, &mut d);
        assert!(d.is_empty(), "{text}: {d:?}");
        eval(&b, b.assignments[0].value, &Vars, &mut Vec::new())
    }

    fn num(text: &str) -> f64 {
        value(text)
            .unwrap()
            .unwrap_or_else(|| panic!("{text} is vacant"))
    }

    fn err(text: &str) -> &'static str {
        value(text).unwrap_err().code
    }

    #[test]
    fn arithmetic_and_precedence() {
        assert_eq!(num("1 + 2 * 3"), 7.0);
        assert_eq!(num("[1 + 2] * 3"), 9.0);
        assert_eq!(num("10 - 4 - 3"), 3.0);
        assert_eq!(num("#1 * #10 / 4"), 5.0);
        assert_eq!(num("-#1 * 3"), -6.0);
        assert_eq!(num("7 MOD 3"), 1.0);
        assert_eq!(num("-7 MOD 3"), -1.0);
        assert_eq!(num("6 AND 3"), 2.0);
        assert_eq!(num("6 OR 3"), 7.0);
        assert_eq!(num("6 XOR 3"), 5.0);
        // Fanuc precedence: AND binds like *, so 1 + (2 AND 3) = 3.
        assert_eq!(num("1 + 2 AND 3"), 3.0);
        assert_eq!(num("#[#1 + 8]"), 10.0);
    }

    #[test]
    fn functions_in_degrees() {
        assert!((num("SIN[30]") - 0.5).abs() < 1e-15);
        assert!((num("COS[60]") - 0.5).abs() < 1e-15);
        assert!((num("TAN[45]") - 1.0).abs() < 1e-15);
        assert!((num("ASIN[0.5]") - 30.0).abs() < 1e-12);
        assert!((num("ACOS[0.5]") - 60.0).abs() < 1e-12);
        assert_eq!(num("ATAN[1]/[1]"), 45.0);
        assert_eq!(num("ATAN[-1, 0]"), 270.0);
        assert_eq!(num("ATAN[1, -1]"), 135.0);
        assert_eq!(num("SQRT[16]"), 4.0);
        assert_eq!(num("ABS[-2.5]"), 2.5);
        assert_eq!(num("ROUND[2.5]"), 3.0);
        assert_eq!(num("ROUND[-2.5]"), -3.0);
        assert_eq!(num("FIX[1.7]"), 1.0);
        assert_eq!(num("FIX[-1.7]"), -1.0);
        assert_eq!(num("FUP[1.2]"), 2.0);
        assert_eq!(num("FUP[-1.2]"), -2.0);
        assert_eq!(num("FUP[3]"), 3.0);
        assert!((num("LN[EXP[2]]") - 2.0).abs() < 1e-15);
    }

    #[test]
    fn vacant_follows_fanucs_table() {
        // #2 is vacant, #3 is 0.
        assert_eq!(value("#2").unwrap(), None);
        assert_eq!(value("[#2]").unwrap(), None);
        assert_eq!(value("#0").unwrap(), None);
        assert_eq!(num("#2 * 5"), 0.0);
        assert_eq!(num("#2 + #2"), 0.0);
        assert_eq!(num("-#2"), 0.0);
        assert_eq!(num("SIN[#2]"), 0.0);
        assert_eq!(num("#2 EQ #0"), 1.0);
        assert_eq!(num("#2 NE 0"), 1.0);
        assert_eq!(num("#3 EQ #0"), 0.0);
        assert_eq!(num("#3 NE 0"), 0.0);
        assert_eq!(num("#2 GE #0"), 1.0);
        assert_eq!(num("#2 GT 0"), 0.0);
        assert_eq!(num("#3 GE #0"), 1.0);
        assert_eq!(num("#3 LT 1"), 1.0);
    }

    #[test]
    fn errors() {
        assert_eq!(err("1 / 0"), "mazatrol::division-by-zero");
        assert_eq!(err("1 MOD #3"), "mazatrol::division-by-zero");
        assert_eq!(err("SQRT[-4]"), "mazatrol::bad-argument");
        assert_eq!(err("ASIN[2]"), "mazatrol::bad-argument");
        assert_eq!(err("LN[0]"), "mazatrol::bad-argument");
        assert_eq!(err("ATAN[0]/[0]"), "mazatrol::bad-argument");
        assert_eq!(err("1.5 AND 1"), "mazatrol::bad-argument");
        assert_eq!(err("EXP[200]"), "mazatrol::bad-argument");
        assert_eq!(err("#[#2]"), "mazatrol::variable-range");
        assert_eq!(err("#[-1]"), "mazatrol::variable-range");
        let e = value("SQRT[-4]").unwrap_err();
        assert_eq!(e.message, "SQRT of -4: the argument is negative");
    }

    #[test]
    fn a_long_chain_evaluates_in_constant_stack() {
        std::thread::Builder::new()
            .stack_size(128 * 1024)
            .spawn(|| assert_eq!(num(&format!("1{}", "+1".repeat(50_000))), 50_001.0))
            .unwrap()
            .join()
            .unwrap();
    }
}
