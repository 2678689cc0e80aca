//! Bounded, bracketed root solve: Newton's method safeguarded by bisection.
//!
//! For an increasing function `f` with `f(lo) ≤ 0 ≤ f(hi)` (the caller establishes the
//! bracket, from values it computed or from a proven bound), each step evaluates
//! `(f(x), f'(x))` once, shrinks the bracket by the sign of `f(x)`, and moves to the
//! Newton point when it lies inside the bracket and is at most half the previous move
//! away, otherwise to the midpoint (as Numerical Recipes' `rtsafe`: where `f` is flat at
//! its rounding level Newton creeps by equal steps, and the bisections keep halving the
//! bracket). It returns
//! the last evaluated point when
//!
//! * `|f(x)|` is within the caller's `residual` — the rounding level of `f`, below which
//!   the root is not determined in this precision — or
//! * the Newton step is within [`TOLERANCE_EPSILONS`] machine epsilons of `x`, or
//! * the bracket is within that many epsilons of `max(|x|, ε)` (the variable lives in
//!   `[0, 1]`);
//!
//! and fails with [`Error::NumericalFailure`] after [`MAX_EVALUATIONS`] or on a NaN. It
//! never panics.

use crate::error::{Error, Result};
use crate::real::Real;

/// Evaluations at most: bisection alone narrows `[0, 1]` to `2⁻¹²⁸`, below f64's
/// absolute floor `2ε²` (a root next to 0 needs about 103 halvings); Newton from the
/// first-order guess takes a few (measured on the grid, see `docs/physics.md` §7).
pub(super) const MAX_EVALUATIONS: usize = 128;

/// Relative stopping tolerance on `x`, in machine epsilons of the evaluation precision.
const TOLERANCE_EPSILONS: f32 = 2.0;

/// One evaluation: `f(x)`, `f'(x)` (zero or non-finite: no Newton step), and what the
/// caller wants back at the root.
pub(super) struct Sample<R, T> {
    pub value: R,
    pub slope: R,
    pub payload: T,
}

/// The root of the increasing `f` in `[lo, hi]`, starting at `guess` (clamped into the
/// bracket), accepted where `|f| ≤ residual`: the last evaluated `x` and its payload.
pub(super) fn increasing_root<R: Real, T>(
    mut f: impl FnMut(R) -> Sample<R, T>,
    mut lo: R,
    mut hi: R,
    guess: R,
    residual: R,
) -> Result<(R, T)> {
    let ordered = lo <= hi;
    if !ordered {
        return Err(Error::NumericalFailure);
    }
    let tolerance = R::of(TOLERANCE_EPSILONS) * R::epsilon();
    // The ends may be roots themselves (a bound can be tight); they may be tried as long
    // as they have not been evaluated.
    let (mut lo_tried, mut hi_tried) = (false, false);
    let inside = |x: R, lo: R, hi: R, lo_tried: bool, hi_tried: bool| {
        (x > lo && x < hi) || (x == lo && !lo_tried) || (x == hi && !hi_tried)
    };
    let mut x = if inside(guess, lo, hi, false, false) {
        guess
    } else {
        R::of(0.5) * (lo + hi)
    };
    // The previous move; the first Newton step is free (any move inside the bracket is
    // at most half of this).
    let mut last_move = R::of(2.0) * (hi - lo);
    for _ in 0..MAX_EVALUATIONS {
        let Sample {
            value,
            slope,
            payload,
        } = f(x);
        if value.partial_cmp(&R::ZERO).is_none() {
            return Err(Error::NumericalFailure); // NaN
        }
        if R::abs(value) <= residual {
            return Ok((x, payload));
        }
        if value < R::ZERO {
            lo = x;
            lo_tried = true;
        } else {
            hi = x;
            hi_tried = true;
        }
        let scale = R::abs(x) * tolerance;
        // The bracket test is relative to x but never below ε (absolute, w ∈ [0, 1]):
        // where Newton cannot help (a square-root singularity with the root a few ulps
        // above 0, as a nearly plastic impact, e* ≈ 1e-38, puts the impact end) a purely
        // relative width would take about a thousand halvings (found by the `collide`
        // fuzz target); with the floor, ~103 in f64. A root below ε is below what the
        // precision resolves next to w = 1 anyway. Newton steps keep the relative test.
        if hi - lo <= R::max(R::abs(x), R::epsilon()) * tolerance {
            return Ok((x, payload));
        }
        let step = value / slope; // ±inf or NaN when the slope is 0 or not finite
                                  // A Newton point past an end not yet tried goes to that end (a tight bound).
        let newton = match x - step {
            n if n > hi && !hi_tried => hi,
            n if n < lo && !lo_tried => lo,
            n => n,
        };
        let converging = R::abs(newton - x) <= R::of(0.5) * last_move;
        if slope > R::ZERO && inside(newton, lo, hi, lo_tried, hi_tried) && converging {
            if R::abs(step) <= scale {
                return Ok((x, payload));
            }
            last_move = R::abs(newton - x);
            x = newton;
        } else {
            let middle = R::of(0.5) * (lo + hi);
            last_move = R::abs(middle - x);
            x = middle;
        }
    }
    Err(Error::NumericalFailure)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(x: f64, value: f64, slope: f64) -> Sample<f64, f64> {
        Sample {
            value,
            slope,
            payload: x,
        }
    }

    /// A square-root singularity with its root a few ulps above 0 (how a nearly
    /// plastic impact's end looks): converges on the absolute floor of the tolerance.
    #[test]
    fn finds_a_root_next_to_zero_under_a_square_root() {
        let depth = 1e-19;
        let found = increasing_root(
            |x: f64| {
                let root = x.max(0.0).sqrt();
                let slope = if root > 0.0 { 0.5 / root } else { 0.0 };
                sample(x, root - depth, slope)
            },
            0.0,
            1.0,
            0.0,
            4.0 * f64::EPSILON * depth,
        );
        let (x, _) = found.expect("converges");
        assert!((0.0..=4.0 * f64::EPSILON).contains(&x), "{x:e}");
    }

    /// Found by the `collide` fuzz target: an impact at 3.6e-22 m/s in f32, whose work
    /// `D` is subnormal, so `√D` is flat over whole stretches of `w`: Newton crept by
    /// equal steps of 1e-5 of the bracket and ran out of evaluations (`NumericalFailure`
    /// for a valid input). A function that is flat at ±1e-6 either side of its root
    /// (Newton steps of 1e-6) reproduces it.
    #[test]
    fn a_function_flat_at_its_rounding_level_is_bisected() {
        let (x, _) = increasing_root(
            |x: f32| Sample {
                value: if x < 0.7 { -1e-6 } else { 1e-6 },
                slope: 1.0,
                payload: x,
            },
            0.0,
            1.0,
            0.1,
            1e-9,
        )
        .expect("converges");
        assert!((x - 0.7).abs() < 1e-6, "{x}");
    }

    #[test]
    fn finds_a_root_quadratically() {
        let mut calls = 0;
        let (x, at) = increasing_root(
            |x: f64| {
                calls += 1;
                sample(x, x * x * x - 0.125, 3.0 * x * x)
            },
            0.0,
            1.0,
            0.6,
            0.0,
        )
        .unwrap();
        assert!((x - 0.5).abs() < 1e-14 && at == x);
        assert!(calls <= 8, "{calls}");
    }

    #[test]
    fn falls_back_to_bisection_without_a_slope() {
        let (x, _) = increasing_root(|x: f64| sample(x, x - 0.3, 0.0), 0.0, 1.0, 0.9, 0.0).unwrap();
        assert!((x - 0.3).abs() < 1e-13);
    }

    #[test]
    fn reports_failure_instead_of_nan() {
        let nan = increasing_root(|x: f64| sample(x, f64::NAN, 1.0), 0.0, 1.0, 0.5, 0.0);
        assert_eq!(nan.unwrap_err(), Error::NumericalFailure);
        let empty = increasing_root(|x: f64| sample(x, x, 1.0), 1.0, 0.0, 0.5, 0.0);
        assert_eq!(empty.unwrap_err(), Error::NumericalFailure);
    }

    #[test]
    fn a_root_near_the_lower_end_is_found_to_relative_precision() {
        let (x, _) =
            increasing_root(|x: f64| sample(x, x - 1e-12, 1.0), 0.0, 1.0, 0.5, 0.0).unwrap();
        assert!((x - 1e-12).abs() < 1e-24, "{x}");
    }
}
