//! The friction budget `S(p) = ∫ μ dp` (m/s) a sliding contact spends by specific normal
//! impulse `p`, on the general path's curved slide (`curved`).
//!
//! A constant μ spends `S = μ p`. A speed-dependent law `μ(|v|)` spends it as the slip
//! speed falls: `d|v|/dS = −k(S)`, `dp = dS/μ(|v|)`. The slide's pieces give `|v|` at
//! each piece's start ([`curved::Profile`]); between two of them the slip speed is taken
//! to fall linearly in `S`, at the piece's own compliance `k_k = Δ|v|/ΔS`, so that each
//! piece is the `friction` module's closed form (`p = (G(v_k) − G(v_{k+1}))/k_k`, and its
//! inverse for `S(p)`). One compliance for the whole slide (`k̄ = |v₀|/s*`, as the fast
//! paths take) misses how the slip speed falls where the slip turns: against the exact
//! slide it puts `p*` and `S(p)` up to 12 % off where the pieces are within 0.33 %
//! (`tests`), and with `μ(0)` up to 1 it put the throw up to 0.114° off against the
//! reference where `μ(0)·μ_s ≤ 0.08` (issue 16 item 3: 0.1°; `docs/physics.md` §4 item 8).

use super::curved::{CurvedSlide, Point, Profile};
use crate::friction::FrictionLaw;
use crate::real::Real;

/// `S(p)` for one slide, up to the stick budget at the grip `p*`.
pub(super) struct Budget<R> {
    law: FrictionLaw,
    /// `p*`, the normal impulse at which the slip stops (m/s; may be +inf for tiny μ).
    pub grip_normal: R,
    /// The budget that stops the slip: the sliding path's length (m/s).
    pub stick_budget: R,
    /// The slide's pieces, with a speed-dependent law's normal impulse at each point.
    profile: Profile<R>,
}

/// The piece from `start` to `end`: the slip speed's fall (m/s; floored at the smallest
/// normal f32, so that neither it nor the compliance is zero) and the compliance
/// `Δ|v|/ΔS` along it.
fn piece<R: Real>(start: &Point<R>, end: &Point<R>) -> (R, R) {
    let change = R::max(start.speed - end.speed, R::of(f32::MIN_POSITIVE));
    (change, change / (end.budget - start.budget))
}

impl<R: Real> Budget<R> {
    pub(super) fn new(law: FrictionLaw, curved: &CurvedSlide<R>) -> Self {
        let speed_dependent = matches!(law, FrictionLaw::SpeedDependent { .. });
        let (stick_budget, mut profile) = curved.profile(speed_dependent);
        let grip_normal = match law {
            FrictionLaw::Constant(mu) => stick_budget / R::of(mu),
            FrictionLaw::SpeedDependent { .. } => {
                // Each piece's normal impulse in closed form (`friction`), summed.
                let mut points = profile.points.iter_mut();
                let mut previous = points.next().map_or(
                    Point {
                        budget: R::ZERO,
                        speed: R::ZERO,
                        normal: R::ZERO,
                    },
                    |first| *first,
                );
                for point in points {
                    let (change, compliance) = piece(&previous, point);
                    point.normal = previous.normal
                        + law.normal_impulse_for_change(previous.speed, change, compliance);
                    previous = *point;
                }
                previous.normal
            }
        };
        Self {
            law,
            grip_normal,
            stick_budget,
            profile,
        }
    }

    /// `S(p)` for a normal impulse `normal` (m/s). Out of line: the general path takes it
    /// at up to three normal impulses.
    #[inline(never)]
    pub(super) fn after(&self, normal: R) -> R {
        if normal >= self.grip_normal {
            return self.stick_budget;
        }
        if let FrictionLaw::Constant(mu) = self.law {
            return R::of(mu) * normal;
        }
        // The piece in which the normal impulse ends.
        let mut points = self.profile.points.iter();
        let mut start = points.next();
        for end in points {
            if let (Some(start), true) = (start, end.normal > normal) {
                let (_, compliance) = piece(start, end);
                let change = self
                    .law
                    .slip_change(start.speed, normal - start.normal, compliance);
                return R::min(start.budget + change / compliance, end.budget);
            }
            start = Some(end);
        }
        self.stick_budget
    }
}

#[cfg(test)]
mod tests;
