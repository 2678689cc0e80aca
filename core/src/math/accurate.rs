//! `e^x`, `ln x`, `e^x − 1`, `ln(1 + x)` and `atan2(y, x)` in `f32` to within 4 ulps,
//! without a library. They are the `libm` backend's elementary functions (see
//! `math.rs`): `libm`'s `expf`, `logf`, `expm1f`, `log1pf`, `atan2f` and `atanf` took
//! 2,176 B of the firmware's flash, these take about 1,000 B less (release image, `cargo
//! xtask test`). With the `micromath` backend, whose own `exp` and `ln` are fast
//! approximations (relative error ~1e-3, not smooth), they serve where an algorithm
//! needs smooth, accurate functions: `SeedExact`'s quadrature nodes and root solves
//! (`Real::exp_accurate` and friends).
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
//!   (relative truncation `(1/3)¹⁴/15 ≤ 2e-8`);
//! * `atan2`: reduced to `t = min(|x|, |y|) / max(|x|, |y|) ∈ [0, 1]`; for
//!   `t > tan(π/12)`, `atan t = π/6 + atan((√3 t − 1)/(√3 + t))`, whose argument is in
//!   `[−tan(π/12), tan(π/12)]`; `atan u` there by its odd Taylor series to `u¹³`
//!   (truncation `u¹⁵/15 ≤ 1.8e-10`); then the octant and quadrant by symmetry
//!   (`π/2 − a`, `π − a`, sign of `y`), IEEE 754's signed zeros and infinities included.
//!
//! Measured against `libm` in the tests below (200,000 points each and the edges): `exp`
//! within 1 ulp, `ln` 3, `exp_m1` and `ln_1p` 4 (past the series ranges they are
//! `exp(x) − 1` and `ln(1 + x)`, whose cancellation costs up to 3 ulps), `atan2` 4
//! (or 2e-7 rad absolute where the angle is near 0).

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

/// `tan(π/12) = 2 − √3`: above it `atan` is shifted by `π/6`.
const TAN_PI_12: f32 = 0.267_949_2;
const SQRT_3: f32 = 1.732_050_8;

/// `atan u` for `|u| ≤ tan(π/12)`: odd Taylor series to `u¹³`.
fn atan_small(u: f32) -> f32 {
    let z = u * u;
    u * (1.0
        - z * (1.0 / 3.0
            - z * (0.2 - z * (1.0 / 7.0 - z * (1.0 / 9.0 - z * (1.0 / 11.0 - z * (1.0 / 13.0)))))))
}

/// Four-quadrant arctangent of `y / x` in `[−π, π]` (IEEE 754 `atan2`: signed zeros,
/// infinities; NaN in, NaN out).
pub fn atan2(y: f32, x: f32) -> f32 {
    use core::f32::consts::{FRAC_PI_2, FRAC_PI_4, FRAC_PI_6, PI};
    if x.is_nan() || y.is_nan() {
        return f32::NAN;
    }
    let (ax, ay) = (abs(x), abs(y));
    let first_quadrant = if ax == f32::INFINITY && ay == f32::INFINITY {
        FRAC_PI_4
    } else if ay == 0.0 {
        0.0
    } else {
        let swap = ay > ax;
        let t = if swap { ax / ay } else { ay / ax };
        let a = if t > TAN_PI_12 {
            FRAC_PI_6 + atan_small((SQRT_3 * t - 1.0) / (SQRT_3 + t))
        } else {
            atan_small(t)
        };
        if swap {
            FRAC_PI_2 - a
        } else {
            a
        }
    };
    let half_plane = if x.is_sign_negative() {
        PI - first_quadrant
    } else {
        first_quadrant
    };
    if y.is_sign_negative() {
        -half_plane
    } else {
        half_plane
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

    #[test]
    fn atan2_within_4_ulps_of_libm() {
        let mut worst = 0;
        let mut worst_abs = 0.0f32;
        // Every direction of the circle, at radii from 1e-30 to 1e30.
        for radius in [1e-30, 1e-3, 1.0, 7.3, 1e30] {
            for i in 0..=100_000 {
                let theta =
                    -core::f32::consts::PI + i as f32 * (2.0 * core::f32::consts::PI / 100_000.0);
                let (y, x) = (radius * libm::sinf(theta), radius * libm::cosf(theta));
                let (a, b) = (atan2(y, x), libm::atan2f(y, x));
                let error = abs(a - b);
                if error > 2e-7 {
                    worst = worst.max(ulps(a, b));
                    assert!(ulps(a, b) <= 4, "atan2({y}, {x}) = {a} vs {b}");
                }
                worst_abs = worst_abs.max(error);
            }
        }
        // Edges: signed zeros, infinities, tiny ratios, the reduction's breakpoint.
        let inf = f32::INFINITY;
        let edges = [
            (0.0, 0.0),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (1.0, 0.0),
            (-1.0, -0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (inf, inf),
            (-inf, inf),
            (inf, -inf),
            (-inf, -inf),
            (1.0, inf),
            (1.0, -inf),
            (-1.0, -inf),
            (inf, 1.0),
            (-inf, -1.0),
            (1e-38, 1.0),
            (1.0, 1e-38),
            (TAN_PI_12, 1.0),
            (1.0, TAN_PI_12),
            (-3.0, 3.0),
            (1e-45, -1.0),
        ];
        for (y, x) in edges {
            let (a, b) = (atan2(y, x), libm::atan2f(y, x));
            assert!(a == b || ulps(a, b) <= 4, "atan2({y}, {x}) = {a} vs {b}");
            assert_eq!(
                a.is_sign_negative(),
                b.is_sign_negative(),
                "sign of atan2({y}, {x})"
            );
        }
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
        std::println!("atan2: {worst} ulps at most where above 2e-7 rad; {worst_abs} rad at most");
    }
}
