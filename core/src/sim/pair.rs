//! Two balls on the table: when they touch, and what the collision does.
//!
//! **When.** While both are in one motion phase each centre is a quadratic in time, so
//! with `d(σ) = ΔP + ΔQ σ + ΔS σ²` their difference the contact is the first rise of
//! the quartic `(2R)² − |d(σ)|²` through zero ([`first_rise`]), phase by phase over the
//! merged phase boundaries of the two. A box test on each phase's Bézier control
//! points skips the phases in which the two cannot come within `2R`.
//!
//! **What.** The collision models ([`collide`]) take a cue ball hitting an object ball
//! at rest with no spin. Two moving, spinning balls map onto that: in the frame moving
//! with ball `b`, `a` approaches with `v_a − v_b`; and for equal balls the ball–ball
//! contact's slip depends on the spins only through `ω_a + ω_b`, while its impulse
//! changes both spins by the same amount (the contact point is `+R n̂` from `a`'s centre
//! and `−R n̂` from `b`'s, the forces opposite), so `a` is given the spin sum and `b`
//! none. Each ball then keeps its own spin plus the change the model gives its
//! counterpart, and its velocity in the table frame. This is exact for the ball–ball
//! impulse; the models' table-contact terms (cue-ball/table friction during the impact,
//! seed §4) are evaluated as if `b` were at rest, which they are not when it moves.

use super::crossing::within_reach;
use super::roots::first_rise;
use super::track::{piece_at, Track};
use crate::error::Result;
use crate::impact::Impact;
use crate::model::{collide, Model};
use crate::params::Params;
use crate::vector::Vec3;

/// A ball's state at an instant: centre (m), velocity (m/s; `z > 0` a hop) and spin
/// (rad/s), table frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct State {
    pub position: Vec3,
    pub velocity: Vec3,
    pub spin: Vec3,
}

/// First time at or after `now` at which the centres of `a` and `b` come within `reach`
/// (m) while approaching, if they do before both stop and before `horizon` (s).
pub(crate) fn contact_time(
    a: &Track,
    b: &Track,
    now: f32,
    reach: f32,
    horizon: f32,
) -> Option<f32> {
    let end = if a.stop() > b.stop() {
        a.stop()
    } else {
        b.stop()
    };
    let end = if horizon < end { horizon } else { end };
    if end <= now {
        return None; // both at rest
    }
    // The boxes around the two whole paths, one grown by the reach, must meet.
    let (box_a, box_b) = (&a.bounds, &b.bounds);
    if box_a.min.x > box_b.max.x + reach
        || box_b.min.x > box_a.max.x + reach
        || box_a.min.y > box_b.max.y + reach
        || box_b.min.y > box_a.max.y + reach
    {
        return None;
    }
    let (pieces_a, pieces_b) = (a.pieces(), b.pieces());
    let mut from = now;
    while from < end {
        let (Some(pa), Some(pb)) = (piece_at(pieces_a, from), piece_at(pieces_b, from)) else {
            return None;
        };
        let to = if pa.to < pb.to { pa.to } else { pb.to };
        let to = if to < end { to } else { end };
        if to <= from || to.is_nan() {
            return None; // no progress: cannot happen with contiguous pieces
        }
        {
            let (p_a, q_a, s_a) = pa.at(from);
            let (p_b, q_b, s_b) = pb.at(from);
            let (dp, dq, ds) = (p_a - p_b, q_a - q_b, s_a - s_b);
            let span = to - from;
            if within_reach(dp, dq, ds, span, reach) {
                let reach2 = reach * reach;
                let c = [
                    reach2 - dp.dot(dp),
                    -2.0 * dp.dot(dq),
                    -(dq.dot(dq) + 2.0 * dp.dot(ds)),
                    -2.0 * dq.dot(ds),
                    -ds.dot(ds),
                ];
                let value = |x: f32| {
                    let d = dp + dq * x + ds * (x * x);
                    reach2 - d.dot(d)
                };
                if let Some(sigma) = first_rise(&c, span, value) {
                    return Some(from + sigma);
                }
            }
        }
        from = to;
    }
    None
}

/// Closing speed of `a` and `b` along their line of centres (m/s; negative when they
/// separate).
pub(crate) fn closing_speed(a: &State, b: &State) -> f32 {
    let line = b.position - a.position;
    let line = Vec3::new(line.x, line.y, 0.0);
    let distance = line.length();
    if distance <= 0.0 || distance.is_nan() {
        return 0.0;
    }
    (a.velocity - b.velocity).dot(line) * (1.0 / distance)
}

/// `a` and `b` locked together: both take the mean velocity and the mean spin, so that
/// they move as one, touching, until something else hits one of them. For two balls
/// pressed together by their different decelerations (one rolling into another that
/// slows along another direction), whose collisions would otherwise repeat without end
/// (inelastic collapse). Momentum is kept and kinetic energy does not grow: the mean's
/// square is at most the mean of the squares.
pub(crate) fn lock(a: &State, b: &State) -> (State, State) {
    let velocity = (a.velocity + b.velocity) * 0.5;
    let velocity = Vec3::new(velocity.x, velocity.y, 0.0);
    let spin = (a.spin + b.spin) * 0.5;
    (
        State {
            position: a.position,
            velocity,
            spin,
        },
        State {
            position: b.position,
            velocity,
            spin,
        },
    )
}

/// The states of `a` and `b` after they collide with `params` and `model`, or `None` if
/// they are not approaching along their line of centres (a graze within rounding).
pub(crate) fn resolve(
    params: &Params,
    model: Model,
    a: &State,
    b: &State,
) -> Result<Option<(State, State)>> {
    let line = b.position - a.position;
    let line = Vec3::new(line.x, line.y, 0.0);
    let distance = line.length();
    if distance <= 0.0 || distance.is_nan() {
        return Ok(None);
    }
    let centres = line * (1.0 / distance);
    let across = Vec3::new(-centres.y, centres.x, 0.0); // collision-frame y = ẑ × x
    let relative = a.velocity - b.velocity;
    let (v_x, v_y) = (relative.dot(centres), relative.dot(across));
    if v_x <= 0.0 || v_x.is_nan() {
        return Ok(None);
    }
    let spin = a.spin + b.spin;
    let impact = Impact::from_velocity([v_x, v_y], [spin.dot(centres), spin.dot(across), spin.z])?;
    let outcome = collide(params, &impact, model)?;
    let to_table = |c: Vec3| centres * c.x + across * c.y + Vec3::new(0.0, 0.0, c.z);
    let base = Vec3::new(b.velocity.x, b.velocity.y, 0.0);
    let after_a = State {
        position: a.position,
        velocity: base + to_table(outcome.cue_ball.velocity),
        spin: a.spin + to_table(outcome.cue_ball.spin) - spin,
    };
    let after_b = State {
        position: b.position,
        velocity: base + to_table(outcome.object_ball.velocity),
        spin: b.spin + to_table(outcome.object_ball.spin),
    };
    Ok(Some((after_a, after_b)))
}
