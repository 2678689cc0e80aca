//! A-priori error estimates of each tier and the `Auto` tier selection.
//!
//! The error measure is the foundation issue's: `max(|Δv|, R|Δω|) / U` over both balls
//! (full 3-vectors), against the first-principles reference. Each estimate is the size
//! of the leading effect the tier leaves out, computed from the inputs alone (per unit
//! mass, m/s; `p₀ = (1+e*) U_x / 2`, slip `v₀`, stick budget `s* = |K⁻¹v₀|`, friction
//! budget `S₀ = μ(|v₀|) p₀`, grip fraction `f = min(S₀/s*, 1)`, friction impulse
//! `J = min(μ(0) p₀, s*)`, anisotropy `(k_y − k_z)/k_y`, table friction
//! `X = μ_s |v_z0|/|v₀| J` when the object ball is pressed), times a constant
//! calibrated on a grid with another seed (`cargo run --release -p cuesight-host
//! --example estimate_explore`) and checked on the foundation grid
//! (`host-tests/tests/auto.rs`):
//!
//! | tier | leading error left out | estimate |
//! |---|---|---|
//! | `Ideal` | restitution loss and all friction | `max((1−e*) U_x/2 + 1.4 J, 2.5·1.4 J) / U` |
//! | `Kim` | slip-direction turn (∝ f, anisotropy) and grip (`S₀ > s*`) | `2.5 (S₀ f (k_y−k_z)/k_y + max(0, S₀ − s*)) / U` |
//! | `KimGrip` | second-order direction error, table-friction direction and timing | `0.06 (2.5 J f (k_y−k_z)/k_y + X) / U` |
//! | `SeedExact` | table friction along `−x` (seed eq. (7)) instead of against the table-contact slip | `1.5 · 2.5 X λ / U + 2e-6`, `λ = μ(0) ŷ/(1 + 2.5 μ(0) ẑ)` |
//! | `Exact` | step error (24 steps) | `a (2.5 J + X) / U + 5e-6`, `a` = 0.002 in the calibrated domain, 0.04 outside it |
//!
//! Every estimate adds the f32 rounding of the answer, `16 · 2⁻²⁴ · max(1, R|ω|/U)`: an
//! answer is rounded at the scale of the largest of the cue ball's speed and its spin's
//! `R|ω|` (to 10⁴ rad/s at a speed of 0.01 m/s, `R|ω|` is 2·10⁴ U), and the error is
//! measured in units of U.
//!
//! (`2.5 = 1/ν` turns a friction impulse into `R Δω`; `1.4` stands for `1 + μ_s + μ_ct`.
//! `SeedExact`: the pressed object ball's table-contact slip leans towards `y` by
//! `λ = |J_y|/(p + |J_z|/ν)` while it slides, `(ŷ, ẑ)` the shares of the initial slip; the
//! neglected table friction component `X λ` spins the object ball about `x` by
//! `R ΔΩ_x = 2.5 X λ`. Its floor is its f32 rounding, ≤ 5e-7 of U against the
//! reference solving the seed's own physics.)
//!
//! Outside the calibrated domain (μ(0) > 0.12, μ_s > 0.4, e* < 0.9 or any cue-ball/table
//! friction μ_ct, which `Kim`, `SeedExact` and `Ideal` ignore) `Kim`, `KimGrip` and
//! `SeedExact` report an infinite estimate; `Ideal`'s estimate is the size of the effects
//! it leaves out and holds anywhere; `Exact`'s factor is 20 times larger there (its step
//! error grows with μ and μ_s where the contact grips and the object ball is pressed).
//! The rounding term, `Exact`'s outer factor and floor were chosen on the domain map's
//! scenes of seed 17 (`cuesight_host::domain`, 100,000 scenes: `Auto(1e-3)`'s estimate
//! at or above its true error in 99.99 %, never below 0.56 of it) and are checked on
//! seed 16's (`host-tests/tests/domain.rs`; docs/accuracy-domain.md).
//!
//! `Auto`'s ladder ([`select`]) is the Pareto front of `docs/tradeoff.md`: `Ideal` where
//! neither a friction impulse nor a restitution loss acts, else `KimGrip`, else `Exact`.
//! At a tolerance of at least [`KIM_GRIP_DECLARED_BOUND`] (5e-3) a scene inside
//! `KimGrip`'s validity domain goes to `KimGrip` on that bound alone, without the
//! features above.

use crate::impact::Impact;
use crate::kim_grip::initial_slip;
use crate::model::Model;
use crate::params::Params;

/// `KimGrip`'s error `max(|Δv|, R|Δω|) / U` anywhere in its validity domain
/// ([`crate::validity::kim_grip`]), as declared there and held by the domain map on
/// every scene it answers (`host-tests/tests/domain.rs`: within 0.25 % of U in velocity
/// and 0.5 % in R ω; issue 16, item 3's figures).
pub const KIM_GRIP_DECLARED_BOUND: f32 = 5e-3;

/// Calibrated factors (see module docs).
const KIM_GRIP_FACTOR: f32 = 0.06;
const EXACT_FACTOR: f32 = 0.002;
/// `Exact`'s factor outside the calibrated domain.
const EXACT_FACTOR_OUTSIDE: f32 = 0.04;
const EXACT_FLOOR: f32 = 5e-6;
/// f32 units in the last place an answer is off by, at most (module docs).
const ROUNDING_ULPS: f32 = 16.0 * f32::EPSILON / 2.0;
const SEED_EXACT_FACTOR: f32 = 1.5;
const SEED_EXACT_FLOOR: f32 = 2e-6;

/// Estimated error `max(|Δv|, R|Δω|) / U` of `model` for this scene. `Auto` returns the
/// estimate of the tier it would pick for `tolerance`. Outside the calibrated domain
/// (module docs) `Kim`, `KimGrip` and `SeedExact` report an infinite estimate.
pub fn error_estimate(params: &Params, impact: &Impact, model: Model) -> f32 {
    let f = Features::of(params, impact);
    match model {
        Model::Ideal => f.ideal(),
        Model::Kim => f.kim(),
        Model::KimGrip => f.kim_grip(),
        Model::SeedExact => f.seed_exact(),
        Model::Exact => f.exact(),
        Model::Auto { tolerance } => select(params, impact, tolerance).1,
    }
}

/// The cheapest tier whose estimate meets `tolerance` (`Exact` if none does), with its
/// estimate.
///
/// The ladder is the Pareto front of `docs/tradeoff.md` (mean instructions on the
/// Cortex-M4F against the largest error on the grid): `Ideal` (96 instructions),
/// `KimGrip` (129), `Exact` (11,590). `Kim` (163, 9.26 % of U) and `SeedExact` (4,225,
/// 0.140 %) are dominated by `KimGrip` (129, 0.111 %): cheaper or as cheap and more
/// accurate, so `Auto` never picks them; they stay callable as the seed's
/// reproductions.
///
/// `Ideal` is picked only where nothing it leaves out acts: no friction impulse (`J = 0`:
/// μ(0) = 0, or no slip at the contact, where no friction acts either) and no
/// restitution loss (e* = 1). Never where a friction law acts on a moving object ball
/// (issue 16, item 5): at a thin cut the whole impact is a small
/// share of `U`, so an estimate against `U` let `Ideal` through where its throw is
/// wholly wrong (`--cut 89.9 --roll --mu 0.06`: 0° where the reference throws the
/// object ball 3.4°), and a friction too weak to matter against `T` (μ = 7e-5 at an
/// 89.84° cut) still turns the object ball. And not at e* < 1 either, though its
/// estimate would allow it: `Auto` then jumped by up to `T` between μ = 0 (`Ideal`) and
/// the smallest μ (the next tier), where it is continuous
/// (`core/tests/extremes.rs`, `friction_to_zero_is_continuous`).
///
/// At a tolerance `KimGrip`'s declared bound meets ([`KIM_GRIP_DECLARED_BOUND`], 5e-3 of
/// U), its validity domain alone decides: `Auto`'s `collide` checks a flag `Params`
/// computed and evaluates `KimGrip` without the features, so that `Auto(1e-2)` costs
/// little more than `KimGrip` (issue 16, item 5: the estimate's overhead at most a
/// quarter of `KimGrip`'s instructions). Here the estimate is the smaller of that bound
/// and `KimGrip`'s own estimate. Not where `Ideal` is exact (no friction, elastic):
/// those take the full selection below, and so do nearly plastic contacts (e* < 0.01,
/// where the domain's edge depends on whether μ_ct is zero).
#[inline(never)]
pub fn select(params: &Params, impact: &Impact, tolerance: f32) -> (Model, f32) {
    let f = Features::of(params, impact);
    if declared_kim_grip(params, tolerance) {
        // The tier `Auto` evaluates (`model::auto` decides on the flag alone, without
        // the features), with the smaller of its two bounds.
        // (Infinite outside the calibrated domain: the bound.)
        let own = f.kim_grip();
        let estimate = if own < KIM_GRIP_DECLARED_BOUND {
            own
        } else {
            KIM_GRIP_DECLARED_BOUND
        };
        return (Model::KimGrip, estimate);
    }
    // No friction impulse and elastic: `Ideal` leaves out nothing, its estimate is the
    // rounding (`ideal()` with `J = 0` and no restitution loss).
    if f.impulse == 0.0 && f.restitution_loss == 0.0 && f.rounding <= tolerance {
        return (Model::Ideal, f.rounding);
    }
    let kim_grip = f.kim_grip();
    if kim_grip <= tolerance {
        return (Model::KimGrip, kim_grip);
    }
    (Model::Exact, f.exact())
}

/// `tolerance` is one `KimGrip`'s declared bound meets and the scene is one `Auto` sends
/// to `KimGrip` on it (computed with `params`: inside the validity domain, not
/// frictionless and elastic, e* ≥ 0.01, so that the pick does not jump as μ_ct → 0
/// where the domain's edge depends on it; `core/tests/extremes.rs`).
#[inline(always)]
pub(crate) fn declared_kim_grip(params: &Params, tolerance: f32) -> bool {
    tolerance >= KIM_GRIP_DECLARED_BOUND && params.derived().auto_kim_grip
}

struct Features {
    /// Inside the domain the factors were calibrated on (the foundation grid's):
    /// μ(0) ≤ 0.12, μ_s ≤ 0.4, e* ≥ 0.9, μ_ct ≤ 1e-3 (negligible cue-ball/table friction).
    calibrated: bool,
    /// `1 + μ_s + μ_ct`: how much table friction can add to a friction impulse.
    table_factor: f32,
    speed: f32,
    restitution_loss: f32,
    impulse: f32,
    kim_budget: f32,
    stick_budget: f32,
    fraction: f32,
    anisotropy: f32,
    table: f32,
    /// The answer's f32 rounding in units of U (module docs).
    rounding: f32,
    /// Lean of the pressed object ball's table-contact slip towards `y` while it slides,
    /// `|J_y| / (p + |J_z|/ν)` with `J ≈ μ p`: `μ ŷ / (1 + μ ẑ/ν)` (`ŷ`, `ẑ` the slip
    /// direction's shares): the direction eq. (7) neglects.
    table_lean: f32,
}

impl Features {
    fn of(params: &Params, impact: &Impact) -> Self {
        let u = impact.velocity();
        // U ≥ U_x > 0: the bound keeps the estimates numbers when the squares underflow.
        let speed = crate::math::max(crate::math::sqrt(u.x * u.x + u.y * u.y), u.x);
        let e = params.restitution();
        let p0 = 0.5 * (1.0 + e) * u.x;
        let (v_y, v_z) = initial_slip::<f32>(params, impact);
        let scale = crate::math::max(crate::math::abs(v_y), crate::math::abs(v_z));
        let law = params.friction_law();
        let pressed = v_z > 0.0;
        let k_z = if pressed {
            (2.4 - params.mu_s()) / 0.4
        } else {
            6.0
        };
        let (slip, stick_budget) = if scale > 0.0 {
            let (y, z) = (v_y / scale, v_z / scale);
            let norm = crate::math::sqrt(y * y + z * z);
            let (sy, sz) = (y / 7.0, z / k_z);
            (norm * scale, crate::math::sqrt(sy * sy + sz * sz) * scale)
        } else {
            (0.0, 0.0)
        };
        let kim_budget = law.at(slip) * p0;
        // μ(0), the law's largest value, `a + b` without the `exp` of `at(0)` (the same
        // value: exp(0) is 1).
        let mu0 = law.largest();
        let impulse = crate::math::max(0.0, (mu0 * p0).min(stick_budget));
        let fraction = if kim_budget >= stick_budget {
            1.0
        } else {
            kim_budget / stick_budget
        };
        let vertical_share = if slip > 0.0 {
            crate::math::abs(v_z) / slip
        } else {
            0.0
        };
        let calibrated =
            mu0 <= 0.12 && params.mu_s() <= 0.4 && e >= 0.9 && params.cue_table_friction() <= 1e-3;
        // `R|ω|/U`: infinite rather than NaN where the speed underflows (U ≥ U_x > 0).
        let spin_scale = params.radius() * impact.spin().length() / speed;
        Self {
            calibrated,
            rounding: ROUNDING_ULPS * crate::math::max(1.0, spin_scale),
            table_factor: 1.0 + params.mu_s() + params.cue_table_friction(),
            speed,
            restitution_loss: 0.5 * (1.0 - e) * u.x,
            impulse,
            kim_budget,
            stick_budget,
            fraction,
            anisotropy: (7.0 - k_z) / 7.0,
            table_lean: if slip > 0.0 {
                (crate::math::abs(v_y) / slip) * mu0 / (1.0 + 2.5 * vertical_share * mu0)
            } else {
                0.0
            },
            table: if pressed {
                params.mu_s() * vertical_share * impulse
            } else {
                0.0
            },
        }
    }

    fn ideal(&self) -> f32 {
        let velocity = self.restitution_loss + self.table_factor * self.impulse;
        let spin = 2.5 * self.table_factor * self.impulse;
        crate::math::max(velocity, spin) / self.speed + self.rounding
    }

    fn kim(&self) -> f32 {
        if !self.calibrated {
            // Outside the calibrated domain Kim's leading-term estimate is not trusted
            // (and it ignores μ_ct): never pick it there.
            return f32::INFINITY;
        }
        let turn = self.kim_budget * self.fraction * self.anisotropy;
        let grip = crate::math::max(self.kim_budget - self.stick_budget, 0.0);
        2.5 * (turn + grip) / self.speed + self.rounding
    }

    fn kim_grip(&self) -> f32 {
        if !self.calibrated {
            // Outside the calibrated domain KimGrip's approximations (first order in
            // μ μ_s, table friction along a mean direction) are not bounded by this
            // estimate: leave those scenes to Exact.
            return f32::INFINITY;
        }
        KIM_GRIP_FACTOR * (2.5 * self.impulse * self.fraction * self.anisotropy + self.table)
            / self.speed
            + self.rounding
    }

    fn seed_exact(&self) -> f32 {
        if !self.calibrated {
            // Outside the calibrated domain (and SeedExact ignores μ_ct, as the seed
            // does): not bounded by this estimate, leave those scenes to Exact.
            return f32::INFINITY;
        }
        SEED_EXACT_FACTOR * 2.5 * self.table * self.table_lean / self.speed
            + SEED_EXACT_FLOOR
            + self.rounding
    }

    fn exact(&self) -> f32 {
        let factor = if self.calibrated {
            EXACT_FACTOR
        } else {
            EXACT_FACTOR_OUTSIDE
        };
        factor * (2.5 * self.impulse + self.table) / self.speed + EXACT_FLOOR + self.rounding
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FrictionLaw;

    /// Found by the `collide` fuzz target: at a valid speed so small that its square
    /// underflows (4.8e-35 m/s), `speed` was zero and the estimates 0/0 = NaN.
    #[test]
    fn estimates_are_numbers_at_a_speed_whose_square_underflows() {
        let law = FrictionLaw::speed_dependent(3.9161823e-4, 0.04, 3.3333333).unwrap();
        let params = Params::new(0.05, 0.94924325, 0.010546875, 0.020527344, 0.21977976)
            .unwrap()
            .with_friction_law(law);
        for velocity in [
            [3.8954666e-36, -4.7990406e-35],
            [1e-45, 0.0],
            [1e-30, 1e-30],
        ] {
            let impact =
                Impact::from_velocity(velocity, [4.814825e-35, -199.98438, -200.0]).unwrap();
            for model in Model::ALL {
                let estimate = error_estimate(&params, &impact, model);
                assert!(estimate >= 0.0, "{model:?} {velocity:?}: {estimate}");
            }
            let (_, estimate) = select(&params, &impact, 1e-3);
            assert!(estimate >= 0.0, "select {velocity:?}: {estimate}");
        }
    }
}
