//! `KimGrip`'s normal impulse: the compression end and Stronge's energetic restitution
//! (`W_restitution = e*² |W_compression|`, seed eq. (37)) on the relative normal velocity
//! `v_x(p)`, piecewise linear in the normal impulse `p` (m/s per unit mass) while the
//! pressed ball's table friction acts at a constant rate up to the grip, slope 2 after.

use crate::real::Real;

/// Final normal impulse per unit mass (m/s) for approach speed `a`, energetic
/// restitution `e`, table-friction rate `ρ` acting up to the grip impulse `p*`;
/// `first_normal` is the frictionless impulse `(1+e)a/2` (the caller has it).
///
/// `v_x(p) = −a + (2 − ρ) p` for `p ≤ p*`, slope 2 after; compression ends at
/// `v_x = 0`; restitution ends when the work done since then is `e² |W_c|`.
///
/// Returns the impulse and whether the contact slides to the end (`p ≤ p*`, regime
/// `Sliding`; otherwise `p > p*` and it grips): the branch taken here decides it, so
/// the callers need no second comparison. At `p = p*` exactly both regimes give the
/// same friction (the direction meets the stick impulse there).
///
/// `CLAMPED` keeps the two square roots' arguments non-negative and the one division
/// defined where rounding or `e = 0` could break them. Without it (the fast path)
/// such a scene gives NaN, which the caller's guard hands to the clamped general path.
#[inline(always)]
pub(super) fn final_normal_impulse<R: Real, const CLAMPED: bool>(
    a: R,
    e: R,
    first_normal: R,
    rho: R,
    grip: R,
) -> (R, bool) {
    let half = R::of(0.5);
    // Half the sliding slope, 1 − ρ/2, so that the sliding end (1+e) a/(2 − ρ) is one
    // division of the frictionless impulse.
    let relief = R::ONE - half * rho;
    let sliding_end = first_normal / relief;
    if sliding_end <= grip {
        return (sliding_end, true);
    }
    (
        gripped_normal_impulse::<R, CLAMPED>(a, e, relief, grip),
        false,
    )
}

/// [`final_normal_impulse`] when the contact grips (`p* <` the sliding end
/// `(1+e) a/(2 − ρ)`), given `relief = 1 − ρ/2`.
#[inline(always)]
pub(super) fn gripped_normal_impulse<R: Real, const CLAMPED: bool>(
    a: R,
    e: R,
    relief: R,
    grip: R,
) -> R {
    let slope = relief + relief; // 2 − ρ
    let compression_end = a / slope;
    if grip >= compression_end {
        grip_in_restitution::<R, CLAMPED>(e * e * a * compression_end, slope, compression_end, grip)
    } else {
        grip_in_compression::<R, CLAMPED>(a, e, slope, grip)
    }
}

/// The final normal impulse when the contact grips at `p* = grip` during restitution,
/// after the compression end `p_c` and on the slope `slope` (`v_x = slope (p − p_c)`
/// up to `p*`, slope 2 after), `twice_work = e² a p_c` being twice the work restitution
/// must do (`e² |W_c|`, `|W_c| = a p_c/2`).
///
/// At the grip `v* = slope (p* − p_c)`; the work done from `p_c` to `p*` is
/// `v* (p* − p_c)/2`, so twice the work left is `w = e² a p_c − v* (p* − p_c)`, done on
/// the slope-2 piece: `v* q + q² = w/2`, whose root `q = w/(v* + √(v*² + 2w))` has no
/// cancellation. `w > 0` and `v* ≥ 0` in exact arithmetic (the grip comes before the
/// sliding end).
#[inline(always)]
fn grip_in_restitution<R: Real, const CLAMPED: bool>(
    twice_work: R,
    slope: R,
    compression_end: R,
    grip: R,
) -> R {
    let past_compression = grip - compression_end;
    let v_star = slope * past_compression;
    let twice_rest = twice_work - v_star * past_compression;
    let twice_rest = if CLAMPED {
        R::max(twice_rest, R::ZERO)
    } else {
        twice_rest
    };
    let denominator = v_star + R::sqrt_inline(v_star * v_star + (twice_rest + twice_rest));
    let extra = if !CLAMPED || denominator > R::ZERO {
        twice_rest / denominator
    } else {
        R::ZERO
    };
    grip + extra
}

/// The final normal impulse when the contact grips at `p* = grip` during compression
/// (`v_x = −a + slope p` up to `p*`): slope 2 from `p*`, compression ends at `p_c`,
/// then `(p − p_c)² = e² |W_c|`, `W_c < 0` in exact arithmetic.
#[inline(always)]
fn grip_in_compression<R: Real, const CLAMPED: bool>(a: R, e: R, slope: R, grip: R) -> R {
    let half = R::of(0.5);
    let v_star = -a + slope * grip;
    let work_at_grip = -a * grip + half * slope * grip * grip;
    let compression_end = grip - half * v_star;
    let compression_work = work_at_grip - R::of(0.25) * v_star * v_star;
    let depth = if CLAMPED {
        R::max(-compression_work, R::ZERO)
    } else {
        -compression_work
    };
    compression_end + e * R::sqrt_inline(depth)
}

/// [`final_normal_impulse`] (clamped) with the table friction's rate `rho_compression`
/// up to the end of compression and `rho_restitution` after it, both up to the grip
/// impulse `p* = grip` (`curved`: a pressed object ball's table friction grows as the
/// slip turns towards its vertical axis; one rate for both otherwise). Returns the
/// impulse, whether the contact slides to the end, and the compression end `p_c`
/// (where the rate changes).
///
/// `v_x(p) = −a + (2 − ρ_c) p` up to `p_c = a/(2 − ρ_c)`, so `|W_c| = a p_c/2`; then
/// `v_x = (2 − ρ_r)(p − p_c)` up to `p*` and slope 2 after. A grip during compression
/// sees only `ρ_c`; with `ρ_c = ρ_r = ρ` this is [`final_normal_impulse`]'s
/// `(1+e)a/(2 − ρ)`.
#[inline(never)]
pub(super) fn two_rate_normal_impulse<R: Real>(
    a: R,
    e: R,
    rho_compression: R,
    rho_restitution: R,
    grip: R,
) -> (R, bool, R) {
    let slope = R::of(2.0) - rho_compression;
    let compression_end = a / slope;
    if grip < compression_end {
        return (
            grip_in_compression::<R, true>(a, e, slope, grip),
            false,
            compression_end,
        );
    }
    // Twice the work restitution must do, e² a p_c.
    let twice_work = e * e * a * compression_end;
    let slope = R::of(2.0) - rho_restitution;
    // Sliding to the end: slope q²/2 = e² a p_c/2.
    let sliding_end = compression_end + R::sqrt_inline(R::max(twice_work / slope, R::ZERO));
    if sliding_end <= grip {
        return (sliding_end, true, compression_end);
    }
    let normal = grip_in_restitution::<R, true>(twice_work, slope, compression_end, grip);
    (normal, false, compression_end)
}

#[cfg(test)]
mod tests;
