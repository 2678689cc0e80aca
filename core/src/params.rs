//! Physical parameters of a collision, validated on construction.

use crate::error::{check, Field, Result};
use crate::friction::FrictionLaw;

/// Ball and contact parameters (seed §2, physics-notes §5).
///
/// Build with [`Params::new`] or start from [`Params::POOL`] and replace fields with
/// the `with_*` methods; every constructor validates, so a `Params` value is always
/// usable.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Params {
    friction: FrictionLaw,
    restitution: f32,
    mu_s: f32,
    cue_table_friction: f32,
    radius: f32,
    mass: f32,
    /// Constants of the models derived from the fields above, computed once here
    /// instead of on every collision.
    derived: Derived,
}

/// Per-`Params` constants of the hot path, a pure function of the other fields
/// ([`Derived::of`]); every constructor recomputes them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Derived {
    /// μ when `KimGrip`'s fast path applies (constant μ in (0, 1], μ_ct = 0, inside
    /// `KimGrip`'s validity domain), else 0.
    pub kim_grip_mu: f32,
    /// Smallest `|v₀|²` ((m/s)²) the fast path takes: its `MIN_SLIP_SQUARED` when it
    /// applies, +∞ when not, so that one comparison of the slip sends every other
    /// scene to the general path.
    pub kim_grip_min_slip_squared: f32,
    /// `(1 + e*)/2`: the frictionless normal impulse per unit approach speed.
    pub half_one_plus_restitution: f32,
    /// `μ μ_s` for the fast path's table-friction rate (`kim_grip_mu` times μ_s).
    pub kim_grip_mu_mu_s: f32,
    /// `k_z = (2 + ν − μ_s)/ν = 6 − 2.5 μ_s` when the object ball is pressed into the
    /// table (seed eq. (23) with erratum E1).
    pub pressed_k_z: f32,
    /// `1/(k_y + k_z) = 1/(13 − 2.5 μ_s)`, same case (`kim_grip`).
    pub pressed_boundary: f32,
    /// `1/(ν R)` (1/m): spin change per unit specific impulse at the contact.
    pub spin_per_impulse: f32,
    /// `Auto` at a tolerance of at least `estimate::KIM_GRIP_DECLARED_BOUND` picks
    /// `KimGrip` on its declared bound alone (`estimate::select`): inside `KimGrip`'s
    /// validity domain, not frictionless and elastic (where `Ideal` is exact), e* ≥
    /// 0.01 (the domain's edge that depends on μ_ct).
    pub auto_kim_grip: bool,
    /// Where `KimGrip` refuses these parameters (`validity::kim_grip`): the reason and
    /// the value past its limit.
    pub kim_grip_refusal: Option<(crate::validity::Reason, f32)>,
    /// The speed-dependent law `μ(v) = a + b e^{−cv}` when `KimGrip`'s speed-dependent
    /// fast path applies to it (validated ranges with `b > 0`, `c > 0`, μ_ct = 0, inside
    /// `KimGrip`'s validity domain), else `None`.
    #[cfg(feature = "speed-path")]
    pub kim_grip_speed_law: Option<SpeedLaw>,
}

/// A speed-dependent friction law `μ(v) = a + b e^{−cv}` (TP A.14) as `KimGrip`'s
/// speed-dependent fast path uses it (`kim_grip::speed_path`).
#[cfg(feature = "speed-path")]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct SpeedLaw {
    /// `a`, the high-speed limit.
    pub a: f32,
    /// `b`, the amplitude.
    pub b: f32,
    /// `c` (s/m), the decay rate.
    pub c: f32,
}

impl Derived {
    const fn of(
        friction: FrictionLaw,
        restitution: f32,
        mu_s: f32,
        mu_ct: f32,
        radius: f32,
    ) -> Self {
        // Inside `KimGrip`'s validity domain (`validity::kim_grip`, which returns the
        // refusal kept here): scenes outside it go to the general path, which refuses
        // them, so the fast paths pay nothing for it; and `Auto` at a loose tolerance
        // picks `KimGrip` on it (the test `auto_kim_grip_is_the_validity_domain`).
        let largest = friction.largest();
        let kim_grip_refusal =
            crate::validity::kim_grip_refusal(&friction, mu_s, mu_ct, restitution);
        let inside = kim_grip_refusal.is_none();
        // The fast paths' region (`kim_grip::curved`): μ ≤ `CURVED_MIN_MU` (a
        // speed-dependent law's μ(0)), μ_s ≤ `CURVED_MIN_MU_S`, μ·μ_s ≤
        // `CURVED_MIN_MU_MU_S`; the general path follows the slide in pieces everywhere
        // else. μ ≤ `CURVED_MIN_MU` also keeps the fast path's guard in the validated range
        // (a law built from the enum's variant skips `FrictionLaw::constant`'s check; the
        // general path guards every impulse).
        let straight = (mu_s <= crate::kim_grip::CURVED_MIN_MU_S)
            & (largest * mu_s <= crate::kim_grip::CURVED_MIN_MU_MU_S);
        let kim_grip_mu = match friction {
            FrictionLaw::Constant(mu)
                if mu > 0.0
                    && mu <= crate::kim_grip::CURVED_MIN_MU
                    && mu_ct == 0.0
                    && inside
                    && straight =>
            {
                mu
            }
            _ => 0.0,
        };
        #[cfg(feature = "speed-path")]
        let kim_grip_speed_law = match friction {
            // The validated ranges too (a ≥ 1e-6, c ≤ 100; NaN fails every test): a law
            // built from the enum's variant skips `FrictionLaw::speed_dependent`'s check
            // (the `collide` fuzz target found a = −0.92 giving an infinite velocity).
            FrictionLaw::SpeedDependent { a, b, c }
                if a >= 1e-6
                    && b > 0.0
                    && a + b <= crate::kim_grip::CURVED_MIN_MU
                    && c > 0.0
                    && c <= 100.0
                    && mu_ct == 0.0
                    && inside
                    && straight =>
            {
                Some(SpeedLaw { a, b, c })
            }
            _ => None,
        };
        let pressed_k_z = 6.0 - 2.5 * mu_s;
        let auto_kim_grip = inside
            & ((largest > 0.0) | (restitution < 1.0))
            & (restitution >= crate::validity::KIM_GRIP_MIN_RESTITUTION);
        Self {
            auto_kim_grip,
            kim_grip_refusal,
            #[cfg(feature = "speed-path")]
            kim_grip_speed_law,
            kim_grip_mu,
            kim_grip_min_slip_squared: if kim_grip_mu > 0.0 {
                crate::kim_grip::FAST_PATH_MIN_SLIP_SQUARED
            } else {
                f32::INFINITY
            },
            kim_grip_mu_mu_s: kim_grip_mu * mu_s,
            half_one_plus_restitution: 0.5 * (1.0 + restitution),
            pressed_k_z,
            pressed_boundary: 1.0 / (7.0 + pressed_k_z),
            spin_per_impulse: 2.5 / radius,
        }
    }
}

impl Params {
    /// Pool defaults: μ = 0.05, e* = 0.95, μ_s = 0.3, R = 28.575 mm, M = 0.17 kg.
    pub const POOL: Self =
        Self::assemble(FrictionLaw::Constant(0.05), 0.95, 0.3, 0.0, 0.028575, 0.17);

    /// The one place a `Params` is put together (inputs already validated), so that
    /// [`Derived`] always matches the fields.
    // Out of line: one copy for every constructor and override (the firmware's flash).
    #[inline(never)]
    const fn assemble(
        friction: FrictionLaw,
        restitution: f32,
        mu_s: f32,
        cue_table_friction: f32,
        radius: f32,
        mass: f32,
    ) -> Self {
        Self {
            friction,
            restitution,
            mu_s,
            cue_table_friction,
            radius,
            mass,
            derived: Derived::of(friction, restitution, mu_s, cue_table_friction, radius),
        }
    }

    /// Validate and build.
    ///
    /// * `mu` — ball–ball friction coefficient μ, in `[0, 1]`;
    /// * `restitution` — Stronge's energetic coefficient e* (seed eq. (37)), in `[0, 1]`;
    /// * `mu_s` — object-ball/table static friction μ_s, in `[0, 1]`;
    /// * `radius` — R in metres, in `[0.001, 1]`;
    /// * `mass` — M in kilograms, in `[0.001, 100]`.
    pub fn new(mu: f32, restitution: f32, mu_s: f32, radius: f32, mass: f32) -> Result<Self> {
        Ok(Self::assemble(
            FrictionLaw::constant(mu)?,
            check(Field::Restitution, restitution, 0.0, 1.0, false)?,
            check(Field::TableFriction, mu_s, 0.0, 1.0, false)?,
            0.0,
            check(Field::Radius, radius, 0.001, 1.0, false)?,
            check(Field::Mass, mass, 0.001, 100.0, false)?,
        ))
    }

    /// Replace the friction by a constant μ (validated).
    pub fn with_mu(self, mu: f32) -> Result<Self> {
        Ok(self.with_friction_law(FrictionLaw::constant(mu)?))
    }

    /// Set the cue-ball/table sliding friction μ_ct (in `[0, 1]`; default 0, as the seed
    /// neglects it). It acts while the cue ball is pressed into the cloth — a draw shot,
    /// where the ball–ball friction pushes the cue ball down — against the cue ball's
    /// table-contact slip. Used by `KimGrip`, `Exact` and the reference; `Kim` and `Ideal`
    /// ignore it.
    pub fn with_cue_table_friction(self, mu_ct: f32) -> Result<Self> {
        let mu_ct = check(Field::CueTableFriction, mu_ct, 0.0, 1.0, false)?;
        Ok(Self::assemble(
            self.friction,
            self.restitution,
            self.mu_s,
            mu_ct,
            self.radius,
            self.mass,
        ))
    }

    /// Replace the friction law (already validated by its constructor).
    pub fn with_friction_law(self, friction: FrictionLaw) -> Self {
        Self::assemble(
            friction,
            self.restitution,
            self.mu_s,
            self.cue_table_friction,
            self.radius,
            self.mass,
        )
    }

    /// Replace e* (validated).
    pub fn with_restitution(self, restitution: f32) -> Result<Self> {
        let restitution = check(Field::Restitution, restitution, 0.0, 1.0, false)?;
        Ok(Self::assemble(
            self.friction,
            restitution,
            self.mu_s,
            self.cue_table_friction,
            self.radius,
            self.mass,
        ))
    }

    /// Replace μ_s (validated).
    pub fn with_mu_s(self, mu_s: f32) -> Result<Self> {
        let mu_s = check(Field::TableFriction, mu_s, 0.0, 1.0, false)?;
        Ok(Self::assemble(
            self.friction,
            self.restitution,
            mu_s,
            self.cue_table_friction,
            self.radius,
            self.mass,
        ))
    }

    /// Replace R and M (validated).
    pub fn with_ball(self, radius: f32, mass: f32) -> Result<Self> {
        let radius = check(Field::Radius, radius, 0.001, 1.0, false)?;
        let mass = check(Field::Mass, mass, 0.001, 100.0, false)?;
        Ok(Self::assemble(
            self.friction,
            self.restitution,
            self.mu_s,
            self.cue_table_friction,
            radius,
            mass,
        ))
    }

    /// Replace the friction law (already validated by its constructor), e*, μ_s, R and
    /// M (each validated, in that order; μ_ct kept): [`Self::with_friction_law`],
    /// [`Self::with_restitution`], [`Self::with_mu_s`] and [`Self::with_ball`] in one,
    /// with the same first error, assembled once (the link's overrides: flash).
    pub fn with_contact(
        self,
        friction: FrictionLaw,
        restitution: f32,
        mu_s: f32,
        radius: f32,
        mass: f32,
    ) -> Result<Self> {
        Ok(Self::assemble(
            friction,
            check(Field::Restitution, restitution, 0.0, 1.0, false)?,
            check(Field::TableFriction, mu_s, 0.0, 1.0, false)?,
            self.cue_table_friction,
            check(Field::Radius, radius, 0.001, 1.0, false)?,
            check(Field::Mass, mass, 0.001, 100.0, false)?,
        ))
    }

    /// Ball–ball friction coefficient μ: the constant value, or for a speed-dependent
    /// law its value at zero slip speed (the stick limit).
    pub fn mu(&self) -> f32 {
        self.friction.at(0.0)
    }

    /// The ball–ball friction law.
    pub const fn friction_law(&self) -> FrictionLaw {
        self.friction
    }
    /// Energetic coefficient of restitution e*.
    pub const fn restitution(&self) -> f32 {
        self.restitution
    }
    /// Object-ball/table static friction μ_s.
    pub const fn mu_s(&self) -> f32 {
        self.mu_s
    }
    /// Cue-ball/table sliding friction μ_ct (0 unless set).
    pub const fn cue_table_friction(&self) -> f32 {
        self.cue_table_friction
    }
    /// Ball radius R (m).
    pub const fn radius(&self) -> f32 {
        self.radius
    }
    /// Ball mass M (kg).
    pub const fn mass(&self) -> f32 {
        self.mass
    }
    /// The derived constants of the hot path.
    pub(crate) const fn derived(&self) -> &Derived {
        &self.derived
    }
}

impl Default for Params {
    fn default() -> Self {
        Self::POOL
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Error;

    #[test]
    fn with_contact_is_the_chained_setters() {
        let base = Params::POOL.with_cue_table_friction(0.2).unwrap();
        let law = FrictionLaw::MARLOW;
        let chained = |e: f32, mu_s: f32, r: f32, m: f32| {
            base.with_friction_law(law)
                .with_restitution(e)
                .and_then(|p| p.with_mu_s(mu_s))
                .and_then(|p| p.with_ball(r, m))
        };
        for (e, mu_s, r, m) in [
            (0.9, 0.2, 0.03, 0.2),
            (1.5, 2.0, 0.0, -1.0),
            (0.9, f32::NAN, 2.0, 0.2),
            (0.9, 0.2, 0.0005, f32::INFINITY),
            (0.9, 0.2, 0.03, 200.0),
        ] {
            assert_eq!(
                base.with_contact(law, e, mu_s, r, m),
                chained(e, mu_s, r, m)
            );
        }
    }

    #[test]
    fn pool_defaults_validate() {
        let p = Params::POOL;
        assert_eq!(
            Params::new(p.mu(), p.restitution(), p.mu_s(), p.radius(), p.mass()),
            Ok(p)
        );
    }

    #[test]
    fn each_field_is_named_in_its_error() {
        let p = Params::POOL;
        assert_eq!(p.with_mu(-0.1).unwrap_err().field(), Some(Field::Friction));
        assert_eq!(
            p.with_restitution(1.01).unwrap_err().field(),
            Some(Field::Restitution)
        );
        assert_eq!(
            p.with_mu_s(f32::NAN).unwrap_err(),
            Error::NotFinite {
                field: Field::TableFriction
            }
        );
        assert_eq!(
            p.with_ball(0.0, 0.17).unwrap_err().field(),
            Some(Field::Radius)
        );
        assert_eq!(
            p.with_ball(0.03, -1.0).unwrap_err().field(),
            Some(Field::Mass)
        );
    }
}
