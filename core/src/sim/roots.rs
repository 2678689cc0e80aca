//! The first time a polynomial of degree ≤ 4 rises through zero on an interval: the
//! event-time solver of the table simulation, robust at tangency.
//!
//! Within one motion phase a ball's centre is a quadratic in time (TP A.4,
//! [`crate::travel`]), so two balls touch where `(2R)² − |d(σ)|² = 0` with `d` the
//! quadratic difference of their centres: a quartic in `σ`. A ball reaches a cushion or
//! pocket line where `n · r(σ) − c = 0`: a quadratic. Closed-form quartic roots lose
//! their digits near double roots, which is exactly a grazing contact; instead the
//! interval is cut at the critical points of the polynomial (the roots of its cubic
//! derivative, isolated in turn between the roots of the quadratic second derivative,
//! which have a closed form), so that the polynomial is monotone on every piece, and
//! the root in the first piece on which it rises to zero or above is bracketed to 1e-7
//! s (regula falsi, Illinois). A graze that touches
//! zero is found however small the overlap; one that stays below it is not an event.
//!
//! The value itself comes from the caller (`value`), evaluated from the geometry rather
//! than from the expanded coefficients, which cancel near contact; the coefficients are
//! only used for the derivatives.

use crate::math;

/// Coefficients `c[0] + c[1] σ + c[2] σ² + c[3] σ³ + c[4] σ⁴`.
pub(crate) type Poly = [f32; 5];

/// Horner evaluation.
pub(crate) fn eval(c: &Poly, x: f32) -> f32 {
    (((c[4] * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0]
}

fn derivative(c: &Poly) -> Poly {
    [c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4], 0.0]
}

/// Iteration cap of [`bracket`]: far more than it needs (the Illinois method gains
/// about 1.44 digits per step; a bracket of a few seconds closes to 1e-7 s in about ten),
/// so that a pathological function still ends.
const STEPS: usize = 48;

/// A bracket `(low, high)` of a sign change of `f` inside `[low, high]` (`f(low)` and
/// `f(high)` of opposite signs or zero), narrowed until `high − low` is within
/// [`tolerance_at`] `high` or the
/// floats between them run out; `low` keeps the sign of `f(low)`. Regula falsi with the
/// Illinois modification (Dowell & Jarratt 1971): the secant through the bracket's ends,
/// halving the weight of an end kept twice in a row, so it converges superlinearly
/// where plain bisection needs ~24 steps for f32.
fn bracket(f: impl Fn(f32) -> f32, mut low: f32, mut high: f32) -> (f32, f32) {
    let (mut f_low, mut f_high) = (f(low), f(high));
    let low_sign = f_low >= 0.0;
    let mut kept = 0i8; // +1: low kept last time, −1: high kept
    for _ in 0..STEPS {
        if high - low <= tolerance_at(high) {
            break;
        }
        let denominator = f_high - f_low;
        let mut middle = if denominator != 0.0 {
            low - f_low * (high - low) / denominator
        } else {
            0.5 * (low + high)
        };
        // Keep strictly inside (rounding, or a NaN from an overflow, falls back to the
        // midpoint).
        if !(middle > low && middle < high) {
            middle = 0.5 * (low + high);
            if middle <= low || middle >= high {
                break;
            }
        }
        let f_middle = f(middle);
        if (f_middle >= 0.0) == low_sign {
            low = middle;
            f_low = f_middle;
            if kept == -1 {
                f_high *= 0.5;
            }
            kept = -1;
        } else {
            high = middle;
            f_high = f_middle;
            if kept == 1 {
                f_low *= 0.5;
            }
            kept = 1;
        }
    }
    (low, high)
}

/// Time resolution of the event solver (s): 1e-7 s, or 4 float steps at `x` where that
/// is more. A ball at 10 m/s moves 1 µm in 1e-7 s.
fn tolerance_at(x: f32) -> f32 {
    let steps = 5e-7 * math::abs(x);
    if steps > 1e-7 {
        steps
    } else {
        1e-7
    }
}

/// Real roots of the quadratic `c[0] + c[1] x + c[2] x²` strictly inside `(low, high)`,
/// sorted, into `out`; returns how many (stable form, Numerical Recipes §5.6).
fn quadratic_roots_in(c0: f32, c1: f32, c2: f32, low: f32, high: f32, out: &mut [f32; 2]) -> usize {
    let mut roots = [f32::NAN; 2];
    let scale = math::max(math::max(math::abs(c2), math::abs(c1)), math::abs(c0));
    if scale == 0.0 {
        return 0;
    }
    if math::abs(c2) <= 1e-7 * scale {
        if c1 != 0.0 {
            roots[0] = -c0 / c1;
        }
    } else {
        let discriminant = c1 * c1 - 4.0 * c2 * c0;
        if discriminant >= 0.0 {
            let root = math::sqrt(discriminant);
            let q = -0.5 * (c1 + if c1 >= 0.0 { root } else { -root });
            roots[0] = q / c2;
            if q != 0.0 {
                roots[1] = c0 / q;
            }
        }
    }
    if roots[1] < roots[0] {
        roots.swap(0, 1);
    }
    let mut n = 0;
    for r in roots {
        // NaN fails both comparisons.
        if r > low && r < high {
            out[n] = r;
            n += 1;
        }
    }
    n
}

/// The first `σ` in `[0, span]` at which the polynomial rises to zero or above: the
/// start of the first piece on which it increases and ends at or above zero if it is
/// already there, else the last float below the root in that piece (so that at the
/// returned time the polynomial is still just below zero: two balls not yet
/// overlapping, a centre not yet past a line). `None` if it never does.
///
/// `coefficients` give the shape (derivatives), `value` the value; they describe the
/// same polynomial. A piece on which it is constant is not a rise (two balls at rest,
/// touching).
pub(crate) fn first_rise(
    coefficients: &Poly,
    span: f32,
    value: impl Fn(f32) -> f32,
) -> Option<f32> {
    if span < 0.0 || span.is_nan() {
        return None;
    }
    let first = derivative(coefficients);
    let second = derivative(&first);
    // Pieces on which the first derivative is monotone: cut at the second's roots.
    let mut cuts = [0.0f32; 2];
    let n_cuts = quadratic_roots_in(second[0], second[1], second[2], 0.0, span, &mut cuts);
    let mut knots = [0.0f32; 4];
    let mut n_knots = 0;
    let mut low = 0.0;
    for high in cuts.into_iter().take(n_cuts).chain(core::iter::once(span)) {
        let (d_low, d_high) = (eval(&first, low), eval(&first, high));
        if (d_low < 0.0 && d_high > 0.0) || (d_low > 0.0 && d_high < 0.0) {
            let (a, b) = bracket(|x| eval(&first, x), low, high);
            knots[n_knots] = 0.5 * (a + b);
            n_knots += 1;
        }
        low = high;
    }
    // Pieces on which the polynomial is monotone.
    let mut low = 0.0;
    let mut at_low = value(0.0);
    for high in knots
        .into_iter()
        .take(n_knots)
        .chain(core::iter::once(span))
    {
        let at_high = value(high);
        if at_high >= 0.0 && at_high > at_low {
            if at_low >= 0.0 {
                return Some(low);
            }
            return Some(bracket(&value, low, high).0);
        }
        low = high;
        at_low = at_high;
    }
    None
}

/// [`first_rise`] for a polynomial of degree ≤ 2, `c[0] + c[1] σ + c[2] σ²` (a centre
/// crossing a line): the root in closed form (stable, Numerical Recipes §5.6) where the
/// polynomial increases, then moved down to the last float below zero, as `first_rise`
/// returns it; `first_rise` itself where that takes more than a few steps (a root the
/// formula rounds too far).
pub(crate) fn first_rise_quadratic(
    c: [f32; 3],
    span: f32,
    value: impl Fn(f32) -> f32,
) -> Option<f32> {
    if span < 0.0 || span.is_nan() {
        return None;
    }
    let (c0, c1, c2) = (c[0], c[1], c[2]);
    let rising_now = c1 > 0.0 || (c1 == 0.0 && c2 > 0.0);
    if c0 >= 0.0 && rising_now {
        return Some(0.0);
    }
    let mut roots = [f32::NAN; 2];
    let n = quadratic_roots_in(c0, c1, c2, 0.0, span, &mut roots);
    // The root at which it rises: where the derivative c1 + 2 c2 σ is not negative.
    let root = roots
        .into_iter()
        .take(n)
        .find(|&r| c1 + 2.0 * c2 * r >= 0.0)
        // A root at the very end (the formula's interval is open).
        .or_else(|| (c1 + 2.0 * c2 * span > 0.0 && value(span) >= 0.0).then_some(span));
    let mut sigma = root?;
    for _ in 0..4 {
        if value(sigma) < 0.0 {
            return Some(sigma);
        }
        if sigma <= 0.0 {
            break;
        }
        sigma = f32::from_bits(sigma.to_bits() - 1);
    }
    first_rise(&[c0, c1, c2, 0.0, 0.0], span, value)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rise(c: Poly, span: f32) -> Option<f32> {
        first_rise(&c, span, |x| eval(&c, x))
    }

    #[test]
    fn a_quadratic_rises_at_its_larger_root_after_dipping() {
        // (x − 1)(x − 3) = 3 − 4x + x²: positive, falls through 1, rises through 3.
        let t = rise([3.0, -4.0, 1.0, 0.0, 0.0], 10.0).unwrap();
        assert!((t - 3.0).abs() < 1e-6, "{t}");
        assert!(eval(&[3.0, -4.0, 1.0, 0.0, 0.0], t) < 0.0);
    }

    #[test]
    fn a_rise_already_under_way_is_now() {
        assert_eq!(rise([0.0, 1.0, 0.0, 0.0, 0.0], 1.0), Some(0.0));
        assert_eq!(rise([2.0, 1.0, 0.0, 0.0, 0.0], 1.0), Some(0.0));
    }

    #[test]
    fn constant_and_falling_are_no_rise() {
        assert_eq!(rise([0.0; 5], 1.0), None);
        assert_eq!(rise([-1.0, 0.0, 0.0, 0.0, 0.0], 1.0), None);
        assert_eq!(rise([0.0, -1.0, 0.0, 0.0, 0.0], 1.0), None);
    }

    #[test]
    fn a_graze_touching_zero_is_found_and_one_below_is_not() {
        // −(x − 2)² + ε: a parabola whose top is just at or below zero.
        for (eps, found) in [(1e-6f32, true), (0.0, true), (-1e-6, false)] {
            let c = [-4.0 + eps, 4.0, -1.0, 0.0, 0.0];
            let t = rise(c, 5.0);
            assert_eq!(t.is_some(), found, "eps {eps}: {t:?}");
            if let Some(t) = t {
                assert!((t - 2.0).abs() < 2e-3, "{t}");
            }
        }
    }

    #[test]
    fn a_quartic_with_four_roots_rises_at_the_first_upward_one() {
        // −(x − 1)(x − 2)(x − 3)(x − 4): negative, rises through 1, falls at 2, rises at 3.
        // (x−1)(x−2)(x−3)(x−4) = x⁴ − 10x³ + 35x² − 50x + 24.
        let c = [-24.0, 50.0, -35.0, 10.0, -1.0];
        let t = rise(c, 5.0).unwrap();
        assert!((t - 1.0).abs() < 1e-5, "{t}");
        // From σ = 2 on (falling through 2) the next rise is at 3.
        let shifted = |x: f32| eval(&c, x + 2.0);
        // c(x + 2) expanded: roots at −1, 0, 1, 2.
        let d = [0.0, -2.0, 1.0, 2.0, -1.0];
        for x in [0.3f32, 1.5] {
            assert!((eval(&d, x) - shifted(x)).abs() < 1e-4);
        }
        let t = first_rise(&d, 3.0, shifted).unwrap();
        assert!((t - 1.0).abs() < 1e-5, "{t}");
    }

    /// The closed form agrees with the general solver on quadratics of every shape.
    #[test]
    fn the_quadratic_shortcut_agrees_with_the_general_solver() {
        let mut checked = 0;
        for c0 in [-2.0f32, -0.5, -1e-6, 0.0, 1e-6, 0.7] {
            for c1 in [-3.0f32, -1.0, 0.0, 0.4, 2.5] {
                for c2 in [-1.5f32, -0.2, 0.0, 0.3, 4.0] {
                    for span in [0.5f32, 2.0, 10.0] {
                        let c = [c0, c1, c2, 0.0, 0.0];
                        let value = |x: f32| eval(&c, x);
                        let general = first_rise(&c, span, value);
                        let quick = first_rise_quadratic([c0, c1, c2], span, value);
                        match (general, quick) {
                            (None, None) => {}
                            (Some(a), Some(b)) => assert!(
                                (a - b).abs() <= 1e-5 * (1.0 + a.abs()),
                                "{c:?} on {span}: {a} vs {b}"
                            ),
                            _ => panic!("{c:?} on {span}: {general:?} vs {quick:?}"),
                        }
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 450);
    }

    #[test]
    fn an_empty_or_invalid_span_has_no_rise() {
        assert_eq!(rise([1.0, 1.0, 0.0, 0.0, 0.0], 0.0), None);
        assert_eq!(rise([-1.0, 1.0, 0.0, 0.0, 0.0], f32::NAN), None);
        assert_eq!(rise([-1.0, 1.0, 0.0, 0.0, 0.0], -1.0), None);
    }
}
