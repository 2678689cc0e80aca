//! `SeedExact`: the seed's exact sliding solution, eqs. (24)–(41) with erratum E1, plus
//! a stick branch — the closed formulation issue 4 names, evaluated without `std`.
//!
//! **Physics.** Exactly the seed's model: ball–ball Coulomb friction `μ` against the
//! contact slip, the object ball's table friction `μ_s` times its pressing impulse
//! along `−x` (seed eq. (7)), no cue-ball/table friction (the seed neglects it; `μ_ct`
//! is ignored here, as in `Kim`), gravity and contact time neglected, Stronge's energetic
//! restitution (eq. (37)). E1 (sign of the table-friction torque, seed eq. (10)) is
//! applied throughout: `k_z = 2β_z = (2+ν−μ_s)/ν`. Within that model the only
//! approximations are the quadrature of the seed's integrals (29)–(30), (33), (36)
//! (`path` module: 8-point Gauss–Legendre, error below f32 resolution in the calibrated
//! domain) and the root solves' stopping rule (`root` module: the function solved within
//! `RESIDUAL_EPSILONS` roundings of its scale, or `w` within 2 ε).
//! What the model itself leaves out — table friction against the table-contact slip,
//! which leans by `O(μ)` towards `y` — is up to 0.36 % of U on the foundation grid
//! (`docs/physics.md` §7); `Exact` integrates it.
//!
//! **Solution** (per unit mass, impulses in m/s, `a = U_i cos φ`, `ρ`, `P`, `I_z` as in
//! `path`; `X = μ_s Θ(v_z0) v_z0 (1 − ρ^{k_z})/k_z` is the table friction so far):
//!
//! 1. *Sliding* (seed (29), (31) with E1): the slip slides along (24) to `ρ` after the
//!    normal impulse `P(ρ)`; the normal relative velocity is
//!    `v_x = −a + 2P − X` and the normal work `W = −aP + P² + (μ_s/k_z)(I_z − v_z0 P)`
//!    (eq. (33)).
//! 2. *Compression end* `p_c` (eq. (32)): the root of `v_x = 0` (bracketed Newton, `root`
//!    module), solved for `w = 1 − ρ^κ` (`path` module), in which `v_x` is nearly linear.
//! 3. *Restitution* (eqs. (35)–(37)): the impact ends when the work since `p_c`,
//!    `D = (P − p_c)² + (μ_s/k_z) ∫_{p_c}^{P} (v_z − v_z(p_c)) dp` (eq. (36)), reaches
//!    `e*² |W(p_c)|`; solved as `√D = e* √|W(p_c)|` (linear in `P − p_c` near `p_c`),
//!    with `D` integrated from `p_c` so that it keeps its digits when small.
//! 4. *Outcome* (eqs. (39)–(41), E1): friction impulse on the object ball
//!    `J = (v_y0 (ρ^{k_y} − 1)/k_y, v_z0 (ρ^{k_z} − 1)/k_z)` (eq. (57)), table friction
//!    `X`, normal impulse `p_f`, assembled by `Outcome::from_impulses`.
//!
//! **Brackets.** `v_x(ρ = 1) = −a < 0`. The other end comes from a proven bound: while
//! sliding `dv_x/dp ≥ s = 2 − μ_max μ_s`, so `p_f ≤ p̄ = (1+e*) a/s`; and `g(ρ) ≥ ρ⁶`
//! gives `P(ρ) ≥ |v₀| (1 − ρ⁷)/(7 μ_max)`. If `7 μ_max p̄ < |v₀|` the slip cannot stop
//! and `ρ̄ = (1 − 7 μ_max p̄/|v₀|)^{1/7}` brackets both roots (`P(ρ̄) ≥ p̄`; for a slip
//! along `y` without table friction the bound is tight and the root lies on it, which
//! the solver allows for). Otherwise the
//! stick point `ρ = 0` is evaluated and brackets them, or decides the grip.
//!
//! **Stick branch** (erratum E6; the seed assumes sliding throughout). When the slip
//! reaches zero at `P* = P(0)` the contact sticks with zero friction from then on: the
//! normal impulse acts through both centres and cannot restart slip, and without
//! friction there is no pressing, so no more table friction (the argument of
//! `KimGrip`, confirmed by the reference). The friction impulse is then exactly
//! `J = −K⁻¹ v₀` and `X = μ_s v_z0/k_z`, and `v_x` grows with slope 2 after `P*`:
//! gripping during compression (`v_x(P*) ≤ 0`) gives `p_c = P* − v_x*/2`,
//! `W_c = W* − v_x*²/4`, `p_f = p_c + e* √|W_c|`; gripping during restitution solves
//! `v_x* s + s² = e*²|W_c| − D*` for the rest `s = p_f − P*`. Both are continuous with
//! the sliding solution at the boundary.
//!
//! **Friction laws.** Constant μ, and the speed-dependent `μ(|v|)` of TP A.14: the path
//! (24) does not depend on μ, only the pace along it (`path` module docs), so the same
//! solution holds with `1/μ(|v|)` inside the integrals (4 quadrature panels).
//!
//! **Failure.** A root solve that cannot confirm its bracket or does not converge within
//! `root::MAX_EVALUATIONS` returns [`Error::NumericalFailure`]; nothing panics. When
//! the slip cannot change by more than a rounding (`1 − ρ̄⁷ ≤ 7 ε`, or `|v₀|/μ` overflows),
//! the constant-direction limit of the solution is exact to that precision and used.

mod path;
mod root;

use crate::error::{Error, Result};
use crate::impact::Impact;
use crate::kim_grip::initial_slip;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;
use path::{Point, SlipPath, K_Y};
use root::{increasing_root, Sample};

/// The root solves stop where the function solved is within this many machine epsilons
/// of its scale: `v_x = −a + 2P − X` at the compression end (scale `a`; `P` is an
/// 8-term quadrature sum whose nodes `ρ = 1 − q t` are themselves rounded, a few ε of
/// `P`), `√D − e*√|W_c|` at the end (scale `e*√|W_c|`). Below that the root is not
/// determined in this precision, and Newton steps would only chase the rounding.
const RESIDUAL_EPSILONS: f32 = 4.0;

// Not inlined into `model::collide_in` (see `kim_grip::collide`).
#[inline(never)]
pub(crate) fn collide<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    let result = solve::<R>(params, impact);
    // Known f32 failure (found by the `collide` fuzz target; not yet understood): at
    // extreme scenes (U 82 m/s, ω_y 10⁴ rad/s, R 1 cm, a slip almost all vertical) the
    // impulses integrated to the stick point come out NaN in f32, and the outcome is
    // `NumericalFailure` though the input is valid. On a host the same solution is then
    // evaluated in f64 and rounded; the device, where f64 is software (and over the
    // flash budget), keeps the typed error.
    #[cfg(not(target_os = "none"))]
    if R::SINGLE && result == Err(Error::NumericalFailure) {
        return solve::<f64>(params, impact);
    }
    result
}

/// [`collide`] in the evaluation precision `R`.
fn solve<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    let law = params.friction_law();
    let restitution = R::of(params.restitution());
    let approach = R::of(impact.velocity().x);
    let (slip_y, slip_z) = initial_slip::<R>(params, impact);
    if law.is_frictionless() || (slip_y == R::ZERO && slip_z == R::ZERO) {
        // No friction, or no slip and so no friction direction (exact gearing).
        let normal = R::of(0.5) * (R::ONE + restitution) * approach;
        return Outcome::without_friction(params, impact, normal, law.is_frictionless());
    }
    let path = SlipPath::new(slip_y, slip_z, R::of(params.mu_s()), law);
    // μ_s Θ(−θ₀): only the pressed object ball (topspin, v_z0 > 0) feels the table.
    let table_mu = if slip_z > R::ZERO {
        R::of(params.mu_s())
    } else {
        R::ZERO
    };
    let impact_model = Impulse {
        approach,
        restitution,
        table_mu,
        path: &path,
    };
    let Some(end) = impact_model.solve()? else {
        return constant_direction(params, impact, &path, table_mu);
    };
    let j_y = slip_y * end.point.y_change / R::of(K_Y);
    let j_z = slip_z * end.point.z_change / path.k_z;
    // X = μ_s |J_z| along −x (seed eq. (7)); J_z ≤ 0 when the object ball is pressed.
    // X ≤ μ_s μ p_f ≤ p_f holds in the model (|J_z| ≤ ∫ μ dp); the bound only guards the
    // rounding at μ μ_s = 1, where the object ball's V_x = p_f − X is zero.
    let table = R::min(-table_mu * j_z, end.normal);
    let impulses = SpecificImpulses {
        normal: end.normal,
        friction_y: j_y,
        friction_z: j_z,
        table,
        table_y: R::ZERO,
        table_size: R::abs(table),
        cue_table_x: R::ZERO,
        cue_table_y: R::ZERO,
    };
    Outcome::from_impulses(params, impact, impulses, end.regime)
}

/// The limit of the sliding solution when the slip barely changes (`q̄ ≤ ε`, or `|v₀|/μ`
/// overflows): friction of constant direction `−v̂₀` and size `μ(|v₀|) dp` (seed eq.
/// (57) at `θ = θ₀`), so `v_x = −a + s p` with `s = 2 − μ μ_s ĉ_z` (eq. (31)) and
/// `p_f = (1+e*) a/s` exactly (eqs. (32)–(37) with a constant slope). Its error against
/// the full solution is `O(q̄)` of the friction impulse: rounding.
fn constant_direction<R: Real>(
    params: &Params,
    impact: &Impact,
    path: &SlipPath<R>,
    table_mu: R,
) -> Result<Outcome> {
    let (slip_y, slip_z) = initial_slip::<R>(params, impact);
    let approach = R::of(impact.velocity().x);
    let mu = path.mu_min();
    let (unit_y, unit_z) = (slip_y / path.speed, slip_z / path.speed);
    let slope = R::of(2.0) - mu * table_mu * unit_z;
    let normal = (R::ONE + R::of(params.restitution())) * approach / slope;
    let friction = mu * normal;
    let (j_y, j_z) = (-friction * unit_y, -friction * unit_z);
    let table = R::min(-table_mu * j_z, normal);
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

/// The normal-impulse timeline of one impact along its sliding path.
struct Impulse<'a, R> {
    /// `a = U_i cos φ` (m/s).
    approach: R,
    /// `e*`.
    restitution: R,
    /// `μ_s Θ(−θ₀)`.
    table_mu: R,
    path: &'a SlipPath<R>,
}

/// Where the impact ends: the slip state, the final normal impulse `p_f` (m/s) and
/// whether the contact gripped.
struct End<R> {
    point: Point<R>,
    normal: R,
    regime: Regime,
}

impl<R: Real> Impulse<'_, R> {
    /// Table friction so far, `X = −μ_s v_z0 (ρ^{k_z} − 1)/k_z` (m/s).
    fn table(&self, at: &Point<R>) -> R {
        -self.table_mu * self.path.slip_z * at.z_change / self.path.k_z
    }

    /// Normal relative velocity `v_x = −a + 2P − X` (seed eq. (31), E1; m/s).
    fn normal_velocity(&self, at: &Point<R>) -> R {
        -self.approach + R::of(2.0) * at.normal - self.table(at)
    }

    /// `dv_x/dw = 2 dP/dw − dX/dw`, `w = 1 − ρ^κ`; `dX/dw = μ_s v_z0/k_z` (`κ = k_z`, or
    /// `v_z0 = 0`) (m/s).
    fn normal_velocity_slope(&self, at: &Point<R>) -> R {
        R::of(2.0) * at.slope_w - self.table_mu * self.path.slip_z / self.path.k_z
    }

    /// Normal work so far, `W = −aP + P² + (μ_s/k_z)(I_z − v_z0 P)` (seed eq. (33), E1;
    /// m²/s²).
    fn work(&self, at: &Point<R>) -> R {
        let tilt = self.table_mu / self.path.k_z;
        (at.normal - self.approach) * at.normal
            + tilt * (at.vertical - self.path.slip_z * at.normal)
    }

    /// The state at `q` after the compression end `c`, and the normal work since `c`,
    /// `D = ΔP² + (μ_s/k_z) ∫_{p_c}^{P} (v_z − v_z(p_c)) dp` (seed eq. (36); m²/s²),
    /// integrated from `c` so that it keeps its digits when it is small.
    fn after(&self, c: &Point<R>, q: R) -> (Point<R>, R) {
        let (at, lag) = self.path.point_after(c, q);
        let delta = at.normal - c.normal;
        let tilt = self.table_mu / self.path.k_z;
        (at, delta * delta + tilt * lag)
    }

    /// The impact's end; `None` when friction cannot move the slip in this precision.
    ///
    /// The roots are solved for `w = 1 − ρ^κ` (`path` module), in which `v_x` and `√D`
    /// are nearly linear (exactly, for a slip along one axis): Newton converges in a few
    /// steps from the first-order guess, even near the stick point where `P(q)` is flat.
    fn solve(&self) -> Result<Option<End<R>>> {
        let (a, e, path) = (self.approach, self.restitution, self.path);
        // |v₀|/μ overflows (or is NaN): friction too weak to move the slip in this
        // precision.
        let pace = path.max_pace();
        let pace_is_finite = R::abs(pace) < R::of(f32::INFINITY);
        if !pace_is_finite {
            return Ok(None);
        }
        let mu_max = path.mu_max();
        // p̄ = (1+e*) a / s, s = 2 − μ_max μ_s ≥ 1.
        let bound = (R::ONE + e) * a / (R::of(2.0) - mu_max * self.table_mu);
        let ratio = R::of(K_Y) * mu_max * bound / path.speed;
        let compression = |w: R| {
            let at = path.point(path.q_of_w(w));
            Sample {
                value: self.normal_velocity(&at),
                slope: self.normal_velocity_slope(&at),
                payload: at,
            }
        };
        // First-order guess: P ≈ (|v₀|/μ(|v₀|)) w/κ near contact, p_c ≈ a/2.
        let guess = path.kappa * R::of(0.5) * a / pace;
        // v_x = −a + 2P − X is known to a few roundings of a: stop there.
        let residual = R::of(RESIDUAL_EPSILONS) * R::epsilon() * a;

        if ratio < R::ONE {
            // The slip cannot stop: ρ̄^{k_y} = 1 − ratio brackets both roots.
            let resolved = ratio > R::of(K_Y) * R::epsilon();
            if !resolved {
                // The slip changes by less than 7 q̄ ≈ ratio ≤ 7 ε of itself.
                return Ok(None);
            }
            let w_bar = path.w_of_y_ratio(ratio);
            let (w_c, c) = increasing_root(compression, R::ZERO, w_bar, guess, residual)?;
            let end = self.restitution_root(&c, w_c, w_bar)?;
            return Ok(Some(End {
                normal: end.normal,
                point: end,
                regime: Regime::Sliding,
            }));
        }

        // The slip may stop: evaluate the stick point ρ = 0.
        let stick = path.point(R::ONE);
        let v_stick = self.normal_velocity(&stick);
        let w_stick = self.work(&stick);
        let slides_through_compression = v_stick > R::ZERO;
        if !slides_through_compression {
            // Grips during compression; v_x then grows with slope 2 from v_stick.
            let compression_end = stick.normal - R::of(0.5) * v_stick;
            let compression_work = w_stick - R::of(0.25) * v_stick * v_stick;
            let depth = R::sqrt(R::max(-compression_work, R::ZERO));
            return Ok(Some(End {
                point: stick,
                normal: compression_end + e * depth,
                regime: Regime::Gripping,
            }));
        }
        // Slides through compression: v_x(0) = −a < 0 < v_x(stick) brackets p_c.
        let (w_c, c) = increasing_root(compression, R::ZERO, R::ONE, guess, residual)?;
        let target = e * e * R::max(-self.work(&c), R::ZERO);
        let (_, done_at_stick) = self.after(&c, R::ONE);
        if done_at_stick <= target {
            // Grips during restitution: v_stick s + s² = target − done_at_stick.
            let rest = target - done_at_stick;
            let root = R::sqrt(v_stick * v_stick + R::of(4.0) * rest);
            let denominator = v_stick + root;
            let extra = if denominator > R::ZERO {
                R::of(2.0) * rest / denominator
            } else {
                R::ZERO
            };
            return Ok(Some(End {
                normal: stick.normal + extra,
                point: stick,
                regime: Regime::Gripping,
            }));
        }
        let end = self.restitution_root(&c, w_c, R::ONE)?;
        Ok(Some(End {
            normal: end.normal,
            point: end,
            regime: Regime::Sliding,
        }))
    }

    /// The end of restitution after the compression end `c` (at `w_c`), sliding, with
    /// the root bracketed in `[w_c, hi]` (`D(w_c) = 0`, `D(hi) ≥ e*² |W_c|`).
    fn restitution_root(&self, c: &Point<R>, w_c: R, hi: R) -> Result<Point<R>> {
        let e = self.restitution;
        let compression_work = R::max(-self.work(c), R::ZERO);
        if e == R::ZERO || compression_work == R::ZERO {
            return Ok(*c);
        }
        let depth = e * R::sqrt(compression_work);
        let restitution = |w: R| {
            let (at, done) = self.after(c, self.path.q_of_w(w));
            let root = R::sqrt(R::max(done, R::ZERO));
            // d√D/dw = v_x (dP/dw) / (2√D); no Newton step at D = 0.
            let slope = if root > R::ZERO {
                self.normal_velocity(&at) * at.slope_w / (R::of(2.0) * root)
            } else {
                R::ZERO
            };
            Sample {
                value: root - depth,
                slope,
                payload: at,
            }
        };
        // √D ≈ P − p_c near p_c: step the depth along dP/dw at p_c.
        let guess = if c.slope_w > R::ZERO {
            w_c + depth / c.slope_w
        } else {
            R::of(0.5) * (w_c + hi)
        };
        // √D − depth is known to a few roundings of depth.
        let residual = R::of(RESIDUAL_EPSILONS) * R::epsilon() * depth;
        let (_, end) = increasing_root(restitution, w_c, hi, guess, residual)?;
        if end.normal < c.normal {
            return Err(Error::NumericalFailure);
        }
        Ok(end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by the `collide` fuzz target: a nearly plastic impact (e* = 2.4e-38) in
    /// f64 put the impact end's root a few ulps above w = 0 under a square root, and
    /// the root solve ran out of evaluations (`NumericalFailure` for a valid input).
    #[test]
    #[cfg(feature = "libm")]
    fn a_nearly_plastic_grazing_impact_solves_in_f64() {
        let law = crate::FrictionLaw::speed_dependent(0.05, 0.2, 1.992_187_5).unwrap();
        let params = crate::Params::POOL
            .with_friction_law(law)
            .with_restitution(2.406_568e-38)
            .unwrap()
            .with_mu_s(0.4)
            .unwrap()
            .with_ball(0.030_980_391, 0.105_210_036)
            .unwrap();
        let impact =
            crate::Impact::from_velocity([1.947_072e-6, 10.000_001], [200.0, 200.0, -200.0])
                .unwrap();
        for restitution in [2.406_568e-38, 1e-30, 0.0, 1e-10] {
            let params = params.with_restitution(restitution).unwrap();
            let f64_outcome = crate::collide_f64(&params, &impact, crate::Model::SeedExact);
            let f32_outcome = crate::collide(&params, &impact, crate::Model::SeedExact);
            assert!(
                f64_outcome.is_ok() && f32_outcome.is_ok(),
                "e* = {restitution:e}"
            );
        }
    }

    /// Found by the `collide` fuzz target: at 3.6e-22 m/s the f32 work is subnormal and
    /// flat in steps along the impact, Newton crept and the end's root solve ran out of
    /// evaluations (`NumericalFailure` for a valid input).
    #[test]
    fn an_impact_whose_work_is_subnormal_solves_in_f32() {
        let law =
            crate::FrictionLaw::speed_dependent(0.121_569_51, 0.121_568_63, 0.009_155_273).unwrap();
        let params = Params::new(0.1, 0.500_015_26, 0.796_902_5, 0.416_570_43, 47.726_395)
            .unwrap()
            .with_friction_law(law);
        let impact = Impact::from_velocity(
            [3.632_260_7e-22, 3.369_334_4e-20],
            [-9921.875, 9.688_645e-39, 0.0],
        )
        .unwrap();
        let f32_outcome = crate::collide(&params, &impact, crate::Model::SeedExact).unwrap();
        let normal = f32_outcome.impulses.normal;
        let exact = crate::collide(&params, &impact, crate::Model::Exact).unwrap();
        let reference = exact.impulses.normal;
        assert!(
            (normal - reference).abs() <= 0.05 * reference,
            "{normal} vs {reference}"
        );
    }

    fn params(mu: f32, e: f32, mu_s: f32) -> Params {
        Params::new(mu, e, mu_s, 0.028575, 0.17).unwrap()
    }

    /// μ_s = 0, head-on topspin: the slip path is a straight line and the normal motion
    /// is the frictionless one, so `p_f = (1+e)a/2` and `J_z = −μ p_f` exactly.
    #[test]
    fn head_on_topspin_without_table_friction_is_the_textbook_case() {
        let (mu, e, a) = (0.05f32, 0.9f32, 2.0f32);
        let impact = Impact::rolling([a, 0.0], 0.028575).unwrap();
        let out = collide::<f64>(&params(mu, e, 0.0), &impact).unwrap();
        let normal = 0.5 * (1.0 + e as f64) * a as f64;
        let m = 0.17f64;
        assert!(((out.impulses.normal as f64) / m - normal).abs() < 1e-6);
        let jz = out.impulses.friction.z as f64 / m;
        assert!((jz + mu as f64 * normal).abs() < 1e-6, "{jz}");
        assert_eq!(out.regime, Regime::Sliding);
    }

    /// A stun shot at a small cut grips (E6): the friction impulse is the stick
    /// impulse `v_y0/7` exactly.
    #[test]
    fn small_cut_stun_grips_with_the_stick_impulse() {
        let impact = Impact::from_cut_degrees(2.0, 3.0, [0.0; 3]).unwrap();
        let out = collide::<f64>(&params(0.05, 0.95, 0.3), &impact).unwrap();
        assert_eq!(out.regime, Regime::Gripping);
        let v_y0 = -(impact.velocity().y as f64);
        let jy = out.impulses.friction.y as f64 / 0.17;
        assert!((jy + v_y0 / 7.0).abs() < 1e-7, "{jy} vs {}", -v_y0 / 7.0);
    }
}
