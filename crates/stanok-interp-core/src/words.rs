//! STEP 2 of a block (grbl's "import words"): the words of a parsed block, their values evaluated,
//! sorted into G codes, M codes and letter slots, with the span of each so that later checks can
//! point at the word that is wrong.
//!
//! Invariant: after `Words::fill` succeeds every letter appears at most once (a front end's
//! [`WordRules`] say what a repeated letter is: refused, as RS274/NGC does, or the last one kept
//! with a warning, as AxiOMA's manual says; one letter may keep its second word as an extra word).
//! `used` records which letters a function consumed, so that a word nothing consumed is reported
//! instead of ignored.
//!
//! The values of expression words come from the front end ([`WordValues`]): the core reads
//! numbers, the front end evaluates its own expression languages (RS274/NGC parameters and
//! expressions, AxiOMA's high-level language).

use stanok_canon::Diagnostic;
use stanok_syntax::{Address, Block, ColSpan, ExprId, Keyword, Value};

/// One evaluated value and the word it came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Val {
    /// Value as written (program units, not yet converted).
    pub v: f64,
    /// The word.
    pub span: ColSpan,
}

/// The evaluated words of one block.
#[derive(Debug)]
pub struct Words {
    /// G codes ×10 (`G91.1` → 911), in written order.
    pub g: Vec<(u32, ColSpan)>,
    /// M codes, in written order.
    pub m: Vec<(u32, ColSpan)>,
    /// Single-letter words other than G, M (`letter[b'X' - b'A']`), valid where `present` has the bit.
    letter: [Val; 29],
    /// Letters written in this block (bit i = letter `A + i`).
    present: u32,
    /// Letters a function has consumed.
    used: u32,
    /// Extended addresses (AxiOMA `S2=1000` → (b'S', 2, 1000)).
    pub indexed: Vec<(u8, u8, Val)>,
    /// Keywords with their index and value (AxiOMA `CR=`, Balt-System `CVU=` …).
    pub keywords: Vec<(Keyword, Option<u8>, Option<Val>, ColSpan)>,
    /// The second word of the letter [`WordRules::second_word`] names (Mazatrol `T01 T02 M6`: the
    /// tool prepared next).
    pub second: Option<Val>,
}

/// What a repeated letter means in a dialect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Repeated {
    /// An error with this code ("Multiple X words on one line", LinuxCNC's wording).
    Refuse(&'static str),
    /// The last word takes effect; a warning with this code names the earlier one.
    LastWins(&'static str),
}

/// A front end's rules for sorting a block's words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WordRules {
    /// A letter written twice.
    pub repeated: Repeated,
    /// A letter whose second word is kept in [`Words::second`] instead of being a repeat.
    pub second_word: Option<u8>,
}

/// The values of a block's expression words, as the front end evaluates them.
pub trait WordValues {
    /// The value of `Value::Expr` (the block's expression arena).
    fn expr(&self, block: &Block, e: ExprId, at: ColSpan) -> Result<f64, Diagnostic>;
    /// The value of `Value::Expr`, or None when the expression has no value and the word is
    /// dropped as if not written (Fanuc's vacant variable, Mazatrol EIA/ISO).
    #[inline(always)]
    fn expr_or_vacant(
        &self,
        block: &Block,
        e: ExprId,
        at: ColSpan,
    ) -> Result<Option<f64>, Diagnostic> {
        self.expr(block, e, at).map(Some)
    }

    /// The value of `Value::Hll`, evaluated before the block (None: no value).
    fn hll(&self, _id: u32) -> Option<f64> {
        None
    }
}

/// Word values of a dialect without expressions: an expression word is refused.
pub struct NoExpressions(pub &'static str);

impl WordValues for NoExpressions {
    fn expr(&self, block: &Block, _e: ExprId, at: ColSpan) -> Result<f64, Diagnostic> {
        Err(Diagnostic::error(
            "interp::unsupported",
            format!(
                "parameters and expressions are not supported by the {} front end",
                self.0
            ),
            block.span_of(at),
        ))
    }
}

impl Default for Words {
    fn default() -> Self {
        Words {
            g: Vec::new(),
            m: Vec::new(),
            letter: [Val {
                v: 0.0,
                span: ColSpan::default(),
            }; 29],
            present: 0,
            used: 0,
            indexed: Vec::new(),
            keywords: Vec::new(),
            second: None,
        }
    }
}

/// `x.round()` (halves away from zero) without a call: x86-64 has no rounding instruction before
/// SSE4.1, so `f64::round` is a libm call (≈ 24 instructions on every G word). Below 2^52 the
/// truncating conversion `x as i64` is exact and so is `x − trunc(x)`; at and above 2^52 every
/// `f64` is an integer already. Equal to `f64::round` for every finite `x` except that it may
/// return `+0.0` for `round` = `-0.0` (the codes compare and convert zero the same either way);
/// the proptest in this file checks it.
#[inline(always)]
fn round_half_away(x: f64) -> f64 {
    if x.abs() >= 4_503_599_627_370_496.0 || x.is_nan() {
        return x;
    }
    let t = x as i64 as f64;
    let f = x - t;
    if f >= 0.5 {
        t + 1.0
    } else if f <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

/// Slot of a letter: A–Z (either case), then LinuxCNC's polar words `@` (radius) and `^` (angle)
/// and its spindle selection `$`; 31 for any other byte (no word has it). A table: one load per
/// word of every block, where a `match` and a case fold cost four more instructions.
const SLOT: [u8; 256] = {
    let mut t = [31u8; 256];
    let mut i = 0;
    while i < 26 {
        t[b'A' as usize + i] = i as u8;
        t[b'a' as usize + i] = i as u8;
        i += 1;
    }
    t[b'@' as usize] = 26;
    t[b'^' as usize] = 27;
    t[b'$' as usize] = 28;
    t
};

#[inline(always)]
const fn idx(letter: u8) -> usize {
    SLOT[letter as usize] as usize
}

/// The fast path of [`Words::fill`]: the bit of each letter stored as a value (upper-case A–Z
/// but G and M, and `@ ^ $`), 0 for every other byte; one load for the four tests.
const PLAIN_BIT: [u32; 256] = {
    let mut t = [0u32; 256];
    let mut c = 0;
    while c < 256 {
        let l = c as u8;
        if (l.is_ascii_uppercase() && l != b'G' && l != b'M') || l == b'@' || l == b'^' || l == b'$'
        {
            t[c] = 1 << idx(l);
        }
        c += 1;
    }
    t
};

/// The bit of `letter` in [`Words::written`].
pub const fn letter_bit(letter: u8) -> u32 {
    1 << idx(letter)
}

fn letter_of(i: usize) -> u8 {
    match i {
        26 => b'@',
        27 => b'^',
        28 => b'$',
        i => b'A' + i as u8,
    }
}

impl Words {
    /// Clears for reuse.
    pub fn clear(&mut self) {
        self.g.clear();
        self.m.clear();
        self.present = 0;
        self.used = 0;
        self.indexed.clear();
        self.keywords.clear();
        self.second = None;
    }

    /// Evaluates and sorts the words of `block`.
    #[inline]
    pub fn fill(
        &mut self,
        block: &Block,
        values: &impl WordValues,
        rules: &WordRules,
        warnings: &mut Vec<Diagnostic>,
    ) -> Result<(), Diagnostic> {
        self.clear();
        // Bounded work per block: a diagnostic's column is counted along the line, so a block of
        // a megabyte of words warning at each would cost the square of its length.
        if block.words.len() > stanok_syntax::MAX_WORDS_PER_BLOCK {
            let w = &block.words[stanok_syntax::MAX_WORDS_PER_BLOCK];
            return Err(Diagnostic::error(
                "syntax::too-many-words",
                format!(
                    "more than {} words in one block",
                    stanok_syntax::MAX_WORDS_PER_BLOCK
                ),
                block.span_of(w.span),
            )
            .with_note("split the block: no control reads a block this long"));
        }
        for w in &block.words {
            // The bulk of every program: an upper-case letter other than G and M (or `@ ^ $`)
            // with a finite literal number, the first of its letter in the block. Stored here
            // with the tests the general path below makes, in fewer branches; anything else
            // (codes, expressions, repeats, errors) takes the general path.
            if let Address::Letter(l) = w.address {
                if let Value::Number(v) = w.value {
                    let bit = PLAIN_BIT[l as usize];
                    if bit != 0 && self.present & bit == 0 && v.is_finite() {
                        self.letter[idx(l)] = Val { v, span: w.span };
                        self.present |= bit;
                        continue;
                    }
                }
            }
            let value = match w.value {
                Value::None => None,
                Value::Number(v) => Some(v),
                Value::Expr(e) => match values.expr_or_vacant(block, e, w.span)? {
                    Some(v) => Some(v),
                    None => continue,
                },
                // Evaluated by the front end before the block (AxiOMA's HLL).
                Value::Hll(e) => values.hll(e.0),
            };
            let val = value.map(|v| Val { v, span: w.span });
            match w.address {
                Address::Letter(l) => {
                    let Some(val) = val else {
                        return Err(Diagnostic::error(
                            "interp::missing-value",
                            format!("{} word has no value", l as char),
                            block.span_of(w.span),
                        ));
                    };
                    if !val.v.is_finite() {
                        return Err(Diagnostic::error(
                            "interp::bad-value",
                            format!("{} word value is not a finite number", l as char),
                            block.span_of(w.span),
                        ));
                    }
                    match l {
                        b'G' => {
                            let code = round_half_away(val.v * 10.0);
                            if (val.v * 10.0 - code).abs() > 1e-3 || !(0.0..=9999.0).contains(&code)
                            {
                                return Err(Diagnostic::error(
                                    "interp::unknown-g-code",
                                    format!("Unknown g code used: G{}", val.v),
                                    block.span_of(w.span),
                                ));
                            }
                            self.g.push((code as u32, w.span));
                        }
                        b'M' => {
                            let code = round_half_away(val.v);
                            if (val.v - code).abs() > 1e-6 || !(0.0..=9999.0).contains(&code) {
                                return Err(Diagnostic::error(
                                    "interp::unknown-m-code",
                                    format!("Unknown m code used: M{}", val.v),
                                    block.span_of(w.span),
                                ));
                            }
                            self.m.push((code as u32, w.span));
                        }
                        b'A'..=b'Z' | b'@' | b'^' | b'$' => {
                            let i = idx(l);
                            if self.present & (1 << i) != 0 {
                                // Mazatrol `T01 T02 M6`: the second T is the next tool (prepared).
                                if rules.second_word == Some(l) && self.second.is_none() {
                                    self.second = Some(val);
                                    continue;
                                }
                                let prev = self.letter[i];
                                match rules.repeated {
                                    Repeated::Refuse(code) => {
                                        return Err(Diagnostic::error(
                                            code,
                                            format!(
                                                "Multiple {} words on one line",
                                                (l as char).to_ascii_lowercase()
                                            ),
                                            block.span_of(w.span),
                                        ))
                                    }
                                    Repeated::LastWins(code) => warnings.push(
                                        Diagnostic::warning(
                                            code,
                                            format!(
                                                "{} appears twice in this block: only the last one takes effect",
                                                l as char
                                            ),
                                            block.span_of(w.span),
                                        )
                                        .with_note(format!(
                                            "the earlier one is `{}`",
                                            block.slice(prev.span)
                                        )),
                                    ),
                                }
                            }
                            self.letter[i] = val;
                            self.present |= 1 << i;
                        }
                        _ => {
                            return Err(Diagnostic::error(
                                "interp::bad-address",
                                "not a word address",
                                block.span_of(w.span),
                            ))
                        }
                    }
                }
                Address::Indexed { letter, index } => {
                    let Some(val) = val else {
                        return Err(Diagnostic::error(
                            "interp::missing-value",
                            format!("{}{}= has no value", letter as char, index),
                            block.span_of(w.span),
                        ));
                    };
                    self.indexed.push((letter, index, val));
                }
                Address::Keyword { keyword, index } => {
                    self.keywords.push((keyword, index, val, w.span));
                }
            }
        }
        Ok(())
    }

    /// The value of a letter, marking it used.
    pub fn take(&mut self, letter: u8) -> Option<Val> {
        let i = idx(letter);
        if self.present & (1 << i) == 0 {
            return None;
        }
        self.used |= 1 << i;
        Some(self.letter[i])
    }

    /// Multiplies a written letter's value by `k` (RS274/NGC G7: X words are diameters, halved
    /// before any code reads them). Does not mark it used.
    pub fn scale(&mut self, letter: u8, k: f64) {
        if self.has(letter) {
            self.letter[idx(letter)].v *= k;
        }
    }

    /// The value of a letter without marking it used.
    pub fn peek(&self, letter: u8) -> Option<Val> {
        self.has(letter).then(|| self.letter[idx(letter)])
    }

    /// True if the letter was written (does not mark it used).
    pub fn has(&self, letter: u8) -> bool {
        self.present & (1 << idx(letter)) != 0
    }

    /// The letters written in the block, one bit each ([`letter_bit`]).
    #[inline(always)]
    pub fn written(&self) -> u32 {
        self.present
    }

    /// True when every written letter was consumed (the usual end of a block).
    #[inline(always)]
    pub fn all_used(&self) -> bool {
        self.present & !self.used == 0
    }

    /// The first letter that was written but never consumed, if any.
    pub fn first_unused(&self) -> Option<(u8, Val)> {
        let left = self.present & !self.used;
        if left == 0 {
            return None;
        }
        let i = left.trailing_zeros() as usize;
        Some((letter_of(i), self.letter[i]))
    }

    /// True if the letter was consumed already.
    pub fn is_used(&self, letter: u8) -> bool {
        self.used & (1 << idx(letter)) != 0
    }

    /// True if any of the given letters was written.
    pub fn any(&self, letters: &[u8]) -> bool {
        letters.iter().any(|&l| self.has(l))
    }
}

#[cfg(test)]
mod tests {
    use super::round_half_away;
    use proptest::prelude::*;

    #[test]
    fn rounds_halves_away_from_zero_like_f64_round() {
        for x in [
            0.0,
            0.49,
            0.5,
            1.5,
            2.5,
            -0.5,
            -1.5,
            -2.49,
            9999.4999,
            9999.5,
            330.0004,
            329.9996,
            0.49999999999999994,
            -0.49999999999999994,
            4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            1e300,
            -1e300,
            f64::MAX,
            f64::MIN,
        ] {
            assert_eq!(round_half_away(x), x.round(), "{x}");
        }
        assert!(round_half_away(f64::NAN).is_nan());
    }

    #[test]
    fn slots_fold_case_and_stay_distinct() {
        let letters: Vec<u8> = (b'A'..=b'Z').chain(*b"@^$").collect();
        for (i, &l) in letters.iter().enumerate() {
            assert_eq!(super::idx(l), i, "{}", l as char);
            assert_eq!(super::letter_of(i), l);
            assert_eq!(super::idx(l.to_ascii_lowercase()), super::idx(l));
        }
        assert_eq!(super::idx(b'1'), 31);
    }

    proptest! {
        #[test]
        fn equals_f64_round(x in any::<f64>()) {
            let (got, want) = (round_half_away(x), x.round());
            prop_assert!(got == want || (got.is_nan() && want.is_nan()), "{x}: {got} vs {want}");
        }

        #[test]
        fn equals_f64_round_near_codes(code in 0u32..100_000, off in -0.6f64..0.6) {
            let x = code as f64 + off;
            prop_assert_eq!(round_half_away(x), x.round(), "{}", x);
        }
    }
}
