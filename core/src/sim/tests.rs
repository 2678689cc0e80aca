//! The simulation's invariants over random tables, its typed errors and named cases.

use super::*;
use crate::shot::Stroke;
use crate::strike::TipOffset;
use crate::table::{BallSet, Scene, Table};
use crate::{Error, NU};

const R: f32 = BallSet::POOL.radius;

/// Kinetic energy per unit mass of a ball (J/kg): `½|v|² + ½ ν R² |ω|²`.
fn energy(velocity: Vec3, spin: Vec3) -> f32 {
    0.5 * velocity.dot(velocity) + 0.5 * NU * R * R * spin.dot(spin)
}

/// A small xorshift for reproducible scenes without a dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, low: f32, high: f32) -> f32 {
        low + (high - low) * self.next()
    }
}

fn random_scene(rng: &mut Rng, table: Table, balls: usize) -> Scene {
    let mut scene = Scene::new(
        table.clone(),
        R,
        [
            rng.range(0.2, table.length() - 0.2),
            rng.range(0.2, table.width() - 0.2),
        ],
    )
    .unwrap();
    while scene.balls().len() < balls {
        let _ = scene.add_ball([
            rng.range(0.1, table.length() - 0.1),
            rng.range(0.1, table.width() - 0.1),
        ]);
    }
    scene
}

/// The first `N` events (kind, ball) of `stroke` played on `scene` with the pool setup,
/// how many events there were, and the finish.
fn first_events<const N: usize>(
    scene: &Scene,
    stroke: &Stroke,
) -> ([Option<(EventKind, usize)>; N], usize, Finish) {
    let mut kinds = [None; N];
    let mut n = 0;
    let end = play(scene, stroke, &Setup::POOL, |event, _| {
        if let Some(slot) = kinds.get_mut(n) {
            *slot = Some((event.kind, event.ball));
        }
        n += 1;
    })
    .unwrap();
    (kinds, n, end)
}

#[test]
fn a_stun_shot_stops_the_cue_ball_and_sends_the_object_ball_off_the_far_cushion() {
    let mut scene = Scene::new(Table::pool(), R, [0.635, 0.635]).unwrap();
    scene.add_ball([1.27, 0.635]).unwrap();
    let stroke = Stroke::new(3.0, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
    let (kinds, n, end) = first_events::<8>(&scene, &stroke);
    assert_eq!(kinds[0], Some((EventKind::Ball, 0)), "{kinds:?}");
    assert!(
        kinds[..n].contains(&Some((EventKind::Cushion, 1))),
        "{kinds:?}"
    );
    // The object ball comes back along the long axis and rests on it.
    let one = end.position(1).unwrap();
    assert!((one.y - 0.635).abs() < 1e-3, "{one:?}");
}

#[test]
fn energy_never_grows_and_balls_never_overlap_at_any_event() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut checked = 0;
    for scene_index in 0..400 {
        let table = [Table::pool(), Table::carom(), Table::snooker()][scene_index % 3].clone();
        let scene = random_scene(&mut rng, table, 2 + scene_index % 15);
        let angle = rng.range(-3.2, 3.2);
        let tip = TipOffset::new(rng.range(-0.35, 0.35) * R, rng.range(-0.35, 0.35) * R).unwrap();
        let stroke = Stroke::at_angle(rng.range(0.3, 8.0), tip, angle).unwrap();
        let mut previous = f32::INFINITY;
        let mut last_time = 0.0f32;
        let result = play(&scene, &stroke, &Setup::POOL, |event, paths| {
            assert!(event.time >= last_time, "events out of order: {event:?}");
            last_time = event.time;
            let mut total = 0.0;
            let mut centres = [None; 16];
            for (i, centre) in centres.iter_mut().enumerate() {
                if let Some((since, motion)) = paths.motion(i) {
                    let t = event.time - since;
                    total += energy(motion.velocity_at(t), motion.spin_at(t));
                    *centre = Some(motion.position_at(t));
                }
            }
            assert!(
                total <= previous * (1.0 + 1e-5) + 1e-9,
                "scene {scene_index}: energy {previous} -> {total} at {event:?}"
            );
            previous = total;
            for i in 0..16 {
                for j in i + 1..16 {
                    if let (Some(a), Some(b)) = (centres[i], centres[j]) {
                        let d = (a - b).length();
                        assert!(
                            d >= 2.0 * R * (1.0 - 1e-4),
                            "scene {scene_index}: balls {i}, {j} {d} apart at {event:?}"
                        );
                    }
                }
            }
        });
        match result {
            Ok(_) => checked += 1,
            Err(Error::Unfinished { .. }) => {}
            Err(e) => panic!("scene {scene_index}: {e}"),
        }
    }
    assert!(checked >= 390, "{checked}");
}

#[test]
fn every_bad_input_is_a_typed_error_naming_it() {
    let mut scene = Scene::new(Table::pool(), R, [0.635, 0.635]).unwrap();
    scene.add_ball([1.27, 0.635]).unwrap();
    let stroke = Stroke::new(3.0, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
    let field = |result: crate::Result<Finish>| result.unwrap_err().field();
    // A shot that does not end within its event limit.
    let short = Setup {
        max_events: 2,
        ..Setup::POOL
    };
    assert!(matches!(
        play(&scene, &stroke, &short, |_, _| {}),
        Err(Error::Unfinished { events: 2, .. })
    ));
    // Cushions whose nose is below the ball's equator or above its top.
    for height in [0.9 * R, 2.0 * R] {
        let low = Setup {
            cushion: Cushion::new(0.85, 0.2, height).unwrap(),
            ..Setup::POOL
        };
        assert_eq!(
            field(play(&scene, &stroke, &low, |_, _| {})),
            Some(crate::Field::Cushion)
        );
    }
    assert_eq!(
        Cushion::new(1.5, 0.2, 0.03).unwrap_err().field(),
        Some(crate::Field::Cushion)
    );
    assert_eq!(
        Cushion::new(0.8, f32::NAN, 0.03).unwrap_err().field(),
        Some(crate::Field::Cushion)
    );
    let spin = Setup {
        spin_decay: -1.0,
        ..Setup::POOL
    };
    assert_eq!(
        field(play(&scene, &stroke, &spin, |_, _| {})),
        Some(crate::Field::SpinDecay)
    );
    // Balls of another size than the setup's.
    assert_eq!(
        field(play(&scene, &stroke, &Setup::carom().unwrap(), |_, _| {})),
        Some(crate::Field::SetupRadius)
    );
    // A launch of a ball that is not there, or out of range.
    let launch = |ball, speed| {
        [Launch {
            ball,
            velocity: Vec3::new(speed, 0.0, 0.0),
            spin: Vec3::ZERO,
        }]
    };
    assert_eq!(
        field(simulate(&scene, &launch(5, 1.0), &Setup::POOL, |_, _| {})),
        Some(crate::Field::BallIndex)
    );
    assert_eq!(
        field(simulate(&scene, &launch(1, 2e3), &Setup::POOL, |_, _| {})),
        Some(crate::Field::Velocity)
    );
    // Capacity and overlap are the scene's: it never holds more than 16 balls or two
    // overlapping ones (`Scene::add_ball`).
}

#[test]
fn a_three_cushion_carom_shot_plays_to_the_end() {
    let setup = Setup::carom().unwrap();
    let r = BallSet::CAROM.radius;
    let mut scene = Scene::new(Table::carom(), r, [0.7, 0.4]).unwrap();
    scene.add_ball([1.4, 0.9]).unwrap();
    scene.add_ball([2.2, 1.1]).unwrap();
    let stroke = Stroke::at_angle(4.0, TipOffset::new(0.3 * r, 0.2 * r).unwrap(), 0.6).unwrap();
    let (mut cushions, mut balls) = (0, 0);
    let end = play(&scene, &stroke, &setup, |event, _| match event.kind {
        EventKind::Cushion => cushions += 1,
        EventKind::Ball => balls += 1,
        EventKind::Pocket(_) => panic!("a carom table has no pockets"),
        EventKind::Rest => {}
    })
    .unwrap();
    assert!(
        cushions >= 3 && balls >= 1,
        "{cushions} cushions, {balls} collisions"
    );
    assert!(end.positions().iter().all(Option::is_some));
}

/// A ball resting in a corner's mouth (its centre 85 mm from the corner, inside the
/// rails' nose lines) stays until it is hit, then drops when pushed into the pocket.
#[test]
fn a_ball_in_a_corners_mouth_drops_when_hit_towards_the_pocket() {
    let mut scene = Scene::new(Table::pool(), R, [0.4, 0.4]).unwrap();
    scene.add_ball([0.06, 0.06]).unwrap();
    let stroke = Stroke::new(2.0, TipOffset::CENTRE, [-1.0, -1.0]).unwrap();
    let (kinds, _, end) = first_events::<3>(&scene, &stroke);
    assert_eq!(kinds[0], Some((EventKind::Ball, 0)), "{kinds:?}");
    assert_eq!(kinds[1], Some((EventKind::Pocket(0), 1)), "{kinds:?}");
    assert_eq!(end.position(1), None);
    // Left alone, it stays.
    let away = Stroke::new(2.0, TipOffset::CENTRE, [1.0, 0.2]).unwrap();
    let end = play(&scene, &away, &Setup::POOL, |_, _| {}).unwrap();
    assert_eq!(end.position(1), Some(Vec3::new(0.06, 0.06, 0.0)));
}
