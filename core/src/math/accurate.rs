//! `e^x`, `ln x`, `e^x − 1` and `ln(1 + x)` in `f32` to within 4 ulps, without a
//! library: for the `micromath` backend, whose own `exp` and `ln` are fast
//! approximations (relative error ~1e-3, not smooth), where an algorithm needs smooth,
//! accurate elementary functions — `SeedExact`'s quadrature nodes and root solves
//! (`Real::exp_accurate` and friends). With the `libm` backend those are `libm`'s.
//!
//! Methods (classical; the constants are exact Taylor coefficients):
//!
//! * `exp`: `x = k ln 2 + r`, `|r| ≤ ln 2 / 2` (`ln 2` split in a high part exact in
//!   f32 and a low part), `e^r` by its Taylor polynomial of degree 7 (truncation
//!   `r⁸/8! ≤ 5.6e-9 < ε/2`), times `2^k` built from its bits;
//! * `ln`: `x = 2^e m`, `m ∈ [√½, √2)`, `ln m = 2 atanh s`, `s = (m − 1)/(m + 1)` (exact
//!   numerator, `|s| ≤ 0.172`), series to `s⁹` (truncation `2 s¹¹/11 ≤ 6e-10`);
//! * `exp_m1` for `|x| < 0.35`: Taylor to degree 9 (relative truncation `x⁸/9! ≤ 7e-9`);
//! * `ln_1p` for `|x| < 1/2`: `2 atanh(x/(2 + x))`, `|s| ≤ 1/3`, series to `s¹⁵`
//!   (relative truncation `(1/3)¹⁴/15 ≤ 2e-8`).
//!
//! Measured against `libm` in the tests below (200,000 points each and the edges): `exp`
//! within 1 ulp, `ln` 3, `exp_m1` and `ln_1p` 4 (past the series ranges they are
//! `exp(x) − 1` and `ln(1 + x)`, whose cancellation costs up to 3 ulps).

use core::f32::consts::LOG2_E;

use super::abs;

/// `ln 2` split: the high part has trailing zero bits, so `k · LN2_HI` is exact.
const LN2_HI: f32 = 0.693_138_1; // 0x3f31_7180
const LN2_LO: f32 = 9.058_001e-6; // 0x3717_f7d1

/// `2^k` for `k ∈ [−126, 127]`.
fn two_to(k: i32) -> f32 {
    f32::from_bits(((k + 127) as u32) << 23)
}

/// `e^x`.
pub fn exp(x: f32) -> f32 {
    if x.is_nan() {
        return x;
    }
    if x > 88.722_84 {
        return f32::INFINITY;
    }
    if x < -103.972_08 {
        return 0.0;
    }
    let half = if x < 0.0 { -0.5 } else { 0.5 };
    let k = (x * LOG2_E + half) as i32;
    let r = (x - k as f32 * LN2_HI) - k as f32 * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0
                    + r * (1.0 / 24.0
                        + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    if k < -125 {
        // Subnormal result: scale in two steps.
        p * two_to(k + 64) * two_to(-64)
    } else if k > 127 {
        p * two_to(k - 1) * 2.0
    } else {
        p * two_to(k)
    }
}

/// `ln x` (`x > 0`; NaN below 0, `−∞` at 0).
pub fn ln(x: f32) -> f32 {
    if x.is_nan() || x < 0.0 {
        return f32::NAN;
    }
    if x == 0.0 {
        return f32::NEG_INFINITY;
    }
    if x == f32::INFINITY {
        return x;
    }
    let (x, bias) = if x < f32::MIN_POSITIVE {
        (x * two_to(25), -25)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    let mut e = ((bits >> 23) & 0xff) as i32 - 127 + bias;
    let mut m = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000); // [1, 2)
    if m > core::f32::consts::SQRT_2 {
        m *= 0.5;
        e += 1;
    }
    let s = (m - 1.0) / (m + 1.0);
    let z = s * s;
    let ln_m = 2.0 * s * (1.0 + z * (1.0 / 3.0 + z * (0.2 + z * (1.0 / 7.0 + z / 9.0))));
    e as f32 * LN2_HI + (ln_m + e as f32 * LN2_LO)
}

/// `e^x − 1`, accurate near 0.
pub fn exp_m1(x: f32) -> f32 {
    if abs(x) < 0.35 {
        x * (1.0
            + x * (0.5
                + x * (1.0 / 6.0
                    + x * (1.0 / 24.0
                        + x * (1.0 / 120.0
                            + x * (1.0 / 720.0 + x * (1.0 / 5040.0 + x * (1.0 / 40320.0))))))))
    } else {
        exp(x) - 1.0
    }
}

/// `ln(1 + x)`, accurate near 0 (`x > −1`).
pub fn ln_1p(x: f32) -> f32 {
    if abs(x) < 0.5 {
        let s = x / (2.0 + x);
        let z = s * s;
        let series = 1.0
            + z * (1.0 / 3.0
                + z * (0.2
                    + z * (1.0 / 7.0
                        + z * (1.0 / 9.0
                            + z * (1.0 / 11.0 + z * (1.0 / 13.0 + z * (1.0 / 15.0)))))));
        2.0 * s * series
    } else {
        ln(1.0 + x)
    }
}

#[cfg(all(test, feature = "libm"))]
mod tests {
    extern crate std;
    use super::*;

    /// Distance in ulps between two finite f32 of the same sign.
    fn ulps(a: f32, b: f32) -> u32 {
        if a == b {
            return 0;
        }
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs() as u32
    }

    /// Points spread over `[lo, hi]`, ends included.
    fn sweep(lo: f32, hi: f32, n: usize) -> impl Iterator<Item = f32> {
        (0..=n).map(move |i| lo + (hi - lo) * (i as f32 / n as f32))
    }

    #[test]
    fn exp_within_4_ulps_of_libm() {
        let mut worst = 0;
        for x in sweep(-103.0, 88.0, 200_000).chain([0.0, -1e-30, 1e-7, -87.5]) {
            let (a, b) = (exp(x), libm::expf(x));
            worst = worst.max(ulps(a, b));
            assert!(ulps(a, b) <= 4, "exp({x}) = {a} vs {b}");
        }
        std::println!("exp: {worst} ulps at most");
    }

    #[test]
    fn ln_within_4_ulps_of_libm() {
        let mut worst = 0;
        let points = sweep(1e-6, 4.0, 200_000)
            .chain(sweep(0.999, 1.001, 20_000))
            .chain([1e-40, 1e-30, f32::MIN_POSITIVE, 1.0, 1e30]);
        for x in points {
            let (a, b) = (ln(x), libm::logf(x));
            worst = worst.max(ulps(a, b));
            assert!(ulps(a, b) <= 4, "ln({x}) = {a} vs {b}");
        }
        std::println!("ln: {worst} ulps at most");
    }

    #[test]
    fn exp_m1_and_ln_1p_within_4_ulps_of_libm() {
        let mut worst = 0;
        for x in sweep(-0.999, 3.0, 200_000).chain([1e-30, -1e-20, 1e-7, -0.34999, 0.35]) {
            let (a, b) = (ln_1p(x), libm::log1pf(x));
            worst = worst.max(ulps(a, b));
            assert!(ulps(a, b) <= 4, "ln_1p({x}) = {a} vs {b}");
        }
        for x in sweep(-20.0, 5.0, 200_000).chain([1e-30, -1e-20, 1e-7, -0.34999, 0.35]) {
            let (a, b) = (exp_m1(x), libm::expm1f(x));
            worst = worst.max(ulps(a, b));
            assert!(ulps(a, b) <= 4, "exp_m1({x}) = {a} vs {b}");
        }
        std::println!("ln_1p, exp_m1: {worst} ulps at most");
    }
}
