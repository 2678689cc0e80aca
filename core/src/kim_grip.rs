//! `KimGrip`: the seed's first-order model with a gripping branch (erratum E6) and a
//! second-order correction of the friction direction. Continuous everywhere.
//!
//! Everything is per unit mass (impulses in m/s). Notation: approach speed
//! `a = U_i cos φ`; tangential slip `v₀ = (v_y0, v_z0)` (seed eq. (11)).
//!
//! **Tangential compliance.** A friction impulse `j` on the object ball (and `−j` on
//! the cue ball) changes the slip by `K j` with `K = diag(k_y, k_z)` (seed eqs. (19),
//! (23) with erratum E1):
//! `k_y = 2(1+ν)/ν`, and `k_z = (2+ν−μ_s)/ν` when the object ball is pressed into the
//! table (`v_z0 > 0`, topspin: its table friction `μ_s` per unit of pressing impulse
//! spins it back) or `k_z = (2+ν)/ν` when the cue ball is (draw; the seed neglects the
//! cue-ball/table friction).
//!
//! **Grip.** If the slip vanishes during the impact the contact then sticks with zero
//! friction (the normal impulse acts through both centres and cannot restart slip),
//! so the total friction impulse is exactly `j_stick = −K⁻¹ v₀`. Sliding needs a
//! friction "budget" `μ p` of at least `s* ≈ |j_stick|` (exact when `K` is isotropic;
//! within 1.3 % for `k_y/k_z ≤ 1.4`, see `docs/physics.md`).
//!
//! **Slide.** `K` is anisotropic, so the slip direction rotates during the impact
//! (seed eq. (21)) and the impulse direction differs from `−v̂₀` at second order. The
//! exact sliding impulse after a budget `S = μ p` is `K⁻¹(v(S) − v₀)` along the curve of
//! the invariant (24). We use the direction of `v_m = v₀ − α(S) K v̂₀` with
//! `α(S) = S/2 + (|v₀|/(k_y+k_z) − s*/2)(S/s*)²`: the midpoint rule (second order) for
//! small `S`, and at `S = s*` exactly parallel to `K⁻¹v₀`, so the slide impulse meets
//! `j_stick` there and the model is continuous across the boundary.
//!
//! **Normal impulse.** While the object ball slides against the table its friction
//! `μ_s` times the pressing impulse acts along `−x`, at a rate `ρ = μ μ_s |ĵ_z|` per unit
//! normal impulse (`|ĵ_z|` at the first-order end of the slide, linear in the spent
//! budget between its exact values at the start and at the grip, see
//! `TangentialSlip::pressing_share`), and stops when the contact grips at `p* = s*/μ`. With
//! `v_x(p) = −a + 2p − ρ min(p, p*)`, the compression end and Stronge's energetic
//! restitution (`W_restitution = e*² |W_compression|`, seed eq. (37)) give `p_f` in
//! closed form on each linear piece. The table friction impulse itself, `ρ min(p, p*)`,
//! is capped by its Coulomb cone `μ_s (−j_z)` (the table's normal impulse on the object
//! ball is the downward friction `−j_z`; the first-order rate can overshoot it) and
//! directed along the table-contact slip of the ball–ball impulses alone.
//!
//! **A cloth of large friction** (`μ_s >` [`CURVED_MIN_MU_S`], the object ball pressed):
//! `k_y/k_z` exceeds 1.4 and the single direction and `s*` lose accuracy near the grip,
//! so the general path follows the slide in pieces and gives the table friction one rate
//! for compression and another for restitution (`curved`, `normal`); the fast paths
//! decline such `Params`.

use crate::error::Result;
use crate::friction::FrictionLaw;
use crate::impact::Impact;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

mod curved;
mod fast_path;
mod normal;
mod slip;
#[cfg(feature = "speed-path")]
mod speed_path;
pub(crate) use curved::CURVED_MIN_MU_S;
pub(crate) use fast_path::MIN_SLIP_SQUARED as FAST_PATH_MIN_SLIP_SQUARED;
use normal::{final_normal_impulse, gripped_normal_impulse, two_rate_normal_impulse};
use slip::TangentialSlip;

/// Largest `|v₀|²` ((m/s)²) treated as exact gearing, a slip of 1 pm/s: the fast
/// path's smallest slip, so that with a constant μ every scene is either on the fast
/// path or without friction.
const GEARING_SLIP_SQUARED: f32 = FAST_PATH_MIN_SLIP_SQUARED;

/// `ν = 2/5`, exact in `R`.
fn nu<R: Real>() -> R {
    R::of(2.0) / R::of(5.0)
}

/// Slip change per unit specific friction impulse along `y` (seed eq. (19)):
/// `2(1+ν)/ν = 7`.
fn k_y<R: Real>() -> R {
    R::of(7.0)
}

// Not inlined into `model::collide_in`: there LLVM hoists work shared by several models'
// code (divisions included) above the dispatch, where every model pays for it.
#[inline(never)]
pub(crate) fn collide<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    // The fast path declines (`None`) every scene it does not cover, those whose
    // `Params` it does not apply to included (their minimum slip is +∞).
    match fast_path::collide::<R>(params, impact) {
        Some(outcome) => Ok(outcome),
        #[cfg(feature = "speed-path")]
        None => beyond_fast_path::<R>(params, impact),
        #[cfg(not(feature = "speed-path"))]
        None => general::<R>(params, impact),
    }
}

/// Every scene the constant-μ fast path declines: TP A.14's speed-dependent μ(v) in
/// closed form (`speed_path`, f32 only), else the general path. Not inlined, so that
/// the constant-μ fast path's code stays as it was without it.
#[cfg(feature = "speed-path")]
#[inline(never)]
fn beyond_fast_path<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    if R::SINGLE {
        if let Some(outcome) = speed_path::collide(params, impact) {
            return Ok(outcome);
        }
    }
    general::<R>(params, impact)
}

/// Every scene of the validity domain (`crate::validity`; outside it the typed
/// refusal): any friction law, the cue ball's table friction, slips down to 1 pm/s
/// (scaled to their largest component); below that, exact gearing.
#[inline(never)]
fn general<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    crate::validity::kim_grip(params)?;
    let half = R::of(0.5);
    let law = params.friction_law();
    let restitution = R::of(params.restitution());
    let approach = R::of(impact.velocity().x);
    let frictionless_normal = half * (R::ONE + restitution) * approach;
    let (slip_y, slip_z) = initial_slip::<R>(params, impact);
    // A slip below 1 pm/s (`GEARING_SLIP_SQUARED`, a square that underflows included)
    // is exact gearing: the friction impulse that would stop it, `|K⁻¹v₀| ≤ |v₀|/5`, is
    // below 2e-13 m/s, and an f32 slip computed from velocities and spins of order
    // 1 m/s is rounding noise far above that.
    let slip_squared = slip_y * slip_y + slip_z * slip_z;
    let gearing = slip_squared < R::of(GEARING_SLIP_SQUARED);
    if law.is_frictionless() || gearing || frictionless_normal == R::ZERO {
        // No friction, or no slip and so no friction direction (exact gearing).
        return Outcome::without_friction(
            params,
            impact,
            frictionless_normal,
            law.is_frictionless(),
        );
    }

    let scale = R::max(R::abs(slip_y), R::abs(slip_z));
    let object_pressed = slip_z > R::ZERO;
    // Draw presses the cue ball into the cloth; its table friction μ_ct (if set) acts
    // against its table-contact slip c' = U + ω × (−R ẑ), taken at its initial direction.
    let mu_ct = R::of(params.cue_table_friction());
    let (cue_dir_x, cue_dir_y) = if !object_pressed && slip_z < R::ZERO && mu_ct > R::ZERO {
        let (u, w, radius) = (impact.velocity(), impact.spin(), R::of(params.radius()));
        let (c_x, c_y) = (
            R::of(u.x) - radius * R::of(w.y),
            R::of(u.y) + radius * R::of(w.x),
        );
        let length = R::sqrt(c_x * c_x + c_y * c_y);
        if length > R::ZERO {
            (c_x / length, c_y / length)
        } else {
            (R::ZERO, R::ZERO)
        }
    } else {
        (R::ZERO, R::ZERO)
    };
    let k_z = if object_pressed {
        (R::of(2.0) + nu::<R>() - R::of(params.mu_s())) / nu::<R>()
    } else {
        (R::of(2.0) + nu::<R>() + mu_ct * cue_dir_x) / nu::<R>()
    };
    // The cue ball's table friction also moves the slip along y: Δv_y = 7 J_y + k_yz J_z.
    let k_yz = mu_ct * cue_dir_y;
    let slip = TangentialSlip::new(slip_y, slip_z, scale, k_yz, k_z);
    if slip.stick_budget == R::ZERO {
        // A slip so small that the impulse cancelling it underflows: exact gearing.
        return Outcome::without_friction(params, impact, frictionless_normal, false);
    }
    let slip_speed = slip.unit_norm * scale;
    // A pressed object ball on a cloth of large friction: the slip's turn followed in
    // pieces (`curved`), whose sliding path's length replaces s* as the grip threshold.
    // (Pressed, so the cue ball's table friction does not act: `K` is diagonal.)
    let curved = (object_pressed && params.mu_s() > CURVED_MIN_MU_S)
        .then(|| curved::CurvedSlide::new(slip.unit_y, slip.unit_z, scale, k_z));
    let stick_budget = match &curved {
        Some(curved) => curved.stop_budget(),
        None => slip.stick_budget,
    };
    // Effective compliance along the slip path, k̄ = |v₀| / s* (see `friction`).
    let compliance = slip_speed / stick_budget;
    // p*: the normal impulse at which the slip would stop (may be +inf for tiny μ).
    let grip_normal = match law {
        FrictionLaw::Constant(mu) => stick_budget / R::of(mu),
        FrictionLaw::SpeedDependent { .. } => {
            law.normal_impulse_between(slip_speed, R::ZERO, compliance)
        }
    };
    // Friction budget S(p) = ∫ μ dp spent by normal impulse p while sliding.
    let budget_after = |normal: R| -> R {
        if normal >= grip_normal {
            stick_budget
        } else {
            match law {
                FrictionLaw::Constant(mu) => R::of(mu) * normal,
                FrictionLaw::SpeedDependent { .. } => {
                    law.slip_change(slip_speed, normal, compliance) / compliance
                }
            }
        }
    };

    // The friction direction's vertical share at the first-order budget, for the
    // table-friction rate ρ (table impulse per unit normal impulse while sliding).
    let first_budget = budget_after(frictionless_normal);
    let first_span = R::min(frictionless_normal, grip_normal);
    // The table friction's rate (table impulse along x per unit normal impulse) up to
    // the end of compression and after it.
    let (compression_rate, restitution_rate) = match &curved {
        None => {
            let first_share_z = slip.pressing_share(first_budget);
            // One rate while sliding: the object ball's table friction (topspin) holds
            // it back, the cue ball's (draw) slows the approach.
            let table_rate = if first_span <= R::ZERO {
                // The slip stops at once (or no impact at all): no span for a rate.
                R::ZERO
            } else if object_pressed {
                R::of(params.mu_s()) * first_share_z * first_budget / first_span
            } else {
                -mu_ct * cue_dir_x * first_share_z * first_budget / first_span
            };
            (table_rate, table_rate)
        }
        Some(curved) => {
            // While the object ball's table contact slides its friction is μ_s times the
            // pressing impulse |J_z(S)|, which grows faster as the slip turns towards z:
            // one rate up to the first-order compression end a/2, another after it, from
            // the pieces' |J_z| there and at the first-order end.
            let mu_s = R::of(params.mu_s());
            let pressing = |budget: R| -> R {
                if budget >= stick_budget {
                    R::abs(slip.stick_z)
                } else {
                    R::abs(curved.impulse(budget).1)
                }
            };
            let compression_span = R::min(half * approach, grip_normal);
            let compression_pressing = pressing(budget_after(compression_span));
            let compression_rate = if compression_span > R::ZERO {
                mu_s * compression_pressing / compression_span
            } else {
                R::ZERO
            };
            let rest_span = first_span - compression_span;
            let restitution_rate = if rest_span > R::of(1e-3) * first_span {
                // Pressing per unit normal impulse: at least 0, at most the fastest μ.
                let rate = (pressing(first_budget) - compression_pressing) / rest_span;
                mu_s * R::min(R::max(rate, R::ZERO), R::of(law.largest()))
            } else {
                compression_rate
            };
            (compression_rate, restitution_rate)
        }
    };
    let (normal, slides, compression_end) = two_rate_normal_impulse(
        approach,
        restitution,
        compression_rate,
        restitution_rate,
        grip_normal,
    );
    let span = R::min(normal, grip_normal);
    let pressed_table = compression_rate * R::min(span, compression_end)
        + restitution_rate * R::max(span - compression_end, R::ZERO);

    let (j_y, j_z, regime) = if slides {
        let budget = budget_after(normal);
        let (j_y, j_z) = match &curved {
            Some(curved) => curved.impulse(budget),
            None => {
                let (dir_y, dir_z) = slip.friction_direction(budget);
                (budget * dir_y, budget * dir_z)
            }
        };
        (j_y, j_z, Regime::Sliding)
    } else {
        (slip.stick_y, slip.stick_z, Regime::Gripping)
    };
    let (table, cue_table_x, cue_table_y) = if object_pressed {
        // Coulomb's cone at the object ball's table contact: its friction impulse is at
        // most μ_s times the table's normal impulse on it, which (per unit mass, m/s) is
        // the downward ball–ball friction −j_z (j_z ≤ 0 here; the max takes rounding
        // out). The rate ρ, fixed from the first-order budget, can put ρ·min(p, p*)
        // above that (issue 16 item 3: the invariants suite's object-ball table cone);
        // the cone caps it.
        let cone = R::of(params.mu_s()) * R::max(-j_z, R::ZERO);
        (R::min(pressed_table, cone), R::ZERO, R::ZERO)
    } else {
        // Pressing impulse on the cue ball = the upward friction impulse on the object.
        let pressing = R::max(j_z, R::ZERO);
        (
            R::ZERO,
            -mu_ct * pressing * cue_dir_x,
            -mu_ct * pressing * cue_dir_y,
        )
    };
    let (table_x, table_y) = table_friction_components(table, span, j_y, j_z);
    let impulses = SpecificImpulses {
        normal,
        friction_y: j_y,
        friction_z: j_z,
        table: table_x,
        table_y,
        table_size: table,
        cue_table_x,
        cue_table_y,
    };
    Outcome::from_impulses(params, impact, impulses, regime)
}

/// Initial tangential slip `(v_y0, v_z0)` (seed eq. (11)) evaluated in `R`.
pub(crate) fn initial_slip<R: Real>(params: &Params, impact: &Impact) -> (R, R) {
    let radius = R::of(params.radius());
    let u = impact.velocity();
    let w = impact.spin();
    (-R::of(u.y) - radius * R::of(w.z), radius * R::of(w.y))
}

/// Split the table friction `table` (m/s) on the pressed object ball along its
/// table-contact slip `c = V + Ω × (−R ẑ)` (first-principles Coulomb direction; the seed's
/// eq. (7) takes `c ∥ x̂`). At the end of the pressing span every impulse has grown
/// roughly in proportion, so the final `c` gives the mean direction, that of the slip
/// the ball–ball impulses alone give (see [`table_contact_slip`]). Returns the `−x`
/// magnitude and the `y` component of the table impulse.
#[inline(always)]
fn table_friction_components<R: Real>(table: R, span: R, j_y: R, j_z: R) -> (R, R) {
    let (slip_x, slip_y) = table_contact_slip(span, j_y, j_z);
    let length = R::sqrt(slip_x * slip_x + slip_y * slip_y);
    if length > R::ZERO {
        let scale = table / length;
        (scale * slip_x, -scale * slip_y)
    } else {
        // No slip at the table contact: no direction; the seed's −x (eq. (7)).
        (table, R::ZERO)
    }
}

/// The direction `(c_x, c_y)` (m/s) of the object ball's table-contact slip at the end of
/// the pressing span (see [`table_friction_components`]): that of the slip the ball–ball
/// impulses alone give, `c_free = (p − j_z/ν, j_y)` per unit mass (the normal impulse `p`
/// along x; the friction `j_z`, acting at `−R x̂`, spins the ball by `Ω_y = j_z/(ν R)`,
/// which adds `−R Ω_y`; `j_y` moves it along y and spins it about z only). The table
/// friction `T` (m/s, at `−R ẑ`) moves the contact by `(1 + 1/ν) T` (its impulse plus the
/// spin it gives, `I = ν m R²`), and Coulomb's law directs it against the slip,
/// `T = −|T| ĉ`, so while the contact slides (`(1 + 1/ν)|T| < |c_free|`, as the model
/// assumes) `c = c_free − (1 + 1/ν)|T| ĉ` stays parallel to `c_free`. Before issue 16
/// item 3 this took `c_x = p − X − (j_z + X)/ν` with `X` the friction's whole size but
/// `c_y = j_y`, as if all of `T` acted along x: that turned the direction towards y, and
/// reversed `c_x` where `(1 + 1/ν) X` exceeded `c_free`'s x component.
/// `1/ν = 5/2` is exact in `R` (`nu()` is 2/5 rounded); both components are `≥ 0`
/// along x (`p ≥ 0`, `j_z ≤ 0` with the object ball pressed), so `c_x ≥ 0` exactly.
#[inline(always)]
fn table_contact_slip<R: Real>(span: R, j_y: R, j_z: R) -> (R, R) {
    (span - j_z * R::of(2.5), j_y)
}

#[cfg(test)]
mod tests;
