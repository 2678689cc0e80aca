//! The one math shim: every floating-point function the core calls goes through here.
//!
//! Backends are chosen by Cargo feature: `libm` (default, accurate) or `micromath`
//! (smaller and faster, approximate). Exactly one must be enabled. With `libm`, `exp`,
//! `ln`, `exp_m1`, `ln_1p` and `atan2` are `math::accurate`'s f32 routines, within 1–4 ulps
//! of the `libm` crate's (its tests check them against it): on the firmware they take
//! about 1,160 B less flash than `libm`'s `expf`, `logf`, `expm1f`, `log1pf`, `atan2f`
//! and `atanf`; on the host `libm` gives the square root. On an FPU-equipped Cortex-M (`thumbv7em-none-eabihf`) the square root is
//! the hardware `vsqrt.f32` instruction whatever the backend: it is exact (IEEE 754
//! correctly rounded) and about 14 cycles, while `libm::sqrtf` is a software loop.
//!
//! Only [`sqrt`] and [`abs`] are on the hot path; the trigonometric functions are
//! used to build inputs from angles and to report angles, never inside a collision.

#[cfg(all(feature = "libm", feature = "micromath"))]
compile_error!(
    "cuesight: enable exactly one math backend feature: `libm` or `micromath`, not both"
);
#[cfg(not(any(feature = "libm", feature = "micromath")))]
compile_error!("cuesight: enable one math backend feature: `libm` (default) or `micromath`");

#[cfg(feature = "micromath")]
use micromath::F32Ext as _;

// Accurate elementary functions: the `libm` backend's `exp`, `ln`, `exp_m1`, `ln_1p`
// and `atan2`, and with `micromath` its `Real::exp_accurate` and friends.
// (`atan2` is unused with `micromath`, which has its own.)
#[cfg_attr(feature = "micromath", allow(dead_code))]
pub(crate) mod accurate;

// Short polynomial `e^{−x}`, `ln` and `(1 − e^{−x})/x` for KimGrip's speed-dependent
// friction fast path (f32 only; the core feature `speed-path`).
#[cfg(feature = "speed-path")]
pub(crate) mod fast;

/// Square root of `x` (`x ≥ 0`; returns NaN for negative input like IEEE `sqrt`).
/// Out of line with the `compact-sqrt` feature (the firmware's: smaller than the
/// inlined block at every call), else inlined (`sqrt_inline`).
#[cfg_attr(feature = "compact-sqrt", inline(never))]
#[cfg_attr(not(feature = "compact-sqrt"), inline(always))]
pub fn sqrt(x: f32) -> f32 {
    sqrt_inline(x)
}

/// [`sqrt`], inlined whatever `compact-sqrt` says: for `KimGrip`'s fast paths, whose
/// instruction counts are held to targets on the images that ship (out of line, the
/// fast path's longest branch took 164 instructions instead of 147).
#[inline(always)]
pub(crate) fn sqrt_inline(x: f32) -> f32 {
    #[cfg(all(
        target_arch = "arm",
        target_abi = "eabihf",
        not(feature = "unstable-intrinsics")
    ))]
    {
        let bits: u32;
        // Rust 1.95 refuses an `f32` operand in an FPU register on thumbv7em-none-eabihf
        // (the `sreg` class asks for `vfp2`, which implies double precision;
        // rust-lang/rust#159976, fixed in later releases), but accepts s0 as a clobber:
        // the operand travels through a core register and s0 is the scratch register.
        // Five instructions per root (two moves the compiler adds, three here) instead
        // of the compiler's one `vsqrt.f32`.
        // SAFETY: `vsqrt.f32` is a pure FPU instruction; the only register written
        // besides the output is s0, declared clobbered.
        #[allow(unsafe_code)]
        unsafe {
            core::arch::asm!(
                "vmov s0, {input}",
                "vsqrt.f32 s0, s0",
                "vmov {output}, s0",
                input = in(reg) x.to_bits(),
                output = lateout(reg) bits,
                out("s0") _,
                options(pure, nomem, nostack, preserves_flags),
            );
        }
        f32::from_bits(bits)
    }
    // The compiler's own square root (LLVM `llvm.sqrt.f32`): a bare `vsqrt.f32` with no
    // register shuffling. Nightly only (the `unstable-intrinsics` feature).
    #[cfg(all(
        target_arch = "arm",
        target_abi = "eabihf",
        feature = "unstable-intrinsics"
    ))]
    {
        // SAFETY: `sqrtf32` has no precondition (negative input gives NaN, as IEEE).
        #[allow(unsafe_code)]
        unsafe {
            core::intrinsics::sqrtf32(x)
        }
    }
    #[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
    {
        #[cfg(feature = "libm")]
        {
            libm::sqrtf(x)
        }
        #[cfg(feature = "micromath")]
        {
            x.sqrt()
        }
    }
}

/// Square roots of `a` and `b` together: `(sqrt(a), sqrt(b))`, each exactly as
/// [`sqrt`]. On the Cortex-M4F one `asm!` block takes both (s0 and s1 scratch, the
/// operands moved in and out as a pair), eight instructions instead of ten.
#[inline(always)]
pub fn sqrt_pair(a: f32, b: f32) -> (f32, f32) {
    #[cfg(all(
        target_arch = "arm",
        target_abi = "eabihf",
        not(feature = "unstable-intrinsics")
    ))]
    {
        let (root_a, root_b): (u32, u32);
        // SAFETY: as in `sqrt`; s0 and s1 are declared clobbered.
        #[allow(unsafe_code)]
        unsafe {
            core::arch::asm!(
                "vmov s0, s1, {a}, {b}",
                "vsqrt.f32 s0, s0",
                "vsqrt.f32 s1, s1",
                "vmov {a}, {b}, s0, s1",
                a = inout(reg) a.to_bits() => root_a,
                b = inout(reg) b.to_bits() => root_b,
                out("s0") _,
                out("s1") _,
                options(pure, nomem, nostack, preserves_flags),
            );
        }
        (f32::from_bits(root_a), f32::from_bits(root_b))
    }
    #[cfg(not(all(
        target_arch = "arm",
        target_abi = "eabihf",
        not(feature = "unstable-intrinsics")
    )))]
    {
        (sqrt_inline(a), sqrt_inline(b))
    }
}

/// Absolute value (bit operation: exact, no call).
#[inline(always)]
pub fn abs(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
}

/// Larger of `a` and `b` (for non-NaN inputs). A comparison, because `f32::max` lowers
/// to a `fmaxf` library call on ARMv7-M, which has no `vmaxnm`.
#[inline(always)]
pub fn max(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

mod sincos;

/// Sine of `x` (radians). Input construction only. Both backends use the f32-only
/// `sincos` reduction and polynomials (within 1.2e-7 of the exact value for
/// |x| ≤ 8192): `libm::sinf` reduces in f64, which is software on the Cortex-M4F.
#[inline]
pub fn sin(x: f32) -> f32 {
    sincos::sin_cos(x).0
}

/// Cosine of `x` (radians). Input construction only; see [`sin`].
#[inline]
pub fn cos(x: f32) -> f32 {
    sincos::sin_cos(x).1
}

/// `(sin x, cos x)` in one reduction; see [`sin`].
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    sincos::sin_cos(x)
}

/// `e^x`. Only for the speed-dependent friction law.
#[inline]
pub fn exp(x: f32) -> f32 {
    #[cfg(feature = "libm")]
    {
        accurate::exp(x)
    }
    #[cfg(feature = "micromath")]
    {
        x.exp()
    }
}

/// Natural logarithm of `x` (`x > 0`). Only for the speed-dependent friction law.
#[inline]
pub fn ln(x: f32) -> f32 {
    #[cfg(feature = "libm")]
    {
        accurate::ln(x)
    }
    #[cfg(feature = "micromath")]
    {
        x.ln()
    }
}

/// `e^x − 1`, accurate near zero. Only for the speed-dependent friction law.
#[inline]
pub fn exp_m1(x: f32) -> f32 {
    #[cfg(feature = "libm")]
    {
        accurate::exp_m1(x)
    }
    #[cfg(feature = "micromath")]
    {
        // Taylor series where `exp(x) − 1` would cancel (error < x⁴/24 ≤ 4e-14).
        if abs(x) < 1e-3 {
            x * (1.0 + x * (0.5 + x / 6.0))
        } else {
            x.exp() - 1.0
        }
    }
}

/// `ln(1 + x)`, accurate near zero. Only for the speed-dependent friction law.
#[inline]
pub fn ln_1p(x: f32) -> f32 {
    #[cfg(feature = "libm")]
    {
        accurate::ln_1p(x)
    }
    #[cfg(feature = "micromath")]
    {
        if abs(x) < 1e-3 {
            x * (1.0 - x * (0.5 - x / 3.0))
        } else {
            (1.0 + x).ln()
        }
    }
}

/// Four-quadrant arctangent of `y / x` in radians, in `[-π, π]`. Reporting only.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    #[cfg(feature = "libm")]
    {
        accurate::atan2(y, x)
    }
    #[cfg(feature = "micromath")]
    {
        y.atan2(x)
    }
}

/// `true` when `x` is neither NaN nor infinite.
#[inline(always)]
pub fn is_finite(x: f32) -> bool {
    // Exponent bits all ones means NaN or ±Inf.
    (x.to_bits() & 0x7f80_0000) != 0x7f80_0000
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sqrt_is_exact_on_squares_and_zero() {
        assert_eq!(sqrt_pair(16.0, 2.25), (4.0, 1.5));
        assert_eq!(sqrt(0.0), 0.0);
        assert_eq!(sqrt(16.0), 4.0);
        assert_eq!(sqrt(2.25), 1.5);
    }

    #[test]
    fn abs_clears_only_the_sign() {
        assert_eq!(abs(-2.5), 2.5);
        assert_eq!(abs(2.5), 2.5);
        assert_eq!(abs(-0.0).to_bits(), 0.0f32.to_bits());
    }

    #[test]
    fn is_finite_rejects_nan_and_infinities() {
        assert!(is_finite(1.0e38));
        assert!(is_finite(-1.0e-45));
        assert!(!is_finite(f32::NAN));
        assert!(!is_finite(f32::INFINITY));
        assert!(!is_finite(f32::NEG_INFINITY));
    }

    #[test]
    fn atan2_quadrants() {
        let quarter = core::f32::consts::FRAC_PI_2;
        assert!((atan2(1.0, 0.0) - quarter).abs() < 1e-6);
        assert!((atan2(-1.0, 0.0) + quarter).abs() < 1e-6);
    }
}
