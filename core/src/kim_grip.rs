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

use crate::error::Result;
use crate::friction::FrictionLaw;
use crate::impact::Impact;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

mod fast_path;
pub(crate) use fast_path::MIN_SLIP_SQUARED as FAST_PATH_MIN_SLIP_SQUARED;

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
        None => general::<R>(params, impact),
    }
}

/// Every scene: any friction law, the cue ball's table friction, slips down to zero
/// (scaled to their largest component).
#[inline(never)]
fn general<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    let half = R::of(0.5);
    let law = params.friction_law();
    let restitution = R::of(params.restitution());
    let approach = R::of(impact.velocity().x);
    let frictionless_normal = half * (R::ONE + restitution) * approach;
    let (slip_y, slip_z) = initial_slip::<R>(params, impact);
    let scale = R::max(R::abs(slip_y), R::abs(slip_z));
    if law.is_frictionless() || scale == R::ZERO || frictionless_normal == R::ZERO {
        // No friction, or no slip and so no friction direction (exact gearing).
        return Outcome::without_friction(
            params,
            impact,
            frictionless_normal,
            law.is_frictionless(),
        );
    }

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
    // Effective compliance along the slip path, k̄ = |v₀| / s* (see `friction`).
    let compliance = slip_speed / slip.stick_budget;
    // p*: the normal impulse at which the slip would stop (may be +inf for tiny μ).
    let grip_normal = match law {
        FrictionLaw::Constant(mu) => slip.stick_budget / R::of(mu),
        FrictionLaw::SpeedDependent { .. } => {
            law.normal_impulse_between(slip_speed, R::ZERO, compliance)
        }
    };
    // Friction budget S(p) = ∫ μ dp spent by normal impulse p while sliding.
    let budget_after = |normal: R| -> R {
        if normal >= grip_normal {
            slip.stick_budget
        } else {
            match law {
                FrictionLaw::Constant(mu) => R::of(mu) * normal,
                FrictionLaw::SpeedDependent { .. } => {
                    law.slip_change(slip_speed, normal, compliance) / compliance
                }
            }
        }
    };

    // Direction at the first-order budget, for the table-friction rate ρ (table
    // impulse per unit normal impulse while sliding).
    let first_budget = budget_after(frictionless_normal);
    let (_, first_dir_z) = slip.friction_direction(first_budget);
    let first_span = R::min(frictionless_normal, grip_normal);
    // Table friction along x per unit normal impulse while sliding: the object ball's
    // (topspin) holds it back, the cue ball's (draw) slows the approach.
    let table_rate = if first_span <= R::ZERO {
        // The slip stops at once (or no impact at all): nothing to spread a rate over.
        R::ZERO
    } else if object_pressed {
        R::of(params.mu_s()) * R::abs(first_dir_z) * first_budget / first_span
    } else {
        -mu_ct * cue_dir_x * R::abs(first_dir_z) * first_budget / first_span
    };
    let (normal, slides) = final_normal_impulse(
        approach,
        restitution,
        R::ONE + restitution,
        table_rate,
        grip_normal,
    );

    let (j_y, j_z, regime) = if slides {
        let budget = budget_after(normal);
        let (dir_y, dir_z) = slip.friction_direction(budget);
        (budget * dir_y, budget * dir_z, Regime::Sliding)
    } else {
        (slip.stick_y, slip.stick_z, Regime::Gripping)
    };
    let pressing_span = R::min(normal, grip_normal);
    let (table, cue_table_x, cue_table_y) = if object_pressed {
        (table_rate * pressing_span, R::ZERO, R::ZERO)
    } else {
        // Pressing impulse on the cue ball = the upward friction impulse on the object.
        let pressing = R::max(j_z, R::ZERO);
        (
            R::ZERO,
            -mu_ct * pressing * cue_dir_x,
            -mu_ct * pressing * cue_dir_y,
        )
    };
    let (table_x, table_y) = table_friction_components(table, pressing_span, j_y, j_z);
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
/// roughly in proportion, so the final `c` gives the mean direction:
/// `c_x = p − X − (j_z + X)/ν` (the spin `Ω_y` adds `−R Ω_y`), `c_y = j_y`. Returns the
/// `−x` magnitude and the `y` component of the table impulse.
#[inline(always)]
fn table_friction_components<R: Real>(table: R, span: R, j_y: R, j_z: R) -> (R, R) {
    let (slip_x, slip_y) = table_contact_slip(table, span, j_y, j_z);
    let length = R::sqrt(slip_x * slip_x + slip_y * slip_y);
    if length > R::ZERO {
        let scale = table / length;
        (scale * slip_x, -scale * slip_y)
    } else {
        // No slip at the table contact: no direction; the seed's −x (eq. (7)).
        (table, R::ZERO)
    }
}

/// The object ball's table-contact slip `(c_x, c_y)` (m/s) at the end of the pressing
/// span (see [`table_friction_components`]), for table friction `table` (m/s).
#[inline(always)]
fn table_contact_slip<R: Real>(table: R, span: R, j_y: R, j_z: R) -> (R, R) {
    (span - table - (j_z + table) / nu::<R>(), j_y)
}

/// The initial tangential slip and the quantities derived from it. The slip
/// compliance is `K = [[k_y, k_yz], [0, k_z]]` (`Δv = K J`).
struct TangentialSlip<R> {
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
}

impl<R: Real> TangentialSlip<R> {
    fn new(slip_y: R, slip_z: R, scale: R, k_yz: R, k_z: R) -> Self {
        let unit_y = slip_y / scale;
        let unit_z = slip_z / scale;
        let unit_norm = R::sqrt(unit_y * unit_y + unit_z * unit_z);
        // K⁻¹ u, u = v₀ / scale.
        let inverse_z = unit_z / k_z;
        let inverse_y = (unit_y - k_yz * inverse_z) / k_y::<R>();
        let unit_stick = R::sqrt(inverse_y * inverse_y + inverse_z * inverse_z);
        // α_b/|v₀| = cross(u, K⁻¹u) / cross(K u, K⁻¹u); 1/(k_y + k_z) when K is
        // diagonal, and any value when v₀ is an eigenvector (the direction cannot turn).
        let (ku_y, ku_z) = (k_y::<R>() * unit_y + k_yz * unit_z, k_z * unit_z);
        let numerator = unit_y * inverse_z - unit_z * inverse_y;
        let denominator = ku_y * inverse_z - ku_z * inverse_y;
        let boundary_alpha_per_norm = if R::abs(denominator) > R::of(1e-12) {
            numerator / denominator
        } else {
            R::ONE / (k_y::<R>() + k_z)
        };
        Self {
            unit_y,
            unit_z,
            k_yz,
            k_z,
            unit_norm,
            stick_y: -inverse_y * scale,
            stick_z: -inverse_z * scale,
            stick_budget: unit_stick * scale,
            boundary_alpha_per_norm,
            stick_per_norm: unit_stick / unit_norm,
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

    /// `σ = s* / |v₀|`, a pure number of order `1/k`.
    fn stick_budget_per_norm(&self) -> R {
        self.stick_per_norm
    }
}

/// Final normal impulse per unit mass (m/s) for approach speed `a`, energetic
/// restitution `e`, table-friction rate `ρ` acting up to the grip impulse `p*`.
///
/// `v_x(p) = −a + (2 − ρ) p` for `p ≤ p*`, slope 2 after; compression ends at
/// `v_x = 0`; restitution ends when the work done since then is `e² |W_c|`.
///
/// `one_plus_e` is `1 + e` (the caller may have it precomputed). Returns the impulse
/// and whether the contact slides to the end (`p ≤ p*`, regime `Sliding`; otherwise
/// `p > p*` and it grips): the branch taken here decides it, so the callers need no
/// second comparison. At `p = p*` exactly both regimes give the same friction (the
/// direction meets the stick impulse there).
#[inline(always)]
fn final_normal_impulse<R: Real>(a: R, e: R, one_plus_e: R, rho: R, grip: R) -> (R, bool) {
    let (half, two) = (R::of(0.5), R::of(2.0));
    let slope = two - rho;
    let compression_end = a / slope;
    let sliding_end = one_plus_e * compression_end;
    if sliding_end <= grip {
        return (sliding_end, true);
    }
    if grip >= compression_end {
        // Grip during restitution: work `slope (p*−p_c)²/2` done on the sliding piece,
        // the rest `e² a p_c / 2 − that` on the slope-2 piece: v* q + q² = rest.
        let v_star = slope * (grip - compression_end);
        let rest = R::max(
            half * e * e * a * compression_end - half * v_star * (grip - compression_end),
            R::ZERO,
        );
        let denominator = v_star + R::sqrt(v_star * v_star + R::of(4.0) * rest);
        let extra = if denominator > R::ZERO {
            two * rest / denominator
        } else {
            R::ZERO
        };
        (grip + extra, false)
    } else {
        // Grip during compression: slope 2 from p*, compression ends at p_c, then
        // (p − p_c)² = e² |W_c|.
        let v_star = -a + slope * grip;
        let work_at_grip = -a * grip + half * slope * grip * grip;
        let compression_end = grip - half * v_star;
        let compression_work = work_at_grip - R::of(0.25) * v_star * v_star;
        let depth = R::max(-compression_work, R::ZERO);
        (compression_end + e * R::sqrt(depth), false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A friction law built from the enum's variant bypasses `FrictionLaw::constant`'s
    /// range check; the fast path's guard assumes μ ≤ 1, so such laws take the general
    /// path, whose guard reports the error (found by the `collide` fuzz target: μ = ∞
    /// gave a NaN velocity through the fast path).
    #[test]
    fn unvalidated_friction_never_gives_a_non_finite_outcome() {
        let impacts = [
            // Topspin (object ball pressed), stun with side spin, draw.
            Impact::from_velocity([2.0, -10.0], [340.9, 68.6, 0.0]),
            Impact::from_velocity([2.0, 0.3], [0.0, -20.0, 10.0]),
            Impact::from_velocity([3.0, 0.0], [0.0, -90.0, 0.0]),
        ];
        for mu in [f32::INFINITY, 1e30, 1.5, f32::NAN, -0.5, f32::MIN_POSITIVE] {
            let params = Params::POOL.with_friction_law(FrictionLaw::Constant(mu));
            for impact in &impacts {
                let impact = impact.as_ref().expect("valid impact");
                let results = [
                    collide::<f32>(&params, impact),
                    collide::<f64>(&params, impact),
                ];
                for outcome in results.iter().flatten() {
                    assert!(outcome.is_finite(), "mu = {mu}: {outcome:?}");
                }
            }
        }
    }

    /// The fast path's topspin branch has no zero-length branch for the table-contact
    /// slip: a slip whose square underflows (a vanishing approach speed) gives an
    /// infinite or NaN table friction there, which its guard must hand to the general
    /// path. Without that guard these scenes come out NaN.
    #[test]
    fn underflowing_table_slip_takes_the_general_path() {
        let params = Params::POOL;
        let mut declined = 0;
        for approach in [f32::from_bits(1), 1e-44, 1e-40, 1e-38, 1e-30, 1e-22, 1e-19] {
            for side in [0.0, 1e-30, 0.5] {
                // Topspin: the object ball is pressed into the cloth.
                let impact = Impact::from_velocity([approach, side], [0.0, 70.0, 0.0])
                    .expect("valid impact");
                let fast = fast_path::collide::<f32>(&params, &impact);
                if let Some(outcome) = fast {
                    assert!(outcome.is_finite(), "a = {approach:e}: {outcome:?}");
                } else {
                    declined += 1;
                }
                let outcome = collide::<f32>(&params, &impact).expect("a finite outcome");
                assert!(outcome.is_finite(), "a = {approach:e}: {outcome:?}");
            }
        }
        assert!(declined > 0, "no scene reached the table-slip guard");
    }

    #[test]
    fn normal_impulse_without_table_is_one_plus_e_half() {
        assert!(
            (final_normal_impulse(2.0f32, 0.9, 1.0 + 0.9, 0.0, f32::INFINITY).0 - 1.9).abs() < 1e-6
        );
    }

    #[test]
    fn normal_impulse_is_continuous_across_grip_cases() {
        let (a, e, rho) = (1.0f32, 0.9f32, 0.04f32);
        let p_c = a / (2.0 - rho);
        for grip in [p_c, (1.0 + e) * p_c] {
            let (below, _) = final_normal_impulse(a, e, 1.0 + e, rho, grip * (1.0 - 1e-6));
            let (above, _) = final_normal_impulse(a, e, 1.0 + e, rho, grip * (1.0 + 1e-6));
            assert!((below - above).abs() < 1e-5, "{below} vs {above} at {grip}");
        }
    }

    #[test]
    fn early_grip_tends_to_the_frictionless_impulse() {
        // Table friction that stops immediately leaves the frictionless (1+e) a / 2.
        let (p, slides) = final_normal_impulse(1.0f32, 0.95, 1.0 + 0.95, 0.04, 0.0);
        assert!(!slides);
        assert!((p - 0.975).abs() < 1e-6);
    }

    #[test]
    fn direction_meets_stick_impulse_at_the_boundary() {
        let slip = TangentialSlip::new(-0.7f32, 0.5, 0.7, 0.0, 5.0);
        let (dy, dz) = slip.friction_direction(slip.stick_budget);
        let (sy, sz) = (
            slip.stick_y / slip.stick_budget,
            slip.stick_z / slip.stick_budget,
        );
        assert!((dy - sy).abs() < 1e-6 && (dz - sz).abs() < 1e-6);
    }

    /// The fast path evaluates the general path's equations specialised (diagonal `K`,
    /// constant μ, unscaled slip), so both must agree to rounding wherever the fast
    /// path applies. Differences are in units of the scene's speed scale
    /// `S = max(U, R|ω|)`: `f32` within 2e-6 S (a few ulps of the largest term), `f64`
    /// within 3e-7 S (the outcome is rounded to `f32`: a difference of 1e-16 can still
    /// round to neighbouring `f32` values, 1.2e-7 S apart at most), and the same regime
    /// away from the slide/grip boundary.
    #[test]
    fn fast_path_agrees_with_the_general_path() {
        fn largest_difference<R: Real>(params: &Params, impact: &Impact) -> Option<(f32, bool)> {
            let fast = fast_path::collide::<R>(params, impact)?;
            let general = general::<R>(params, impact).ok()?;
            let scale = impact.speed().max(params.radius() * impact.spin().length());
            let mut worst = 0.0f32;
            for (a, b) in [
                (fast.cue_ball, general.cue_ball),
                (fast.object_ball, general.object_ball),
            ] {
                let dv = a.velocity - b.velocity;
                let dw = a.spin - b.spin;
                worst = worst
                    .max(dv.length() / scale)
                    .max(params.radius() * dw.length() / scale);
            }
            Some((worst, fast.regime == general.regime))
        }
        // A small deterministic generator (no dev-dependency in the unit tests).
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut uniform = |lo: f32, hi: f32| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
        };
        let (mut checked, mut regime_differs) = (0, 0);
        let (mut worst32, mut worst64) = (0.0f32, 0.0f32);
        for _ in 0..20_000 {
            let params = Params::new(
                uniform(1e-4, 1.0),
                uniform(0.0, 1.0),
                uniform(0.0, 1.0),
                uniform(0.01, 0.1),
                uniform(0.1, 1.0),
            )
            .unwrap();
            let speed = uniform(0.01, 10.0);
            let cut = uniform(-1.5, 1.5);
            let spin = [
                uniform(-300.0, 300.0),
                uniform(-300.0, 300.0),
                uniform(-300.0, 300.0),
            ];
            let impact = Impact::from_velocity(
                [speed * crate::math::cos(cut), speed * crate::math::sin(cut)],
                spin,
            )
            .unwrap();
            if let Some((d32, same32)) = largest_difference::<f32>(&params, &impact) {
                let (d64, _) = largest_difference::<f64>(&params, &impact).unwrap();
                checked += 1;
                worst32 = worst32.max(d32);
                worst64 = worst64.max(d64);
                regime_differs += usize::from(!same32);
            }
        }
        assert!(checked > 19_000, "fast path taken in only {checked} scenes");
        assert!(
            worst32 <= 2e-6,
            "f32: fast and general differ by {worst32:e} S"
        );
        assert!(
            worst64 <= 3e-7,
            "f64: fast and general differ by {worst64:e} S"
        );
        assert!(
            regime_differs <= 2,
            "regime differs in {regime_differs} scenes"
        );
    }
}
