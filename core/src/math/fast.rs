//! Short polynomial elementary functions for `KimGrip`'s speed-dependent friction fast
//! path (`kim_grip::speed_path`): straight-line f32 code, no call, no table, a few
//! instructions each on the Cortex-M4F where `accurate`'s routines take ~100. Each is a
//! Chebyshev fit (`mpmath.chebyfit`, the coefficients below) on a reduced range:
//!
//! * [`exp_neg`]: `e^{−x} = 2^t`, `t = −x log₂e = n + f` with `n` an integer and
//!   `f ∈ (−½, ½]`; `2^f` a degree-5 fit (error 7.9e-8 relative on the range), `2^n`
//!   added to the exponent bits. Relative error below `4e-7 + 8e-8 x` over `[0, 86]`
//!   (the `x`-proportional part is the f32 rounding of `x log₂e`: `e^{−x}`'s condition
//!   number is `x`, so an f32 argument carries that much anyway).
//! * [`ln`]: `q = 2^e m`, `m ∈ [1, 2)` from the bits; `ln m = 2 atanh s`,
//!   `s = (m − 1)/(m + 1) ∈ [0, ⅓)`, with `atanh(s)/s` a degree-3 fit in `s²` (error
//!   1.8e-7 relative). Absolute error below `4e-7 + 1.2e-7 |ln q|` for every positive
//!   normal `q` (the second part is the rounding of `e ln 2`).
//! * [`ln_one_minus_negated`]: `−ln(1 − y)`, relative error below 4e-7 on `[0, 1)`.
//! * [`one_minus_exp_neg_over`]: `φ(x) = (1 − e^{−x})/x` on `[0, 1]`, degree 5 (error
//!   6.7e-8); its callers keep `x` in that range.
//!
//! The bounds are checked against `accurate`'s routines by this module's tests.

/// Degree-5 Chebyshev fit of `2^f` on `[−½, ½]`, highest power first (its linear
/// coefficient is a fitted value near ln 2, not the constant).
#[allow(clippy::approx_constant)]
const EXP2: [f32; 6] = [
    0.001_339_086_3,
    0.009_676_032,
    0.055_503_57,
    0.240_221_07,
    0.693_147_2,
    1.000_000_1,
];

/// Degree-3 fit of `2 atanh(s)/s` in `u = s²` on `[0, 1/9]`, highest power first (the
/// factor 2 of `ln m = 2 atanh s` folded in).
const LN_ATANH: [f32; 4] = [0.342_036_2, 0.395_931_86, 0.666_758_5, 1.999_999_7];

/// Degree-5 fit of `φ(x) = (1 − e^{−x})/x` on `[0, 1]`, highest power first.
const PHI: [f32; 6] = [
    -0.000_912_545_4,
    0.007_837_364,
    -0.041_418_763,
    0.166_609_67,
    -0.499_995_16,
    0.999_999_94,
];

/// Horner's rule, highest power first.
#[inline(always)]
fn horner<const N: usize>(coefficients: &[f32; N], x: f32) -> f32 {
    let mut sum = coefficients[0];
    let mut k = 1;
    while k < N {
        sum = sum * x + coefficients[k];
        k += 1;
    }
    sum
}

/// `e^{−x}` for `x ≥ 0` (module docs): exactly representable exponents only, so past
/// `x ≈ 86.6` the result stays at about `2^{−125}` instead of going subnormal.
#[inline(always)]
pub fn exp_neg(x: f32) -> f32 {
    let t = x * -core::f32::consts::LOG2_E;
    let t = if t < -125.0 { -125.0 } else { t };
    // Round to the nearest integer (t ≤ 0): truncation of t − ½.
    let n = (t - 0.5) as i32;
    let f = t - n as f32;
    let scaled = horner(&EXP2, f).to_bits() as i32 + (n << 23);
    f32::from_bits(scaled as u32)
}

/// Natural logarithm of a positive normal `q` (module docs).
#[inline(always)]
pub fn ln(q: f32) -> f32 {
    let bits = q.to_bits();
    let exponent = (bits >> 23) as i32 - 127;
    let mantissa = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000);
    let s = (mantissa - 1.0) / (mantissa + 1.0);
    exponent as f32 * core::f32::consts::LN_2 + s * horner(&LN_ATANH, s * s)
}

/// `−ln(1 − y)` for `y ∈ [0, 1)` without forming `1 − y` where that would lose digits:
/// `2 atanh(s)`, `s = y/(2 − y) ≤ ⅓`, for `y ≤ ½` (the fit of [`ln`] in `s`; relative
/// error below 2e-7), and [`ln`] of `1 − y` (exact there, Sterbenz) above.
#[inline(always)]
pub fn ln_one_minus_negated(y: f32) -> f32 {
    if y <= 0.5 {
        let s = y / (2.0 - y);
        s * horner(&LN_ATANH, s * s)
    } else {
        -ln(1.0 - y)
    }
}

/// `φ(x) = (1 − e^{−x})/x` for `x ∈ [0, 1]` (module docs); `φ(0) = 1`.
#[inline(always)]
pub fn one_minus_exp_neg_over(x: f32) -> f32 {
    horner(&PHI, x)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn exp_neg_within_its_bound() {
        let mut worst = 0.0f64;
        let mut x = 0.0f32;
        while x < 86.0 {
            let exact = (-(x as f64)).exp();
            let error = ((exp_neg(x) as f64 - exact) / exact).abs();
            worst = worst.max(error / (4e-7 + 8e-8 * x as f64));
            x += 0.000_37;
        }
        assert!(worst < 1.0, "relative error {worst} times its bound");
        assert!(exp_neg(1e4) > 0.0 && exp_neg(1e4) < 1e-37);
    }

    #[test]
    fn ln_within_its_bound() {
        let mut worst = 0.0f64;
        let mut q = 1.2e-38f32;
        while q <= 1.0 {
            let exact = (q as f64).ln();
            let error = (ln(q) as f64 - exact).abs();
            worst = worst.max(error / (4e-7 + 1.2e-7 * exact.abs()));
            q *= 1.000_07;
        }
        assert!(worst < 1.0, "absolute error {worst} times its bound");
        assert!(ln(1.0).abs() < 4e-7);
    }

    #[test]
    fn ln_one_minus_within_4e7_relative() {
        let mut worst = 0.0f64;
        let mut y = 1e-30f32;
        while y < 1.0 {
            let exact = -(-(y as f64)).ln_1p();
            let error = ((ln_one_minus_negated(y) as f64 - exact) / exact).abs();
            worst = worst.max(error);
            y = if y < 0.99 { y * 1.000_3 } else { y + 1e-7 };
        }
        assert!(worst < 4e-7, "worst relative error {worst:e}");
        assert_eq!(ln_one_minus_negated(0.0), 0.0);
    }

    #[test]
    fn phi_within_1e7_relative_on_its_range() {
        let mut worst = 0.0f64;
        for i in 0..=100_000 {
            let x = i as f64 / 100_000.0;
            let exact = if x == 0.0 { 1.0 } else { -(-x).exp_m1() / x };
            let error = ((one_minus_exp_neg_over(x as f32) as f64 - exact) / exact).abs();
            worst = worst.max(error);
        }
        assert!(worst < 1e-7 + 1.2e-7, "worst relative error {worst:e}");
    }
}
