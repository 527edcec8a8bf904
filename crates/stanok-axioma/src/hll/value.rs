//! Values of the AxiOMA high-level language and C's arithmetic on them.
//!
//! Semantics (C's, made safe): `int`/`long`/`bool` operands give integer arithmetic in 64 bits
//! (an `int` variable then checks that a stored value fits 32 bits); if either operand is
//! `double` the operation is floating. Integer `/` truncates toward zero and `%` takes the sign of
//! the dividend, as C99. Where C has undefined behaviour Stanok gives a diagnostic instead:
//! integer overflow, division or remainder by zero (also floating: a CNC value must never be
//! inf/NaN), shifts outside 0…63, `%` on doubles. Strings compare with `==` `!=` `<` … and join
//! with `+` (Stanok's offer; C has no string `+`); mixing a string with a number is a type error.

use stanok_syntax::hll::{HBinOp, HType, HUnOp};

/// One value.
#[derive(Debug, Clone, PartialEq)]
pub enum HVal {
    /// `int`, `long` (and integer literals).
    Int(i64),
    /// `double`.
    Double(f64),
    /// `bool`.
    Bool(bool),
    /// `string`.
    Str(String),
}

/// Longest string (the MSG limit, spec axioma-1 §4).
pub const MAX_STRING: usize = 256;

impl HVal {
    /// The zero of a type (C leaves uninitialised variables undefined; Stanok zeroes them).
    pub fn zero(ty: HType) -> HVal {
        match ty {
            HType::Int | HType::Long => HVal::Int(0),
            HType::Double => HVal::Double(0.0),
            HType::Bool => HVal::Bool(false),
            HType::String => HVal::Str(String::new()),
        }
    }

    /// The name of the value's kind in messages.
    pub fn kind(&self) -> &'static str {
        match self {
            HVal::Int(_) => "integer",
            HVal::Double(_) => "double",
            HVal::Bool(_) => "bool",
            HVal::Str(_) => "string",
        }
    }

    /// The number it is, for arithmetic, word values and conditions. None for strings.
    pub fn number(&self) -> Option<f64> {
        match *self {
            HVal::Int(i) => Some(i as f64),
            HVal::Double(d) => Some(d),
            HVal::Bool(b) => Some(b as i64 as f64),
            HVal::Str(_) => None,
        }
    }

    fn int(&self) -> Option<i64> {
        match *self {
            HVal::Int(i) => Some(i),
            HVal::Bool(b) => Some(b as i64),
            _ => None,
        }
    }

    /// C truth: nonzero. None for strings.
    pub fn truth(&self) -> Option<bool> {
        self.number().map(|v| v != 0.0)
    }

    /// Converts for storing in a variable of type `ty` (C's implicit conversions: double → int
    /// truncates toward zero). Err with the reason.
    pub fn convert(self, ty: HType) -> Result<HVal, String> {
        match (ty, self) {
            (HType::String, HVal::Str(s)) => {
                if s.chars().count() > MAX_STRING {
                    Err(format!("string longer than {MAX_STRING} characters"))
                } else {
                    Ok(HVal::Str(s))
                }
            }
            (HType::String, v) => Err(format!("a {} cannot be stored in a string", v.kind())),
            (_, HVal::Str(_)) => Err(format!("a string cannot be stored in a {}", ty.name())),
            (HType::Double, v) => Ok(HVal::Double(v.number().unwrap_or(0.0))),
            (HType::Bool, v) => Ok(HVal::Bool(v.truth().unwrap_or(false))),
            (HType::Int | HType::Long, v) => {
                let i = match v {
                    HVal::Double(d) => {
                        let t = d.trunc();
                        if !(-9.2e18..9.2e18).contains(&t) {
                            return Err(format!("{d} does not fit an integer"));
                        }
                        t as i64
                    }
                    v => v.int().unwrap_or(0),
                };
                if ty == HType::Int && i32::try_from(i).is_err() {
                    return Err(format!("{i} does not fit an int (32 bits)"));
                }
                Ok(HVal::Int(i))
            }
        }
    }
}

/// A unary operator.
pub fn unary(op: HUnOp, v: HVal) -> Result<HVal, String> {
    match (op, v) {
        (HUnOp::Not, v) => match v.truth() {
            Some(t) => Ok(HVal::Bool(!t)),
            None => Err("`!` needs a number or a bool, not a string".into()),
        },
        (_, HVal::Str(_)) => Err("a string has no sign".into()),
        (HUnOp::Plus, HVal::Bool(b)) => Ok(HVal::Int(b as i64)),
        (HUnOp::Plus, v) => Ok(v),
        (HUnOp::Neg, HVal::Double(d)) => Ok(HVal::Double(-d)),
        (HUnOp::Neg, v) => {
            let i = v.int().unwrap_or(0);
            i.checked_neg()
                .map(HVal::Int)
                .ok_or_else(|| "integer overflow".into())
        }
        (HUnOp::BitNot, HVal::Double(_)) => Err("`~` needs an integer".into()),
        (HUnOp::BitNot, v) => Ok(HVal::Int(!v.int().unwrap_or(0))),
    }
}

/// A binary operator other than `&&`/`||` (those short-circuit in the evaluator).
pub fn binary(op: HBinOp, a: HVal, b: HVal) -> Result<HVal, String> {
    use HBinOp::*;
    if let (HVal::Str(x), HVal::Str(y)) = (&a, &b) {
        return Ok(match op {
            Add => {
                let mut s = x.clone();
                s.push_str(y);
                HVal::Str(s)
            }
            Eq => HVal::Bool(x == y),
            Ne => HVal::Bool(x != y),
            Lt => HVal::Bool(x < y),
            Le => HVal::Bool(x <= y),
            Gt => HVal::Bool(x > y),
            Ge => HVal::Bool(x >= y),
            _ => return Err(format!("`{}` is not defined for strings", op.symbol())),
        });
    }
    if matches!(a, HVal::Str(_)) || matches!(b, HVal::Str(_)) {
        return Err(format!(
            "`{}` of a {} and a {}: type mismatch (use sprintf to put numbers into text)",
            op.symbol(),
            a.kind(),
            b.kind()
        ));
    }
    if let (Some(x), Some(y)) = (a.int(), b.int()) {
        let overflow = || "integer overflow".to_string();
        return Ok(match op {
            Add => HVal::Int(x.checked_add(y).ok_or_else(overflow)?),
            Sub => HVal::Int(x.checked_sub(y).ok_or_else(overflow)?),
            Mul => HVal::Int(x.checked_mul(y).ok_or_else(overflow)?),
            Div | Rem if y == 0 => return Err("division by zero".into()),
            Div => HVal::Int(x.checked_div(y).ok_or_else(overflow)?),
            Rem => HVal::Int(x.checked_rem(y).ok_or_else(overflow)?),
            Shl | Shr if !(0..64).contains(&y) => {
                return Err(format!("shift by {y}: only 0 … 63 is defined"))
            }
            Shl => HVal::Int(x.checked_shl(y as u32).ok_or_else(overflow)?),
            Shr => HVal::Int(x >> y),
            BitAnd => HVal::Int(x & y),
            BitOr => HVal::Int(x | y),
            BitXor => HVal::Int(x ^ y),
            Lt => HVal::Bool(x < y),
            Le => HVal::Bool(x <= y),
            Gt => HVal::Bool(x > y),
            Ge => HVal::Bool(x >= y),
            Eq => HVal::Bool(x == y),
            Ne => HVal::Bool(x != y),
            And => HVal::Bool(x != 0 && y != 0),
            Or => HVal::Bool(x != 0 || y != 0),
        });
    }
    let x = a.number().unwrap_or(0.0);
    let y = b.number().unwrap_or(0.0);
    let v = match op {
        Add => x + y,
        Sub => x - y,
        Mul => x * y,
        Div if y == 0.0 => return Err("division by zero".into()),
        Div => x / y,
        Rem | Shl | Shr | BitAnd | BitOr | BitXor => {
            return Err(format!(
                "`{}` needs integers (C does not define it for double)",
                op.symbol()
            ))
        }
        Lt => return Ok(HVal::Bool(x < y)),
        Le => return Ok(HVal::Bool(x <= y)),
        Gt => return Ok(HVal::Bool(x > y)),
        Ge => return Ok(HVal::Bool(x >= y)),
        Eq => return Ok(HVal::Bool(x == y)),
        Ne => return Ok(HVal::Bool(x != y)),
        And => return Ok(HVal::Bool(x != 0.0 && y != 0.0)),
        Or => return Ok(HVal::Bool(x != 0.0 || y != 0.0)),
    };
    finite(v)
}

/// A floating result, refused when it is not finite.
pub fn finite(v: f64) -> Result<HVal, String> {
    if v.is_finite() {
        Ok(HVal::Double(v))
    } else {
        Err("the result is not a finite number".into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c_integer_and_floating_semantics() {
        let i = HVal::Int;
        let d = HVal::Double;
        assert_eq!(binary(HBinOp::Div, i(7), i(2)), Ok(i(3)));
        assert_eq!(binary(HBinOp::Div, i(-7), i(2)), Ok(i(-3)));
        assert_eq!(binary(HBinOp::Rem, i(-7), i(2)), Ok(i(-1)));
        assert_eq!(binary(HBinOp::Div, i(7), d(2.0)), Ok(d(3.5)));
        assert!(binary(HBinOp::Div, i(1), i(0)).is_err());
        assert!(binary(HBinOp::Div, d(1.0), d(0.0)).is_err());
        assert!(binary(HBinOp::Rem, d(1.0), d(2.0)).is_err());
        assert!(binary(HBinOp::Add, i(i64::MAX), i(1)).is_err());
        assert_eq!(
            binary(HBinOp::Add, HVal::Str("a".into()), HVal::Str("b".into())),
            Ok(HVal::Str("ab".into()))
        );
        assert!(binary(HBinOp::Add, HVal::Str("a".into()), i(1)).is_err());
        assert_eq!(HVal::Double(-2.7).convert(HType::Int), Ok(i(-2)));
        assert!(HVal::Int(1 << 40).convert(HType::Int).is_err());
        assert_eq!(HVal::Int(1 << 40).convert(HType::Long), Ok(i(1 << 40)));
        assert_eq!(HVal::Int(3).convert(HType::Bool), Ok(HVal::Bool(true)));
    }
}
