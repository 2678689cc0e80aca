//! Shot guidance chain (core `shot`, `aim`, `travel`): published anchors, inverse-aim
//! round trip, and agreement with a forward chain that uses the reference solver for
//! the collision.

use cuesight::aim::{solve_aim, AimError};
use cuesight::shot::{play, play_with, ShotSetup, Stroke};
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{BallSet, Scene, Table};
use cuesight::travel::{Cloth, Motion};
use cuesight::{collide, Impact, Model, Params, Vec3};
use rand::{Rng, SeedableRng};

const R: f32 = BallSet::POOL.radius;

fn setup(model: Model) -> ShotSetup {
    ShotSetup {
        params: Params::POOL,
        cue: Cue::TYPICAL,
        cloth: Cloth::TYPICAL,
        model,
    }
}

fn angle_between(a: Vec3, b: Vec3) -> f32 {
    (a.x * b.y - a.y * b.x).atan2(a.dot(b)).to_degrees()
}

/// Carom angle of a rolling cue ball after an ideal collision at cut `cut_deg`, through
/// the whole chain (strike at 2R/5 above centre gives natural roll, travel, contact).
fn carom_angle(cut_deg: f32) -> f32 {
    let cut = cut_deg.to_radians();
    let cue = [0.6, 0.635];
    let contact = Vec3::new(cue[0] + 0.8, cue[1], 0.0);
    let object = contact + Vec3::new(cut.cos(), -cut.sin(), 0.0) * (2.0 * R);
    let mut scene = Scene::new(Table::pool(), R, cue).unwrap();
    scene.add_ball([object.x, object.y]).unwrap();
    let stroke = Stroke::new(3.0, TipOffset::new(0.0, 0.4 * R).unwrap(), [1.0, 0.0]).unwrap();
    let shot = play(&scene, &stroke, &setup(Model::Ideal)).unwrap();
    let c = shot.contact.expect("hits the object ball");
    assert!(
        (c.cut_angle.to_degrees() - cut_deg).abs() < 0.01,
        "cut {}",
        c.cut_angle.to_degrees()
    );
    angle_between(stroke.aim(), c.cue_after.rolling_velocity).abs()
}

/// The 30° rule (TP A.4): rolling cue ball, ideal collision: carom angle
/// atan(sin φ cos φ / (sin² φ + 2/5)), maximum 33.749° at φ = 28.126°.
#[test]
fn thirty_degree_rule() {
    for cut in [10.0f32, 28.126, 45.0, 60.0] {
        let (s, c) = (cut.to_radians().sin(), cut.to_radians().cos());
        let expected = (s * c / (s * s + 0.4)).atan().to_degrees();
        let got = carom_angle(cut);
        assert!(
            (got - expected).abs() < 0.01,
            "cut {cut}: {got} vs {expected}"
        );
    }
    let (mut best_cut, mut best) = (0.0, 0.0);
    for i in 0..=400 {
        let cut = 24.0 + 0.02 * i as f32;
        let a = carom_angle(cut);
        if a > best {
            (best_cut, best) = (cut, a);
        }
    }
    cuesight_figures::record!("shot-thirty-degree-max", "{best:.3}");
    cuesight_figures::record!("shot-thirty-degree-max-at", "{best_cut:.1}");
    assert!((best - 33.749).abs() < 0.005, "max {best}");
    assert!((best_cut - 28.126).abs() < 0.1, "at {best_cut}");
}

/// The 90° rule: a stun cue ball and the object ball leave at right angles after an
/// ideal collision, and stay on those lines (the stun ball has no spin to curve it).
#[test]
fn ninety_degree_rule() {
    for cut in [15.0f32, 30.0, 60.0] {
        let impact = Impact::from_cut_degrees(2.0, cut, [0.0; 3]).unwrap();
        let out = collide(&Params::POOL, &impact, Model::Ideal).unwrap();
        let cue = Motion::new(
            Vec3::ZERO,
            out.cue_ball.velocity,
            out.cue_ball.spin,
            R,
            &Cloth::TYPICAL,
        )
        .unwrap();
        let object = Motion::new(
            Vec3::ZERO,
            out.object_ball.velocity,
            out.object_ball.spin,
            R,
            &Cloth::TYPICAL,
        )
        .unwrap();
        let separation = angle_between(object.rolling_velocity, cue.rolling_velocity).abs();
        assert!((separation - 90.0).abs() < 1e-3, "cut {cut}: {separation}");
        assert!(angle_between(cue.initial_velocity, cue.rolling_velocity).abs() < 1e-3);
    }
}

struct Case {
    scene: Scene,
    pocket: usize,
    speed: f32,
    tip: TipOffset,
}

fn cases(count: usize) -> Vec<Case> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let table = Table::pool();
    let mut out = Vec::new();
    while out.len() < count {
        let cue = [
            rng.random_range(0.3..2.2f32),
            rng.random_range(0.2..1.07f32),
        ];
        let object = [
            rng.random_range(0.3..2.2f32),
            rng.random_range(0.2..1.07f32),
        ];
        let mut scene = Scene::new(table.clone(), R, cue).unwrap();
        if scene.add_ball(object).is_err() {
            continue;
        }
        // The pocket that needs the smallest cut.
        let (c, o) = (
            Vec3::new(cue[0], cue[1], 0.0),
            Vec3::new(object[0], object[1], 0.0),
        );
        let aim = o - c;
        let pocket = (0..table.pockets().len())
            .min_by(|&a, &b| {
                let cut = |i: usize| angle_between(aim, table.pockets()[i].centre() - o).abs();
                cut(a).total_cmp(&cut(b))
            })
            .unwrap();
        let cut = angle_between(aim, table.pockets()[pocket].centre() - o).abs();
        if cut > 60.0 {
            continue;
        }
        let tip = TipOffset::new(
            rng.random_range(-0.3..0.3f32) * R,
            rng.random_range(-0.3..0.3f32) * R,
        )
        .unwrap();
        out.push(Case {
            scene,
            pocket,
            speed: rng.random_range(2.0..5.0f32),
            tip,
        });
    }
    out
}

/// Miss of the object ball at the pocket, as an angle seen from the object ball (deg).
fn miss_deg(case: &Case, aim: Vec3, reference: bool) -> Option<f32> {
    let stroke = Stroke::new(case.speed, case.tip, [aim.x, aim.y]).unwrap();
    let s = setup(Model::KimGrip);
    let shot = if reference {
        play_with(&case.scene, &stroke, &s, |p, i| {
            Ok(cuesight_host::reference::collide(p, i))
        })
        .unwrap()
    } else {
        play(&case.scene, &stroke, &s).unwrap()
    };
    let c = shot.contact?;
    let pocket = case.scene.table().pockets()[case.pocket];
    let (a, b) = (pocket.a, pocket.b);
    let along = (b - a) * (1.0 / (b - a).length());
    let centre = pocket.centre();
    let t = c
        .object_after
        .crossing(centre - along * 20.0, centre + along * 20.0)?;
    let miss = along.dot(c.object_after.position_at(t) - centre);
    let distance = (centre - case.scene.balls()[c.object_ball]).length();
    Some((miss / distance).atan().to_degrees().abs())
}

/// Inverse aim: the forward model at the solved aim reaches the pocket centre within
/// 0.01°; a forward chain with the reference solver for the collision agrees within
/// 0.1°. Reports the aim corrections against the naive ghost-ball aim.
#[test]
fn inverse_aim_round_trip_and_reference_agreement() {
    let all = cases(60);
    let mut solved = 0;
    let (mut worst_self, mut worst_reference, mut largest_correction) = (0.0f32, 0.0f32, 0.0f32);
    for case in &all {
        match solve_aim(
            &case.scene,
            1,
            case.pocket,
            case.speed,
            case.tip,
            &setup(Model::KimGrip),
        ) {
            Ok(solution) => {
                solved += 1;
                let own = miss_deg(case, solution.aim, false).expect("reaches the pocket line");
                let reference =
                    miss_deg(case, solution.aim, true).expect("reference reaches it too");
                worst_self = worst_self.max(own);
                worst_reference = worst_reference.max(reference);
                largest_correction = largest_correction.max(solution.correction_mm);
                assert!(own <= 0.01, "round trip {own} deg");
                assert!(reference <= 0.1, "reference chain {reference} deg");
            }
            Err(AimError::PocketUnreachable) | Err(AimError::ObjectBallNotHit) => {}
            Err(e) => panic!("unexpected {e:?}"),
        }
    }
    println!(
        "{solved}/{} solved; worst round-trip miss {worst_self:.2e} deg, worst reference-chain miss {worst_reference:.4} deg, largest correction {largest_correction:.2} mm",
        all.len()
    );
    cuesight_figures::record!("shot-aim-scenes", "{}", all.len());
    cuesight_figures::record!("shot-aim-solved", "{solved}");
    cuesight_figures::record!("shot-aim-unsolved", "{}", all.len() - solved);
    cuesight_figures::record!("shot-aim-round-trip-miss", "{worst_self:.2e}");
    cuesight_figures::record!("shot-aim-reference-miss", "{worst_reference:.4}");
    cuesight_figures::record!("shot-aim-correction-max", "{largest_correction:.1}");
    assert!(solved >= 40, "only {solved} solved");
}
