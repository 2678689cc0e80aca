//! The cue ball's state at the instant of contact, in the collision frame.

use crate::error::{check, Error, Field, Result};
use crate::math;
use crate::vector::Vec3;

const MAX_SPEED: f32 = 100.0; // m/s
const MAX_SPIN: f32 = 10_000.0; // rad/s

/// Cue ball at contact: horizontal velocity `U_i (cos φ, sin φ, 0)` and angular
/// velocity `ω_i`; the object ball is at rest (seed §2, eq. (11)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Impact {
    velocity: Vec3,
    spin: Vec3,
}

impl Impact {
    /// From the cue-ball velocity in the collision frame (`[v_x, v_y]`, m/s) and spin
    /// (`[ω_x, ω_y, ω_z]`, rad/s). `v_x` must be positive: the cue ball approaches the
    /// object ball. Topspin (follow) is `ω_y > 0`, draw `ω_y < 0`; `ω_z > 0` is
    /// counter-clockwise seen from above.
    pub fn from_velocity(velocity: [f32; 2], spin: [f32; 3]) -> Result<Self> {
        let vx = check(Field::VelocityX, velocity[0], 0.0, MAX_SPEED, true)?;
        let vy = check(Field::VelocityY, velocity[1], -MAX_SPEED, MAX_SPEED, false)?;
        let spin = Vec3::new(
            check(Field::SpinX, spin[0], -MAX_SPIN, MAX_SPIN, false)?,
            check(Field::SpinY, spin[1], -MAX_SPIN, MAX_SPIN, false)?,
            check(Field::SpinZ, spin[2], -MAX_SPIN, MAX_SPIN, false)?,
        );
        Ok(Self {
            velocity: Vec3::new(vx, vy, 0.0),
            spin,
        })
    }

    /// From speed `U_i` (m/s), cut angle `φ` (radians, `|φ| < π/2`) and spin (rad/s).
    pub fn from_cut(speed: f32, cut_angle: f32, spin: [f32; 3]) -> Result<Self> {
        let speed = check(Field::Speed, speed, 0.0, MAX_SPEED, true)?;
        let cut = check(
            Field::CutAngle,
            cut_angle,
            -core::f32::consts::FRAC_PI_2,
            core::f32::consts::FRAC_PI_2,
            true,
        )?;
        if cut >= core::f32::consts::FRAC_PI_2 {
            return Err(Error::OutOfRange {
                field: Field::CutAngle,
                value: cut_angle,
            });
        }
        let vx = speed * math::cos(cut);
        let vy = speed * math::sin(cut);
        if vx <= 0.0 {
            // Grazing to within f32 resolution: no approach along the line of centres.
            return Err(Error::OutOfRange {
                field: Field::CutAngle,
                value: cut_angle,
            });
        }
        Self::from_velocity([vx, vy], spin)
    }

    /// As [`Impact::from_cut`] with the cut angle in degrees (`|φ| < 90`).
    pub fn from_cut_degrees(speed: f32, cut_angle_deg: f32, spin: [f32; 3]) -> Result<Self> {
        let deg = check(Field::CutAngle, cut_angle_deg, -90.0, 90.0, true)?;
        if deg >= 90.0 {
            return Err(Error::OutOfRange {
                field: Field::CutAngle,
                value: cut_angle_deg,
            });
        }
        Self::from_cut(speed, deg.to_radians(), spin).map_err(|e| match e {
            Error::OutOfRange {
                field: Field::CutAngle,
                ..
            } => Error::OutOfRange {
                field: Field::CutAngle,
                value: cut_angle_deg,
            },
            other => other,
        })
    }

    /// Natural roll for the given velocity: `ω = ẑ × v / R` (physics-notes §1), i.e.
    /// no slip at the table contact. `radius` in metres.
    // Out of line: the firmware's boot self-test and `collide` both call it (flash).
    #[inline(never)]
    pub fn rolling(velocity: [f32; 2], radius: f32) -> Result<Self> {
        let radius = check(Field::Radius, radius, 0.001, 1.0, false)?;
        Self::from_velocity(velocity, [-velocity[1] / radius, velocity[0] / radius, 0.0])
    }

    /// Cue-ball velocity before impact (m/s); `z` is zero.
    pub const fn velocity(&self) -> Vec3 {
        self.velocity
    }

    /// Cue-ball angular velocity before impact (rad/s).
    pub const fn spin(&self) -> Vec3 {
        self.spin
    }

    /// Speed `U_i = |velocity|` (m/s).
    pub fn speed(&self) -> f32 {
        self.velocity.length()
    }

    /// Initial slip of the object-ball contact point relative to the cue-ball one,
    /// tangential part `(v_y0, v_z0)` (m/s), seed eq. (11):
    /// `v_y0 = −U_i sin φ − R ω_z`, `v_z0 = R ω_y`.
    pub fn initial_slip(&self, radius: f32) -> (f32, f32) {
        (
            -self.velocity.y - radius * self.spin.z,
            radius * self.spin.y,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rolling_head_on_is_topspin() {
        let i = Impact::rolling([2.0, 0.0], 0.028575).unwrap();
        assert!((i.spin().y - 2.0 / 0.028575).abs() < 1e-3);
        assert_eq!(i.spin().x, 0.0);
    }

    #[test]
    fn cut_angle_limits() {
        assert!(Impact::from_cut_degrees(1.0, 89.9, [0.0; 3]).is_ok());
        assert_eq!(
            Impact::from_cut_degrees(1.0, 90.0, [0.0; 3])
                .unwrap_err()
                .field(),
            Some(Field::CutAngle)
        );
        assert_eq!(
            Impact::from_cut_degrees(1.0, -95.0, [0.0; 3])
                .unwrap_err()
                .field(),
            Some(Field::CutAngle)
        );
        assert_eq!(
            Impact::from_cut_degrees(0.0, 10.0, [0.0; 3])
                .unwrap_err()
                .field(),
            Some(Field::Speed)
        );
        assert_eq!(
            Impact::from_velocity([-1.0, 0.0], [0.0; 3])
                .unwrap_err()
                .field(),
            Some(Field::VelocityX)
        );
        assert_eq!(
            Impact::from_velocity([1.0, 0.0], [0.0, f32::NAN, 0.0])
                .unwrap_err()
                .field(),
            Some(Field::SpinY)
        );
    }
}
