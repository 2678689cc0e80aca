//! Model selection and the single entry point [`collide`].

use crate::error::{Field, Result};
use crate::impact::Impact;
use crate::outcome::Outcome;
use crate::params::Params;
use crate::real::Real;

/// Which collision model to evaluate.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Model {
    /// Frictionless, perfectly elastic (`μ = 0`, `e* = 1` whatever `Params` say):
    /// the normal velocity is exchanged, spins are untouched.
    Ideal,
    /// The seed's first-order closed forms, eqs. (52)–(54), with erratum E1 applied.
    /// Assumes sliding for the whole impact: wrong where the contact grips.
    Kim,
    /// `Kim` plus a gripping branch (erratum E6) and a second-order slip-direction
    /// correction; continuous across the slide/grip boundary. The model to use.
    KimGrip,
    /// The seed's exact sliding solution, eqs. (24)–(41) with erratum E1, and a stick
    /// branch (`seed_exact` module): the seed's integrals by 8-point Gauss–Legendre
    /// quadrature, compression end and impact end by bracketed Newton solves. Exact for
    /// the seed's physics, whose object-ball table friction points along `−x` (eq. (7)):
    /// up to ~0.4 % of U from the first-principles result when the object ball is pressed
    /// (topspin), within quadrature error otherwise. Ignores `μ_ct`, as the seed does.
    /// May return [`Error::NumericalFailure`](crate::Error::NumericalFailure) if a root solve fails (never observed).
    SeedExact,
    /// The full rigid-body impact integrated in fixed memory (`exact` module): the
    /// reference solver's physics at a fixed step count. Slowest, most accurate.
    Exact,
    /// The cheapest tier on the Pareto front of cost and accuracy (`Ideal`, `KimGrip`,
    /// `Exact`: `Kim` and `SeedExact` are dominated by `KimGrip`) whose a-priori error
    /// estimate ([`crate::error_estimate`]) is at most `tolerance`, in
    /// `max(|Δv|, R|Δω|) / U` (e.g. 1e-3 for 0.1 % of the cue-ball speed); `Exact` if none
    /// is. `Ideal` also only where the friction it leaves out is within `tolerance` of the
    /// object ball's normal impulse, so a thin cut keeps its throw
    /// ([`crate::select_model`]).
    ///
    /// ```
    /// use cuesight::{collide, error_estimate, select_model, Impact, Model, Params};
    ///
    /// let params = Params::POOL;
    /// let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0, 40.0, 0.0])?;
    /// // Which tier `Auto` evaluates, and that tier's estimate.
    /// let (tier, estimate) = select_model(&params, &impact, 1e-3);
    /// assert!(estimate <= 1e-3);
    /// assert_eq!(estimate, error_estimate(&params, &impact, tier));
    /// // `Auto` gives exactly that tier's outcome.
    /// let auto = collide(&params, &impact, Model::Auto { tolerance: 1e-3 })?;
    /// assert_eq!(auto, collide(&params, &impact, tier)?);
    /// // A looser tolerance never picks a dearer tier.
    /// let (loose, _) = select_model(&params, &impact, 0.1);
    /// let rank = |m: Model| Model::ALL.iter().position(|&x| x == m);
    /// assert!(rank(loose) <= rank(tier));
    /// // The tolerance is checked.
    /// assert!(collide(&params, &impact, Model::Auto { tolerance: 0.0 }).is_err());
    /// # Ok::<(), cuesight::Error>(())
    /// ```
    Auto {
        /// Accepted relative error, in `(0, 1]`.
        tolerance: f32,
    },
}

impl Model {
    /// Every model, cheapest first.
    pub const ALL: [Model; 5] = [
        Model::Ideal,
        Model::Kim,
        Model::KimGrip,
        Model::SeedExact,
        Model::Exact,
    ];

    /// Whether this build evaluates the model: all but `SeedExact` without the
    /// `seed-exact` feature and `Kim` without the `kim` feature, which
    /// [`crate::collide`] answers with
    /// [`Error::ModelLeftOut`](crate::Error::ModelLeftOut) (the firmware leaves both out).
    pub const fn built(self) -> bool {
        match self {
            Model::SeedExact => cfg!(feature = "seed-exact"),
            Model::Kim => cfg!(feature = "kim"),
            _ => true,
        }
    }

    /// Lower-case, hyphenated name (`ideal`, `kim`, `kim-grip`, `seed-exact`, `exact`).
    #[inline(never)]
    pub const fn name(self) -> &'static str {
        match self {
            Model::Ideal => "ideal",
            Model::Kim => "kim",
            Model::KimGrip => "kim-grip",
            Model::SeedExact => "seed-exact",
            Model::Exact => "exact",
            Model::Auto { .. } => "auto",
        }
    }

    /// Parse a name as printed by [`Model::name`]; `auto` gets a tolerance of 1e-3.
    pub fn from_name(name: &str) -> Option<Self> {
        if name == "auto" {
            return Some(Model::Auto { tolerance: 1e-3 });
        }
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Predict the outcome of the cue ball described by `impact` hitting a resting object
/// ball, with `params`, using `model`, evaluated in `f32`.
///
/// Inputs are validated by their constructors, so the errors are an `Auto` tolerance
/// outside `(0, 1]` ([`Field::Tolerance`]) and
/// [`Error::NumericalFailure`](crate::Error::NumericalFailure), a guard that turns any
/// non-finite result into an error instead of a NaN (never observed on the test grids).
///
/// ```
/// use cuesight::{collide, Impact, Model, Params, Regime};
///
/// // The README's shot: 2 m/s, cut 30°, 40 rad/s of topspin, μ = 0.06.
/// let params = Params::POOL.with_mu(0.06)?;
/// let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0, 40.0, 0.0])?;
/// let out = collide(&params, &impact, Model::KimGrip)?;
/// assert_eq!(out.regime, Regime::Sliding);
/// assert!((out.throw_angle_deg() - 2.17).abs() < 0.01); // object ball thrown 2.17°
/// assert!(out.cue_ball.velocity.z > 0.0); // the cue ball hops
///
/// // Every tier answers the same question; Ideal has no throw at all.
/// let ideal = collide(&params, &impact, Model::Ideal)?;
/// assert!(ideal.throw_angle_deg().abs() < 1e-4);
/// # Ok::<(), cuesight::Error>(())
/// ```
pub fn collide(params: &Params, impact: &Impact, model: Model) -> Result<Outcome> {
    collide_in::<f32>(params, impact, model)
}

/// As [`collide`], evaluated in `f64` (software double precision on the Cortex-M4F;
/// for measuring what precision buys). Needs the `libm` backend.
#[cfg(feature = "libm")]
pub fn collide_f64(params: &Params, impact: &Impact, model: Model) -> Result<Outcome> {
    collide_in::<f64>(params, impact, model)
}

/// As [`collide`], evaluated in the precision `R` ([`Real`]: `f32`, or `f64` with
/// `libm`). Inputs and outputs are `f32` whatever `R`.
///
/// Every model builds its outcome with the guard of `Outcome::from_impulses` (no NaN,
/// no infinity), and each is called in tail position so that its outcome is written
/// straight into the caller's `Result`.
pub fn collide_in<R: Real>(params: &Params, impact: &Impact, model: Model) -> Result<Outcome> {
    match model {
        Model::Ideal => crate::ideal::collide::<R>(params, impact),
        #[cfg(feature = "kim")]
        Model::Kim => crate::kim::collide::<R>(params, impact),
        #[cfg(not(feature = "kim"))]
        Model::Kim => Err(crate::Error::ModelLeftOut),
        Model::KimGrip => crate::kim_grip::collide::<R>(params, impact),
        #[cfg(feature = "seed-exact")]
        Model::SeedExact => crate::seed_exact::collide::<R>(params, impact),
        #[cfg(not(feature = "seed-exact"))]
        Model::SeedExact => Err(crate::Error::ModelLeftOut),
        Model::Exact => crate::exact::collide::<R>(params, impact),
        Model::Auto { tolerance } => auto::<R>(params, impact, tolerance),
    }
}

/// [`Model::Auto`]: validate the tolerance, pick the tier, evaluate it. Kept out of
/// [`collide_in`] so that the dispatch of the other models stays a jump.
#[inline(never)]
fn auto<R: Real>(params: &Params, impact: &Impact, tolerance: f32) -> Result<Outcome> {
    crate::error::check(Field::Tolerance, tolerance, 0.0, 1.0, true)?;
    // `select`'s first rung, here too: no call into it on the cheap path.
    if crate::estimate::declared_kim_grip(params, tolerance) {
        return crate::kim_grip::collide::<R>(params, impact);
    }
    let (tier, _) = crate::estimate::select(params, impact, tolerance);
    collide_in::<R>(params, impact, tier)
}
