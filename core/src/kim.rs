//! The seed's first-order closed forms, eqs. (52)–(54), with erratum E1.
//!
//! Per unit mass, with approach speed `a = U_i cos φ`, frictionless normal impulse
//! `p₀ = (1 + e*) a / 2` (m/s) and the initial slip direction `θ₀` of eqs. (11)–(13)
//! (`cos θ₀ = −v_y0 / v_∥0`, `sin θ₀ = −v_z0 / v_∥0`, erratum E2 applied):
//!
//! * friction impulse on the object ball `j = μ p₀ (cos θ₀, sin θ₀)` (eq. (57) at first
//!   order);
//! * table friction on the object ball `X = μ_s |j_z|` when it is pressed (`θ₀ < 0`);
//! * normal impulse `p_f = p₀ (1 − μ μ_s sin θ₀ / 2)` (eq. (50)).
//!
//! Assembled by [`Outcome::from_impulses`] this reproduces (52), (53) and (54) with
//! E1's corrected object-ball spin `Ω_y = μ(1+e)/(2ν) · U cos φ / R · (1 − μ_s) sin θ₀`.
//! The model assumes the contact slides throughout. Where the friction impulse `μ p₀`
//! exceeds the stick impulse `s* = |K⁻¹ v₀|` (the contact grips) it refuses the scene
//! with [`crate::Error::OutsideValidity`] ([`crate::validity::Reason::Grips`]); see
//! `kim_grip` for the model that covers gripping.

use crate::error::Result;
use crate::impact::Impact;
use crate::kim_grip::initial_slip;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

// Not inlined into `model::collide_in` (see `kim_grip::collide`).
#[inline(never)]
pub(crate) fn collide<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    let half = R::of(0.5);
    let law = params.friction_law();
    let approach = R::of(impact.velocity().x);
    let frictionless_normal = half * (R::ONE + R::of(params.restitution())) * approach;
    let (slip_y, slip_z) = initial_slip::<R>(params, impact);
    let scale = R::max(R::abs(slip_y), R::abs(slip_z));
    if law.is_frictionless() || scale == R::ZERO {
        // No friction, or no slip and so no friction direction (exact gearing).
        return Outcome::without_friction(
            params,
            impact,
            frictionless_normal,
            law.is_frictionless(),
        );
    }
    // Unit slip direction, scaled first so that tiny slips cannot underflow.
    let (unit_y, unit_z) = (slip_y / scale, slip_z / scale);
    let inv_norm = R::ONE / R::sqrt(unit_y * unit_y + unit_z * unit_z);
    // First order: μ at the initial slip speed (TP A.14 does the same).
    let mu = law.at_in(scale / inv_norm);
    let cos_theta0 = -unit_y * inv_norm;
    let sin_theta0 = -unit_z * inv_norm;
    let friction = mu * frictionless_normal;
    let (j_y, j_z) = (friction * cos_theta0, friction * sin_theta0);
    // μ_s acts only through the pressed object ball: μ_s Θ(−θ₀).
    let mu_s = if sin_theta0 < R::ZERO {
        R::of(params.mu_s())
    } else {
        R::ZERO
    };
    // The validity domain (`crate::validity`): the slide must not outlast the slip.
    // Stick impulse s* = |K⁻¹ v₀| with K = diag(7, k_z), k_z = (2 + ν − μ_s)/ν with
    // the object ball pressed (the μ_s Kim applies), 6 otherwise; in units of `scale`.
    let k_z = (R::of(2.4) - mu_s) / R::of(crate::NU);
    // Compared as squares in units of `scale`: the square root only on refusal.
    let (stick_y, stick_z) = (unit_y / R::of(7.0), unit_z / k_z);
    let stick_squared = stick_y * stick_y + stick_z * stick_z;
    let unit_friction = friction / scale;
    if unit_friction * unit_friction > stick_squared {
        // +∞ (a stick impulse that underflows) reported as the largest f32.
        let grip_index = unit_friction / R::sqrt(stick_squared);
        let grip_index = R::min(grip_index, R::of(f32::MAX)).to_f32();
        return Err(crate::validity::outside(
            crate::validity::Reason::Grips,
            grip_index,
        ));
    }
    let table = mu_s * R::abs(j_z);
    let normal = frictionless_normal * (R::ONE - half * mu * mu_s * sin_theta0);
    let impulses = SpecificImpulses {
        normal,
        friction_y: j_y,
        friction_z: j_z,
        table,
        table_y: R::ZERO,
        table_size: R::abs(table),
        cue_table_x: R::ZERO,
        cue_table_y: R::ZERO,
    };
    Outcome::from_impulses(params, impact, impulses, Regime::Sliding)
}
