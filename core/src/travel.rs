//! A ball's motion on the cloth after a strike or a collision (TP A.4, TP 4.1): sliding
//! on a parabola until the contact rolls, then rolling in a straight line until rolling
//! resistance stops it; a ball lifted by the collision flies first.
//!
//! With the table-contact slip `u = v + ω × (−R ẑ) = (v_x − R ω_y, v_y + R ω_x)`, cloth
//! friction `μ_c M g` acts against `u`, whose direction stays constant while it slides
//! (TP A.4), so:
//!
//! * `r(t) = r₀ + v₀ t − ½ μ_c g t² û`, `v(t) = v₀ − μ_c g t û` for `t ≤ t_s`,
//!   `t_s = 2|u₀| / (7 μ_c g)` (the slip falls at `(1 + 1/ν) μ_c g = 3.5 μ_c g`);
//! * the rolling velocity `v_r = v₀ − (2/7) u₀` (`= 5/7 v₀ + 2/7 ω₀ × R ẑ`);
//! * then `|v|` falls at `μ_r g` along `v̂_r`: the ball stops after `|v_r| / (μ_r g)`, at
//!   `|v_r|² / (2 μ_r g)` from where it started rolling.
//!
//! A ball that leaves the cloth with `v_z > 0` flies for `2 v_z / g` (hop height
//! `v_z² / (2g)`) and lands with its horizontal velocity and spin unchanged (bounces,
//! spin decay about `z` and cushions are not modelled). Positions are in metres on the
//! table, times in seconds.

use crate::error::{check, Error, Field, Result};
use crate::math;
use crate::vector::Vec3;
use crate::NU;

/// Standard gravity (m/s²).
pub const GRAVITY: f32 = 9.81;

/// Largest velocity component a [`Motion`] accepts (m/s).
const MAX_VELOCITY: f32 = 1000.0;
/// Largest spin component a [`Motion`] accepts (rad/s).
const MAX_SPIN: f32 = 1e6;

/// Smallest accepted cloth sliding friction and rolling resistance ([`Cloth::new`]).
pub const MIN_CLOTH_FRICTION: f32 = 1e-3;

/// Ball–cloth friction.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cloth {
    sliding: f32,
    rolling: f32,
}

impl Cloth {
    /// Typical pool cloth: sliding μ_c = 0.2, rolling resistance μ_r = 0.01
    /// (physics-notes §5).
    pub const TYPICAL: Self = Self {
        sliding: 0.2,
        rolling: 0.01,
    };

    /// Sliding friction `μ_c` in `[0.001, 1]` and rolling resistance `μ_r` in
    /// `[0.001, 0.5]`. Real cloths are far inside (μ_c 0.15–0.4, μ_r 0.005–0.015); the
    /// lower bounds keep every time and distance finite: sliding lasts `2|u|/(7 μ_c g)`
    /// and rolling `|v|/(μ_r g)`, which overflow f32 as μ → 0 (at μ = 1e-45 the motion
    /// came out infinite and NaN).
    pub fn new(sliding: f32, rolling: f32) -> Result<Self> {
        Ok(Self {
            sliding: check(
                Field::ClothFriction,
                sliding,
                MIN_CLOTH_FRICTION,
                1.0,
                false,
            )?,
            rolling: check(
                Field::RollingResistance,
                rolling,
                MIN_CLOTH_FRICTION,
                0.5,
                false,
            )?,
        })
    }

    /// Sliding friction coefficient μ_c.
    pub const fn sliding(&self) -> f32 {
        self.sliding
    }

    /// Rolling resistance coefficient μ_r.
    pub const fn rolling(&self) -> f32 {
        self.rolling
    }
}

/// Closed-form motion of one ball from a starting state until it stops.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Motion {
    /// Where the ball starts (m; `z` ignored).
    pub start: Vec3,
    /// Flight time before it is back on the cloth (s; zero if it never leaves it).
    pub air_time: f32,
    /// Hop height of the centre above its resting height (m).
    pub hop_height: f32,
    /// Horizontal velocity when the cloth phase starts (m/s).
    pub initial_velocity: Vec3,
    /// Constant acceleration while sliding (m/s², horizontal).
    pub sliding_acceleration: Vec3,
    /// Sliding time (s) once on the cloth.
    pub sliding_time: f32,
    /// Velocity when pure rolling starts (m/s).
    pub rolling_velocity: Vec3,
    /// Rolling time until the ball stops (s).
    pub rolling_time: f32,
    /// Spin at the start (rad/s).
    pub initial_spin: Vec3,
    rolling_deceleration: f32,
    radius: f32,
}

impl Motion {
    /// Motion of a ball at `position` with velocity `velocity` (m/s; a positive `z` is a
    /// hop) and spin `spin` (rad/s), radius `radius` (m), on `cloth`.
    ///
    /// Errors: a position component not finite ([`Field::Position`]; the path may leave
    /// the table, as cushions are not modelled),
    /// a velocity component beyond ±1000 m/s ([`Field::Velocity`]), a spin component
    /// beyond ±1e6 rad/s ([`Field::Spin`]; what any collision of the valid domain can
    /// give, a 1 mm ball included), `radius` outside `[0.001, 1]` m ([`Field::Radius`]).
    /// Within them every time, velocity and position is finite.
    pub fn new(
        position: Vec3,
        velocity: Vec3,
        spin: Vec3,
        radius: f32,
        cloth: &Cloth,
    ) -> Result<Self> {
        // The usual, valid case in three squared norms: a norm within the bound puts
        // every component within it, and NaN, ±∞ or an overflowing square fail the
        // comparison. The component checks below then only run to accept a vector
        // whose norm alone is over (each component within) or to name what is wrong.
        if position.dot(position) <= f32::MAX
            && velocity.dot(velocity) <= MAX_VELOCITY * MAX_VELOCITY
            && spin.dot(spin) <= MAX_SPIN * MAX_SPIN
            && (0.001..=1.0).contains(&radius)
        {
            return Ok(Self::unchecked(position, velocity, spin, radius, cloth));
        }
        for x in [position.x, position.y, position.z] {
            if !math::is_finite(x) {
                return Err(Error::NotFinite {
                    field: Field::Position,
                });
            }
        }
        for v in [velocity.x, velocity.y, velocity.z] {
            check(Field::Velocity, v, -MAX_VELOCITY, MAX_VELOCITY, false)?;
        }
        for w in [spin.x, spin.y, spin.z] {
            check(Field::Spin, w, -MAX_SPIN, MAX_SPIN, false)?;
        }
        let radius = check(Field::Radius, radius, 0.001, 1.0, false)?;
        Ok(Self::unchecked(position, velocity, spin, radius, cloth))
    }

    /// [`Motion::new`] for inputs known to be in range.
    fn unchecked(position: Vec3, velocity: Vec3, spin: Vec3, radius: f32, cloth: &Cloth) -> Self {
        let air_time = if velocity.z > 0.0 {
            2.0 * velocity.z / GRAVITY
        } else {
            0.0
        };
        let hop_height = if velocity.z > 0.0 {
            velocity.z * velocity.z / (2.0 * GRAVITY)
        } else {
            0.0
        };
        let horizontal = Vec3::new(velocity.x, velocity.y, 0.0);
        let slip = Vec3::new(
            velocity.x - radius * spin.y,
            velocity.y + radius * spin.x,
            0.0,
        );
        let slip_speed = slip.length();
        let friction = cloth.sliding * GRAVITY;
        let (sliding_acceleration, sliding_time) = if slip_speed > 0.0 {
            (
                slip * (-friction / slip_speed),
                slip_speed / ((1.0 + 1.0 / NU) * friction),
            )
        } else {
            (Vec3::ZERO, 0.0)
        };
        let rolling_velocity = horizontal + sliding_acceleration * sliding_time;
        let rolling_deceleration = cloth.rolling * GRAVITY;
        let rolling_time = rolling_velocity.length() / rolling_deceleration;
        Self {
            start: Vec3::new(position.x, position.y, 0.0),
            air_time,
            hop_height,
            initial_velocity: horizontal,
            sliding_acceleration,
            sliding_time,
            rolling_velocity,
            rolling_time,
            initial_spin: spin,
            rolling_deceleration,
            radius,
        }
    }

    /// Spin at time `t` (s; a negative or NaN time is the start): constant in flight; while sliding the cloth friction's
    /// torque `(−R ẑ) × M a` turns it towards natural roll; then natural roll `ẑ × v / R`
    /// (the spin about `z` is kept: its slow decay is not modelled).
    pub fn spin_at(&self, t: f32) -> Vec3 {
        let t = start_clamped(t);
        let w = self.initial_spin;
        if t >= self.stop_time() {
            return Vec3::new(0.0, 0.0, w.z);
        }
        if t <= self.air_time {
            return w;
        }
        let sliding = t - self.air_time;
        if sliding <= self.sliding_time {
            let a = self.sliding_acceleration;
            return w + Vec3::new(a.y, -a.x, 0.0) * (sliding / (NU * self.radius));
        }
        let v = self.velocity_at(t);
        Vec3::new(-v.y / self.radius, v.x / self.radius, w.z)
    }

    /// Each phase as `r(τ) − start = p + q τ + s τ²`, `τ ∈ [0, span]`, starting at
    /// time `offset`. Displacements from the start rather than positions: they keep
    /// their digits whatever the start, and a mirrored start gives exactly mirrored
    /// times.
    pub(crate) fn phases(&self) -> [(f32, f32, Vec3, Vec3, Vec3); 3] {
        let speed = self.rolling_velocity.length();
        let rolling_direction = if speed > 0.0 {
            self.rolling_velocity * (1.0 / speed)
        } else {
            Vec3::ZERO
        };
        [
            (
                0.0,
                self.air_time,
                Vec3::ZERO,
                self.initial_velocity,
                Vec3::ZERO,
            ),
            (
                self.air_time,
                self.sliding_time,
                self.landing_offset(),
                self.initial_velocity,
                self.sliding_acceleration * 0.5,
            ),
            (
                self.air_time + self.sliding_time,
                self.rolling_time,
                self.rolling_offset(),
                self.rolling_velocity,
                rolling_direction * (-0.5 * self.rolling_deceleration),
            ),
        ]
    }

    /// First time (s) at which the centre has advanced `distance` (m) along the unit
    /// direction `direction` from the start, if it gets that far (0 for `distance ≤ 0`).
    pub fn time_to_reach(&self, direction: Vec3, distance: f32) -> Option<f32> {
        for (offset, span, p, q, s) in self.phases() {
            if span <= 0.0 {
                continue;
            }
            let c = direction.dot(p) - distance;
            if c >= 0.0 {
                // Already there when this phase starts: reached at the end of the
                // previous one, whose root rounding put just past its end.
                return Some(offset);
            }
            let mut roots = [f32::NAN; 2];
            solve_quadratic(direction.dot(s), direction.dot(q), c, &mut roots);
            let first = roots
                .into_iter()
                .filter(|tau| *tau >= 0.0 && *tau <= span)
                .fold(None, |best: Option<f32>, tau| {
                    Some(best.map_or(tau, |b| if tau < b { tau } else { b }))
                });
            if let Some(tau) = first {
                return Some(offset + tau);
            }
        }
        None
    }

    /// Time from the start until the ball stops (s): from then on `velocity_at` is zero
    /// and `position_at` is `rest()`. Out of line: five inlined copies in a firmware image
    /// were larger than their calls.
    #[inline(never)]
    pub fn stop_time(&self) -> f32 {
        self.air_time + self.sliding_time + self.rolling_time
    }

    /// Where the cloth phase starts (after any flight).
    pub fn landing(&self) -> Vec3 {
        self.start + self.landing_offset()
    }

    /// Where pure rolling starts.
    pub fn rolling_start(&self) -> Vec3 {
        self.start + self.rolling_offset()
    }

    /// Where the ball comes to rest.
    pub fn rest(&self) -> Vec3 {
        self.start + self.rest_offset()
    }

    /// Position at time `t` (s) after the start (clamped to the rest position; a
    /// negative or NaN time is the start).
    // Not inlined into its uses in the shot chain and the guidance (100 B of the
    // firmware's flash).
    #[inline(never)]
    pub fn position_at(&self, t: f32) -> Vec3 {
        self.start + self.displacement_at(t)
    }

    /// Displacement from the start at time `t` (s): [`Motion::position_at`] less the
    /// start, computed without it (so it keeps its digits far from the origin, and a
    /// mirrored motion gives an exactly mirrored displacement).
    pub fn displacement_at(&self, t: f32) -> Vec3 {
        let t = start_clamped(t);
        if t >= self.stop_time() {
            return self.rest_offset();
        }
        if t <= self.air_time {
            return self.initial_velocity * t;
        }
        let t = t - self.air_time;
        if t <= self.sliding_time {
            return self.landing_offset()
                + self.initial_velocity * t
                + self.sliding_acceleration * (0.5 * t * t);
        }
        let t = t - self.sliding_time;
        if t >= self.rolling_time {
            return self.rest_offset();
        }
        let speed = self.rolling_velocity.length();
        let travelled = speed * t - 0.5 * self.rolling_deceleration * t * t;
        self.rolling_offset() + self.rolling_velocity * (travelled / speed)
    }

    /// Displacement from the start where the cloth phase starts.
    fn landing_offset(&self) -> Vec3 {
        self.initial_velocity * self.air_time
    }

    /// Displacement from the start where pure rolling starts.
    fn rolling_offset(&self) -> Vec3 {
        let t = self.sliding_time;
        self.landing_offset()
            + self.initial_velocity * t
            + self.sliding_acceleration * (0.5 * t * t)
    }

    /// Displacement from the start at rest.
    fn rest_offset(&self) -> Vec3 {
        if self.rolling_velocity.length() == 0.0 {
            return self.rolling_offset();
        }
        self.rolling_offset() + self.rolling_velocity * (0.5 * self.rolling_time)
    }

    /// Velocity at time `t` (s) after the start (horizontal; a negative or NaN time is
    /// the start).
    pub fn velocity_at(&self, t: f32) -> Vec3 {
        let t = start_clamped(t);
        if t >= self.stop_time() {
            return Vec3::ZERO;
        }
        if t <= self.air_time {
            return self.initial_velocity;
        }
        let t = t - self.air_time;
        if t <= self.sliding_time {
            return self.initial_velocity + self.sliding_acceleration * t;
        }
        let t = t - self.sliding_time;
        if t >= self.rolling_time {
            return Vec3::ZERO;
        }
        let speed = self.rolling_velocity.length();
        self.rolling_velocity * ((speed - self.rolling_deceleration * t) / speed)
    }

    /// An axis-aligned box that contains the whole path: each phase is a straight line
    /// or a parabola, and a parabola lies inside the triangle of its Bézier control
    /// points `p`, `p + q T/2`, `p + q T + s T²`.
    pub fn bounds(&self) -> Bounds {
        let mut b = Bounds {
            min: self.start,
            max: self.start,
        };
        let landing = self.landing_offset();
        let control = landing + self.initial_velocity * (0.5 * self.sliding_time);
        for offset in [landing, control, self.rolling_offset(), self.rest_offset()] {
            b.include(self.start + offset);
        }
        b
    }

    /// First time (s) the centre crosses the segment from `a` to `b` (table plane), if
    /// it does before stopping. Each phase is a polynomial of degree ≤ 2 in time, so the
    /// crossings are roots of `n · (r(t) − a) = 0`, `n ⟂ (b − a)`, with
    /// `r(t) − a = (start − a) + displacement`.
    pub fn crossing(&self, a: Vec3, b: Vec3) -> Option<f32> {
        self.crossing_from(self.start - a, Vec3::new(b.x - a.x, b.y - a.y, 0.0), true)
    }

    /// First time (s) the centre crosses the whole line through `point` along
    /// `direction` (any non-zero length), if it does before stopping.
    pub fn crossing_line(&self, point: Vec3, direction: Vec3) -> Option<f32> {
        self.crossing_from(
            self.start - point,
            Vec3::new(direction.x, direction.y, 0.0),
            false,
        )
    }

    /// Crossing of the line through `start − base` along `along`; within the segment
    /// `along` long from there when `segment`. `base` is from the line's point to the
    /// start: the phases are displacements from the start.
    fn crossing_from(&self, base: Vec3, along: Vec3, segment: bool) -> Option<f32> {
        let normal = Vec3::new(-along.y, along.x, 0.0);
        let length_squared = along.dot(along);
        if length_squared == 0.0 {
            return None;
        }
        let within =
            |point: Vec3| !segment || (0.0..=1.0).contains(&(along.dot(point) / length_squared));
        // Side of the line at the previous phase's start, and whether that phase had a
        // root inside it.
        let mut previous: Option<(f32, bool)> = None;
        for (offset, span, p, q, s) in self.phases() {
            if span <= 0.0 {
                continue;
            }
            let c0 = normal.dot(base + p);
            if let Some((side, crossed)) = previous {
                if !crossed && side * c0 < 0.0 {
                    // The previous phase ended on the other side without a root inside
                    // it: its crossing rounded to just past its end. It is here.
                    if within(base + p) {
                        return Some(offset);
                    }
                }
            }
            let c1 = normal.dot(q);
            let c2 = normal.dot(s);
            let mut roots = [f32::NAN; 2];
            solve_quadratic(c2, c1, c0, &mut roots);
            let mut best: Option<f32> = None;
            let mut crossed = false;
            for tau in roots {
                if !(tau >= 0.0 && tau <= span) {
                    continue;
                }
                crossed = true;
                let point = base + p + q * tau + s * (tau * tau);
                if within(point) && best.is_none_or(|b| tau < b) {
                    best = Some(tau);
                }
            }
            if let Some(tau) = best {
                return Some(offset + tau);
            }
            previous = Some((c0, crossed));
        }
        None
    }
}

/// `t` for `t > 0`, else 0 (negative times and NaN are the start).
fn start_clamped(t: f32) -> f32 {
    if t > 0.0 {
        t
    } else {
        0.0
    }
}

/// An axis-aligned box in the table plane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Bounds {
    /// Smallest `x`, `y`.
    pub min: Vec3,
    /// Largest `x`, `y`.
    pub max: Vec3,
}

impl Bounds {
    fn include(&mut self, p: Vec3) {
        self.min = Vec3::new(
            if p.x < self.min.x { p.x } else { self.min.x },
            if p.y < self.min.y { p.y } else { self.min.y },
            0.0,
        );
        self.max = Vec3::new(
            if p.x > self.max.x { p.x } else { self.max.x },
            if p.y > self.max.y { p.y } else { self.max.y },
            0.0,
        );
    }

    /// `true` when the box around the segment from `a` to `b` overlaps this one.
    pub fn overlaps(&self, a: Vec3, b: Vec3) -> bool {
        let (low_x, high_x) = if a.x < b.x { (a.x, b.x) } else { (b.x, a.x) };
        let (low_y, high_y) = if a.y < b.y { (a.y, b.y) } else { (b.y, a.y) };
        high_x >= self.min.x && low_x <= self.max.x && high_y >= self.min.y && low_y <= self.max.y
    }
}

/// Real roots of `a x² + b x + c = 0` into `roots` (NaN where absent), stable form.
fn solve_quadratic(a: f32, b: f32, c: f32, roots: &mut [f32; 2]) {
    let scale = math::max(math::max(math::abs(a), math::abs(b)), math::abs(c));
    if scale == 0.0 {
        return;
    }
    if math::abs(a) <= 1e-7 * scale {
        if b != 0.0 {
            roots[0] = -c / b;
        }
        return;
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return;
    }
    let root = math::sqrt(discriminant);
    let q = -0.5 * (b + if b >= 0.0 { root } else { -root });
    roots[0] = q / a;
    if q != 0.0 {
        roots[1] = c / q;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f32 = 0.028575;

    #[test]
    fn stun_ball_rolls_at_five_sevenths_after_tp_4_1_distance() {
        let v0 = 2.0;
        let m = Motion::new(
            Vec3::ZERO,
            Vec3::new(v0, 0.0, 0.0),
            Vec3::ZERO,
            R,
            &Cloth::TYPICAL,
        )
        .unwrap();
        assert!((m.rolling_velocity.x - 5.0 / 7.0 * v0).abs() < 1e-5);
        let expected = 12.0 * v0 * v0 / (49.0 * 0.2 * GRAVITY); // TP 4.1
        assert!(
            (m.rolling_start().x - expected).abs() < 1e-5,
            "{}",
            m.rolling_start().x
        );
    }

    #[test]
    fn natural_roll_does_not_slide() {
        let v = Vec3::new(1.0, 0.5, 0.0);
        let spin = Vec3::new(-0.5 / R, 1.0 / R, 0.0);
        let m = Motion::new(Vec3::ZERO, v, spin, R, &Cloth::TYPICAL).unwrap();
        assert!(m.sliding_time < 1e-6);
        assert!((m.rest() - v * (v.length() / (2.0 * 0.01 * GRAVITY))).length() < 1e-4);
    }

    /// Targets within a few ulp of where sliding ends were not reached at all: the
    /// sliding phase's root rounded to just past its end, and the rolling phase started
    /// already past the target (found in a played shot: a carom ball with draw at
    /// 0.5 m/s missed an object ball it reaches). Every distance and line around the
    /// switch is now reached, at times continuous across it.
    #[test]
    fn targets_at_the_sliding_to_rolling_switch_are_reached() {
        let mut gaps = 0;
        for radius in [0.028575f32, 0.02625, 0.03075] {
            for speed in [0.3f32, 0.6, 1.1, 2.0] {
                for draw in [0.0f32, -0.5, -1.1, 0.6] {
                    let m = Motion::new(
                        Vec3::new(0.2, 0.7, 0.0),
                        Vec3::new(speed, 0.0, 0.0),
                        Vec3::new(0.0, draw * speed / radius, 0.0),
                        radius,
                        &Cloth::TYPICAL,
                    )
                    .unwrap();
                    let dir = Vec3::new(1.0, 0.0, 0.0);
                    let switch = m.rolling_start().x - m.start.x;
                    let mut d = switch;
                    for _ in 0..64 {
                        d = f32::from_bits(d.to_bits() - 1);
                    }
                    for _ in 0..128 {
                        let t = m.time_to_reach(dir, d);
                        let x = m.start.x + d;
                        let c = m.crossing(Vec3::new(x, 0.0, 0.0), Vec3::new(x, 2.0, 0.0));
                        match (t, c) {
                            (Some(t), Some(c)) => {
                                let near = (t - m.sliding_time).abs() < 1e-4;
                                assert!(near && (c - m.sliding_time).abs() < 1e-4, "{t} {c}");
                            }
                            _ => gaps += 1,
                        }
                        d = f32::from_bits(d.to_bits() + 1);
                    }
                }
            }
        }
        assert_eq!(gaps, 0, "targets near the switch not reached");
    }

    /// Cloth friction and rolling resistance down to the smallest positive f32 were
    /// accepted; the motion then slid or rolled for an infinite time and its rolling
    /// velocity and rest position were infinite or NaN. Now the smallest accepted values
    /// give finite motions at the largest speeds and spins, and anything below is refused.
    #[test]
    fn cloth_friction_is_bounded_away_from_zero() {
        for (sliding, rolling) in [
            (f32::from_bits(1), 0.01),
            (0.2, f32::from_bits(1)),
            (9e-4, 0.01),
            (0.2, 9e-4),
        ] {
            let field = if sliding < MIN_CLOTH_FRICTION {
                Field::ClothFriction
            } else {
                Field::RollingResistance
            };
            let value = if sliding < MIN_CLOTH_FRICTION {
                sliding
            } else {
                rolling
            };
            assert_eq!(
                Cloth::new(sliding, rolling),
                Err(Error::OutOfRange { field, value })
            );
        }
        let least = Cloth::new(MIN_CLOTH_FRICTION, MIN_CLOTH_FRICTION).unwrap();
        let m = Motion::new(
            Vec3::new(1.0, 0.5, 0.0),
            Vec3::new(100.0, -100.0, 20.0),
            Vec3::new(1e4, -1e4, 1e4),
            1.0,
            &least,
        )
        .unwrap();
        for v in [
            m.rolling_velocity,
            m.rolling_start(),
            m.rest(),
            m.position_at(1e3),
        ] {
            assert!(v.is_finite(), "{m:?}");
        }
        assert!(m.stop_time().is_finite(), "{m:?}");
    }

    /// `Motion::new` took any state: a NaN or infinite position, velocity, spin or
    /// radius (or a radius of zero) gave NaN times and positions, and a NaN time gave
    /// a NaN position. Now the state is validated, field by field, and a NaN or
    /// negative time is the start.
    #[test]
    fn motion_state_is_validated() {
        let (p, v, w) = (
            Vec3::new(1.0, 0.5, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::ZERO,
        );
        let new = |p: Vec3, v: Vec3, w: Vec3, r: f32| Motion::new(p, v, w, r, &Cloth::TYPICAL);
        let nan = f32::NAN;
        let not_finite = |field| Err(Error::NotFinite { field });
        assert_eq!(
            new(Vec3::new(nan, 0.5, 0.0), v, w, R),
            not_finite(Field::Position)
        );
        assert_eq!(
            new(p, Vec3::new(1.0, f32::INFINITY, 0.0), w, R),
            not_finite(Field::Velocity)
        );
        assert_eq!(
            new(p, v, Vec3::new(0.0, 0.0, nan), R),
            not_finite(Field::Spin)
        );
        assert_eq!(new(p, v, w, nan), not_finite(Field::Radius));
        let out = |field, value| Err(Error::OutOfRange { field, value });
        assert_eq!(new(p, v, w, 0.0), out(Field::Radius, 0.0));
        assert_eq!(
            new(p, Vec3::new(-1e30, 0.0, 0.0), w, R),
            out(Field::Velocity, -1e30)
        );
        assert_eq!(
            new(p, v, Vec3::new(2e6, 0.0, 0.0), R),
            out(Field::Spin, 2e6)
        );
        let far = new(Vec3::new(1.0, -3e38, 0.0), v, w, R).unwrap();
        assert!(far.rest().is_finite() && far.bounds().min.is_finite());
        let m = new(p, Vec3::new(1.0, 0.2, 0.3), Vec3::new(0.0, -9.0, 4.0), R).unwrap();
        for t in [nan, -1.0, f32::NEG_INFINITY] {
            assert_eq!(m.position_at(t), m.start);
            assert_eq!(m.velocity_at(t), m.initial_velocity);
            assert_eq!(m.spin_at(t), m.initial_spin);
        }
    }

    /// Times and displacements do not depend on where the motion starts, and a motion
    /// mirrored across a line `y = c` (start on a grid where `2c − y` is exact) has
    /// exactly mirrored displacements and exactly the same times to reach a distance
    /// and to cross a mirrored segment. Before, the phases were absolute positions: the
    /// start's rounding entered every time (a contact while rolling, the pocket a ball
    /// reaches), and the mirror image of a shot differed in the last bits.
    #[test]
    fn times_and_displacements_are_independent_of_the_start_and_mirror_exactly() {
        let w = 1.27f32;
        for (v, spin, vz) in [
            (Vec3::new(1.3, 0.4, 0.0), Vec3::new(-9.0, 35.0, 12.0), 0.0),
            (Vec3::new(-0.7, 1.1, 0.0), Vec3::new(20.0, -50.0, -3.0), 0.3),
            (Vec3::new(2.0, -0.2, 0.0), Vec3::new(0.0, -80.0, 0.0), 0.0),
        ] {
            let v = Vec3::new(v.x, v.y, vz);
            let mirror_v = Vec3::new(v.x, -v.y, v.z);
            let mirror_w = Vec3::new(-spin.x, spin.y, -spin.z);
            let start = Vec3::new(0.75, 0.3125, 0.0);
            let image = Vec3::new(0.75, w - 0.3125, 0.0);
            let m = Motion::new(start, v, spin, R, &Cloth::TYPICAL).unwrap();
            let far =
                Motion::new(Vec3::new(700.0, -300.0, 0.0), v, spin, R, &Cloth::TYPICAL).unwrap();
            let n = Motion::new(image, mirror_v, mirror_w, R, &Cloth::TYPICAL).unwrap();
            for k in 0..=20 {
                let t = m.stop_time() * k as f32 / 16.0;
                let d = m.displacement_at(t);
                assert_eq!(far.displacement_at(t), d);
                assert_eq!(n.displacement_at(t), Vec3::new(d.x, -d.y, d.z));
            }
            for distance in [0.01f32, 0.2, 0.5, 1.0] {
                let dir = Vec3::new(v.x, v.y, 0.0) * (1.0 / Vec3::new(v.x, v.y, 0.0).length());
                let mirror_dir = Vec3::new(dir.x, -dir.y, 0.0);
                assert_eq!(
                    m.time_to_reach(dir, distance),
                    n.time_to_reach(mirror_dir, distance)
                );
            }
            for (a, b) in [
                (Vec3::new(0.0, 0.5, 0.0), Vec3::new(3.0, 0.5, 0.0)),
                (Vec3::new(1.0, -1.0, 0.0), Vec3::new(1.25, 2.0, 0.0)),
                (Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0)),
            ] {
                let mirror = |p: Vec3| Vec3::new(p.x, w - p.y, 0.0);
                assert_eq!(m.crossing(a, b), n.crossing(mirror(a), mirror(b)));
            }
        }
    }

    /// At `stop_time` the ball had not always stopped: the time left for rolling,
    /// `(stop − air) − slide`, could round below `rolling_time`, so `velocity_at`
    /// returned 9e-10 m/s and `position_at` a point short of `rest()` (found by the
    /// shot property tests: a carom cue ball after a collision). Now it is at rest from
    /// `stop_time` on, exactly.
    #[test]
    fn at_stop_time_the_ball_is_at_rest() {
        let m = Motion::new(
            Vec3::new(0.24805266, 0.16890776, 0.0),
            Vec3::new(0.01979271, 0.00034801944, 0.0),
            Vec3::new(0.00039084745, -0.022228442, -0.18809207),
            0.03075,
            &Cloth::new(0.001_302_2, 0.001_733_14).unwrap(),
        )
        .unwrap();
        let mut checked = 0;
        for (v, w) in [
            (m.initial_velocity, m.initial_spin),
            (Vec3::new(1.3, -0.4, 0.2), Vec3::new(12.0, -40.0, 9.0)),
            (Vec3::new(0.3, 0.0, 0.0), Vec3::new(0.0, -30.0, 0.0)),
        ] {
            for speed in 1..=64 {
                let v = v * (speed as f32 / 16.0);
                let slow = Cloth::new(0.001_302_2, 0.001_733_14).unwrap();
                for cloth in [Cloth::TYPICAL, Cloth::new(0.001, 0.4).unwrap(), slow] {
                    let m = Motion::new(m.start, v, w, 0.03075, &cloth).unwrap();
                    let stop = m.stop_time();
                    assert_eq!(m.velocity_at(stop), Vec3::ZERO, "{m:?}");
                    assert_eq!(m.position_at(stop), m.rest(), "{m:?}");
                    assert_eq!(m.spin_at(stop), Vec3::new(0.0, 0.0, w.z), "{m:?}");
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 576);
    }

    #[test]
    fn crossing_finds_a_segment_ahead_and_ignores_one_behind() {
        let m = Motion::new(
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::ZERO,
            R,
            &Cloth::TYPICAL,
        )
        .unwrap();
        let t = m
            .crossing(Vec3::new(1.0, -0.1, 0.0), Vec3::new(1.0, 0.1, 0.0))
            .unwrap();
        assert!((m.position_at(t).x - 1.0).abs() < 1e-4);
        assert!(m
            .crossing(Vec3::new(-1.0, -0.1, 0.0), Vec3::new(-1.0, 0.1, 0.0))
            .is_none());
        assert!(m
            .crossing(Vec3::new(1.0, 0.05, 0.0), Vec3::new(1.0, 0.1, 0.0))
            .is_none());
    }
}
