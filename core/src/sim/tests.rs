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

#[test]
fn a_stun_shot_stops_the_cue_ball_and_sends_the_object_ball_off_the_far_cushion() {
    let mut scene = Scene::new(Table::pool(), R, [0.635, 0.635]).unwrap();
    scene.add_ball([1.27, 0.635]).unwrap();
    let stroke = Stroke::new(3.0, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
    let mut kinds = [None; 8];
    let mut n = 0;
    let end = play(&scene, &stroke, &Setup::POOL, |event, _| {
        if n < kinds.len() {
            kinds[n] = Some((event.kind, event.ball));
        }
        n += 1;
    })
    .unwrap();
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
