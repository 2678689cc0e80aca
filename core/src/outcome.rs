//! What a collision produces: both balls' post-impact state, the impulses that made
//! it, and the contact regime.

use crate::error::{Error, Result};
use crate::impact::Impact;
use crate::math;
use crate::params::Params;
use crate::real::Real;
use crate::vector::Vec3;

/// Linear and angular velocity of one ball just after the impact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BallState {
    /// Centre velocity (m/s), collision frame; `z > 0` means the ball leaves the table.
    pub velocity: Vec3,
    /// Angular velocity (rad/s), collision frame.
    pub spin: Vec3,
}

/// How the ball–ball contact behaved during the impact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum Regime {
    /// No friction acted (μ = 0, or the `Ideal` model).
    Frictionless,
    /// The contact points slid over each other for the whole impact (seed §3–4).
    Sliding,
    /// The slip vanished during the impact and the contact gripped (erratum E6); this
    /// includes contacts with no initial slip at all (exact gearing).
    Gripping,
}

impl Regime {
    /// Lower-case name (`frictionless`, `sliding`, `gripping`).
    pub const fn name(self) -> &'static str {
        match self {
            Regime::Frictionless => "frictionless",
            Regime::Sliding => "sliding",
            Regime::Gripping => "gripping",
        }
    }
}

/// Impulses exchanged during the impact (N·s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Impulses {
    /// Ball–ball normal impulse `p_f` on the object ball, along `+x`.
    pub normal: f32,
    /// Ball–ball friction impulse on the object ball; `x` is always zero.
    pub friction: Vec3,
    /// Magnitude of the table friction impulse on the object ball (`μ_s` × its table
    /// normal impulse), acting against its table-contact slip, i.e. close to `−x`; zero
    /// unless the object ball is pressed into the table (topspin).
    pub table_friction: f32,
}

/// Which ball the ball–ball friction lifts off the table (`v_z = |j_z|`; the other
/// is pressed into the cloth and keeps `v_z = 0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lifted {
    /// Decided by the sign of `j_z`, the vertical friction on the object ball: the
    /// object ball if `j_z > 0`, else the cue ball.
    BySign,
    /// The cue ball: the caller knows `j_z ≤ 0` (the slip `v_z0 > 0`, topspin).
    Cue,
    /// The object ball: the caller knows `j_z ≥ 0` (`v_z0 ≤ 0`).
    Object,
}

/// Impulses per unit mass (m/s) handed from a model to [`Outcome::from_impulses`],
/// in the model's evaluation precision `R`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SpecificImpulses<R> {
    /// Ball–ball normal impulse on the object ball, along `+x`.
    pub normal: R,
    /// Ball–ball friction impulse on the object ball, `y` component.
    pub friction_y: R,
    /// Ball–ball friction impulse on the object ball, `z` component.
    pub friction_z: R,
    /// Table friction on the object ball along `−x`.
    pub table: R,
    /// Table friction on the object ball, `y` component.
    pub table_y: R,
    /// Size of the object ball's table friction, `|(table, table_y)|` (≥ 0); the model
    /// knows it without a square root.
    pub table_size: R,
    /// Table friction on the cue ball (pressed in a draw shot), `x` component.
    pub cue_table_x: R,
    /// Table friction on the cue ball, `y` component.
    pub cue_table_y: R,
}

/// Largest `Σ j²` ((m/s)²) [`Outcome::from_impulses`] accepts, i.e. every impulse
/// below 1e18 m/s: far above any physical impulse (≤ 2 U ≤ 200 m/s), far below
/// overflow once multiplied into the outcome.
const MAX_SPECIFIC_IMPULSE_SQUARED: f32 = 1e36;

impl<R: Real> SpecificImpulses<R> {
    /// `true` when `Σ j² ≤ MAX_SPECIFIC_IMPULSE_SQUARED`, and so no impulse is NaN,
    /// infinite or above 1e18 m/s (a square that overflows makes the sum infinite).
    /// A multiply-add per impulse; a model's constant-zero terms fold away.
    fn is_bounded(&self) -> bool {
        let size = self.cue_table_x * self.cue_table_x
            + self.cue_table_y * self.cue_table_y
            + self.table_y * self.table_y
            + self.table * self.table
            + self.table_size * self.table_size
            + self.friction_z * self.friction_z
            + self.friction_y * self.friction_y
            + self.normal * self.normal;
        size <= R::of(MAX_SPECIFIC_IMPULSE_SQUARED)
    }

    /// Only a normal impulse.
    pub fn normal_only(normal: R) -> Self {
        Self {
            normal,
            friction_y: R::ZERO,
            friction_z: R::ZERO,
            table: R::ZERO,
            table_y: R::ZERO,
            table_size: R::ZERO,
            cue_table_x: R::ZERO,
            cue_table_y: R::ZERO,
        }
    }
}

/// Result of one collision.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Outcome {
    /// Cue ball after the impact.
    pub cue_ball: BallState,
    /// Object ball after the impact.
    pub object_ball: BallState,
    /// Contact regime that applied.
    pub regime: Regime,
    /// Impulses exchanged.
    pub impulses: Impulses,
}

impl Outcome {
    /// The outcome when no friction acts: `μ = 0` ([`Regime::Frictionless`]) or no
    /// initial slip and so no friction direction (exact gearing, [`Regime::Gripping`]).
    /// `normal` is the specific normal impulse `(1 + e*) U_x / 2` (m/s).
    pub(crate) fn without_friction<R: Real>(
        params: &Params,
        impact: &Impact,
        normal: R,
        frictionless: bool,
    ) -> Result<Self> {
        let regime = if frictionless {
            Regime::Frictionless
        } else {
            Regime::Gripping
        };
        // The guard of `from_impulses` with the other impulses known to be zero (and so
        // their terms left out); no ball leaves the table.
        let impulses = SpecificImpulses::normal_only(normal);
        if !impulses.is_bounded() {
            return Err(Error::NumericalFailure);
        }
        Ok(Self::assemble::<R, false>(
            params,
            impact,
            impulses,
            regime,
            Lifted::Object,
        ))
    }

    /// Assemble both balls' final states from the impulses `j` (all per unit mass, m/s).
    ///
    /// This is also the core's NaN guard: [`Error::NumericalFailure`] unless every
    /// impulse is below 1e18 m/s (`Σ j² ≤ 1e36`). That bound is enough for a finite
    /// outcome: every output is a validated input (|v| ≤ 100 m/s, |ω| ≤ 10⁴ rad/s) plus
    /// an impulse times at most `max(1/(νR), M) ≤ 2,500` (R ≥ 1 mm, M ≤ 100 kg).
    /// Checking the seven impulses costs a fraction of checking the twenty-two outputs.
    ///
    /// This is plain rigid-body bookkeeping (`M ΔV = ΣJ`, `I Δω = Σ r × J`, seed eqs.
    /// (17)–(18) with erratum E1): the ball–ball contact is at `+R x̂` from the cue
    /// ball and `−R x̂` from the object ball; the table acts at `−R ẑ` and only pushes
    /// up, so whichever ball the vertical friction presses down keeps `v_z = 0` and
    /// the other leaves the table with `v_z = |j_z|`.
    pub(crate) fn from_impulses<R: Real>(
        params: &Params,
        impact: &Impact,
        j: SpecificImpulses<R>,
        regime: Regime,
    ) -> Result<Self> {
        if !j.is_bounded() {
            return Err(Error::NumericalFailure);
        }
        Ok(Self::assemble::<R, true>(
            params,
            impact,
            j,
            regime,
            Lifted::BySign,
        ))
    }

    /// [`Outcome::from_impulses`] without the guard, for a caller that has checked
    /// its impulses itself (`kim_grip::fast_path`). With `OBJECT_TABLE` false the
    /// object ball's table friction is known to be zero and its terms are left out
    /// (`x + 0` does not fold in IEEE arithmetic). `lifted` says which ball leaves the
    /// table, when the caller knows it (a constant there, so the test folds away).
    #[inline(always)]
    pub(crate) fn assemble<R: Real, const OBJECT_TABLE: bool>(
        params: &Params,
        impact: &Impact,
        j: SpecificImpulses<R>,
        regime: Regime,
        lifted: Lifted,
    ) -> Self {
        let SpecificImpulses {
            normal,
            friction_y: j_y,
            friction_z: j_z,
            table,
            table_y,
            table_size,
            cue_table_x,
            cue_table_y,
        } = j;
        let zero = R::ZERO;
        let radius = R::of(params.radius());
        let mass = params.mass();
        // Δω per unit specific impulse at the contact: R / (ν M R²) · M = 1 / (ν R).
        let spin_per_impulse = if R::SINGLE {
            R::of(params.derived().spin_per_impulse)
        } else {
            R::of(2.5) / radius
        };
        let u = impact.velocity();
        let w = impact.spin();
        let vec = |x: R, y: R, z: R| Vec3::new(x.to_f32(), y.to_f32(), z.to_f32());
        // The ball the vertical friction pushes up leaves the table with |j_z|.
        let (cue_lift, object_lift) = match lifted {
            Lifted::Cue => (R::abs(j_z), zero),
            Lifted::Object => (zero, R::abs(j_z)),
            Lifted::BySign if j_z > zero => (zero, j_z),
            Lifted::BySign => (-j_z, zero),
        };
        // Cue ball: r × (−J) with r = R x̂ gives R (0, j_z, −j_y); its table friction T
        // at −R ẑ gives R (T_y, −T_x, 0). Without cue-ball table friction (a constant
        // zero in most models, so the test folds away) the sums skip its terms.
        let (cue_velocity, cue_spin) = if cue_table_x == zero && cue_table_y == zero {
            (
                vec(R::of(u.x) - normal, R::of(u.y) - j_y, cue_lift),
                vec(
                    R::of(w.x),
                    R::of(w.y) + j_z * spin_per_impulse,
                    R::of(w.z) - j_y * spin_per_impulse,
                ),
            )
        } else {
            (
                vec(
                    R::of(u.x) - normal + cue_table_x,
                    R::of(u.y) - j_y + cue_table_y,
                    cue_lift,
                ),
                vec(
                    R::of(w.x) + cue_table_y * spin_per_impulse,
                    R::of(w.y) + (j_z - cue_table_x) * spin_per_impulse,
                    R::of(w.z) - j_y * spin_per_impulse,
                ),
            )
        };
        // Object ball: (−R x̂) × J gives the same; table friction at −R ẑ:
        // (−R ẑ) × (−X, T_y, 0) = R (T_y, X, 0).
        let (object_velocity, object_spin) = if OBJECT_TABLE {
            (
                vec(normal - table, j_y + table_y, object_lift),
                vec(
                    table_y * spin_per_impulse,
                    (j_z + table) * spin_per_impulse,
                    -j_y * spin_per_impulse,
                ),
            )
        } else {
            (
                vec(normal, j_y, object_lift),
                vec(zero, j_z * spin_per_impulse, -j_y * spin_per_impulse),
            )
        };
        let normal = normal.to_f32();
        let (j_y, j_z) = (j_y.to_f32(), j_z.to_f32());
        let table_size = table_size.to_f32();
        Self {
            cue_ball: BallState {
                velocity: cue_velocity,
                spin: cue_spin,
            },
            object_ball: BallState {
                velocity: object_velocity,
                spin: object_spin,
            },
            regime,
            impulses: Impulses {
                normal: normal * mass,
                friction: Vec3::new(0.0, j_y * mass, j_z * mass),
                table_friction: table_size * mass,
            },
        }
    }

    /// `true` when every number in the outcome is finite.
    pub fn is_finite(&self) -> bool {
        // One test on the sum instead of twenty: a NaN or an infinity anywhere makes the
        // sum NaN or infinite, and validated inputs keep every term below ~1e6, so the
        // sum cannot overflow on its own.
        let vectors = [
            self.cue_ball.velocity,
            self.cue_ball.spin,
            self.object_ball.velocity,
            self.object_ball.spin,
            self.impulses.friction,
        ];
        let mut total = self.impulses.normal + self.impulses.table_friction;
        for v in vectors {
            total = total + v.x + v.y + v.z;
        }
        math::is_finite(total)
    }

    /// Throw angle ψ (radians): direction of the object ball's horizontal velocity
    /// from the line of centres, `atan2(V_y, V_x)` (seed eq. (55)). Positive when the
    /// object ball is thrown towards `+y`.
    pub fn throw_angle(&self) -> f32 {
        let v = self.object_ball.velocity;
        math::atan2(v.y, v.x)
    }

    /// Throw angle in degrees.
    pub fn throw_angle_deg(&self) -> f32 {
        self.throw_angle().to_degrees()
    }

    /// Cue-ball deflection ψ_c (radians) from the tangent line towards the line of
    /// centres: `atan2(U_x, |U_y|)` of the horizontal velocity (seed eq. (56); TP A.5
    /// calls it the cue-ball deviation). 90° for a head-on follow or stun shot.
    pub fn cue_deflection(&self) -> f32 {
        let u = self.cue_ball.velocity;
        math::atan2(u.x, math::abs(u.y))
    }

    /// Cue-ball deflection in degrees.
    pub fn cue_deflection_deg(&self) -> f32 {
        self.cue_deflection().to_degrees()
    }

    /// Angle between the two balls' horizontal directions of travel (degrees).
    pub fn separation_angle_deg(&self) -> f32 {
        let u = self.cue_ball.velocity;
        let v = self.object_ball.velocity;
        let cross = u.x * v.y - u.y * v.x;
        let dot = u.x * v.x + u.y * v.y;
        math::atan2(math::abs(cross), dot).to_degrees()
    }
}
