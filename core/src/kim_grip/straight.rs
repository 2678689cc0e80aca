//! The general path as it was before every slide was followed in pieces: the single
//! mid-point direction (`docs/physics.md` §4 items 3–5) with one table-friction rate.
//! The constant-μ fast path and the speed-dependent fast path evaluate these equations
//! specialised; this unspecialised evaluation (in `f32` and `f64`) is their test oracle
//! (`tests::fast_path_agrees_with_the_straight_general_path`,
//! `speed_path::tests::speed_path_agrees_with_the_straight_general_path`), and with the
//! `speed-path` feature the speed path's method in `f64` and where it declines (so that
//! both precisions answer alike). Otherwise test-only: the general path itself takes the
//! pieces everywhere (`general`, `curved`).

use super::normal::two_rate_normal_impulse;
use super::slip::TangentialSlip;
use super::{initial_slip, k_y, nu, table_contact_slip, GEARING_SLIP_SQUARED};
use crate::error::Result;
use crate::friction::FrictionLaw;
use crate::impact::Impact;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

/// The straight general path (module docs). Out of line: inlined into the speed path's
/// caller it costs the speed path a dozen instructions.
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
    let k_z = if object_pressed {
        (R::of(2.0) + nu::<R>() - R::of(params.mu_s())) / nu::<R>()
    } else {
        (R::of(2.0) + nu::<R>() + mu_ct * cue_dir_x) / nu::<R>()
    };
    // The cue ball's table friction also moves the slip along y: Δv_y = 7 J_y + k_yz J_z.
    let k_yz = mu_ct * cue_dir_y;
    let slip = StraightSlip::new(slip_y, slip_z, scale, k_yz, k_z);
    if slip.stick_budget == R::ZERO {
        // A slip so small that the impulse cancelling it underflows: exact gearing.
        return Outcome::without_friction(params, impact, frictionless_normal, false);
    }
    let slip_speed = slip.unit_norm * scale;
    let stick_budget = slip.stick_budget;
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
    let first_share_z = slip.pressing_share(first_budget);
    // One rate while sliding: the object ball's table friction (topspin) holds it back,
    // the cue ball's (draw) slows the approach.
    let table_rate = if first_span <= R::ZERO {
        // The slip stops at once (or no impact at all): no span for a rate.
        R::ZERO
    } else if object_pressed {
        R::of(params.mu_s()) * first_share_z * first_budget / first_span
    } else {
        -mu_ct * cue_dir_x * first_share_z * first_budget / first_span
    };
    let (compression_rate, restitution_rate) = (table_rate, table_rate);
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
        let (dir_y, dir_z) = slip.friction_direction(budget);
        let (j_y, j_z) = (budget * dir_y, budget * dir_z);
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

/// The initial tangential slip and the quantities derived from it. The slip
/// compliance is `K = [[k_y, k_yz], [0, k_z]]` (`Δv = K J`).
struct StraightSlip<R> {
    /// Slip direction scaled so its largest component is ±1 (`v₀ / scale`).
    unit_y: R,
    unit_z: R,
    k_yz: R,
    k_z: R,
    /// `|v₀| / scale`.
    unit_norm: R,
    /// Stick impulse `j_stick = −K⁻¹ v₀` (m/s).
    stick_y: R,
    stick_z: R,
    /// `s* = |j_stick|` (m/s): friction budget that stops the slip.
    stick_budget: R,
    /// `α_b / |v₀|`: where `v₀ − α K v̂₀` turns parallel to `K⁻¹ v₀`.
    boundary_alpha_per_norm: R,
    /// `s* / |v₀|`.
    stick_per_norm: R,
    /// `|v̂₀_z|` and `|ĵ_stick,z|`: the friction direction's vertical share when the
    /// slide starts and when it ends in a grip.
    start_share_z: R,
    stick_share_z: R,
}

impl<R: Real> StraightSlip<R> {
    fn new(slip_y: R, slip_z: R, scale: R, k_yz: R, k_z: R) -> Self {
        let base = TangentialSlip::new(slip_y, slip_z, scale, k_yz, k_z);
        let (unit_y, unit_z) = (base.unit_y, base.unit_z);
        let unit_norm = R::sqrt(unit_y * unit_y + unit_z * unit_z);
        // |K⁻¹u| and (K⁻¹u)_z, u = v₀ / scale.
        let unit_stick = base.stick_budget / scale;
        let inverse_z = -base.stick_z / scale;
        Self {
            unit_y,
            unit_z,
            k_yz,
            k_z,
            unit_norm,
            stick_y: base.stick_y,
            stick_z: base.stick_z,
            stick_budget: base.stick_budget,
            // α_b/|v₀| = cross(u, K⁻¹u) / cross(K u, K⁻¹u), 1/(k_y + k_z) for this
            // triangular K (`curved`'s module docs).
            boundary_alpha_per_norm: R::ONE / (k_y::<R>() + k_z),
            stick_per_norm: unit_stick / unit_norm,
            start_share_z: R::abs(unit_z) / unit_norm,
            stick_share_z: R::abs(inverse_z) / unit_stick,
        }
    }

    /// Unit direction of the friction impulse on the object ball after a friction
    /// budget `budget = μ p` (m/s), `budget ≤ s*` (clamped).
    fn friction_direction(&self, budget: R) -> (R, R) {
        let half = R::of(0.5);
        // f = S / s* in [0, 1], written so that no 0/0 or ∞/∞ can occur.
        let fraction = if budget >= self.stick_budget {
            R::ONE
        } else {
            budget / self.stick_budget
        };
        // α / |v₀| in units where |v₀| = unit_norm · scale; σ = s*/|v₀|.
        let sigma = self.stick_budget_per_norm();
        let alpha_per_norm = half * fraction * sigma
            + (self.boundary_alpha_per_norm - half * sigma) * fraction * fraction;
        // v_m / scale = u − (α/|v₀|) K u.
        let mid_y =
            self.unit_y - alpha_per_norm * (k_y::<R>() * self.unit_y + self.k_yz * self.unit_z);
        let mid_z = self.unit_z * (R::ONE - alpha_per_norm * self.k_z);
        let inv = R::ONE / R::sqrt(mid_y * mid_y + mid_z * mid_z);
        (-mid_y * inv, -mid_z * inv)
    }

    /// `|ĵ_z|`, the friction direction's vertical share, for the table-friction rate
    /// after a budget `budget` (m/s): linear in the spent fraction `f = S/s*` (clamped
    /// at 1) between its exact values at the start of the slide (`v̂₀`) and at the
    /// grip (`K⁻¹v₀`, where the direction meets the stick impulse). The mid-point
    /// direction of [`Self::friction_direction`] gives the same ends and costs a square
    /// root in between; against the reference on the 10k grid the interpolation moves
    /// `KimGrip`'s largest velocity error from 0.100 % to 0.111 % of U
    /// (`docs/physics.md` §4).
    fn pressing_share(&self, budget: R) -> R {
        let fraction = if budget >= self.stick_budget {
            R::ONE
        } else {
            budget / self.stick_budget
        };
        self.start_share_z + fraction * (self.stick_share_z - self.start_share_z)
    }

    /// `σ = s* / |v₀|`, a pure number of order `1/k`.
    fn stick_budget_per_norm(&self) -> R {
        self.stick_per_norm
    }
}
