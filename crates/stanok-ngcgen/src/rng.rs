//! The generator's random source: ChaCha8 (a stream that is the same on every platform and
//! every version of `rand_chacha`), seeded from `(seed, index, attempt)`, so a program is
//! reproducible from those three numbers alone. Also the number spellings and letter cases that
//! RS274/NGC accepts, drawn from the same stream.

use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The random source of one program.
pub struct Rng {
    inner: ChaCha8Rng,
    /// Lower-case letters and keywords in this program (a surface form).
    pub lower: bool,
    /// Spaces inside numbers and between letter and value (a surface form).
    pub spaced: bool,
}

impl Rng {
    /// The stream of program `index` of run `seed`, `attempt`-th draw.
    pub fn new(seed: u64, index: u64, attempt: u32) -> Rng {
        // SplitMix64-style mixing so that neighbouring indices get unrelated streams.
        let mut x = seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ u64::from(attempt) << 56;
        x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        x ^= x >> 31;
        Rng {
            inner: ChaCha8Rng::seed_from_u64(x),
            lower: false,
            spaced: false,
        }
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.inner.random::<f64>() < p
    }

    /// A whole number in `0..n` (0 if n is 0).
    pub fn below(&mut self, n: u64) -> u64 {
        if n == 0 {
            0
        } else {
            self.inner.random_range(0..n)
        }
    }

    /// A whole number in `lo..=hi`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        self.inner.random_range(lo..=hi)
    }

    /// An element of a non-empty slice.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len() as u64) as usize]
    }

    /// A value in `lo..hi`, rounded to three decimals (so that its text is exact).
    pub fn value(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.inner.random_range(lo..hi);
        match self.below(4) {
            0 => v.round(),
            1 => (v * 10.0).round() / 10.0,
            _ => (v * 1000.0).round() / 1000.0,
        }
    }

    /// A value of magnitude in `lo..hi` with a random sign.
    pub fn signed(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.value(lo, hi);
        if self.chance(0.5) {
            -v
        } else {
            v
        }
    }

    /// The text of a number in one of the spellings RS274/NGC reads the same: `1.5`, `1.500`,
    /// `+1.5`, `.5`, `2.`, `2`.
    pub fn number_text(&mut self, v: f64) -> String {
        let v = if v == 0.0 { 0.0 } else { v }; // no "-0"
        let mut s = format!("{v}");
        match self.below(8) {
            0 => s = format!("{v:.4}"),
            1 if v >= 0.0 => s = format!("+{s}"),
            2 if v.fract() == 0.0 => s.push('.'),
            3 if v.abs() < 1.0 && v != 0.0 => {
                s = s.replacen("0.", ".", 1);
            }
            _ => {}
        }
        if self.spaced && s.len() > 1 && self.chance(0.3) {
            // A space inside the number: LinuxCNC removes spaces before reading a line.
            let at = 1 + self.below(s.len() as u64 - 1) as usize;
            if s.is_char_boundary(at) {
                s.insert(at, ' ');
            }
        }
        s
    }

    /// A keyword or letter in this program's case.
    pub fn case(&self, text: &str) -> String {
        if self.lower {
            text.to_ascii_lowercase()
        } else {
            text.to_string()
        }
    }
}
