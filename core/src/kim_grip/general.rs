//! `KimGrip`'s general path: every scene of its validity domain the fast paths decline
//! (parent module docs; `docs/physics.md` §4 items 3–8).

use super::budget::Budget;
use super::curved;
use super::normal::two_rate_normal_impulse;
use super::{initial_slip, nu, GEARING_SLIP_SQUARED};
use crate::error::Result;
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
    // Draw presses the cue ball into the cloth, and its table friction μ_ct (if set)
    // acts against its table-contact slip c' = U + ω × (−R ẑ).
    let mu_ct = R::of(params.cue_table_friction());
    let cue_pressed = !object_pressed && slip_z < R::ZERO && mu_ct > R::ZERO;
    let (u, w, radius) = (impact.velocity(), impact.spin(), R::of(params.radius()));
    // The pressed ball's table-contact slip before the impact, negated, in units of
    // `scale`, and the share of `j_z` in it (`curved::CurvedSlide::pressed`): the object
    // ball's is zero; the cue ball's `c'₀`.
    let pressed = if cue_pressed {
        (
            (radius * R::of(w.y) - R::of(u.x)) / scale,
            (-R::of(u.y) - radius * R::of(w.x)) / scale,
            R::of(2.5),
        )
    } else {
        (R::ZERO, R::ZERO, R::of(-2.5))
    };
    // The pressed ball's table-contact slip direction `ĉ` (its table friction acts along
    // `−ĉ`): on the first pass `x̂` (the seed's eq. (7) for the object ball; a drawn cue
    // ball's `c'₀` leans from it by its side component alone); a second pass takes the
    // direction the first pass's pieces turned through (`curved`,
    // [`table_contact_slip`]): the friction's `x` component, through the spin about `y`
    // it gives, changes the slip along `z` (`k_z`), its `y` component, through the
    // ball's velocity, the slip along `y` (`k_yz`). (With the pieces, at μ 0.15–1
    // against the reference: 0.65 % / 1.6 % of U in velocity / R ω before, 0.18 % /
    // 0.31 % now; `host-tests/examples/kim_grip_inside.rs`, seed 16, 10⁶ scenes;
    // `docs/physics.md` §4 item 8. The cue ball's contact slip turns by up to 27° in the
    // impact: §4 item 9.)
    let mut table_direction = (R::ONE, R::ZERO);
    let mut first_pass = true;
    // The table friction per unit pressing impulse on the pressed ball, signed as it
    // enters `K` along `x̂`: `μ_s` for the object ball, `−μ_ct` for the cue ball (it acts
    // on the cue ball, against the approach); 0 for neither.
    let table_mu = if object_pressed {
        R::of(params.mu_s())
    } else if cue_pressed {
        -mu_ct
    } else {
        R::ZERO
    };
    loop {
        let (dir_x, dir_y) = table_direction;
        let k_z = (R::of(2.0) + nu::<R>() - table_mu * dir_x) / nu::<R>();
        // The table friction of the ball pressed into the cloth also moves the slip along
        // y: Δv_y = 7 J_y + k_yz J_z (`μ_s ĉ_y` for the object ball, `μ_ct ĉ'_y` for the
        // cue ball).
        let k_yz = R::abs(table_mu) * dir_y;
        // The slide in pieces (`curved`), whose sliding path's length replaces s* as the
        // grip threshold, and the budget it spends by each normal impulse (`budget`).
        let curved = curved::CurvedSlide::new(slip_y / scale, slip_z / scale, scale, k_yz, k_z);
        let curved = curved.pressed(pressed);
        let budget = Budget::new(law, &curved);
        // The stick budget is positive (no gearing case here): the slip's largest
        // component is at least 0.7 pm/s (`gearing` above) and `|K⁻¹v| ≥ |v|/‖K‖ ≥ |v|/12`
        // (k_y = 7, 3.5 ≤ k_z ≤ 8.5, |k_yz| ≤ 1), so the first piece alone spends at
        // least 1.4e-14 m/s, a normal f32.
        // The stick impulse −K⁻¹v₀ (m/s).
        let (stick_y, stick_z) = curved.stick_impulse();
        let (stick_budget, grip_normal) = (budget.stick_budget, budget.grip_normal);

        // The friction direction's vertical share at the first-order budget, for the
        // table-friction rate ρ (table impulse per unit normal impulse while sliding).
        let first_budget = budget.after(frictionless_normal);
        let first_span = R::min(frictionless_normal, grip_normal);
        // The table friction's rate (table impulse per unit normal impulse) up to the end
        // of compression and after it. While the pressed ball's table contact slides its
        // friction is its μ times the pressing impulse |J_z(S)|, which grows faster as the
        // slip turns towards z: one rate up to the first-order compression end a/2,
        // another after it, from the pieces' |J_z| there and at the first-order end.
        let pressing = |budget: R| -> R {
            if budget >= stick_budget {
                R::abs(stick_z)
            } else {
                R::abs(curved.impulse(budget).1)
            }
        };
        let compression_span = R::min(half * approach, grip_normal);
        let compression_pressing = pressing(budget.after(compression_span));
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
        // Only the table friction's x component (`ĉ_x` of its size) slows the approach.
        let (normal, slides, _) = two_rate_normal_impulse(
            approach,
            restitution,
            compression_rate * dir_x,
            restitution_rate * dir_x,
            grip_normal,
        );
        let span = R::min(normal, grip_normal);
        let budget_end = if slides {
            budget.after(normal)
        } else {
            stick_budget
        };
        // The pieces to the end of the slide: the friction impulse, and the direction of
        // a pressed object ball's table friction (each piece's pressing along its own
        // table-contact slip, which turns as the slip does).
        let marched = curved.march(budget_end, span / budget_end);
        let (j_y, j_z, regime) = if slides {
            let (j_y, j_z) = marched.impulse;
            (j_y, j_z, Regime::Sliding)
        } else {
            (stick_y, stick_z, Regime::Gripping)
        };
        // The direction of the pressed ball's table friction: the pieces' sum, or (no
        // pressing, no slip at its table contact) the pass's own.
        let (t_x, t_y) = marched.table;
        let length = R::sqrt(t_x * t_x + t_y * t_y);
        let (c_x, c_y) = if length > R::ZERO {
            (t_x / length, t_y / length)
        } else {
            table_direction
        };
        // (A ball pressed without friction, `μ_s = 0`, would take the same pass again.)
        if table_mu != R::ZERO && length > R::ZERO && core::mem::take(&mut first_pass) {
            table_direction = (c_x, c_y);
            continue;
        }
        // The pressed ball's table contact slides: its friction is its μ times the
        // table's normal impulse on it, on Coulomb's cone. For the object ball that is
        // (per unit mass, m/s) the downward ball–ball friction −j_z (j_z ≤ 0 here; the max
        // takes rounding out); for the cue ball the upward one on the object ball, j_z.
        // (The rates above only time it for the normal impulse; their sum, from the
        // first-order budget, fell up to 2 % short of it.)
        let (table_x, table_y, table, cue_table_x, cue_table_y) = if object_pressed {
            let cone = R::of(params.mu_s()) * R::max(-j_z, R::ZERO);
            (cone * c_x, -cone * c_y, cone, R::ZERO, R::ZERO)
        } else {
            let cone = mu_ct * R::max(j_z, R::ZERO);
            (R::ZERO, R::ZERO, R::ZERO, -cone * c_x, -cone * c_y)
        };
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
