//! `KimGrip`'s general path: every scene of its validity domain the fast paths decline
//! (parent module docs; `docs/physics.md` §4 items 3–8).

use super::curved::{self, CURVED_MIN_MU, CURVED_MIN_MU_S};
use super::normal::two_rate_normal_impulse;
use super::slip::TangentialSlip;
use super::{initial_slip, nu, table_contact_slip, GEARING_SLIP_SQUARED};
use crate::error::Result;
use crate::friction::FrictionLaw;
use crate::impact::Impact;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

/// Every scene of the validity domain (`crate::validity`; outside it the typed
/// refusal): any friction law, the cue ball's table friction, slips down to 1 pm/s
/// (scaled to their largest component); below that, exact gearing.
#[inline(never)]
pub(super) fn general<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
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
    // The pressed object ball's table-contact slip direction `ĉ` (its table friction acts
    // along `−ĉ`): `x̂` (the seed's eq. (7)) on the first pass. A curved slide (a slip
    // that turns far, `curved`) takes a second pass with the first pass's `ĉ`
    // ([`table_contact_slip`]): the friction's `x` component, through the spin about `y`
    // it gives, changes the slip along `z` (`k_z`), its `y` component, through the ball's
    // velocity, the slip along `y` (`k_yz`). (With the pieces, at μ 0.15–1 against the
    // reference: 0.65 % / 1.6 % of U in velocity / R ω before, 0.18 % / 0.31 % now;
    // `host-tests/examples/kim_grip_inside.rs`, seed 16, 10⁶ scenes; `docs/physics.md`
    // §4 item 8.)
    let mut table_direction = (R::ONE, R::ZERO);
    let mut first_pass = true;
    // The table friction per unit pressing impulse along `x̂` on the object ball: `μ_s`
    // for the object ball pressed, `−μ_ct c'_x` for the cue ball (it acts on the cue
    // ball, against the approach).
    let table_mu = if object_pressed {
        R::of(params.mu_s())
    } else {
        -mu_ct * cue_dir_x
    };
    loop {
        let (dir_x, dir_y) = table_direction;
        let k_z = (R::of(2.0) + nu::<R>() - table_mu * dir_x) / nu::<R>();
        // The table friction of the ball pressed into the cloth also moves the slip along
        // y: Δv_y = 7 J_y + k_yz J_z.
        let k_yz = if object_pressed {
            table_mu * dir_y
        } else {
            mu_ct * cue_dir_y
        };
        let slip = TangentialSlip::new(slip_y, slip_z, scale, k_yz, k_z);
        if slip.stick_budget == R::ZERO {
            // A slip so small that the impulse cancelling it underflows: exact gearing.
            return Outcome::without_friction(params, impact, frictionless_normal, false);
        }
        let slip_speed = slip.unit_norm * scale;
        // A large μ, or a pressed object ball on a cloth of large friction: the slip's
        // turn followed in pieces (`curved`), whose sliding path's length replaces s* as
        // the grip threshold.
        let curved = (law.largest() > CURVED_MIN_MU
            || (object_pressed && params.mu_s() > CURVED_MIN_MU_S))
            .then(|| curved::CurvedSlide::new(slip.unit_y, slip.unit_z, scale, k_yz, k_z));
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
        let budget = Budget {
            law,
            grip_normal,
            stick_budget,
            slip_speed,
            compliance,
        };
        let budget_after = |normal: R| budget.after(normal);

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
                } else {
                    table_mu * first_share_z * first_budget / first_span
                };
                (table_rate, table_rate)
            }
            Some(curved) => {
                // While the object ball's table contact slides its friction is μ_s times the
                // pressing impulse |J_z(S)|, which grows faster as the slip turns towards z:
                // one rate up to the first-order compression end a/2, another after it, from
                // the pieces' |J_z| there and at the first-order end.
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
                    table_mu * compression_pressing / compression_span
                } else {
                    R::ZERO
                };
                let rest_span = first_span - compression_span;
                let restitution_rate = if rest_span > R::of(1e-3) * first_span {
                    // Pressing per unit normal impulse: at least 0, at most the fastest μ.
                    let rate = (pressing(first_budget) - compression_pressing) / rest_span;
                    table_mu * R::min(R::max(rate, R::ZERO), R::of(law.largest()))
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
        if curved.is_some() && object_pressed && core::mem::take(&mut first_pass) {
            let (c_x, c_y) = table_contact_slip(span, j_y, j_z);
            let length = R::sqrt(c_x * c_x + c_y * c_y);
            if length > R::ZERO {
                table_direction = (c_x / length, c_y / length);
                continue;
            }
        }
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
        return Outcome::from_impulses(params, impact, impulses, regime);
    }
}

/// The friction budget `S(p) = ∫ μ dp` (m/s) a sliding contact spends by normal impulse
/// `p`, up to the stick budget at the grip `p*`.
struct Budget<R> {
    law: FrictionLaw,
    /// `p*` (m/s).
    grip_normal: R,
    /// The budget that stops the slip (m/s).
    stick_budget: R,
    /// `|v₀|` (m/s).
    slip_speed: R,
    /// `k̄ = |v₀| / stick_budget` (see `friction`).
    compliance: R,
}

impl<R: Real> Budget<R> {
    /// `S(p)` for a normal impulse `normal` (m/s). Out of line: the general path takes it
    /// at up to three normal impulses.
    #[inline(never)]
    fn after(&self, normal: R) -> R {
        if normal >= self.grip_normal {
            self.stick_budget
        } else {
            match self.law {
                FrictionLaw::Constant(mu) => R::of(mu) * normal,
                FrictionLaw::SpeedDependent { .. } => {
                    self.law
                        .slip_change(self.slip_speed, normal, self.compliance)
                        / self.compliance
                }
            }
        }
    }
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
