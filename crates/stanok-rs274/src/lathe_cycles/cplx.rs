//! Complex numbers with the floating-point steps of C++'s `std::complex<double>` as LinuxCNC's
//! G7x code is compiled (GCC, libstdc++, x86-64 without FMA), so that the lathe-cycle model
//! (`model.rs`) rounds where LinuxCNC rounds.
//!
//! Why bit-exactness matters: LinuxCNC decides some steps by exact comparisons of computed
//! points (an offset level element whose end is one ulp below its start is skipped by G7x.1).
//! Matching its traces on such programs needs the same roundings, not just the same geometry.
//!
//! The operations, as GCC and libgcc compute them:
//! * `a * b` (complex × complex): the schoolbook formula, `(ar·br − ai·bi, ar·bi + ai·br)`, each
//!   product rounded, then the sum (no fused multiply-add on the baseline x86-64 target);
//! * `a / b` (complex ÷ complex): libgcc's `__divdc3`, Smith's algorithm (the scaling it adds for
//!   tiny or huge operands multiplies by powers of two, which changes no rounding here);
//! * complex × real and complex ÷ real: each part alone;
//! * `abs`: the C library's `hypot`; `norm`: libstdc++ computes it as `abs(z)²`.
//!
//! `re` is Z and `im` is X, as in LinuxCNC's `std::complex<double>(z, x)`.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Cx {
    pub re: f64,
    pub im: f64,
}

/// The imaginary unit.
pub(super) const I: Cx = Cx { re: 0.0, im: 1.0 };

impl Cx {
    pub const fn new(re: f64, im: f64) -> Cx {
        Cx { re, im }
    }

    pub fn conj(self) -> Cx {
        Cx::new(self.re, -self.im)
    }

    /// `std::abs`: `hypot(re, im)`.
    pub fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }

    /// `std::norm`: libstdc++ squares `abs` (not `re² + im²`).
    pub fn norm(self) -> f64 {
        let a = self.abs();
        a * a
    }

    /// Complex × real, part by part.
    pub fn scale(self, k: f64) -> Cx {
        Cx::new(self.re * k, self.im * k)
    }

    /// Complex ÷ real, part by part.
    pub fn div_real(self, k: f64) -> Cx {
        Cx::new(self.re / k, self.im / k)
    }

    /// Real ÷ complex: `complex(x, 0) / z`, libgcc's division.
    pub fn real_over(x: f64, z: Cx) -> Cx {
        Cx::new(x, 0.0) / z
    }
}

impl Add for Cx {
    type Output = Cx;
    fn add(self, o: Cx) -> Cx {
        Cx::new(self.re + o.re, self.im + o.im)
    }
}

impl AddAssign for Cx {
    fn add_assign(&mut self, o: Cx) {
        *self = *self + o;
    }
}

impl Sub for Cx {
    type Output = Cx;
    fn sub(self, o: Cx) -> Cx {
        Cx::new(self.re - o.re, self.im - o.im)
    }
}

impl Neg for Cx {
    type Output = Cx;
    fn neg(self) -> Cx {
        Cx::new(-self.re, -self.im)
    }
}

impl Mul for Cx {
    type Output = Cx;
    fn mul(self, o: Cx) -> Cx {
        Cx::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

impl Div for Cx {
    type Output = Cx;
    /// Smith's algorithm as libgcc's `__divdc3` has it: divide through by the larger part of
    /// the divisor (with its branch for a ratio that underflows).
    fn div(self, o: Cx) -> Cx {
        let (a, b, c, d) = (self.re, self.im, o.re, o.im);
        if c.abs() < d.abs() {
            let ratio = c / d;
            let denom = c * ratio + d;
            if ratio.abs() > f64::MIN_POSITIVE {
                Cx::new((a * ratio + b) / denom, (b * ratio - a) / denom)
            } else {
                Cx::new((c * (a / d) + b) / denom, (c * (b / d) - a) / denom)
            }
        } else {
            let ratio = d / c;
            let denom = d * ratio + c;
            if ratio.abs() > f64::MIN_POSITIVE {
                Cx::new((b * ratio + a) / denom, (b - a * ratio) / denom)
            } else {
                Cx::new((a + d * (b / c)) / denom, (b - d * (a / c)) / denom)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn division_by_a_real_divisor_is_part_by_part() {
        let q = Cx::new(3.0, -1.5) / Cx::new(2.0, 0.0);
        assert_eq!(q, Cx::new(1.5, -0.75));
    }

    #[test]
    fn division_inverts_multiplication_within_rounding() {
        let (a, b) = (Cx::new(0.4279, -0.7852), Cx::new(0.6, 0.8));
        let q = (a * b) / b;
        assert!((q - a).abs() < 1e-15, "{q:?}");
    }

    #[test]
    fn norm_squares_hypot() {
        let z = Cx::new(0.1, 0.2);
        assert_eq!(z.norm(), 0.1f64.hypot(0.2).powi(2));
    }
}
