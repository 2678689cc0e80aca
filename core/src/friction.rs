//! Ball–ball friction laws: constant μ, or the speed-dependent fit
//! `μ(v) = a + b·exp(−c·v)` of TP A.14 (Alciatore's fit of Marlow's data), `v` the slip
//! speed of the contact (m/s).
//!
//! While the contact slides, the slip speed falls at `d|v|/dp = −k̄ μ(|v|)` per unit
//! specific normal impulse (m/s per m/s), where `k̄` is the effective slip compliance
//! along the path (`kim_grip`'s fast paths use `k̄ = |v₀| / s*`, its general path each
//! piece's own, `kim_grip::budget`). Hence the normal impulse that takes
//! the slip from `v₀` to `v` is `(G(v₀) − G(v)) / k̄` with `G' = 1/μ`, and the friction
//! budget spent meanwhile, `∫ μ dp`, is exactly `(v₀ − v) / k̄`. For the exponential law
//! `G(v) = [v + ln(a + b e^{−cv}) / c] / a`.

use crate::error::{check, Field, Result};
use crate::real::Real;

/// How the ball–ball friction coefficient depends on the slip speed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrictionLaw {
    /// Constant coefficient μ.
    Constant(f32),
    /// `μ(v) = a + b·exp(−c·v)`, `v` in m/s (TP A.14).
    SpeedDependent {
        /// High-speed limit `a` (> 0).
        a: f32,
        /// Amplitude `b` (≥ 0); `μ(0) = a + b ≤ 1`.
        b: f32,
        /// Decay rate `c` (s/m, ≥ 0).
        c: f32,
    },
}

/// Fixed Newton iterations for inverting the slip–impulse relation (quadratic
/// convergence from the first-order guess; 4 reach f32 precision on the TP A.14 fits).
const NEWTON_ITERATIONS: usize = 4;

impl FrictionLaw {
    /// TP A.14's fit of Marlow's data: a = 9.951e-3, b = 0.108, c = 1.088 s/m.
    pub const MARLOW: Self = Self::SpeedDependent {
        a: 9.951e-3,
        b: 0.108,
        c: 1.088,
    };

    /// Constant μ in `[0, 1]`.
    pub fn constant(mu: f32) -> Result<Self> {
        Ok(Self::Constant(check(Field::Friction, mu, 0.0, 1.0, false)?))
    }

    /// `μ(v) = a + b·exp(−c·v)` with `a ∈ [1e-6, 1]`, `b ∈ [0, 1]`, `a + b ≤ 1`,
    /// `c ∈ [0, 100]` s/m. (`a` bounds the slip integral `∫ dv/μ`; below 1e-6 it would
    /// overflow f32, and no measured law comes near.)
    pub fn speed_dependent(a: f32, b: f32, c: f32) -> Result<Self> {
        let a = check(Field::Friction, a, 1e-6, 1.0, false)?;
        let b = check(Field::FrictionAmplitude, b, 0.0, 1.0, false)?;
        let c = check(Field::FrictionDecay, c, 0.0, 100.0, false)?;
        if a + b > 1.0 {
            return Err(crate::Error::OutOfRange {
                field: Field::FrictionAmplitude,
                value: b,
            });
        }
        Ok(Self::SpeedDependent { a, b, c })
    }

    /// μ at slip speed `v` (m/s).
    pub fn at(&self, slip_speed: f32) -> f32 {
        self.at_in(slip_speed)
    }

    /// μ at slip speed `v` (m/s), evaluated in `R`.
    pub(crate) fn at_in<R: Real>(&self, slip_speed: R) -> R {
        match *self {
            Self::Constant(mu) => R::of(mu),
            Self::SpeedDependent { a, b, c } => {
                R::of(a) + R::of(b) * R::exp(-R::of(c) * slip_speed)
            }
        }
    }

    /// The largest μ of the law: the constant, or `μ(0) = a + b`.
    pub(crate) const fn largest(&self) -> f32 {
        match *self {
            Self::Constant(mu) => mu,
            Self::SpeedDependent { a, b, .. } => a + b,
        }
    }

    /// `true` for a constant zero coefficient.
    pub fn is_frictionless(&self) -> bool {
        matches!(*self, Self::Constant(mu) if mu == 0.0)
    }

    /// Specific normal impulse (m/s) over which the slip speed falls from `from` to
    /// `to` (`0 ≤ to ≤ from`) at effective compliance `compliance`.
    pub(crate) fn normal_impulse_between<R: Real>(&self, from: R, to: R, compliance: R) -> R {
        self.normal_impulse_for_change(from, R::max(from - to, R::ZERO), compliance)
    }

    /// Specific normal impulse (m/s) over which the slip speed falls by `change` from
    /// `from` (`0 ≤ change ≤ from`). Taking the change itself, not the end speed, keeps a
    /// change far below the slip's own resolution.
    pub(crate) fn normal_impulse_for_change<R: Real>(
        &self,
        from: R,
        change: R,
        compliance: R,
    ) -> R {
        match *self {
            Self::Constant(mu) => change / (R::of(mu) * compliance),
            Self::SpeedDependent { a, b, c } => {
                let (a, b, c) = (R::of(a), R::of(b), R::of(c));
                if c == R::ZERO {
                    return change / ((a + b) * compliance);
                }
                // ln((a + b e^{−c v₀}) / (a + b e^{−c v})) written as ln(1 + q) with
                // q = b e^{−c v} (e^{−c δ} − 1) / (a + b e^{−c v}), δ = v₀ − v ≥ 0, so that
                // a tiny slip change keeps its digits (the two terms below nearly cancel
                // to δ a / (a + b e^{−c v}) when c δ is small).
                let decay = b * R::exp(-c * (from - change));
                let q = decay * R::exp_m1(-c * change) / (a + decay);
                R::max(change + R::ln_1p(q) / c, R::ZERO) / (a * compliance)
            }
        }
    }

    /// How much the slip speed falls (m/s) over a specific normal impulse `normal` of
    /// sliding from `from` (all of it if the slip stops before).
    pub(crate) fn slip_change<R: Real>(&self, from: R, normal: R, compliance: R) -> R {
        match *self {
            Self::Constant(mu) => R::min(R::of(mu) * compliance * normal, from),
            Self::SpeedDependent { .. } => {
                if normal >= self.normal_impulse_for_change(from, from, compliance) {
                    return from;
                }
                // Newton on D(δ) = (G(v₀) − G(v₀ − δ))/k̄ − p, D' = 1/(k̄ μ(v₀ − δ)),
                // bracketed in [0, v₀].
                let mut change = R::min(self.at_in(from) * compliance * normal, from);
                for _ in 0..NEWTON_ITERATIONS {
                    let residual =
                        self.normal_impulse_for_change(from, change, compliance) - normal;
                    change = change - residual * compliance * self.at_in(from - change);
                    change = R::min(R::max(change, R::ZERO), from);
                }
                change
            }
        }
    }

    /// Slip speed (m/s) after a specific normal impulse `normal` of sliding from `from`
    /// (zero if the slip would stop before).
    #[cfg(test)]
    pub(crate) fn slip_after<R: Real>(&self, from: R, normal: R, compliance: R) -> R {
        from - self.slip_change(from, normal, compliance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_law_is_linear() {
        let law = FrictionLaw::Constant(0.05);
        assert!((law.normal_impulse_between(1.0f32, 0.5, 7.0) - 0.5 / 0.35).abs() < 1e-6);
        assert!((law.slip_after(1.0f32, 0.5 / 0.35, 7.0) - 0.5).abs() < 1e-6);
        assert_eq!(law.slip_after(1.0f32, 100.0, 7.0), 0.0);
    }

    #[test]
    fn marlow_inverse_round_trips() {
        let law = FrictionLaw::MARLOW;
        for (from, to) in [(0.447f32, 0.3f32), (3.0, 0.1), (0.05, 0.0), (8.0, 7.5)] {
            let normal = law.normal_impulse_between(from, to, 6.5);
            let back = law.slip_after(from, normal, 6.5);
            assert!(
                (back - to).abs() < 2e-5 * from.max(1.0),
                "{from} -> {to}: {back}"
            );
        }
    }

    #[test]
    fn marlow_values() {
        // TP A.14: μ(0) = a + b, μ(0.447 m/s) ≈ 0.0764.
        assert!((FrictionLaw::MARLOW.at(0.0) - 0.117_951).abs() < 1e-6);
        assert!((FrictionLaw::MARLOW.at(0.447) - 0.0764).abs() < 1e-4);
    }

    #[test]
    fn validation_names_fields() {
        assert!(FrictionLaw::speed_dependent(0.0, 0.1, 1.0).is_err());
        assert_eq!(
            FrictionLaw::speed_dependent(0.5, 0.6, 1.0)
                .unwrap_err()
                .field(),
            Some(Field::FrictionAmplitude)
        );
        assert_eq!(
            FrictionLaw::speed_dependent(0.01, 0.1, f32::NAN)
                .unwrap_err()
                .field(),
            Some(Field::FrictionDecay)
        );
    }
}
