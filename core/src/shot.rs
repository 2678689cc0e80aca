//! The forward shot chain: stroke → cue-ball travel → first contact → collision →
//! both balls' paths → pocket.
//!
//! 1. The cue strike (TP A.30, [`crate::strike`]) gives the cue ball's speed and spin
//!    in its travel frame; with a level cue the cloth slip is along the aim, so the cue
//!    ball travels straight (sliding, then rolling; [`crate::travel`]).
//! 2. The first ball whose centre comes within `2R` of the cue ball's path is hit
//!    (swept-sphere test, [`Scene::contact_distance`]), if the cue ball gets there with
//!    some speed towards it (a ball it reaches at rest, or grazes within rounding, is
//!    passed).
//! 3. At contact the line of centres fixes the collision frame (physics-notes §1): the
//!    cut angle and the collision-frame velocity and spin follow by projection, and the
//!    chosen model (normally `Auto`) predicts the outcome.
//! 4. Both balls' post-impact states, rotated back to the table, start their own
//!    [`Motion`]s; the object ball reaches a pocket if its centre crosses the pocket's
//!    target segment before it stops.

use crate::error::{check, Error, Field, Result};
use crate::impact::Impact;
use crate::math;
use crate::model::{collide, Model};
use crate::outcome::Outcome;
use crate::params::Params;
use crate::strike::{strike, Cue, Strike, TipOffset, MAX_CUE_SPEED};
use crate::table::Scene;
use crate::travel::{Cloth, Motion};
use crate::vector::Vec3;

/// A stroke: cue speed at the tip impact, tip offset, and horizontal aim direction.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stroke {
    /// Cue speed just before the tip hits the ball (m/s).
    pub cue_speed: f32,
    /// Tip offset from the ball centre.
    pub tip: TipOffset,
    aim: Vec3,
}

impl Stroke {
    /// Stroke at `cue_speed` (m/s, in `(0, 20]`, [`Field::CueSpeed`]) aimed along
    /// `direction` (table frame, any finite non-zero length, [`Field::Aim`]). The tip
    /// offset's bound needs the ball radius: [`play`] checks it.
    pub fn new(cue_speed: f32, tip: TipOffset, direction: [f32; 2]) -> Result<Self> {
        let cue_speed = check(Field::CueSpeed, cue_speed, 0.0, MAX_CUE_SPEED, true)?;
        let (x, y) = (direction[0], direction[1]);
        if !math::is_finite(x) || !math::is_finite(y) {
            return Err(Error::NotFinite { field: Field::Aim });
        }
        // Scaled by the larger component first, so that squaring neither underflows
        // (a subnormal direction lost its digits or came out zero) nor overflows.
        let scale = math::max(math::abs(x), math::abs(y));
        if scale == 0.0 {
            return Err(Error::OutOfRange {
                field: Field::Aim,
                value: 0.0,
            });
        }
        let (x, y) = (x / scale, y / scale);
        let length = math::sqrt(x * x + y * y);
        Ok(Self {
            cue_speed,
            tip,
            aim: Vec3::new(x / length, y / length, 0.0),
        })
    }

    /// Stroke aimed at `angle` (rad, counter-clockwise from the table's `x` axis, in
    /// `[-1000, 1000]`, [`Field::AimAngle`]).
    pub fn at_angle(cue_speed: f32, tip: TipOffset, angle: f32) -> Result<Self> {
        let angle = check(Field::AimAngle, angle, -1e3, 1e3, false)?;
        Self::new(cue_speed, tip, [math::cos(angle), math::sin(angle)])
    }

    /// Unit aim direction.
    pub const fn aim(&self) -> Vec3 {
        self.aim
    }
}

/// Everything the shot chain needs besides the scene and the stroke.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShotSetup {
    /// Collision parameters (its radius and mass must be the scene's balls').
    pub params: Params,
    /// The cue.
    pub cue: Cue,
    /// The cloth.
    pub cloth: Cloth,
    /// The collision model (e.g. `Model::Auto { tolerance: 1e-3 }`).
    pub model: Model,
}

/// The first collision of a shot and what follows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Index of the ball hit.
    pub object_ball: usize,
    /// Time from the strike to the contact (s).
    pub time: f32,
    /// Cue-ball centre at contact (m).
    pub cue_position: Vec3,
    /// Unit line of centres (the collision frame's `x`, table frame).
    pub line_of_centres: Vec3,
    /// Cut angle φ (rad): from the line of centres to the cue ball's velocity,
    /// counter-clockwise positive.
    pub cut_angle: f32,
    /// The collision-frame input handed to the model.
    pub impact: Impact,
    /// The model's output, collision frame.
    pub outcome: Outcome,
    /// Cue ball from the contact on (table frame).
    pub cue_after: Motion,
    /// Object ball from the contact on (table frame).
    pub object_after: Motion,
    /// First pocket whose target segment the object ball's centre crosses, with the
    /// time after the impact (s).
    pub pocket: Option<(usize, f32)>,
}

/// A played shot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    /// Cue-ball launch (travel frame: `x` along the aim).
    pub launch: Strike,
    /// Cue ball from the strike on, ignoring any collision.
    pub cue_before: Motion,
    /// The first collision, if the cue ball reaches a ball.
    pub contact: Option<Contact>,
}

/// Play `stroke` on `scene` with the model of `setup`.
///
/// Errors: the setup's ball radius is not the scene's ([`Field::SetupRadius`]), the
/// stroke's cue speed or tip offset is out of range ([`crate::strike::strike`]), an
/// `Auto` tolerance is out of range ([`Field::Tolerance`], whether or not a ball is
/// hit).
pub fn play(scene: &Scene, stroke: &Stroke, setup: &ShotSetup) -> Result<Shot> {
    // Completed where it lies: moving a `Shot` (several hundred bytes) out of its
    // `Result` and into a new one is two copies on the device (`memcpy`).
    let mut played = play_without_pocket(scene, stroke, setup);
    if let Ok(shot) = &mut played {
        find_pocket(shot, scene);
    }
    played
}

/// [`play`] but for [`Contact::pocket`], left at `None`: for the guidance, which follows
/// both balls' paths to their ends itself ([`crate::guidance`]).
pub(crate) fn play_without_pocket(
    scene: &Scene,
    stroke: &Stroke,
    setup: &ShotSetup,
) -> Result<Shot> {
    check_model(setup.model)?;
    let model = setup.model;
    play_chain(scene, stroke, setup, &mut |params, impact| {
        collide(params, impact, model)
    })
}

/// The `Auto` tolerance must be in `(0, 1]` (checked up front: `collide` checks it only
/// when a ball is hit).
pub(crate) fn check_model(model: Model) -> Result<()> {
    if let Model::Auto { tolerance } = model {
        check(Field::Tolerance, tolerance, 0.0, 1.0, true)?;
    }
    Ok(())
}

/// A collision predictor for the shot chain: the outcome of `impact` with `params`.
pub(crate) type Collision<'a> = dyn FnMut(&Params, &Impact) -> Result<Outcome> + 'a;

/// Play `stroke` on `scene`, predicting the collision with `collision` (e.g. a host-side
/// reference solver); `setup.model` is not used.
pub fn play_with<F>(
    scene: &Scene,
    stroke: &Stroke,
    setup: &ShotSetup,
    mut collision: F,
) -> Result<Shot>
where
    F: FnMut(&Params, &Impact) -> Result<Outcome>,
{
    let mut played = play_chain(scene, stroke, setup, &mut collision);
    if let Ok(shot) = &mut played {
        find_pocket(shot, scene);
    }
    played
}

/// The shot chain of [`play`] and [`play_with`] but for [`Contact::pocket`], which it
/// leaves at `None` ([`find_pocket`] adds it), with the collision behind a `dyn`
/// reference: the image holds one copy of the chain whatever the predictor, which
/// `play`, the guidance and the aim solver's forward evaluations ([`crate::aim`]) share
/// (each generic copy was about 2.5 KB on the Cortex-M4), and none of the pocket search
/// when only the guidance and the aim solver are linked (they follow the object ball
/// themselves).
pub(crate) fn play_chain(
    scene: &Scene,
    stroke: &Stroke,
    setup: &ShotSetup,
    collision: &mut Collision<'_>,
) -> Result<Shot> {
    let params = &setup.params;
    let radius = scene.radius();
    if math::abs(params.radius() - radius) > 1e-6 * radius {
        return Err(Error::OutOfRange {
            field: Field::SetupRadius,
            value: params.radius(),
        });
    }
    let launch = strike(params, &setup.cue, stroke.tip, stroke.cue_speed)?;
    let aim = stroke.aim;
    let side = Vec3::new(-aim.y, aim.x, 0.0); // ẑ × aim
    let travel = launch.velocity();
    let travel_spin = launch.spin;
    // A scene always holds its cue ball; `get` keeps the image free of a bounds panic.
    let cue_start = scene.balls().first().copied().unwrap_or(Vec3::ZERO);
    let velocity = aim * travel.x;
    let spin = aim * travel_spin.x + side * travel_spin.y + Vec3::new(0.0, 0.0, travel_spin.z);
    let cue_before = Motion::new(cue_start, velocity, spin, radius, &setup.cloth)?;

    // First ball on the path that the cue ball reaches with some speed towards it. A
    // ball it meets with no approach speed along the line of centres (it arrives at
    // rest there, or grazes it within rounding) is not hit: the cue ball passes on.
    const _: () = assert!(crate::table::MAX_BALLS <= 32);
    let mut passed: u32 = 0; // one bit per ball index
    let contact = loop {
        let mut first: Option<(usize, f32)> = None;
        for index in 1..scene.balls().len() {
            if passed & (1 << index) != 0 {
                continue;
            }
            if let Some(distance) = scene.contact_distance(aim, index) {
                if first.is_none_or(|(_, d)| distance < d) {
                    first = Some((index, distance));
                }
            }
        }
        let Some((index, time)) = first
            .and_then(|(index, distance)| Some((index, cue_before.time_to_reach(aim, distance)?)))
        else {
            break None;
        };
        match collide_at(scene, setup, &cue_before, aim, index, time, collision)? {
            Some(contact) => break Some(contact),
            None => passed |= 1 << index,
        }
    };
    Ok(Shot {
        launch,
        cue_before,
        contact,
    })
}

fn collide_at(
    scene: &Scene,
    setup: &ShotSetup,
    cue_before: &Motion,
    aim: Vec3,
    index: usize,
    time: f32,
    collision: &mut Collision<'_>,
) -> Result<Option<Contact>> {
    let radius = scene.radius();
    let cue_position = cue_before.position_at(time);
    let object_position = scene.balls().get(index).copied().ok_or(Error::OutOfRange {
        field: Field::BallIndex,
        value: index as f32,
    })?;
    // The line of centres from the contact geometry rather than from the computed
    // positions: exact for a straight shot (the positions' rounding turned it by an ulp
    // even then), exactly mirrored with the scene, and accurate to a few ε near a graze.
    let Some(centres) = scene.contact_line(aim, index) else {
        return Ok(None);
    };
    let across = Vec3::new(-centres.y, centres.x, 0.0); // collision-frame y = ẑ × x
    let v = cue_before.velocity_at(time);
    let w = cue_before.spin_at(time);
    let (v_x, v_y) = (v.dot(centres), v.dot(across));
    if v_x <= 0.0 || v_x.is_nan() {
        return Ok(None); // no approach: no collision
    }
    let impact = Impact::from_velocity([v_x, v_y], [w.dot(centres), w.dot(across), w.z])?;
    let outcome = collision(&setup.params, &impact)?;
    let to_table = |c: Vec3| to_table(centres, across, c);
    let cue_after = Motion::new(
        cue_position,
        to_table(outcome.cue_ball.velocity),
        to_table(outcome.cue_ball.spin),
        radius,
        &setup.cloth,
    )?;
    let object_after = Motion::new(
        object_position,
        to_table(outcome.object_ball.velocity),
        to_table(outcome.object_ball.spin),
        radius,
        &setup.cloth,
    )?;
    Ok(Some(Contact {
        object_ball: index,
        time,
        cue_position,
        line_of_centres: centres,
        cut_angle: math::atan2(v_y, v_x),
        impact,
        outcome,
        cue_after,
        object_after,
        pocket: None,
    }))
}

/// A collision-frame vector `c` in the table's frame (`x` along `centres`, `y` along
/// `across`). Out of line: its four copies inlined cost about 100 B of flash.
#[inline(never)]
fn to_table(centres: Vec3, across: Vec3, c: Vec3) -> Vec3 {
    centres * c.x + across * c.y + Vec3::new(0.0, 0.0, c.z)
}

/// Sets [`Contact::pocket`] of `shot`'s contact, if any: the first pocket of `scene`'s
/// table whose target segment the object ball's centre crosses.
fn find_pocket(shot: &mut Shot, scene: &Scene) {
    let Some(contact) = shot.contact.as_mut() else {
        return;
    };
    let object_after = &contact.object_after;
    let mut pocket: Option<(usize, f32)> = None;
    let reach = object_after.bounds();
    for (i, p) in scene.table().pockets().iter().enumerate() {
        // Cheap rejection: a pocket whose target segment lies outside the box around
        // the whole path cannot be crossed.
        if !reach.overlaps(p.a, p.b) {
            continue;
        }
        if let Some(t) = object_after.crossing(p.a, p.b) {
            if pocket.is_none_or(|(_, best)| t < best) {
                pocket = Some((i, t));
            }
        }
    }
    contact.pocket = pocket;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{BallSet, Table};

    fn setup(model: Model) -> ShotSetup {
        ShotSetup {
            params: Params::POOL,
            cue: Cue::TYPICAL,
            cloth: Cloth::TYPICAL,
            model,
        }
    }

    /// Bisect `f32` inputs between `lo` (where `hit` is true) and `hi` to adjacent values.
    fn bisect(mut lo: f32, mut hi: f32, hit: impl Fn(f32) -> bool) -> (f32, f32) {
        assert!(hit(lo) && !hit(hi));
        while lo.to_bits().abs_diff(hi.to_bits()) > 1 {
            let mid = f32::from_bits((lo.to_bits() + hi.to_bits()) / 2);
            if hit(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (lo, hi)
    }

    /// An aim that grazes the object ball to within rounding met it with a negative
    /// normal velocity, and `play` refused the valid shot (`velocity.x` out of range).
    /// Now such a graze is a miss; every aim across the hit/miss boundary plays.
    #[test]
    fn grazing_the_object_ball_within_rounding_is_a_miss_not_an_error() {
        let r = BallSet::POOL.radius;
        let mut scene = Scene::new(Table::pool(), r, [0.6, 0.508]).unwrap();
        scene.add_ball([1.1, 0.608]).unwrap();
        let setup = setup(Model::KimGrip);
        let d = (0.5f32).hypot(0.1);
        let boundary = (0.1f32).atan2(0.5) + (2.0 * r / d).asin();
        let hit = |angle: f32| {
            let stroke = Stroke::at_angle(3.0, TipOffset::CENTRE, angle).unwrap();
            let shot = play(&scene, &stroke, &setup);
            assert!(shot.is_ok(), "aim {angle}: {shot:?}");
            shot.unwrap().contact.is_some()
        };
        bisect(boundary - 1e-4, boundary + 1e-4, hit);
    }

    /// Aim directions of any finite non-zero size give the unit aim they point along:
    /// small components were squared into the subnormals or to zero (`[3e-22, -4e-22]`
    /// came out 0.1 % off unit length, `[1e-38, 1e-45]` was refused as a zero
    /// direction), and components above 1e6 were refused although finite.
    #[test]
    fn aim_directions_of_any_size_are_normalised() {
        extern crate std;
        let tiny = f32::from_bits(1);
        for (x, y) in [
            (tiny, 0.0f32),
            (0.0, -tiny),
            (3e-22, -4e-22),
            (1e-40, 1e-40),
            (3e-41, -4e-41),
            (1e-38, 1e-45),
            (3.0, 4.0),
            (-3e38, 3e38),
            (f32::MAX, -f32::MAX),
        ] {
            let aim = Stroke::new(1.0, TipOffset::CENTRE, [x, y]).unwrap().aim();
            let (x, y) = (f64::from(x), f64::from(y));
            let length = x.hypot(y);
            let (ex, ey) = (x / length, y / length);
            assert!(
                (f64::from(aim.x) - ex).abs() <= 2e-7 && (f64::from(aim.y) - ey).abs() <= 2e-7,
                "[{x:e}, {y:e}] -> {aim:?}"
            );
        }
        for (x, y) in [(0.0f32, 0.0f32), (-0.0, 0.0)] {
            assert_eq!(
                Stroke::new(1.0, TipOffset::CENTRE, [x, y]),
                Err(Error::OutOfRange {
                    field: Field::Aim,
                    value: 0.0
                })
            );
        }
        for (x, y) in [(f32::NAN, 1.0f32), (1.0, f32::INFINITY)] {
            assert_eq!(
                Stroke::new(1.0, TipOffset::CENTRE, [x, y]),
                Err(Error::NotFinite { field: Field::Aim })
            );
        }
    }

    /// Invalid strokes and setups were caught late or named the wrong field: a NaN or
    /// negative cue speed built a `Stroke` (refused only when played), an aim angle
    /// beyond ±1000 rad was reported as an aim direction, a setup for another ball
    /// size as a radius outside `[0.001, 1]` m (it was inside), and an `Auto` tolerance
    /// of NaN was accepted whenever no ball was hit.
    #[test]
    fn invalid_strokes_and_setups_name_their_field() {
        fn out<T>(field: Field, value: f32) -> Result<T> {
            Err(Error::OutOfRange { field, value })
        }
        let c = TipOffset::CENTRE;
        assert_eq!(
            Stroke::new(f32::NAN, c, [1.0, 0.0]),
            Err(Error::NotFinite {
                field: Field::CueSpeed
            })
        );
        assert_eq!(Stroke::new(-2.0, c, [1.0, 0.0]), out(Field::CueSpeed, -2.0));
        assert_eq!(Stroke::new(21.0, c, [1.0, 0.0]), out(Field::CueSpeed, 21.0));
        assert_eq!(Stroke::at_angle(2.0, c, 2e3), out(Field::AimAngle, 2e3));
        let r = BallSet::POOL.radius;
        let mut scene = Scene::new(Table::pool(), r, [0.5, 0.6]).unwrap();
        scene.add_ball([1.5, 0.6]).unwrap();
        let away = Stroke::new(2.0, c, [0.0, 1.0]).unwrap();
        let mut snooker = setup(Model::KimGrip);
        snooker.params = Params::POOL
            .with_ball(BallSet::SNOOKER.radius, BallSet::SNOOKER.mass)
            .unwrap();
        assert_eq!(
            play(&scene, &away, &snooker).map(|_| ()),
            out(Field::SetupRadius, BallSet::SNOOKER.radius)
        );
        let nan = setup(Model::Auto {
            tolerance: f32::NAN,
        });
        assert_eq!(
            play(&scene, &away, &nan).map(|_| ()),
            Err(Error::NotFinite {
                field: Field::Tolerance
            })
        );
    }

    /// A cue ball that stops exactly touching a ball arrived with zero speed, and `play`
    /// refused the valid shot (`velocity.x = 0`). Now it is no collision; every cue speed
    /// across the reach/stop-short boundary plays.
    #[test]
    fn cue_ball_stopping_exactly_at_a_ball_is_no_collision() {
        let r = BallSet::POOL.radius;
        // Both balls touching the end cushions (the case found: cue speed 0.7088298).
        let table = Table::pool();
        let mut scene = Scene::new(table.clone(), r, [r, 0.635]).unwrap();
        scene.add_ball([table.length() - r, 0.635]).unwrap();
        let setup = setup(Model::KimGrip);
        let reaches = |speed: f32| {
            let stroke = Stroke::new(speed, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
            let shot = play(&scene, &stroke, &setup);
            assert!(shot.is_ok(), "cue speed {speed}: {shot:?}");
            shot.unwrap().contact.is_some()
        };
        bisect(20.0, 0.1, reaches);
    }
}
