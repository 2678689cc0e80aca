//! Single-precision sine and cosine without double precision: Cody–Waite reduction by
//! π/2 in three f32 parts and the Cephes `sinf`/`cosf` polynomials on [−π/4, π/4]
//! (S. L. Moshier, *Cephes Math Library*, `sinf.c`, 1989; coefficients below).
//!
//! Why not `libm::sinf`: its argument reduction (`rem_pio2f`) and kernels work in f64,
//! which on a Cortex-M4F is software floating point — about 6 KB of flash and slow.
//! The core only takes sines and cosines of angles it has validated (a cut angle below
//! 90°, an aim angle within ±1000 rad), where this reduction is accurate.
//!
//! Accuracy (measured against f64 by the tests): within 1.2e-7 absolute for
//! |x| ≤ 8192 rad; outside that range the result stays finite and in [−1, 1] but loses
//! accuracy (the three-part π/2 no longer reduces exactly), and beyond 1.3e7 rad, where
//! an f32 angle has no phase left, it is `(0, 1)`.

/// π/2 in three parts: `PIO2_1` has 8 significant bits, so `k · PIO2_1` is exact for
/// |k| < 2^16; the sum of the three is π/2 to about 2^-60 (Cephes `DP1..DP3`, doubled).
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = 4.837_513e-4;
const PIO2_3: f32 = 7.549_79e-8;
/// 2/π.
const TWO_OVER_PI: f32 = core::f32::consts::FRAC_2_PI;

/// sin(r) for |r| ≤ π/4 (Cephes `sinf` polynomial; relative error ≲ 3e-8).
#[inline(always)]
fn sin_kernel(r: f32, z: f32) -> f32 {
    ((-1.951_529_6e-4 * z + 8.332_161e-3) * z - 1.666_665_5e-1) * z * r + r
}

/// cos(r) for |r| ≤ π/4, `z = r²` (Cephes `cosf` polynomial).
#[inline(always)]
fn cos_kernel(z: f32) -> f32 {
    ((2.443_315_7e-5 * z - 1.388_731_6e-3) * z + 4.166_664_6e-2) * z * z - 0.5 * z + 1.0
}

/// `(sin x, cos x)`. NaN and infinities give NaN (the callers reject them first).
pub fn sin_cos(x: f32) -> (f32, f32) {
    if !super::is_finite(x) {
        return (f32::NAN, f32::NAN);
    }
    // Nearest multiple of π/2.
    let scaled = x * TWO_OVER_PI;
    if super::abs(scaled) >= 8_388_608.0 {
        // |x| > 1.3e7: neighbouring floats are more than π apart, so the angle carries
        // no phase at all; answer a finite, valid pair rather than garbage.
        return (0.0, 1.0);
    }
    let rounded = scaled + if scaled >= 0.0 { 0.5 } else { -0.5 };
    let k = rounded as i32 as f32;
    let r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
    let z = r * r;
    // Clamped: far out (|x| > 8192) the reduction is inexact and a kernel could stray
    // past ±1 by an ulp.
    let clamp = |v: f32| v.clamp(-1.0, 1.0);
    let (s, c) = (clamp(sin_kernel(r, z)), clamp(cos_kernel(z)));
    // Quadrant: k mod 4 (two's complement keeps negative k right).
    match (k as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    /// Largest absolute error against f64 over `n` points spread over [−span, span].
    fn worst(span: f64, n: u32) -> f64 {
        let mut worst = 0.0f64;
        for i in 0..=n {
            let x = (-span + 2.0 * span * f64::from(i) / f64::from(n)) as f32;
            let (s, c) = sin_cos(x);
            let exact = f64::from(x);
            worst = worst
                .max((f64::from(s) - exact.sin()).abs())
                .max((f64::from(c) - exact.cos()).abs());
        }
        worst
    }

    #[test]
    fn within_1_2e_7_of_f64_up_to_8192_radians() {
        for (span, n) in [
            (1.0, 200_000),
            (8.0, 400_000),
            (1000.0, 400_000),
            (8192.0, 400_000),
        ] {
            let error = worst(span, n);
            assert!(error <= 1.2e-7, "span {span}: {error:e}");
        }
    }

    #[test]
    fn exact_at_zero_and_quadrant_signs() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let (s, c) = sin_cos(core::f32::consts::FRAC_PI_2);
        assert!((s - 1.0).abs() < 1e-7 && c.abs() < 1e-7);
        let (s, c) = sin_cos(-core::f32::consts::PI);
        assert!(s.abs() < 1e-6 && (c + 1.0).abs() < 1e-7);
        let (s, c) = sin_cos(-0.5);
        assert!(s < 0.0 && c > 0.0);
    }

    #[test]
    fn odd_and_even_symmetry_is_exact() {
        for i in 0..10_000 {
            let x = i as f32 * 0.001_37;
            let (s, c) = sin_cos(x);
            let (sn, cn) = sin_cos(-x);
            assert_eq!((sn, cn), (-s, c), "x = {x}");
        }
    }

    #[test]
    fn finite_and_bounded_far_out_nan_for_non_finite() {
        for x in [1e4f32, -3e5, 1e10, f32::MAX, -f32::MAX] {
            let (s, c) = sin_cos(x);
            assert!(s.abs() <= 1.0 && c.abs() <= 1.0, "{x}: {s} {c}");
        }
        assert!(sin_cos(f32::NAN).0.is_nan());
        assert!(sin_cos(f32::INFINITY).1.is_nan());
    }
}
