//! The event loop of [`crate::sim`]: cached event times, the earliest event, its
//! resolution.

use super::boundary::{Boundary, Edge};
use super::collapse::{along_cushion, jam, JAM_EVENTS, LOCK_SPEED, LOCK_TIME};
use super::pair::{closing_speed, contact_time, lock, resolve, State};
use super::schedule::Schedule;
use super::track::Track;
use super::{Event, EventKind, Setup, MAX_TIME};
use crate::error::{Error, Field, Result};
use crate::shot::{check_model, Stroke};
use crate::strike::strike;
use crate::table::{Scene, MAX_BALLS};
use crate::travel::Motion;
use crate::vector::Vec3;

/// A ball set moving: velocity (m/s, table frame; `z > 0` a hop) and spin (rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Launch {
    /// Index of the ball in the scene.
    pub ball: usize,
    /// Its velocity.
    pub velocity: Vec3,
    /// Its spin.
    pub spin: Vec3,
}

/// Where the balls ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Finish {
    rest: heapless::Vec<Option<Vec3>, MAX_BALLS>,
    /// Time from the stroke until the last ball stopped or dropped (s).
    pub time: f32,
    /// Events simulated.
    pub events: u32,
}

impl Finish {
    /// Where ball `ball` rests (m), `None` if it dropped into a pocket (or there is no
    /// such ball).
    pub fn position(&self, ball: usize) -> Option<Vec3> {
        self.rest.get(ball).copied().flatten()
    }

    /// Every ball's rest position in scene order, `None` for a pocketed one.
    pub fn positions(&self) -> &[Option<Vec3>] {
        &self.rest
    }
}

/// The balls' paths at an event: what the sink of [`simulate`] can draw.
pub struct Paths<'a> {
    balls: &'a [Ball],
}

impl Paths<'_> {
    /// Ball `ball`'s path from its last event on: the simulation time it starts (s) and
    /// the motion from there; `None` once the ball has dropped.
    pub fn motion(&self, ball: usize) -> Option<(f32, &Motion)> {
        let b = self.balls.get(ball)?;
        (!b.pocketed).then_some((b.track.since, &b.track.motion))
    }
}

#[derive(Clone, Copy, Debug)]
struct Ball {
    track: Track,
    pocketed: bool,
    /// Simulation time of the stop still to report (∞ when none is).
    rest: f32,
    /// Next exit from the cloth (∞ when none).
    exit: (f32, Option<Edge>),
    /// Exits are searched from this time on (or now, if later): a moment after a
    /// cushion contact found not to be one.
    exit_from: f32,
    /// When it last hit a cushion (s).
    last_cushion: Option<f32>,
    /// When it last took part in an event (s), and how many events it has had at that
    /// very time ([`JAM_EVENTS`](super::collapse::JAM_EVENTS)).
    last_event: f32,
    events_at_once: u16,
}

impl Ball {
    /// Count an event of this ball at `now`; `true` once it has had more than
    /// [`JAM_EVENTS`] at that very instant (it is jammed).
    fn note_event(&mut self, now: f32) -> bool {
        if self.last_event == now {
            self.events_at_once = self.events_at_once.saturating_add(1);
        } else {
            self.last_event = now;
            self.events_at_once = 1;
        }
        self.events_at_once > JAM_EVENTS
    }
}

/// Play `stroke` on `scene` (the cue ball is ball 0) and simulate the whole table.
/// `sink` sees every event as it happens, with the paths from it on.
///
/// Errors: those of [`simulate`], and the stroke's ([`crate::strike::strike`]).
pub fn play(
    scene: &Scene,
    stroke: &Stroke,
    setup: &Setup,
    sink: impl FnMut(&Event, &Paths<'_>),
) -> Result<Finish> {
    let shot = &setup.shot;
    let launch = strike(&shot.params, &shot.cue, stroke.tip, stroke.cue_speed)?;
    let aim = stroke.aim();
    let side = Vec3::new(-aim.y, aim.x, 0.0); // ẑ × aim
    let spin = aim * launch.spin.x + side * launch.spin.y + Vec3::new(0.0, 0.0, launch.spin.z);
    let cue = Launch {
        ball: 0,
        velocity: aim * launch.speed,
        spin,
    };
    simulate(scene, &[cue], setup, sink)
}

/// Simulate `scene`'s balls, at rest but for `launches`, until every ball rests or
/// drops. `sink` sees every event as it happens, with the paths from it on.
///
/// The scene keeps every ball on the cloth and no two overlapping. A ball may come to
/// rest in a pocket's mouth, hanging in the jaws, until something moves it.
///
/// Errors: the setup's ball radius is not the scene's ([`Field::SetupRadius`]), its
/// cushion, jaws or spin decay is out of range ([`Field::Cushion`],
/// [`Field::SpinDecay`]), a
/// launch names no ball ([`Field::BallIndex`]) or has a velocity or spin out of range
/// ([`Field::Velocity`], [`Field::Spin`]), the
/// `Auto` tolerance is out of range ([`Field::Tolerance`]), a collision's input is out
/// of the models' range, or the shot has not ended after `setup.max_events` events or
/// [`MAX_TIME`] ([`Error::Unfinished`]).
pub fn simulate(
    scene: &Scene,
    launches: &[Launch],
    setup: &Setup,
    mut sink: impl FnMut(&Event, &Paths<'_>),
) -> Result<Finish> {
    let radius = scene.radius();
    let params = &setup.shot.params;
    if crate::math::abs(params.radius() - radius) > 1e-6 * radius {
        return Err(Error::OutOfRange {
            field: Field::SetupRadius,
            value: params.radius(),
        });
    }
    setup.check(radius)?;
    check_model(setup.shot.model)?;
    let boundary = Boundary::new(scene.table(), &setup.jaws, radius);
    let cloth = &setup.shot.cloth;
    let mut balls: heapless::Vec<Ball, MAX_BALLS> = heapless::Vec::new();
    for &position in scene.balls() {
        let motion = Motion::new(position, Vec3::ZERO, Vec3::ZERO, radius, cloth)?;
        let ball = Ball {
            track: Track::new(motion, 0.0, setup.spin_decay),
            pocketed: false,
            rest: f32::INFINITY,
            exit: (f32::INFINITY, None),
            exit_from: 0.0,
            last_cushion: None,
            last_event: f32::NEG_INFINITY,
            events_at_once: 0,
        };
        // The scene holds at most MAX_BALLS.
        let _ = balls.push(ball);
    }
    let mut dirty: u32 = 0;
    for launch in launches {
        let ball = balls.get_mut(launch.ball).ok_or(Error::OutOfRange {
            field: Field::BallIndex,
            value: launch.ball as f32,
        })?;
        let position = ball.track.motion.start;
        let motion = Motion::new(position, launch.velocity, launch.spin, radius, cloth)?;
        ball.track = Track::new(motion, 0.0, setup.spin_decay);
        dirty |= 1 << launch.ball;
    }
    let reach = 2.0 * radius;
    let mut schedule = Schedule::new();
    let mut now = 0.0f32;
    let mut events = 0u16;
    let mut attempts = 0u32;
    loop {
        // Refresh every cached time that involves a ball whose path changed: first
        // their stops and exits, then their pairs, each searched only until the first
        // exit of either ball (there its path changes, and the pair is looked at
        // again).
        for i in 0..balls.len() {
            if dirty & (1 << i) == 0 {
                continue;
            }
            let ball = &mut balls[i];
            if ball.pocketed {
                ball.rest = f32::INFINITY;
                ball.exit = (f32::INFINITY, None);
            } else {
                let stop = ball.track.stop();
                ball.rest = if stop > ball.track.since {
                    stop
                } else {
                    f32::INFINITY
                };
                let from = if ball.exit_from > now {
                    ball.exit_from
                } else {
                    now
                };
                ball.exit = boundary
                    .exit(&ball.track, from)
                    .map_or((f32::INFINITY, None), |(t, edge)| (t, Some(edge)));
            }
        }
        for i in 0..balls.len() {
            if dirty & (1 << i) == 0 {
                continue;
            }
            for j in 0..balls.len() {
                if j == i || (dirty & (1 << j) != 0 && j < i) {
                    continue; // itself, or a pair already refreshed from j's side
                }
                schedule.set(i, j, pair_time(&balls[i], &balls[j], now, reach));
            }
        }
        dirty = 0;

        // The earliest event.
        let mut next: Option<(f32, EventKind, usize, Option<usize>)> = None;
        let mut consider = |time: f32, kind: EventKind, ball: usize, other: Option<usize>| {
            if time < f32::INFINITY && next.is_none_or(|(t, ..)| time < t) {
                next = Some((time, kind, ball, other));
            }
        };
        if let Some((time, i, j)) = schedule.earliest(balls.len()) {
            consider(time, EventKind::Ball, i, Some(j));
        }
        for (i, ball) in balls.iter().enumerate() {
            if let (time, Some(edge)) = ball.exit {
                let kind = match edge {
                    Edge::Pocket(pocket) => EventKind::Pocket(pocket),
                    Edge::Cushion(..) => EventKind::Cushion,
                };
                consider(time, kind, i, None);
            }
            consider(ball.rest, EventKind::Rest, i, None);
        }
        let Some((time, kind, i, other)) = next else {
            break;
        };
        // Every candidate counts towards the limit, those found not to happen too:
        // each of them moves time on (`later`), but only by a little.
        attempts += 1;
        if events >= setup.max_events
            || attempts > 4 * u32::from(setup.max_events)
            || time > MAX_TIME
        {
            return Err(Error::Unfinished { events, time: now });
        }
        now = if time > now { time } else { now };
        let state = |ball: &Ball| State {
            position: ball.track.position_at(now),
            velocity: ball.track.velocity_at(now),
            spin: ball.track.spin_at(now),
        };
        let position = balls[i].track.position_at(now);
        let restart = |state: &State| -> Result<Track> {
            let motion = Motion::new(state.position, state.velocity, state.spin, radius, cloth)?;
            Ok(Track::new(motion, now, setup.spin_decay))
        };
        // The pocket whose jaw a cushion event's cushion is.
        let mut jaw = None;
        let happened = match (kind, other) {
            (EventKind::Ball, Some(j)) => {
                let (a, b) = (state(&balls[i]), state(&balls[j]));
                let again = now - schedule.last_collision(i, j) < LOCK_TIME;
                let after = if again && closing_speed(&a, &b) < LOCK_SPEED {
                    Some(lock(&a, &b))
                } else {
                    resolve(params, setup.shot.model, &a, &b)?
                };
                match after {
                    Some((a, b)) => {
                        balls[i].track = restart(&a)?;
                        balls[j].track = restart(&b)?;
                        schedule.collided(i, j, now);
                        dirty |= (1 << i) | (1 << j);
                        true
                    }
                    None => {
                        // Not approaching at the contact after all: touching within
                        // rounding just after a collision, or a graze. Look again from a
                        // moment later (two balls pressed together by their
                        // decelerations then collide as soon as they approach).
                        let time = pair_time(&balls[i], &balls[j], later(now), reach);
                        schedule.set(i, j, time);
                        false
                    }
                }
            }
            (EventKind::Cushion, _) => {
                let ball = &balls[i];
                let Some(Edge::Cushion(normal, pocket)) = ball.exit.1 else {
                    return Err(Error::NumericalFailure);
                };
                jaw = pocket;
                let before = state(ball);
                let approach = before.velocity.dot(normal);
                if approach > 0.0 {
                    let again = ball.last_cushion.is_some_and(|t| now - t < LOCK_TIME);
                    let (velocity, spin) = if again && approach < LOCK_SPEED {
                        along_cushion(before.velocity, before.spin, normal)
                    } else {
                        setup
                            .cushion
                            .rebound(radius, before.velocity, before.spin, normal)
                    };
                    balls[i].track = restart(&State {
                        velocity,
                        spin,
                        ..before
                    })?;
                    balls[i].last_cushion = Some(now);
                    dirty |= 1 << i;
                    true
                } else {
                    // Not moving into the cushion at the line (within rounding): look
                    // again from a moment later (its pairs too: they were searched
                    // only until this exit).
                    balls[i].exit_from = later(now);
                    dirty |= 1 << i;
                    false
                }
            }
            (EventKind::Pocket(_), _) => {
                balls[i].pocketed = true;
                dirty |= 1 << i;
                true
            }
            _ => {
                balls[i].rest = f32::INFINITY;
                true
            }
        };
        if happened {
            let jammed = balls[i].note_event(now) | other.is_some_and(|j| balls[j].note_event(now));
            if jammed {
                dirty |= stop_jammed(&mut balls, now, radius, cloth, setup.spin_decay)?;
            }
            events += 1;
            let event = Event {
                time: now,
                kind,
                ball: i,
                other,
                position,
                jaw,
            };
            sink(&event, &Paths { balls: &balls });
        }
    }
    let mut rest = heapless::Vec::new();
    for ball in &balls {
        let _ = rest.push((!ball.pocketed).then(|| ball.track.motion.rest()));
    }
    Ok(Finish {
        rest,
        time: now,
        events: events.into(),
    })
}

/// The next contact of `a` and `b` from `from` on, searched until the first exit of
/// either from the cloth (∞ if none before, or either has dropped).
fn pair_time(a: &Ball, b: &Ball, from: f32, reach: f32) -> f32 {
    if a.pocketed || b.pocketed {
        return f32::INFINITY;
    }
    let horizon = if a.exit.0 < b.exit.0 {
        a.exit.0
    } else {
        b.exit.0
    };
    contact_time(&a.track, &b.track, from, reach, horizon).unwrap_or(f32::INFINITY)
}

/// Stop every ball that [`Ball::note_event`] found jammed ([`jam`]); returns their bits.
#[cold]
#[inline(never)]
fn stop_jammed(
    balls: &mut [Ball],
    now: f32,
    radius: f32,
    cloth: &crate::travel::Cloth,
    spin_decay: f32,
) -> Result<u32> {
    let mut stopped = 0;
    for (index, ball) in balls.iter_mut().enumerate() {
        if ball.last_event == now && ball.events_at_once > JAM_EVENTS {
            let (velocity, spin) = jam(ball.track.spin_at(now));
            let position = ball.track.position_at(now);
            let motion = Motion::new(position, velocity, spin, radius, cloth)?;
            ball.track = Track::new(motion, now, spin_decay);
            ball.events_at_once = 0;
            stopped |= 1 << index;
        }
    }
    Ok(stopped)
}

/// A moment after `t` (s): 1 µs, or a millionth of `t` where that is more (its f32
/// spacing is 1/8 of that at most): far shorter than any event of a shot, long enough
/// to move past a rounding.
fn later(t: f32) -> f32 {
    let step = 1e-6 * t;
    t + if step > 1e-6 { step } else { 1e-6 }
}
