//! Evaluation precision: the models are generic over [`Real`], implemented for `f32`
//! (the Cortex-M4F's hardware precision, the default) and, with the `libm` backend,
//! `f64` (software on the M4F; for measuring what precision costs and buys).
//!
//! Inputs (`Params`, `Impact`) and the `Outcome` stay `f32`; only the evaluation in
//! between changes precision. Every function goes through the math shim.

use core::ops::{Add, Div, Mul, Neg, Sub};

/// A floating-point type the models can be evaluated in.
pub trait Real:
    Copy
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// `true` for `f32`: a constant that `Params` derived once in `f32` is then exactly
    /// what the evaluation would compute, so a model may load it instead.
    const SINGLE: bool;
    /// Widen (or keep) an `f32`.
    fn of(x: f32) -> Self;
    /// Round (or keep) an `f64` constant, e.g. a quadrature node, so that each
    /// precision gets the constant to its own resolution.
    fn of_f64(x: f64) -> Self {
        Self::of(x as f32)
    }
    /// The same constant given at both precisions (`narrow` the `f32` rounding of
    /// `wide`, done at compile time): each precision takes its own, and no `f64` is
    /// converted at run time on an `f32` evaluation (on the Cortex-M4F that would be
    /// a software `__aeabi_d2f`).
    fn of_pair(wide: f64, narrow: f32) -> Self {
        let _ = wide;
        Self::of(narrow)
    }
    /// Machine epsilon (spacing of the values just above 1), for relative tolerances.
    fn epsilon() -> Self {
        Self::of(f32::EPSILON)
    }
    /// Round to `f32`.
    fn to_f32(self) -> f32;
    /// Square root.
    fn sqrt(x: Self) -> Self;
    /// [`Real::sqrt`], always inlined (`math::sqrt_inline`): `KimGrip`'s fast paths.
    fn sqrt_inline(x: Self) -> Self {
        Self::sqrt(x)
    }
    /// Square roots of two numbers, `(sqrt(a), sqrt(b))` (one instruction sequence
    /// for both where that is cheaper: `math::sqrt_pair`).
    fn sqrt_pair(a: Self, b: Self) -> (Self, Self) {
        (Self::sqrt(a), Self::sqrt(b))
    }
    /// Absolute value.
    fn abs(x: Self) -> Self;
    /// `e^x`.
    fn exp(x: Self) -> Self;
    /// Natural logarithm.
    fn ln(x: Self) -> Self;
    /// `e^x − 1`, accurate near zero.
    fn exp_m1(x: Self) -> Self;
    /// `ln(1 + x)`, accurate near zero.
    fn ln_1p(x: Self) -> Self;
    /// `e^x` to this precision's own accuracy whatever the math backend (the `micromath`
    /// backend's `exp` is a ~1e-3 approximation): for an algorithm that needs smooth,
    /// accurate elementary functions (`SeedExact`'s quadrature and root solves).
    fn exp_accurate(x: Self) -> Self {
        Self::exp(x)
    }
    /// `ln x`, as accurate as [`Real::exp_accurate`].
    fn ln_accurate(x: Self) -> Self {
        Self::ln(x)
    }
    /// `e^x − 1`, as accurate as [`Real::exp_accurate`].
    fn exp_m1_accurate(x: Self) -> Self {
        Self::exp_m1(x)
    }
    /// `ln(1 + x)`, as accurate as [`Real::exp_accurate`].
    fn ln_1p_accurate(x: Self) -> Self {
        Self::ln_1p(x)
    }
    /// Larger of two (non-NaN) values, by comparison.
    fn max(a: Self, b: Self) -> Self {
        if a > b {
            a
        } else {
            b
        }
    }
    /// Smaller of two (non-NaN) values, by comparison.
    fn min(a: Self, b: Self) -> Self {
        if a < b {
            a
        } else {
            b
        }
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const SINGLE: bool = true;
    #[inline(always)]
    fn of(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn to_f32(self) -> f32 {
        self
    }
    #[inline(always)]
    fn sqrt(x: Self) -> Self {
        crate::math::sqrt(x)
    }
    #[inline(always)]
    fn sqrt_inline(x: Self) -> Self {
        crate::math::sqrt_inline(x)
    }
    #[inline(always)]
    fn sqrt_pair(a: Self, b: Self) -> (Self, Self) {
        crate::math::sqrt_pair(a, b)
    }
    #[inline(always)]
    fn abs(x: Self) -> Self {
        crate::math::abs(x)
    }
    #[inline(always)]
    fn exp(x: Self) -> Self {
        crate::math::exp(x)
    }
    #[inline(always)]
    fn ln(x: Self) -> Self {
        crate::math::ln(x)
    }
    #[inline(always)]
    fn exp_m1(x: Self) -> Self {
        crate::math::exp_m1(x)
    }
    #[inline(always)]
    fn ln_1p(x: Self) -> Self {
        crate::math::ln_1p(x)
    }
    #[cfg(feature = "micromath")]
    #[inline(always)]
    fn exp_accurate(x: Self) -> Self {
        crate::math::accurate::exp(x)
    }
    #[cfg(feature = "micromath")]
    #[inline(always)]
    fn ln_accurate(x: Self) -> Self {
        crate::math::accurate::ln(x)
    }
    #[cfg(feature = "micromath")]
    #[inline(always)]
    fn exp_m1_accurate(x: Self) -> Self {
        crate::math::accurate::exp_m1(x)
    }
    #[cfg(feature = "micromath")]
    #[inline(always)]
    fn ln_1p_accurate(x: Self) -> Self {
        crate::math::accurate::ln_1p(x)
    }
}

#[cfg(feature = "libm")]
impl Real for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const SINGLE: bool = false;
    #[inline(always)]
    fn of(x: f32) -> Self {
        x as f64
    }
    #[inline(always)]
    fn of_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn of_pair(wide: f64, _narrow: f32) -> Self {
        wide
    }
    #[inline(always)]
    fn epsilon() -> Self {
        f64::EPSILON
    }
    #[inline(always)]
    fn to_f32(self) -> f32 {
        self as f32
    }
    #[inline(always)]
    fn sqrt(x: Self) -> Self {
        libm::sqrt(x)
    }
    #[inline(always)]
    fn abs(x: Self) -> Self {
        f64::from_bits(x.to_bits() & 0x7fff_ffff_ffff_ffff)
    }
    #[inline(always)]
    fn exp(x: Self) -> Self {
        libm::exp(x)
    }
    #[inline(always)]
    fn ln(x: Self) -> Self {
        libm::log(x)
    }
    #[inline(always)]
    fn exp_m1(x: Self) -> Self {
        libm::expm1(x)
    }
    #[inline(always)]
    fn ln_1p(x: Self) -> Self {
        libm::log1p(x)
    }
}
