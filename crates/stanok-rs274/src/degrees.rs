//! Degrees ↔ radians as LinuxCNC's expression evaluator converts them, to the last bit.
//!
//! LinuxCNC writes `sin((x * M_PIl) / 180.0)` and `(asin(x) * 180.0) / M_PIl`: `M_PIl` is a
//! `long double`, so on x86-64 the steps that involve it run in the x87's 80-bit format (64-bit
//! mantissa), each rounded to 64 bits, and the result is rounded to a `double` (53 bits) only when
//! it is passed to `sin` or stored; `asin(x) * 180.0` is still a double product. (ACOS[0.5] is
//! exactly 60 for LinuxCNC, 60 + 1 ulp with `to_degrees`.) A plain `f64` conversion (`to_radians`, `to_degrees`) rounds differently in
//! the last bit often enough to matter: `FUP[ASIN[SIN[3]]]` is 3 for LinuxCNC and 4 with
//! `to_degrees` (seed 20261207, program 2412).
//!
//! ## How it is emulated
//! Each intermediate value is held as a double-double `(hi, lo)` (about 106 bits, from exact
//! two-product and two-sum steps with `mul_add`), then rounded to the x87's 64-bit grid —
//! `hi + k·g` with `g` = ulp(hi)/2¹¹ and `k` rounded half to even (k's parity is the 64-bit
//! mantissa's last bit, `hi` being a multiple of 2g) — and finally to the nearest `f64`
//! (`hi + lo` in f64 arithmetic is that rounding). `M_PIl` itself is exactly
//! `PI_HI + PI_LO`: π rounded to 64 bits, 0xC90FDAA22168C235·2⁻⁶².

/// The 53 high bits of `M_PIl` (= `std::f64::consts::PI`).
const PI_HI: f64 = std::f64::consts::PI;
/// `M_PIl − PI_HI` = 0x235·2⁻⁶², exact.
const PI_LO: f64 = 565.0 / 4_611_686_018_427_387_904.0;

/// `(s, e)` with `s = fl(a + b)` and `a + b = s + e` exactly.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Rounds the double-double `hi + lo` to the x87's 64-bit mantissa; the result is again a pair.
fn round64(hi: f64, lo: f64) -> (f64, f64) {
    let (s, e) = two_sum(hi, lo);
    if e == 0.0 || !s.is_finite() || s == 0.0 {
        return (s, e);
    }
    // The spacing of doubles at s (above |s|), then the 64-bit grid: 2¹¹ times finer. Below a
    // power of two, on the side towards zero, both grids are twice as fine again.
    let bits = s.abs().to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32;
    if exponent == 0 {
        return (s, e); // subnormal: no 64-bit rounding to model
    }
    let mut g = f64::from_bits(((exponent - 52 - 11).max(1) as u64) << 52);
    let power_of_two = bits & ((1u64 << 52) - 1) == 0;
    if power_of_two && (e < 0.0) == (s > 0.0) {
        g /= 2.0;
    }
    let k = (e / g).round_ties_even();
    (s, k * g)
}

/// LinuxCNC's `SIN[x]`: C++ picks the `long double` overload of `sin` for the 64-bit argument, so
/// the result is (to the last bit of a double) sin of the x87 argument, rounded to 64 bits and
/// then to 53 — computed here in double-double ([`sin_cos_dd`]).
pub fn sin_deg(x: f64) -> f64 {
    match sin_cos_dd(radians_64(x)) {
        Some((s, _)) => to_double(s),
        None => x.to_radians().sin(),
    }
}

/// LinuxCNC's `COS[x]` (see [`sin_deg`]).
pub fn cos_deg(x: f64) -> f64 {
    match sin_cos_dd(radians_64(x)) {
        Some((_, c)) => to_double(c),
        None => x.to_radians().cos(),
    }
}

/// LinuxCNC's `TAN[x]` (see [`sin_deg`]).
pub fn tan_deg(x: f64) -> f64 {
    match sin_cos_dd(radians_64(x)) {
        Some((s, c)) if c.0 != 0.0 => to_double(dd_div(s, c)),
        _ => x.to_radians().tan(),
    }
}

/// A double-double rounded as the x87 stores a `long double` into a `double`.
fn to_double(v: (f64, f64)) -> f64 {
    let (hi, lo) = round64(v.0, v.1);
    hi + lo
}

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

fn dd_add(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let (s, e) = two_sum(a.0, b.0);
    two_sum(s, e + a.1 + b.1)
}

fn dd_mul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let (p, e) = two_prod(a.0, b.0);
    two_sum(p, e + a.0 * b.1 + a.1 * b.0)
}

fn dd_div(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let q1 = a.0 / b.0;
    let r = dd_add(a, dd_mul((-q1, 0.0), b));
    let q2 = r.0 / b.0;
    let r = dd_add(r, dd_mul((-q2, 0.0), b));
    let q3 = r.0 / b.0;
    dd_add(two_sum(q1, q2), (q3, 0.0))
}

/// π/2 as three doubles (its first ~160 bits).
const PIO2: [f64; 3] = [
    std::f64::consts::FRAC_PI_2,
    6.123_233_995_736_766e-17,
    -1.497_384_904_859_169_8e-33,
];

/// sin and cos of the double-double `y`, each to about 100 bits, for |y| < 10⁶ (None beyond).
///
/// Range reduction: `r = y − k·π/2` with k the nearest integer, π/2 taken to three doubles and
/// each product exact (`two_prod`), so r keeps ~100 bits for the arguments of degree conversions.
/// Then the Taylor series of sin r and cos r (|r| ≤ π/4: 14 terms reach 10⁻³¹) and the quadrant.
fn sin_cos_dd(y: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
    if y.0.is_nan() || y.0.abs() >= 1e6 {
        return None;
    }
    let k = (y.0 / PIO2[0]).round();
    let mut r = y;
    for p in PIO2 {
        let (h, l) = two_prod(-k, p);
        r = dd_add(r, (h, l));
    }
    let r2 = dd_mul(r, r);
    let (mut sin, mut cos) = (r, (1.0, 0.0));
    let (mut ts, mut tc) = (r, (1.0, 0.0));
    for n in 1..=14 {
        let n = n as f64;
        ts = dd_div(dd_mul(ts, r2), (-(2.0 * n) * (2.0 * n + 1.0), 0.0));
        tc = dd_div(dd_mul(tc, r2), (-(2.0 * n - 1.0) * (2.0 * n), 0.0));
        sin = dd_add(sin, ts);
        cos = dd_add(cos, tc);
    }
    let neg = |v: (f64, f64)| (-v.0, -v.1);
    Some(match (k as i64).rem_euclid(4) {
        0 => (sin, cos),
        1 => (cos, neg(sin)),
        2 => (neg(sin), neg(cos)),
        _ => (neg(cos), sin),
    })
}

/// `(x · M_PIl) / 180`, rounded as the x87 does, as a double.
#[cfg(test)]
fn to_radians(x: f64) -> f64 {
    let (hi, lo) = radians_64(x);
    hi + lo
}

/// `(x · M_PIl) / 180` on the x87's 64-bit grid, as a pair `hi + lo` with `hi` the nearest double.
fn radians_64(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return (x.to_radians(), 0.0);
    }
    // x · M_PIl, exact to ~106 bits: x·PI_HI by two-product, plus x·PI_LO.
    let p = x * PI_HI;
    let p_err = x.mul_add(PI_HI, -p) + x * PI_LO;
    let (t_hi, t_lo) = round64(p, p_err);
    // ÷ 180.
    let q = t_hi / 180.0;
    let r = (-q).mul_add(180.0, t_hi) + t_lo;
    round64(q, r / 180.0)
}

/// `(a · 180) / M_PIl`, rounded as the x87 does, as a double (ASIN, ACOS, ATAN's results).
pub fn to_degrees(a: f64) -> f64 {
    if !a.is_finite() {
        return a.to_degrees();
    }
    // `a * 180.0` is a double product (rounded to 53 bits); only the division by M_PIl is
    // promoted to long double.
    let n = a * 180.0;
    // ÷ (PI_HI + PI_LO).
    let q = n / PI_HI;
    let r = (-q).mul_add(PI_HI, n) - q * PI_LO;
    let (d_hi, d_lo) = round64(q, r / PI_HI);
    d_hi + d_lo
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values rs274 printed (`[[COS[x] - c] * 10¹⁸]`): the correctly rounded cos of the x87's
    /// argument, one ulp off the libm cos of the double argument.
    #[test]
    fn trigonometry_of_the_long_double_argument_as_rs274() {
        let e18 = 1e18;
        let v = (cos_deg(-701.1) - 0.946_085_358_8) * e18;
        assert!((v - 27_545_410.397_067).abs() < 1e-3, "{v}");
        let v = (cos_deg(214.5) - -0.824_126_188_6) * e18;
        assert!((v - -22_015_722.578_317).abs() < 1e-3, "{v}");
        let v = (sin_deg(-184.6) - 0.080_198_924_3) * e18;
        assert!((v - 28_858_818.112_987).abs() < 1e-3, "{v}");
        assert_eq!(sin_deg(30.0), 0.5);
        assert_eq!(tan_deg(45.0), 1.0);
        assert_eq!(cos_deg(0.0), 1.0);
        assert!(sin_deg(1e7).is_finite());
    }

    #[test]
    fn pi_long_double_is_pi_to_64_bits() {
        // M_PIl − π ≈ 5.0·10⁻²⁰ (π = 3.14159265358979323846264…, M_PIl = …323851281…).
        let excess = (PI_LO - 1.224_646_799_147_353_2e-16) * 1e20;
        assert!((excess - 5.0165).abs() < 0.01, "{excess}");
    }

    /// Seed 20261207, program 2412: LinuxCNC's ASIN[SIN[3]] is not above 3 (FUP gives 3).
    #[test]
    fn asin_of_sin_3_is_not_above_3() {
        let v = to_degrees(to_radians(3.0).sin().asin());
        assert!(v <= 3.0, "{v:e}");
        assert!((v - 3.0).abs() < 1e-14);
    }

    #[test]
    fn conversions_agree_with_f64_to_the_last_bits() {
        for i in -720..=720 {
            let x = i as f64 * 0.37;
            let (a, b) = (to_radians(x), x.to_radians());
            assert!(
                (a - b).abs() <= 2.0 * f64::EPSILON * b.abs().max(1e-300),
                "{x}"
            );
            let (a, b) = (to_degrees(x), x.to_degrees());
            assert!(
                (a - b).abs() <= 2.0 * f64::EPSILON * b.abs().max(1e-300),
                "{x}"
            );
        }
        assert_eq!(to_radians(180.0), PI_HI);
        assert_eq!(to_degrees(PI_HI), 180.0);
        assert_eq!(to_degrees(0.5f64.acos()), 60.0);
    }
}
