//! The table simulation's invariants (issue 17): over 100,000 seeded random tables
//! (pool, snooker and carom; 2–16 balls placed at random; strokes of every speed, tip
//! offset and direction; random cloth, cushions, ball–ball friction and restitution),
//! at every event:
//!
//! * kinetic energy (translation and spin, every ball on the table) does not increase
//!   (relative 1e-5: the energies are f32 sums of squares of up to 16 balls);
//! * no two balls overlap (centre distance ≥ 2R less 5e-5 of it: each event time is the
//!   last float before contact, but positions are f32 on a table metres across, 2.4e-7
//!   m apart near 3 m, 4e-6 of 2R);
//! * events come in time order;
//!
//! and every simulation ends (all balls at rest or pocketed): none stops with
//! `Error::Unfinished`. The counts and worst cases are recorded (`table-sim-*`); 5 s
//! for the 100,000 (2 threads, the test profile, which optimises the core).
//!
//! `TABLE_SIM_SEED=N cargo test -p cuesight-host --test table_sim -- --nocapture`
//! prints scene N's setup and events.

use cuesight::shot::Stroke;
use cuesight::sim::{play, Cushion, EventKind, Setup};
use cuesight::strike::TipOffset;
use cuesight::table::{BallSet, Scene, Table, MAX_BALLS};
use cuesight::travel::Cloth;
use cuesight::{Error, Model, NU};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const SCENES: u64 = 100_000;

struct Drawn {
    scene: Scene,
    stroke: Stroke,
    setup: Setup,
}

fn draw(seed: u64) -> Drawn {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (table, balls, setup) = match seed % 3 {
        0 => (Table::pool(), BallSet::POOL, Setup::POOL),
        1 => (
            Table::snooker(),
            BallSet::SNOOKER,
            Setup::snooker().unwrap(),
        ),
        _ => (Table::carom(), BallSet::CAROM, Setup::carom().unwrap()),
    };
    let r = balls.radius;
    let mut scene = Scene::new(
        table.clone(),
        r,
        [
            rng.random_range(0.2..table.length() - 0.2),
            rng.random_range(0.2..table.width() - 0.2),
        ],
    )
    .unwrap();
    let count = rng.random_range(2..=MAX_BALLS);
    for _ in 0..200 {
        if scene.balls().len() >= count {
            break;
        }
        // Placements off the cloth or overlapping are refused; draw again. Balls in the
        // pockets' mouths too, so that the jaws are met from every side.
        let (x, y) = (
            rng.random_range(r..table.length() - r),
            rng.random_range(r..table.width() - r),
        );
        let _ = scene.add_ball([x, y]);
    }
    let tip = loop {
        let (side, height) = (
            rng.random_range(-0.5..0.5f32),
            rng.random_range(-0.5..0.5f32),
        );
        if side * side + height * height <= 0.25 {
            break TipOffset::new(side * r, height * r).unwrap();
        }
    };
    let stroke = Stroke::at_angle(
        rng.random_range(0.05..12.0),
        tip,
        rng.random_range(-3.2..3.2),
    )
    .unwrap();
    let params = setup
        .shot
        .params
        .with_mu(rng.random_range(0.0..0.1))
        .unwrap()
        .with_restitution(rng.random_range(0.5..1.0))
        .unwrap();
    let cushion = Cushion::new(
        rng.random_range(0.5..1.0),
        rng.random_range(0.0..0.5),
        rng.random_range(1.05..1.6) * r,
    )
    .unwrap();
    let cloth = Cloth::new(rng.random_range(0.1..0.4), rng.random_range(0.005..0.02)).unwrap();
    let setup = Setup {
        shot: cuesight::shot::ShotSetup {
            params,
            cloth,
            model: Model::KimGrip,
            ..setup.shot
        },
        cushion,
        spin_decay: rng.random_range(0.0..20.0),
        ..setup
    };
    Drawn {
        scene,
        stroke,
        setup,
    }
}

#[derive(Default)]
struct Tally {
    scenes: u64,
    events: u64,
    ball_events: u64,
    cushion_events: u64,
    pocket_events: u64,
    unfinished: u64,
    worst_energy_ratio: f64,
    closest: f64,
}

fn run(seed: u64, tally: &mut Tally) {
    let Drawn {
        scene,
        stroke,
        setup,
    } = draw(seed);
    let r = scene.radius();
    let balls = scene.balls().len();
    let mut previous = f64::INFINITY;
    let mut last_time = 0.0f32;
    let verbose = std::env::var("TABLE_SIM_SEED").is_ok_and(|s| s == seed.to_string());
    if verbose {
        println!("{scene:?}\n{stroke:?}\n{setup:?}");
    }
    let result = play(&scene, &stroke, &setup, |event, paths| {
        if verbose {
            println!("{event:?}");
            if let (Some((s0, m0)), Some((s4, m4))) = (paths.motion(0), paths.motion(4)) {
                println!("   0: since {s0} {m0:?}\n   4: since {s4} {m4:?}");
                let mut t = event.time;
                while t < event.time + 0.3 {
                    let d = (m0.position_at(t - s0) - m4.position_at(t - s4)).length() / (2.0 * r);
                    print!("{:.4}:{:.5} ", t, d);
                    t += 0.01;
                }
                println!();
            }
        }
        assert!(
            event.time >= last_time,
            "seed {seed}: {event:?} after {last_time}"
        );
        last_time = event.time;
        let mut energy = 0.0f64;
        let mut centres = [None; MAX_BALLS];
        for (i, centre) in centres.iter_mut().enumerate().take(balls) {
            if let Some((since, motion)) = paths.motion(i) {
                let t = event.time - since;
                let (v, w) = (motion.velocity_at(t), motion.spin_at(t));
                energy += 0.5 * f64::from(v.dot(v)) + 0.5 * f64::from(NU * r * r * w.dot(w));
                *centre = Some(motion.position_at(t));
            }
        }
        if previous.is_finite() && previous > 0.0 {
            let ratio = energy / previous;
            tally.worst_energy_ratio = tally.worst_energy_ratio.max(ratio);
            assert!(
                ratio <= 1.0 + 1e-5,
                "seed {seed}: energy ×{ratio} at {event:?}"
            );
        }
        previous = energy;
        for i in 0..balls {
            for j in i + 1..balls {
                if let (Some(a), Some(b)) = (centres[i], centres[j]) {
                    let d = f64::from((a - b).length()) / f64::from(2.0 * r);
                    tally.closest = tally.closest.min(d);
                    assert!(
                        d >= 1.0 - 1e-4,
                        "seed {seed}: balls {i}, {j} at {d} × 2R at {event:?}"
                    );
                }
            }
        }
        match event.kind {
            EventKind::Ball => tally.ball_events += 1,
            EventKind::Cushion => tally.cushion_events += 1,
            EventKind::Pocket(_) => tally.pocket_events += 1,
            EventKind::Rest => {}
        }
        tally.events += 1;
    });
    match result {
        Ok(_) => {}
        Err(Error::Unfinished { events, time }) => {
            println!("seed {seed}: unfinished after {events} events, {time} s");
            tally.unfinished += 1
        }
        Err(e) => panic!("seed {seed}: {e}"),
    }
    tally.scenes += 1;
}

#[test]
fn energy_never_grows_and_balls_never_overlap_over_random_tables() {
    let mut tally = Tally {
        closest: f64::INFINITY,
        ..Tally::default()
    };
    // A survey of other seeds: TABLE_SIM_FIRST=S TABLE_SIM_SCENES=N (figures recorded
    // only for the CI set).
    let number = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    let first = number("TABLE_SIM_FIRST").unwrap_or(0);
    let scenes = number("TABLE_SIM_SCENES").unwrap_or(SCENES);
    for seed in first..first + scenes {
        run(seed, &mut tally);
    }
    println!(
        "{} scenes, {} events ({} ball, {} cushion, {} pocket), {} unfinished; worst energy growth {:.3e}, closest {:.6} × 2R",
        tally.scenes,
        tally.events,
        tally.ball_events,
        tally.cushion_events,
        tally.pocket_events,
        tally.unfinished,
        tally.worst_energy_ratio - 1.0,
        tally.closest
    );
    if (first, scenes) != (0, SCENES) {
        assert_eq!(tally.unfinished, 0, "shots that did not end");
        return;
    }
    cuesight_figures::record!("table-sim-scenes", "{}", tally.scenes);
    cuesight_figures::record!("table-sim-events", "{}", tally.events);
    cuesight_figures::record!("table-sim-unfinished", "{}", tally.unfinished);
    cuesight_figures::record!(
        "table-sim-worst-energy-growth",
        "{:.1e}",
        tally.worst_energy_ratio - 1.0
    );
    cuesight_figures::record!("table-sim-closest", "{:.6}", tally.closest);
    assert!(
        tally.ball_events > SCENES && tally.cushion_events > SCENES && tally.pocket_events > 1000,
        "the scenes exercise every kind of event"
    );
    assert_eq!(tally.unfinished, 0, "shots that did not end");
}
