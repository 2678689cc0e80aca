//! Typed errors: every invalid input is rejected at construction with the field it
//! concerns, so a prediction never starts from a value it cannot handle.

use crate::validity::{Reason, Tier};
use core::fmt;

/// Result alias for the crate.
pub type Result<T> = core::result::Result<T, Error>;

/// An input quantity, named in errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum Field {
    /// Cue-ball speed before impact `U_i` (m/s).
    Speed,
    /// Cut angle `φ` (rad or degrees, as given).
    CutAngle,
    /// Cue-ball velocity component along `x` (m/s).
    VelocityX,
    /// Cue-ball velocity component along `y` (m/s).
    VelocityY,
    /// Cue-ball angular velocity component `ω_x` (rad/s).
    SpinX,
    /// Cue-ball angular velocity component `ω_y` (rad/s).
    SpinY,
    /// Cue-ball angular velocity component `ω_z` (rad/s).
    SpinZ,
    /// Ball–ball friction coefficient `μ`.
    Friction,
    /// Amplitude `b` of the speed-dependent friction law `μ = a + b·exp(−c·v)`.
    FrictionAmplitude,
    /// Decay rate `c` (s/m) of the speed-dependent friction law.
    FrictionDecay,
    /// Energetic coefficient of restitution `e*`.
    Restitution,
    /// Object-ball/table static friction coefficient `μ_s`.
    TableFriction,
    /// Ball radius `R` (m).
    Radius,
    /// Ball mass `M` (kg).
    Mass,
    /// Cue speed at the tip impact `V_cue` (m/s, TP A.30).
    CueSpeed,
    /// Cue mass `m_c` (kg, TP A.30).
    CueMass,
    /// Cue-tip coefficient of restitution `e_t` (TP A.30).
    TipRestitution,
    /// Cue-tip offset `b = (side, height)` from the ball centre (m, TP A.30).
    TipOffset,
    /// Error tolerance of the `Auto` model.
    Tolerance,
    /// Cue-ball/table sliding friction coefficient `μ_ct`.
    CueTableFriction,
    /// Ball–cloth sliding friction `μ_c`.
    ClothFriction,
    /// Rolling resistance `μ_r`.
    RollingResistance,
    /// A position on the table (m).
    Position,
    /// Table dimensions or pocket geometry (m).
    Table,
    /// Aim direction.
    Aim,
    /// Index of a ball in the scene.
    BallIndex,
    /// Number of balls (capacity of the scene).
    BallCount,
    /// Index of a pocket of the table.
    Pocket,
    /// A ball's velocity on the table, any component (m/s; `travel::Motion`).
    Velocity,
    /// A ball's angular velocity on the table, any component (rad/s;
    /// `travel::Motion`).
    Spin,
    /// Distance between two ball centres in a scene (m): at least `2R`.
    Spacing,
    /// Ball radius of a shot setup's collision parameters (m): must be the scene's.
    SetupRadius,
    /// Aim angle (rad, counter-clockwise from the table's `x` axis).
    AimAngle,
    /// A cushion's restitution, friction or nose height (`R ≤ h < 2R`).
    Cushion,
    /// The spin-decay rate of spinning friction (rad/s²).
    SpinDecay,
}

impl Field {
    /// Short name as used by the CLI and the protocol.
    pub const fn name(self) -> &'static str {
        match self {
            Field::Speed => "speed",
            Field::CutAngle => "cut",
            Field::VelocityX => "velocity.x",
            Field::VelocityY => "velocity.y",
            Field::SpinX => "spin.x",
            Field::SpinY => "spin.y",
            Field::SpinZ => "spin.z",
            Field::Friction => "mu",
            Field::FrictionAmplitude => "mu_b",
            Field::FrictionDecay => "mu_c",
            Field::Restitution => "restitution",
            Field::TableFriction => "mu_s",
            Field::Radius => "radius",
            Field::Mass => "mass",
            Field::Tolerance => "tolerance",
            Field::CueTableFriction => "mu_ct",
            Field::ClothFriction => "mu_cloth",
            Field::RollingResistance => "mu_roll",
            Field::Position => "position",
            Field::Table => "table",
            Field::Aim => "aim",
            Field::BallIndex => "ball",
            Field::BallCount => "balls",
            Field::Pocket => "pocket",
            Field::Velocity => "velocity",
            Field::Spin => "spin",
            Field::Spacing => "spacing",
            Field::SetupRadius => "setup_radius",
            Field::Cushion => "cushion",
            Field::SpinDecay => "spin_decay",
            Field::AimAngle => "aim_angle",
            Field::CueSpeed => "cue_speed",
            Field::CueMass => "cue_mass",
            Field::TipRestitution => "tip_restitution",
            Field::TipOffset => "tip_offset",
        }
    }

    /// The accepted range, for messages.
    pub const fn valid_range(self) -> &'static str {
        match self {
            Field::Speed => "(0, 100] m/s",
            Field::CutAngle => "(-90, 90) degrees",
            Field::VelocityX => "(0, 100] m/s (the cue ball must approach the object ball)",
            Field::VelocityY => "[-100, 100] m/s",
            Field::SpinX | Field::SpinY | Field::SpinZ => "[-10000, 10000] rad/s",
            Field::Friction => "[0, 1]",
            Field::FrictionAmplitude => "[0, 1] with a + b <= 1",
            Field::FrictionDecay => "[0, 100] s/m",
            Field::Restitution => "[0, 1]",
            Field::TableFriction => "[0, 1]",
            Field::Radius => "[0.001, 1] m",
            Field::Mass => "[0.001, 100] kg",
            Field::Tolerance => "(0, 1]",
            Field::CueTableFriction => "[0, 1]",
            Field::ClothFriction => "[0.001, 1]",
            Field::RollingResistance => "[0.001, 0.5]",
            Field::Position => "the playing surface: [R, length - R] x [R, width - R] m",
            Field::Table => {
                "length (0, 10] m, width (0, length], corner mouth [0, width/2], side mouth [0, length/2]"
            }
            Field::Aim => "a non-zero finite direction",
            Field::BallIndex => "an object-ball index: 1 to the number of balls - 1",
            Field::BallCount => "1..=16 balls",
            Field::Pocket => "an index of a pocket of the table",
            Field::Velocity => "[-1000, 1000] m/s per component",
            Field::Spin => "[-1e6, 1e6] rad/s per component",
            Field::Spacing => "centre distances of at least 2R (balls may touch)",
            Field::SetupRadius => "the scene's ball radius (to 1e-6 relative)",
            Field::Cushion => "restitution [0, 1], friction [0, 1], nose height [R, 2R) m",
            Field::SpinDecay => "[0, 1000] rad/s²",
            Field::AimAngle => "[-1000, 1000] rad",
            Field::CueSpeed => "(0, 20] m/s",
            Field::CueMass => "[0.1, 2] kg",
            Field::TipRestitution => "[0, 1]",
            Field::TipOffset => "|b| <= 0.5 R (side, height in m)",
        }
    }
}

/// Everything that can go wrong. The core never panics and never returns NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum Error {
    /// The value is NaN or infinite.
    NotFinite {
        /// Which input.
        field: Field,
    },
    /// The value is finite but outside the accepted range ([`Field::valid_range`]).
    OutOfRange {
        /// Which input.
        field: Field,
        /// The rejected value.
        value: f32,
    },
    /// A computed output was not finite. Guarded against by construction and never
    /// observed on the test grids; reported rather than returned as NaN.
    NumericalFailure,
    /// The model asked for was left out of this build ([`crate::Model::built`]; the
    /// `seed-exact` and `kim` features), as on the device.
    ModelLeftOut,
    /// A table simulation had not ended (every ball at rest or pocketed) after its
    /// event limit or time limit ([`crate::sim`]).
    Unfinished {
        /// Events simulated (`u16`: with the `f32` the variant fits the 8 bytes of the
        /// others; a wider count made every `Result` of the crate larger, +688 B of
        /// firmware flash).
        events: u16,
        /// Simulated time reached (s).
        time: f32,
    },
    /// The scene is outside the model's declared validity domain
    /// ([`crate::validity`]): its answer there would not be physical, or not as
    /// accurate as documented. `Exact` (or `Auto`) answers every valid input.
    OutsideValidity {
        /// The model that refused.
        model: Tier,
        /// Which limit the scene crosses.
        reason: Reason,
        /// The scene's value of the limited quantity (see [`Reason`]).
        value: f32,
    },
}

impl Error {
    /// The input the error concerns, if any.
    pub const fn field(&self) -> Option<Field> {
        match self {
            Error::NotFinite { field } | Error::OutOfRange { field, .. } => Some(*field),
            Error::NumericalFailure
            | Error::ModelLeftOut
            | Error::Unfinished { .. }
            | Error::OutsideValidity { .. } => None,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NotFinite { field } => write!(f, "{} must be a finite number", field.name()),
            Error::OutOfRange { field, value } => {
                write!(
                    f,
                    "{} = {} is outside {}",
                    field.name(),
                    value,
                    field.valid_range()
                )
            }
            Error::NumericalFailure => {
                f.write_str("internal numerical failure (non-finite result)")
            }
            Error::ModelLeftOut => {
                f.write_str("this model was left out of this build (cargo features `seed-exact`, `kim`)")
            }
            Error::Unfinished { events, time } => write!(
                f,
                "the shot had not ended after {events} events and {time} s (its event or time limit)"
            ),
            Error::OutsideValidity {
                model,
                reason,
                value,
            } => write!(
                f,
                "{} is valid only where {} (here {value}); use exact or auto",
                model.name(),
                reason.limit()
            ),
        }
    }
}

/// `Box<dyn std::error::Error>` and other error-handling code take it (`?` converts it).
///
/// ```
/// use cuesight::{collide, Impact, Model, Params};
///
/// fn throw_deg(mu: f32) -> Result<f32, Box<dyn std::error::Error>> {
///     let params = Params::POOL.with_mu(mu)?;
///     let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0, 40.0, 0.0])?;
///     Ok(collide(&params, &impact, Model::KimGrip)?.throw_angle_deg())
/// }
///
/// assert!(throw_deg(0.06).is_ok());
/// let error = throw_deg(-0.1).unwrap_err();
/// assert_eq!(error.to_string(), "mu = -0.1 is outside [0, 1]");
/// let error = error.downcast::<cuesight::Error>().unwrap();
/// assert_eq!(error.field(), Some(cuesight::Field::Friction));
/// ```
impl core::error::Error for Error {}

/// Check `value` is finite and within `[min, max]` (or `(min, max]` when
/// `min_exclusive`).
pub(crate) fn check(
    field: Field,
    value: f32,
    min: f32,
    max: f32,
    min_exclusive: bool,
) -> Result<f32> {
    if !crate::math::is_finite(value) {
        return Err(Error::NotFinite { field });
    }
    let above_min = if min_exclusive {
        value > min
    } else {
        value >= min
    };
    if above_min && value <= max {
        Ok(value)
    } else {
        Err(Error::OutOfRange { field, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every `Result` of the crate carries an `Error`: a variant wider than the others'
    /// 8 bytes grows them all (`Unfinished` with a `u32` count cost the firmware 688 B
    /// of flash and 56 B of stack).
    #[test]
    fn an_error_is_eight_bytes() {
        assert_eq!(core::mem::size_of::<Error>(), 8);
    }

    #[test]
    fn check_rejects_nan_inf_and_bounds() {
        assert_eq!(
            check(Field::Mass, f32::NAN, 0.0, 1.0, false),
            Err(Error::NotFinite { field: Field::Mass })
        );
        assert_eq!(
            check(Field::Mass, f32::INFINITY, 0.0, 1.0, false),
            Err(Error::NotFinite { field: Field::Mass })
        );
        assert_eq!(
            check(Field::Mass, 0.0, 0.0, 1.0, true),
            Err(Error::OutOfRange {
                field: Field::Mass,
                value: 0.0
            })
        );
        assert_eq!(check(Field::Mass, 0.0, 0.0, 1.0, false), Ok(0.0));
        assert_eq!(
            check(Field::Mass, 1.5, 0.0, 1.0, false),
            Err(Error::OutOfRange {
                field: Field::Mass,
                value: 1.5
            })
        );
    }
}
