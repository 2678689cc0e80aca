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
//! normal impulse, and stops when the contact grips at `p* = s*/μ`. With
//! `v_x(p) = −a + 2p − ρ min(p, p*)`, the compression end and Stronge's energetic
//! restitution (`W_restitution = e*² |W_compression|`, seed eq. (37)) give `p_f` in
//! closed form on each linear piece.

use crate::friction::FrictionLaw;
use crate::impact::Impact;
use crate::math;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::NU;

/// Slip change per unit specific friction impulse along `y` (seed eq. (19)): `2(1+ν)/ν`.
const K_Y: f32 = 2.0 * (1.0 + NU) / NU;

pub(crate) fn collide(params: &Params, impact: &Impact) -> Outcome {
    let law = params.friction_law();
    let restitution = params.restitution();
    let approach = impact.velocity().x;
    let frictionless_normal = 0.5 * (1.0 + restitution) * approach;
    let (slip_y, slip_z) = impact.initial_slip(params.radius());
    let scale = math::max(math::abs(slip_y), math::abs(slip_z));
    if law.is_frictionless() || scale == 0.0 {
        let regime = if law.is_frictionless() {
            Regime::Frictionless
        } else {
            Regime::Gripping
        };
        return Outcome::from_impulses(
            params,
            impact,
            SpecificImpulses::normal_only(frictionless_normal),
            regime,
        );
    }

    let object_pressed = slip_z > 0.0;
    let k_z = if object_pressed {
        (2.0 + NU - params.mu_s()) / NU
    } else {
        (2.0 + NU) / NU
    };
    let slip = TangentialSlip::new(slip_y, slip_z, scale, k_z);
    if slip.stick_budget == 0.0 {
        // A slip so small that the impulse cancelling it underflows: exact gearing.
        return Outcome::from_impulses(
            params,
            impact,
            SpecificImpulses::normal_only(frictionless_normal),
            Regime::Gripping,
        );
    }
    let slip_speed = slip.unit_norm * scale;
    // Effective compliance along the slip path, k̄ = |v₀| / s* (see `friction`).
    let compliance = slip_speed / slip.stick_budget;
    // p*: the normal impulse at which the slip would stop (may be +inf for tiny μ).
    let grip_normal = law.normal_impulse_between(slip_speed, 0.0, compliance);
    // Friction budget S(p) = ∫ μ dp spent by normal impulse p while sliding.
    let budget_after = |normal: f32| -> f32 {
        if normal >= grip_normal {
            slip.stick_budget
        } else {
            match law {
                FrictionLaw::Constant(mu) => mu * normal,
                FrictionLaw::SpeedDependent { .. } => {
                    (slip_speed - law.slip_after(slip_speed, normal, compliance)) / compliance
                }
            }
        }
    };

    // Direction at the first-order budget, for the table-friction rate ρ (table
    // impulse per unit normal impulse while sliding).
    let first_budget = budget_after(frictionless_normal);
    let (_, first_dir_z) = slip.friction_direction(first_budget);
    let first_span = if frictionless_normal < grip_normal {
        frictionless_normal
    } else {
        grip_normal
    };
    let table_rate = if object_pressed {
        params.mu_s() * math::abs(first_dir_z) * first_budget / first_span
    } else {
        0.0
    };
    let normal = final_normal_impulse(approach, restitution, table_rate, grip_normal);

    let (j_y, j_z, regime) = if normal < grip_normal {
        let budget = budget_after(normal);
        let (dir_y, dir_z) = slip.friction_direction(budget);
        (budget * dir_y, budget * dir_z, Regime::Sliding)
    } else {
        (slip.stick_y, slip.stick_z, Regime::Gripping)
    };
    let pressing_span = if normal < grip_normal {
        normal
    } else {
        grip_normal
    };
    let table = table_rate * pressing_span;
    let (table_x, table_y) = table_friction_components(table, pressing_span, j_y, j_z);
    let impulses = SpecificImpulses {
        normal,
        friction_y: j_y,
        friction_z: j_z,
        table: table_x,
        table_y,
    };
    Outcome::from_impulses(params, impact, impulses, regime)
}

/// Split the table friction `table` (m/s) on the pressed object ball along its
/// table-contact slip `c = V + Ω × (−R ẑ)` (first-principles Coulomb direction; the seed's
/// eq. (7) takes `c ∥ x̂`). At the end of the pressing span every impulse has grown
/// roughly in proportion, so the final `c` gives the mean direction:
/// `c_x = p − X − (j_z + X)/ν` (the spin `Ω_y` adds `−R Ω_y`), `c_y = j_y`. Returns the
/// `−x` magnitude and the `y` component of the table impulse.
fn table_friction_components(table: f32, span: f32, j_y: f32, j_z: f32) -> (f32, f32) {
    if table == 0.0 {
        return (0.0, 0.0);
    }
    let slip_x = span - table - (j_z + table) / NU;
    let slip_y = j_y;
    let length = math::sqrt(slip_x * slip_x + slip_y * slip_y);
    if length == 0.0 {
        return (table, 0.0);
    }
    (table * slip_x / length, -table * slip_y / length)
}

/// The initial tangential slip and the quantities derived from it.
struct TangentialSlip {
    /// Slip direction scaled so its largest component is ±1 (`v₀ / scale`).
    unit_y: f32,
    unit_z: f32,
    k_z: f32,
    /// `|v₀| / scale`.
    unit_norm: f32,
    /// Stick impulse `j_stick = −K⁻¹ v₀` (m/s).
    stick_y: f32,
    stick_z: f32,
    /// `s* = |j_stick|` (m/s): friction budget that stops the slip.
    stick_budget: f32,
}

impl TangentialSlip {
    fn new(slip_y: f32, slip_z: f32, scale: f32, k_z: f32) -> Self {
        let unit_y = slip_y / scale;
        let unit_z = slip_z / scale;
        let unit_norm = math::sqrt(unit_y * unit_y + unit_z * unit_z);
        let (unit_stick_y, unit_stick_z) = (-unit_y / K_Y, -unit_z / k_z);
        let unit_stick = math::sqrt(unit_stick_y * unit_stick_y + unit_stick_z * unit_stick_z);
        Self {
            unit_y,
            unit_z,
            k_z,
            unit_norm,
            stick_y: unit_stick_y * scale,
            stick_z: unit_stick_z * scale,
            stick_budget: unit_stick * scale,
        }
    }

    /// Unit direction of the friction impulse on the object ball after a friction
    /// budget `budget = μ p` (m/s), `budget ≤ s*` (clamped).
    fn friction_direction(&self, budget: f32) -> (f32, f32) {
        // f = S / s* in [0, 1], written so that no 0/0 or ∞/∞ can occur.
        let fraction = if budget >= self.stick_budget {
            1.0
        } else {
            budget / self.stick_budget
        };
        // α / |v₀| in units where |v₀| = unit_norm · scale; σ = s*/|v₀|.
        let sigma = self.stick_budget_per_norm();
        let alpha_per_norm =
            0.5 * fraction * sigma + (1.0 / (K_Y + self.k_z) - 0.5 * sigma) * fraction * fraction;
        // v_m / scale = u − (α/|v₀|) K u.
        let mid_y = self.unit_y * (1.0 - alpha_per_norm * K_Y);
        let mid_z = self.unit_z * (1.0 - alpha_per_norm * self.k_z);
        let inv = 1.0 / math::sqrt(mid_y * mid_y + mid_z * mid_z);
        (-mid_y * inv, -mid_z * inv)
    }

    /// `s* / |v₀|`, a pure number in `[1/k_y, 1/k_z]`.
    fn stick_budget_per_norm(&self) -> f32 {
        let sy = self.unit_y / K_Y;
        let sz = self.unit_z / self.k_z;
        math::sqrt(sy * sy + sz * sz) / self.unit_norm
    }
}

/// Final normal impulse per unit mass (m/s) for approach speed `a`, energetic
/// restitution `e`, table-friction rate `ρ` acting up to the grip impulse `p*`.
///
/// `v_x(p) = −a + (2 − ρ) p` for `p ≤ p*`, slope 2 after; compression ends at
/// `v_x = 0`; restitution ends when the work done since then is `e² |W_c|`.
fn final_normal_impulse(a: f32, e: f32, rho: f32, grip: f32) -> f32 {
    let slope = 2.0 - rho;
    let compression_end = a / slope;
    let sliding_end = (1.0 + e) * compression_end;
    if sliding_end <= grip {
        return sliding_end;
    }
    if grip >= compression_end {
        // Grip during restitution: work `slope (p*−p_c)²/2` done on the sliding piece,
        // the rest `e² a p_c / 2 − that` on the slope-2 piece: v* q + q² = rest.
        let v_star = slope * (grip - compression_end);
        let rest = 0.5 * e * e * a * compression_end - 0.5 * v_star * (grip - compression_end);
        let rest = if rest > 0.0 { rest } else { 0.0 };
        let denominator = v_star + math::sqrt(v_star * v_star + 4.0 * rest);
        let extra = if denominator > 0.0 {
            2.0 * rest / denominator
        } else {
            0.0
        };
        grip + extra
    } else {
        // Grip during compression: slope 2 from p*, compression ends at p_c, then
        // (p − p_c)² = e² |W_c|.
        let v_star = -a + slope * grip;
        let work_at_grip = -a * grip + 0.5 * slope * grip * grip;
        let compression_end = grip - 0.5 * v_star;
        let compression_work = work_at_grip - 0.25 * v_star * v_star;
        let depth = if compression_work < 0.0 {
            -compression_work
        } else {
            0.0
        };
        compression_end + e * math::sqrt(depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_impulse_without_table_is_one_plus_e_half() {
        assert!((final_normal_impulse(2.0, 0.9, 0.0, f32::INFINITY) - 1.9).abs() < 1e-6);
    }

    #[test]
    fn normal_impulse_is_continuous_across_grip_cases() {
        let (a, e, rho) = (1.0, 0.9, 0.04);
        let p_c = a / (2.0 - rho);
        for grip in [p_c, (1.0 + e) * p_c] {
            let below = final_normal_impulse(a, e, rho, grip * (1.0 - 1e-6));
            let above = final_normal_impulse(a, e, rho, grip * (1.0 + 1e-6));
            assert!((below - above).abs() < 1e-5, "{below} vs {above} at {grip}");
        }
    }

    #[test]
    fn early_grip_tends_to_the_frictionless_impulse() {
        // Table friction that stops immediately leaves the frictionless (1+e) a / 2.
        let p = final_normal_impulse(1.0, 0.95, 0.04, 0.0);
        assert!((p - 0.975).abs() < 1e-6);
    }

    #[test]
    fn direction_meets_stick_impulse_at_the_boundary() {
        let slip = TangentialSlip::new(-0.7, 0.5, 0.7, 5.0);
        let (dy, dz) = slip.friction_direction(slip.stick_budget);
        let (sy, sz) = (
            slip.stick_y / slip.stick_budget,
            slip.stick_z / slip.stick_budget,
        );
        assert!((dy - sy).abs() < 1e-6 && (dz - sz).abs() < 1e-6);
    }
}
