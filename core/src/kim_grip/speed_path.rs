//! `KimGrip`'s fast path for the speed-dependent friction `μ(v) = a + b e^{−cv}` of TP
//! A.14 (issue 16, item 6), f32 only: the general path's physics, with its slip–impulse
//! relation solved in closed form instead of by Newton's method.
//!
//! **The slide in closed form.** While the contact slides, the slip speed `v` falls at
//! `dv/dp = −k̄ μ(v)` per unit specific normal impulse `p` (`friction` module docs; `k̄
//! = |v₀|/s*` the effective compliance along the slip path). With `w = e^{cv}` this is
//! linear, `dw/dp = −c k̄ (a w + b)`, so `a w + b = (a w₀ + b) e^{−x}`, `x = a c k̄ p`.
//! Written with the slip change `δ = v₀ − v` and `μ₀ = μ(v₀)`:
//!
//! `e^{−cδ} = 1 − y`, `y = (μ₀/a)(1 − e^{−x}) = μ₀ c k̄ p · φ(x)`, `φ(x) = (1 − e^{−x})/x`,
//!
//! so the friction budget spent, `S(p) = ∫ μ dp = δ/k̄`, is `−ln(1 − y)/(c k̄)`. The slip
//! stops (`δ = v₀`) when `1 − y = e^{−c v₀}`; solving for `p` gives the grip impulse
//! `p* = x*/(a c k̄)`, `x* = c v₀ + ln(μ₀/(a + b))` (no cancellation: `1 − (a/μ₀)(1 −
//! e^{−cv₀}) = e^{−cv₀}(a + b)/μ₀`). Past the first-order end `p₁ = (1+e)a/2`, the table
//! friction's extra impulse `Δ = p − p₁` adds `μ₀ c k̄ e^{−x₁} Δ φ(a c k̄ Δ)` to `y`.
//!
//! Everything else — the grip test, the table-friction rate from the budget at `p₁`,
//! the normal impulse on each piece, the mid-point friction direction, the table
//! friction's cone and direction — is the general path's (parent module), evaluated
//! with `math::fast`'s polynomial `e^{−x}`, `ln` and `φ` (errors below 4e-7).
//!
//! It declines (`None`) a law it does not cover (`Derived::kim_grip_speed_law`), a slip
//! below 1 pm/s, `x₁ = a c k̄ p₁ > 1` (outside `φ`'s fitted range: about 13 m/s of
//! approach with TP A.14's law) and anything the final guard rejects; the general path
//! then runs. The f64 evaluation (`collide_f64`, calibration's Jacobian) keeps the
//! general path: polynomial approximations at 4e-7 would be noise in its differences.

use super::fast_path::{finish, sliding_impulse, table_friction, MIN_SLIP_SQUARED};
use super::{gripped_normal_impulse, k_y};
use crate::impact::Impact;
use crate::math::{self, fast};
use crate::outcome::{Outcome, Regime};
use crate::params::{Params, SpeedLaw};

/// Largest `x₁ = a c k̄ p₁` taken, and largest `c v₀` whose `1 − e^{−cv₀}` is taken as
/// `c v₀ φ(c v₀)`: the end of `φ`'s fitted range.
const MAX_FLOOR_EXPONENT: f32 = 1.0;

/// The speed-dependent fast path, or `None` (module docs).
#[inline(always)]
pub(super) fn collide(params: &Params, impact: &Impact) -> Option<Outcome> {
    let law = params.derived().kim_grip_speed_law?;
    let radius = params.radius();
    let (u, w) = (impact.velocity(), impact.spin());
    // Initial slip (seed eq. (11)), m/s.
    let slip_y = -u.y - radius * w.z;
    let slip_z = radius * w.y;
    let slip_squared = slip_y * slip_y + slip_z * slip_z;
    let covered = slip_squared >= MIN_SLIP_SQUARED;
    if !covered {
        return None;
    }
    if slip_z > 0.0 {
        slide::<true>(params, impact, law, slip_y, slip_z, slip_squared)
    } else {
        slide::<false>(params, impact, law, slip_y, slip_z, slip_squared)
    }
}

/// The law along one slide: what the closed form needs (module docs).
struct Slide {
    law: SpeedLaw,
    /// `c k̄` (per m/s of normal impulse).
    decay_per_normal: f32,
    /// `1 − e^{−c v₀}`: `y` at the grip.
    grip_progress: f32,
    /// `μ₀ = μ(v₀)`.
    initial_mu: f32,
}

impl Slide {
    /// `y(p)` for `x = a c k̄ p ≤ 1`, given `φ(x)`.
    #[inline(always)]
    fn progress(&self, normal: f32, phi: f32) -> f32 {
        self.initial_mu * self.decay_per_normal * normal * phi
    }

    /// The friction budget `S = −ln(1 − y)/(c k̄)` (m/s) for `progress = y`.
    #[inline(always)]
    fn budget(&self, progress: f32) -> f32 {
        fast::ln_one_minus_negated(progress) / self.decay_per_normal
    }

    /// `p* = x*/(a c k̄)` (m/s), `x* = −ln(1 − (a/μ₀)(1 − e^{−cv₀}))`.
    #[inline(always)]
    fn grip_normal(&self) -> f32 {
        let share = self.law.a / self.initial_mu * self.grip_progress;
        fast::ln_one_minus_negated(share) / (self.law.a * self.decay_per_normal)
    }
}

/// The rest of the path for the object ball pressed into the cloth (topspin, `v_z0 > 0`)
/// or not, compiled once for each as `fast_path::slide` (one copy for both saves 200 B
/// of flash and costs 10–17 instructions a branch).
#[inline(always)]
fn slide<const OBJECT_PRESSED: bool>(
    params: &Params,
    impact: &Impact,
    law: SpeedLaw,
    slip_y: f32,
    slip_z: f32,
    slip_squared: f32,
) -> Option<Outcome> {
    let mu_s = params.mu_s();
    let derived = params.derived();
    let (k_z, boundary) = if OBJECT_PRESSED {
        (derived.pressed_k_z, derived.pressed_boundary)
    } else {
        (6.0, 1.0 / 13.0)
    };
    // Stick impulse j_stick = −K⁻¹ v₀ (z component with its sign flipped) and s*.
    let stick_y = -slip_y / k_y::<f32>();
    let stick_z_flipped = slip_z / k_z;
    let (stick_budget, slip_norm) = math::sqrt_pair(
        stick_y * stick_y + stick_z_flipped * stick_z_flipped,
        slip_squared,
    );
    let restitution = params.restitution();
    let approach = impact.velocity().x;
    let first_normal = derived.half_one_plus_restitution * approach;
    let initial_exponent = law.c * slip_norm;
    // e^{−cv₀} and 1 − e^{−cv₀}: the second as c v₀ φ(c v₀) up to c v₀ = 1, where
    // 1 − e^{−cv₀} would cancel (at c v₀ = 6e-8 the exponential's own 4e-7 exceeds it).
    let (initial_decay, grip_progress) = if initial_exponent <= MAX_FLOOR_EXPONENT {
        let progress = initial_exponent * fast::one_minus_exp_neg_over(initial_exponent);
        (1.0 - progress, progress)
    } else {
        let decay = fast::exp_neg(initial_exponent);
        (decay, 1.0 - decay)
    };
    let slide = Slide {
        law,
        decay_per_normal: initial_exponent / stick_budget,
        grip_progress,
        initial_mu: law.a + law.b * initial_decay,
    };
    let first_exponent = law.a * slide.decay_per_normal * first_normal;
    // A NaN fails the comparison too.
    let in_range = first_exponent <= MAX_FLOOR_EXPONENT;
    if !in_range {
        return None;
    }
    let first_phi = fast::one_minus_exp_neg_over(first_exponent);
    let first_progress = slide.progress(first_normal, first_phi);
    // The slip stops where y reaches 1 − e^{−cv₀}.
    let grip_progress = slide.grip_progress;
    // (normal, budget spent or the stick budget, sliding, certain grip, table rate)
    let (normal, budget, slides, certain, table_rate) = if !OBJECT_PRESSED {
        if first_progress < grip_progress {
            let budget = slide.budget(first_progress);
            (first_normal, budget, true, false, 0.0)
        } else {
            let grip = slide.grip_normal();
            let normal = gripped_normal_impulse::<f32, false>(approach, restitution, 1.0, grip);
            (normal, grip, false, false, 0.0)
        }
    } else {
        // ρ = μ_s |ĵ_z| S₁/p₁ (the general path's rate): |ĵ_z| interpolated between v̂₀'s
        // and the stick impulse's z share at the spent fraction f₁ = S₁/s*.
        let end = stick_z_flipped / stick_budget;
        if first_progress >= grip_progress {
            // The contact grips whatever the table friction: f₁ = 1, S₁ = s*.
            let grip = slide.grip_normal();
            let table_rate = mu_s * end * stick_budget / grip;
            let relief = 1.0 - 0.5 * table_rate;
            let normal = gripped_normal_impulse::<f32, false>(approach, restitution, relief, grip);
            (normal, grip, false, true, table_rate)
        } else {
            let first_budget = slide.budget(first_progress);
            let start = slip_z / slip_norm;
            let first_fraction = first_budget / stick_budget;
            let table_rate =
                mu_s * (start + first_fraction * (end - start)) * first_budget / first_normal;
            let relief = 1.0 - 0.5 * table_rate;
            let sliding_end = first_normal / relief;
            // y at the sliding end: y₁ + Δy, Δy = μ₀ c k̄ e^{−x₁} Δ φ(a c k̄ Δ) (module
            // docs); Δ/p₁ = ρ/(2 − ρ) ≤ 4.2 % (ρ ≤ μ μ_s ≤ 0.08), so a c k̄ Δ ≤ 0.042 and
            // φ's series to second order is within 3e-6 of it.
            let excess = sliding_end - first_normal;
            let excess_exponent = law.a * slide.decay_per_normal * excess;
            let excess_phi = 1.0 + excess_exponent * (excess_exponent * (1.0 / 6.0) - 0.5);
            let first_floor = 1.0 - first_exponent * first_phi;
            let increase = slide.progress(excess, excess_phi) * first_floor;
            let progress = first_progress + increase;
            if progress < grip_progress {
                (sliding_end, slide.budget(progress), true, false, table_rate)
            } else {
                let grip = slide.grip_normal();
                let normal =
                    gripped_normal_impulse::<f32, false>(approach, restitution, relief, grip);
                (normal, grip, false, false, table_rate)
            }
        }
    };
    // In the gripping branches `budget` holds p* (the pressing span); sliding, the budget.
    let (j_y, j_z, regime, span) = if slides {
        // The mid-point direction after the fraction f = S/s* of the stick budget.
        let half_sigma = stick_budget / (slip_norm + slip_norm);
        let (j_y, j_z) = sliding_impulse(
            (slip_y, slip_z),
            k_z,
            boundary,
            half_sigma,
            budget / stick_budget,
            budget,
        );
        (j_y, j_z, Regime::Sliding, normal)
    } else {
        (stick_y, -stick_z_flipped, Regime::Gripping, budget)
    };
    let (table, table_y, table_size) = if OBJECT_PRESSED {
        table_friction(certain, (mu_s, stick_z_flipped, table_rate), span, j_y, j_z)
    } else {
        (0.0, 0.0, 0.0)
    };
    // The guard of `fast_path::slide` (same bound, same reasons: μ ≤ 0.15 here), with
    // the budget (or p*) in the sum: a NaN from its logarithm fails it too.
    let guarded = if OBJECT_PRESSED {
        normal + budget + table
    } else {
        normal + budget
    };
    finish::<f32, OBJECT_PRESSED>(
        params,
        impact,
        guarded,
        (normal, j_y, j_z),
        (table, table_y, table_size),
        regime,
    )
}

#[cfg(test)]
mod tests;
