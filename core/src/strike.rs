//! Cue strike: tip offset and cue speed to cue-ball speed and spin (TP A.30).
//!
//! Alciatore's TP A.30 treats the tip–ball impact as a point impulse `J` along the cue
//! line (level cue, no squirt), applied at a perpendicular offset `b` from the ball's
//! centre, with a tip coefficient of restitution `e_t` on the velocity of the contact
//! point. Momentum and angular momentum about the ball's centre give
//!
//! ```text
//! v = (1 + e_t) V_cue / (1 + M/m_c + (5/2)(b/R)²)      (ball speed, m/s)
//! ω = 5 v b / (2 R²)                                    (spin magnitude, rad/s)
//! ```
//!
//! with `V_cue` the cue speed just before contact, `m_c` the cue mass, `M` and `R` the
//! ball's mass and radius (physics-notes §4). The `(5/2)(b/R)²` term is the ball's
//! rotational inertia seen at the contact point, `M R² / I · (b/R)²` with `I = (2/5) M R²`.
//!
//! # Frame and signs
//!
//! Results are in the ball's **travel frame**: `x` along the cue (the direction the ball
//! leaves in), `z` up, `y = z × x` (to the shooter's left), the same handedness as the
//! collision frame of physics-notes §1. The offset is `b = (side, height)` as the shooter
//! sees the ball: `side > 0` right of centre, `height > 0` above centre. The contact
//! point is at `r = (−√(R² − b²), −side, height)` and the angular impulse is
//! `r × J x̂ = J (0, height, side)`, so
//!
//! * **above centre (follow) gives `ω_y > 0`**, the sense of natural roll
//!   `ω = ẑ × v / R` (physics-notes §1); `b = 2R/5` gives exactly `ω = v / R`;
//! * below centre (draw) gives `ω_y < 0`;
//! * **right of centre (right english) gives `ω_z > 0`: counter-clockwise seen from
//!   above.** Pushing the right half of the ball forward turns it to the left, like a
//!   pencil pushed at its right end. This is the sense in which right english throws an
//!   object ball to the *left* (spin-induced throw) and makes the cue ball rebound to the
//!   right off a rail it hits square. (The issue brief stated "right english = clockwise
//!   from above, `ω_z < 0`"; `r × F` gives the opposite sign, and the
//!   `right_english_throws_object_ball_left` test checks the sign against the core's
//!   collision model.)
//!
//! Not modelled: squirt (TP A.31: the cue ball leaves at a small angle to the cue line
//! for off-centre hits), cue elevation (the impulse is taken horizontal), and what the
//! cloth does to speed and spin between the strike and the next collision (TP A.4).

use crate::error::{check, Error, Field, Result};
use crate::impact::Impact;
use crate::math;
use crate::params::Params;
use crate::vector::Vec3;

/// Largest accepted tip offset as a fraction of the ball radius. About half a radius is
/// the usual miscue limit (TP 2.1: a no-slip hit at `0.5 R` already needs a tip friction
/// coefficient of 0.58).
pub const MAX_TIP_OFFSET_FRACTION: f32 = 0.5;

/// Largest accepted cue speed (m/s). Power breaks reach about 10 m/s.
pub const MAX_CUE_SPEED: f32 = 20.0;

/// The cue's mass and tip restitution (TP A.30 parameters `m_c`, `e_t`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cue {
    mass: f32,
    tip_restitution: f32,
}

impl Cue {
    /// A typical pool cue: `m_c = 0.54 kg` (19 oz, 0.5386 kg, the common playing weight)
    /// and `e_t = 0.75`. The restitution is a *typical* value for a leather tip (figures
    /// of 0.7–0.8 are usual), not a measurement of ours; set your own with [`Cue::new`].
    pub const TYPICAL: Self = Self {
        mass: 0.54,
        tip_restitution: 0.75,
    };

    /// Validate and build: `mass` in kg, in `[0.1, 2]`; `tip_restitution` in `[0, 1]`.
    pub fn new(mass: f32, tip_restitution: f32) -> Result<Self> {
        Ok(Self {
            mass: check(Field::CueMass, mass, 0.1, 2.0, false)?,
            tip_restitution: check(Field::TipRestitution, tip_restitution, 0.0, 1.0, false)?,
        })
    }

    /// Cue mass `m_c` (kg).
    pub const fn mass(&self) -> f32 {
        self.mass
    }

    /// Tip coefficient of restitution `e_t`.
    pub const fn tip_restitution(&self) -> f32 {
        self.tip_restitution
    }
}

impl Default for Cue {
    fn default() -> Self {
        Self::TYPICAL
    }
}

/// Where the tip meets the ball, relative to its centre, as the shooter sees it (m).
///
/// `side > 0` is right of centre (right english), `height > 0` above centre (follow).
/// Only finiteness is checked here; the bound `|b| ≤ 0.5 R` needs the ball radius and is
/// checked by [`strike`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TipOffset {
    side: f32,
    height: f32,
}

impl TipOffset {
    /// A centre-ball hit.
    pub const CENTRE: Self = Self {
        side: 0.0,
        height: 0.0,
    };

    /// From the horizontal (`side`) and vertical (`height`) offsets in metres.
    pub fn new(side: f32, height: f32) -> Result<Self> {
        if !math::is_finite(side) || !math::is_finite(height) {
            return Err(Error::NotFinite {
                field: Field::TipOffset,
            });
        }
        Ok(Self { side, height })
    }

    /// From offsets given as fractions of the ball radius `R` (e.g. `0.4` = `2R/5`).
    pub fn from_radius_fraction(side: f32, height: f32, radius: f32) -> Result<Self> {
        let radius = check(Field::Radius, radius, 0.001, 1.0, false)?;
        Self::new(side * radius, height * radius)
    }

    /// Horizontal offset (m), positive right of centre.
    pub const fn side(&self) -> f32 {
        self.side
    }

    /// Vertical offset (m), positive above centre.
    pub const fn height(&self) -> f32 {
        self.height
    }

    /// Distance `|b|` from the centre line (m).
    pub fn magnitude(&self) -> f32 {
        math::sqrt(self.side * self.side + self.height * self.height)
    }
}

/// The cue ball just after the strike, in its travel frame (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Strike {
    /// Ball speed `v` along the travel direction `+x` (m/s).
    pub speed: f32,
    /// Angular velocity (rad/s): `(0, ω_y, ω_z)`, follow `ω_y > 0`, right english
    /// `ω_z > 0` (counter-clockwise from above).
    pub spin: Vec3,
}

impl Strike {
    /// Velocity vector `(v, 0, 0)` in the travel frame (m/s).
    pub const fn velocity(&self) -> Vec3 {
        Vec3::new(self.speed, 0.0, 0.0)
    }

    /// The same state in the collision frame of physics-notes §1 for a cut angle
    /// `cut_angle` (radians): the travel direction is `(cos φ, sin φ, 0)` and the spin
    /// is rotated with it about `z`.
    ///
    /// This assumes the ball arrives with its post-strike state; the cloth's effect over
    /// the distance travelled (TP A.4, natural roll developing) is **not** applied.
    pub fn to_impact(&self, cut_angle: f32) -> Result<Impact> {
        if !math::is_finite(cut_angle) {
            return Err(Error::NotFinite {
                field: Field::CutAngle,
            });
        }
        let (sin, cos) = (math::sin(cut_angle), math::cos(cut_angle));
        let w = self.spin;
        let spin = [w.x * cos - w.y * sin, w.x * sin + w.y * cos, w.z];
        Impact::from_cut(self.speed, cut_angle, spin)
    }
}

/// Cue-ball speed and spin after a strike at cue speed `cue_speed` (m/s, just before
/// contact) with the tip at `tip` on a ball of radius and mass from `params` (TP A.30).
///
/// Errors: `cue_speed` not finite or outside `(0, 20]` m/s ([`Field::CueSpeed`]); `|b|`
/// above `0.5 R` ([`Field::TipOffset`], value `|b|` in metres). Never panics and never
/// returns a non-finite value.
///
/// ```
/// use cuesight::strike::{strike, Cue, TipOffset};
/// use cuesight::{Field, Params};
///
/// let params = Params::POOL;
/// let r = params.radius();
/// // A 2 m/s stroke, the tip 2R/5 above centre: the ball leaves in natural roll.
/// let follow = TipOffset::from_radius_fraction(0.0, 0.4, r)?;
/// let hit = strike(&params, &Cue::TYPICAL, follow, 2.0)?;
/// assert!((hit.spin.y * r - hit.speed).abs() < 1e-5 * hit.speed); // ω_y = v / R
/// assert_eq!(hit.spin.z, 0.0);
/// // Right english spins the ball counter-clockwise seen from above.
/// let right = TipOffset::from_radius_fraction(0.3, 0.0, r)?;
/// assert!(strike(&params, &Cue::TYPICAL, right, 2.0)?.spin.z > 0.0);
/// // Into the collision frame for a 30° cut, then any model.
/// let impact = hit.to_impact(30f32.to_radians())?;
/// let out = cuesight::collide(&params, &impact, cuesight::Model::KimGrip)?;
/// assert!(out.throw_angle_deg() > 0.0);
/// // Miscues are refused: the tip beyond R/2 of the centre.
/// let miscue = TipOffset::from_radius_fraction(0.0, 0.6, r)?;
/// let error = strike(&params, &Cue::TYPICAL, miscue, 2.0).unwrap_err();
/// assert_eq!(error.field(), Some(Field::TipOffset));
/// # Ok::<(), cuesight::Error>(())
/// ```
pub fn strike(params: &Params, cue: &Cue, tip: TipOffset, cue_speed: f32) -> Result<Strike> {
    let cue_speed = check(Field::CueSpeed, cue_speed, 0.0, MAX_CUE_SPEED, true)?;
    let radius = params.radius();
    // Compare in units of R so the bound is scale-free.
    let (side, height) = (tip.side / radius, tip.height / radius);
    let offset_sq = side * side + height * height;
    let limit = MAX_TIP_OFFSET_FRACTION;
    if !math::is_finite(offset_sq) || offset_sq > limit * limit {
        return Err(Error::OutOfRange {
            field: Field::TipOffset,
            value: tip.magnitude(),
        });
    }
    // TP A.30: v = (1 + e_t) V / (1 + M/m_c + (5/2)(b/R)²).
    let denominator = 1.0 + params.mass() / cue.mass + 2.5 * offset_sq;
    let speed = (1.0 + cue.tip_restitution) * cue_speed / denominator;
    // ω = 5 v b / (2 R²), vector form (5 v / (2 R)) (0, height/R, side/R).
    let spin_scale = 2.5 * speed / radius;
    let out = Strike {
        speed,
        spin: Vec3::new(0.0, spin_scale * height, spin_scale * side),
    };
    if math::is_finite(out.speed) && out.spin.is_finite() {
        Ok(out)
    } else {
        Err(Error::NumericalFailure)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use crate::{collide, Model};

    /// `|a − b| ≤ rtol·max(|a|, |b|) + atol` (engineering-style numeric comparison).
    fn close(a: f64, b: f64, rtol: f64, atol: f64) -> bool {
        (a - b).abs() <= rtol * a.abs().max(b.abs()) + atol
    }

    const POOL_R: f64 = 0.028575;
    const POOL_M: f64 = 0.17;

    #[test]
    fn centre_hit_has_no_spin_and_the_textbook_speed() {
        let params = Params::POOL;
        for &v_cue in &[0.5f32, 1.0, 2.5, 6.0, 12.0] {
            let out = strike(&params, &Cue::TYPICAL, TipOffset::CENTRE, v_cue).unwrap();
            // Independent f64 evaluation of (1 + e_t) V / (1 + M/m_c).
            let expected = 1.75 * f64::from(v_cue) / (1.0 + POOL_M / 0.54);
            assert!(
                close(f64::from(out.speed), expected, 1e-6, 0.0),
                "{v_cue}: {} vs {expected}",
                out.speed
            );
            assert_eq!(out.spin, Vec3::ZERO);
        }
        // A hand-checked number: 2 m/s cue, 19 oz cue, 6 oz ball: 1.75·2/1.3148 = 2.662.
        let out = strike(&params, &Cue::TYPICAL, TipOffset::CENTRE, 2.0).unwrap();
        assert!(
            close(f64::from(out.speed), 2.662, 0.0, 5e-4),
            "{}",
            out.speed
        );
    }

    #[test]
    fn two_fifths_radius_above_centre_gives_natural_roll() {
        // The classic anchor: a hit at h = 2R/5 above centre needs no cloth friction to
        // roll, ω = v / R (TP A.30; TP 4.1).
        for params in [
            Params::POOL,
            Params::POOL.with_ball(0.02625, 0.142).unwrap(), // snooker
            Params::POOL.with_ball(0.03075, 0.21).unwrap(),  // carom
        ] {
            let r = params.radius();
            let tip = TipOffset::from_radius_fraction(0.0, 0.4, r).unwrap();
            let out = strike(&params, &Cue::TYPICAL, tip, 3.0).unwrap();
            let roll = f64::from(out.speed) / f64::from(r);
            assert!(close(f64::from(out.spin.y), roll, 1e-5, 0.0), "{:?}", out);
            assert_eq!(out.spin.x, 0.0);
            assert_eq!(out.spin.z, 0.0);
            // Natural roll: the table contact point is at rest, v + ω × (−R ẑ) = 0.
            let contact = out.velocity() + out.spin.cross(Vec3::new(0.0, 0.0, -r));
            assert!(contact.length() < 1e-5 * out.speed, "{contact:?}");
        }
    }

    #[test]
    fn offset_hits_match_an_independent_f64_evaluation() {
        let params = Params::POOL;
        let cue = Cue::new(0.5, 0.8).unwrap();
        let mut checked = 0;
        for i in -5..=5 {
            for j in -5..=5 {
                let (fs, fh) = (0.1 * f64::from(i), 0.1 * f64::from(j));
                let b2 = fs * fs + fh * fh;
                let tip =
                    TipOffset::from_radius_fraction(fs as f32, fh as f32, params.radius()).unwrap();
                let result = strike(&params, &cue, tip, 4.0);
                if b2 > 0.25 + 1e-9 {
                    assert!(result.is_err(), "({fs}, {fh}) must be refused");
                    continue;
                }
                let out = result.unwrap();
                let v = 1.8 * 4.0 / (1.0 + POOL_M / 0.5 + 2.5 * b2);
                let w = 2.5 * v / POOL_R;
                assert!(close(f64::from(out.speed), v, 1e-5, 0.0));
                assert!(close(f64::from(out.spin.y), w * fh, 1e-5, 1e-4));
                assert!(close(f64::from(out.spin.z), w * fs, 1e-5, 1e-4));
                checked += 1;
            }
        }
        assert!(checked > 60);
    }

    #[test]
    fn signs_follow_draw_and_english() {
        let params = Params::POOL;
        let r = params.radius();
        let s = |side: f32, height: f32| {
            let tip = TipOffset::from_radius_fraction(side, height, r).unwrap();
            strike(&params, &Cue::TYPICAL, tip, 2.0).unwrap().spin
        };
        assert!(s(0.0, 0.3).y > 0.0, "follow");
        assert!(s(0.0, -0.3).y < 0.0, "draw");
        assert!(
            s(0.3, 0.0).z > 0.0,
            "right english: counter-clockwise from above"
        );
        assert!(s(-0.3, 0.0).z < 0.0, "left english: clockwise from above");
        // Mirror symmetry: left/right english differ only in the sign of ω_z.
        let (right, left) = (s(0.25, 0.1), s(-0.25, 0.1));
        assert_eq!(right.y, left.y);
        assert_eq!(right.z, -left.z);
    }

    #[test]
    fn right_english_throws_object_ball_left() {
        // Spin-induced throw: right english throws the object ball to the shooter's left
        // (+y). Checked with the core's collision model on a head-on shot, so the strike
        // and the collision share one sign convention.
        let params = Params::POOL;
        let tip = TipOffset::from_radius_fraction(0.4, 0.0, params.radius()).unwrap();
        let hit = strike(&params, &Cue::TYPICAL, tip, 1.0).unwrap();
        let impact = hit.to_impact(0.0).unwrap();
        let out = collide(&params, &impact, Model::KimGrip).unwrap();
        assert!(out.object_ball.velocity.y > 0.0, "{out:?}");
        assert!(out.throw_angle_deg() > 0.0);
    }

    #[test]
    fn to_impact_rotates_natural_roll_with_the_cut() {
        let params = Params::POOL;
        let r = params.radius();
        let tip = TipOffset::from_radius_fraction(0.0, 0.4, r).unwrap();
        let hit = strike(&params, &Cue::TYPICAL, tip, 2.0).unwrap();
        for deg in [-60.0f32, -10.0, 0.0, 25.0, 45.0] {
            let impact = hit.to_impact(deg.to_radians()).unwrap();
            // Still natural roll in the collision frame: ω = ẑ × v / R.
            let v = impact.velocity();
            let roll = Vec3::new(0.0, 0.0, 1.0).cross(v) * (1.0 / r);
            let diff = impact.spin() - roll;
            assert!(diff.length() < 1e-4 * roll.length(), "{deg}: {diff:?}");
        }
        assert_eq!(
            hit.to_impact(f32::NAN),
            Err(Error::NotFinite {
                field: Field::CutAngle
            })
        );
    }

    #[test]
    fn energy_is_never_created_and_is_kept_at_unit_restitution() {
        // Cue speed after the strike from momentum, M v = m_c (V − V'), computed here.
        let params = Params::POOL;
        let r = f64::from(params.radius());
        let m = f64::from(params.mass());
        let inertia = 0.4 * m * r * r;
        for &(mass, e) in &[(0.54f32, 0.75f32), (0.45, 1.0), (0.6, 0.0), (0.2, 1.0)] {
            let cue = Cue::new(mass, e).unwrap();
            for k in 0..=10 {
                let frac = 0.05 * f64::from(k);
                let tip = TipOffset::from_radius_fraction(
                    0.6 * frac as f32,
                    0.8 * frac as f32,
                    params.radius(),
                )
                .unwrap();
                let out = strike(&params, &cue, tip, 3.0).unwrap();
                let (v, w) = (f64::from(out.speed), f64::from(out.spin.length()));
                let mc = f64::from(mass);
                let after_cue = 3.0 - m * v / mc;
                let before = 0.5 * mc * 9.0;
                let after =
                    0.5 * mc * after_cue * after_cue + 0.5 * m * v * v + 0.5 * inertia * w * w;
                if e == 1.0 {
                    assert!(
                        close(after, before, 1e-5, 0.0),
                        "{mass} {frac}: {after} vs {before}"
                    );
                } else {
                    assert!(after <= before * (1.0 + 1e-6), "{mass} {e} {frac}");
                }
            }
        }
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let p = Params::POOL;
        let c = Cue::TYPICAL;
        let centre = TipOffset::CENTRE;
        assert_eq!(
            strike(&p, &c, centre, 0.0),
            Err(Error::OutOfRange {
                field: Field::CueSpeed,
                value: 0.0
            })
        );
        assert_eq!(
            strike(&p, &c, centre, -1.0).unwrap_err().field(),
            Some(Field::CueSpeed)
        );
        assert_eq!(
            strike(&p, &c, centre, 25.0).unwrap_err().field(),
            Some(Field::CueSpeed)
        );
        assert_eq!(
            strike(&p, &c, centre, f32::NAN),
            Err(Error::NotFinite {
                field: Field::CueSpeed
            })
        );
        assert_eq!(
            strike(&p, &c, centre, f32::INFINITY).unwrap_err().field(),
            Some(Field::CueSpeed)
        );
        // Beyond the miscue limit, diagonally: each component alone would pass.
        let far = TipOffset::from_radius_fraction(0.4, 0.4, p.radius()).unwrap();
        match strike(&p, &c, far, 2.0) {
            Err(Error::OutOfRange {
                field: Field::TipOffset,
                value,
            }) => assert!((value - 0.5657 * p.radius()).abs() < 1e-4 * p.radius()),
            other => panic!("{other:?}"),
        }
        // Exactly on the limit is accepted.
        let edge = TipOffset::from_radius_fraction(0.0, -0.5, p.radius()).unwrap();
        assert!(strike(&p, &c, edge, 2.0).is_ok());
        // Huge but finite offsets must not overflow into an accepted NaN.
        let huge = TipOffset::new(3.0e38, 3.0e38).unwrap();
        assert_eq!(
            strike(&p, &c, huge, 2.0).unwrap_err().field(),
            Some(Field::TipOffset)
        );
        assert_eq!(
            TipOffset::new(f32::NAN, 0.0),
            Err(Error::NotFinite {
                field: Field::TipOffset
            })
        );
        assert_eq!(
            TipOffset::new(0.0, f32::NEG_INFINITY).unwrap_err().field(),
            Some(Field::TipOffset)
        );
        assert_eq!(
            Cue::new(0.05, 0.75).unwrap_err().field(),
            Some(Field::CueMass)
        );
        assert_eq!(
            Cue::new(f32::NAN, 0.75).unwrap_err().field(),
            Some(Field::CueMass)
        );
        assert_eq!(
            Cue::new(0.5, 1.2).unwrap_err().field(),
            Some(Field::TipRestitution)
        );
        assert_eq!(
            Cue::new(0.5, -0.1).unwrap_err().field(),
            Some(Field::TipRestitution)
        );
        assert_eq!(
            TipOffset::from_radius_fraction(0.1, 0.1, 0.0)
                .unwrap_err()
                .field(),
            Some(Field::Radius)
        );
    }

    #[test]
    fn outputs_stay_finite_over_the_accepted_range() {
        let p = Params::POOL;
        for &mass in &[0.1f32, 0.54, 2.0] {
            for &e in &[0.0f32, 0.75, 1.0] {
                let cue = Cue::new(mass, e).unwrap();
                for &v in &[f32::MIN_POSITIVE, 1e-3, 1.0, MAX_CUE_SPEED] {
                    for &(s, h) in &[(0.0f32, 0.0f32), (0.5, 0.0), (0.0, -0.5), (0.35, 0.35)] {
                        let tip = TipOffset::from_radius_fraction(s, h, p.radius()).unwrap();
                        let out = strike(&p, &cue, tip, v).unwrap();
                        assert!(out.speed.is_finite() && out.spin.is_finite());
                        assert!(out.speed >= 0.0);
                    }
                }
            }
        }
    }
}
