//! Values of the word-address lab dialects (2P32, MC2101, GOST-20999): what a written number is
//! worth, variables, and the per-axis length/position correction binding of spec §4.8.

use super::LabState;
use crate::LabOptions;
use stanok_canon::{Diagnostic, Span};
use stanok_syntax::labs::words::{Number, Value, Word};
use stanok_syntax::Dialect;

/// mm per integer count of a dimension word without a decimal point: 0.001 mm (GOST-20999 §4.3,
/// 2P32 §3.3), 0.01 mm (MC2101 §3.10). With a point the value is mm.
pub fn count_mm(dialect: Dialect) -> f64 {
    match dialect {
        Dialect::Mc2101 => 0.01,
        _ => 0.001,
    }
}

/// A number in a dimension word (mm or degrees).
pub fn dimension(dialect: Dialect, n: Number) -> f64 {
    if n.point {
        n.value
    } else {
        n.value * count_mm(dialect)
    }
}

/// The number a word stands for: its own, or its variable's ([decide] §4.10: a variable keeps the
/// number as written, point included, and is scaled where it is used like a written number).
pub fn number(w: &Word, st: &LabState) -> Result<Number, Diagnostic> {
    match w.value {
        Some(Value::Number(n)) => Ok(n),
        Some(Value::Variable { number, negative }) => match st.variables.get(&number) {
            Some(&(v, point)) => Ok(Number {
                value: if negative { -v } else { v },
                point,
            }),
            None => Err(Diagnostic::error(
                "lab::unset-variable",
                format!("R{number} has no value"),
                w.span,
            )),
        },
        None => Err(Diagnostic::error(
            "lab::missing-value",
            format!("{} needs a value", w.letter),
            w.span,
        )),
    }
}

/// A word's value as an integer code (G, M, T, D, L, S).
pub fn code(w: &Word, st: &LabState) -> Result<i64, Diagnostic> {
    let n = number(w, st)?;
    if n.point || n.value.fract() != 0.0 || n.value.abs() > 1e9 {
        return Err(Diagnostic::error(
            "lab::not-an-integer",
            format!("{} takes an integer", w.letter),
            w.span,
        ));
    }
    Ok(n.value as i64)
}

/// Index in `Pose` order of an axis letter: X Y Z A B C U V W.
pub fn axis_index(letter: char) -> Option<usize> {
    "XYZABCUVW".find(letter)
}

/// The per-axis correction binding of one block (spec §4.8, [derived], reproduces Tables 8.1 and
/// 8.2): G43/G44 and D wait for the next axis word and bind to it; an axis keeps its mode and
/// corrector until rebound; D alone keeps the mode (G43 when there was none); G49 clears all.
/// A binding with no axis word after it in the block waits for the next block's first axis word
/// ([decide], "the first move programmed after").
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Pending {
    /// +1 after G43, −1 after G44.
    pub mode: Option<i8>,
    /// After D n.
    pub corrector: Option<u32>,
}

impl Pending {
    /// True when something waits for an axis word.
    pub fn is_some(&self) -> bool {
        self.mode.is_some() || self.corrector.is_some()
    }

    /// Binds the waiting G43/G44/D to `axis`.
    pub fn bind(&mut self, st: &mut LabState, axis: usize) {
        if !self.is_some() {
            return;
        }
        let (mode, corr) = st.axis_correction[axis];
        let mode = self.mode.unwrap_or(if mode != 0 { mode } else { 1 });
        st.axis_correction[axis] = (mode, self.corrector.or(corr));
        *self = Pending::default();
    }
}

/// The correction of `axis` in mm as its binding says (0 when off or without a corrector).
pub fn correction(st: &LabState, axis: usize, opts: &LabOptions) -> f64 {
    match st.axis_correction[axis] {
        (0, _) | (_, None) => 0.0,
        (m, Some(n)) => m as f64 * opts.labs.correctors.get(&n).copied().unwrap_or(0.0),
    }
}

/// An error of the word-address dialects.
pub fn err(code: &'static str, msg: impl Into<String>, at: Span) -> Diagnostic {
    Diagnostic::error(code, msg, at)
}
