//! Frictionless, perfectly elastic collision of equal spheres.

use crate::error::Result;
use crate::impact::Impact;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

/// Equal masses, `e* = 1`, `μ = 0`: the cue ball hands its normal velocity `U_x` to the
/// object ball and keeps its tangential velocity and spin (seed §1, Fig. 1).
// Not inlined into `model::collide_in` (see `kim_grip::collide`).
#[inline(never)]
pub(crate) fn collide<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    let normal = R::of(impact.velocity().x); // specific impulse (m/s): (1 + e) U_x / 2 with e = 1
    Outcome::from_impulses(
        params,
        impact,
        SpecificImpulses::normal_only(normal),
        Regime::Frictionless,
    )
}
