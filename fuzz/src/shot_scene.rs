//! Target `shot_scene`: a table, a ball radius, the cue ball and up to 20 object balls
//! (past the scene's capacity of [`MAX_BALLS`]), collision parameters, cue, cloth,
//! model and stroke decoded from the bytes, then the shot entry points: `Table::new`,
//! `Scene::new`/`add_ball`, `Stroke::new`/`at_angle`, `shot::play`,
//! `aim::solve_aim`, `guidance::guide` (what the CLI and the protocol's `shot` answer
//! with) and the `travel::Motion` methods.
//!
//! Checked, whatever the input: no panic; no `NumericalFailure` from `play`, `solve_aim`
//! or `guide` (every input went through its constructor, and the core documents that
//! guard as one valid input never trips); a table's pockets finite; the scene never
//! holds more than [`MAX_BALLS`] balls, `add_ball` returns the new ball's index, or
//! refuses with an input error (ball count only when full) and leaves the scene as it
//! was; every number of an `Ok` shot finite (launch, every motion at its phase
//! boundaries, the contact, the outcome, the pocket time), the ball hit an object ball
//! and the pocket one of the table's; `Motion` queries at finite times finite, and every
//! motion `Motion::new` accepts finite; a solved aim finite, within [`TOLERANCE`] and
//! [`MAX_ITERATIONS`]; every number of an `Ok` guidance finite.

use std::f32::consts::PI;

use cuesight::aim::{solve_aim, AimError, MAX_ITERATIONS, TOLERANCE};
use cuesight::guidance::{guide, Aim, Target};
use cuesight::shot::{play, ShotSetup, Stroke};
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{BallSet, Scene, Table, MAX_BALLS};
use cuesight::travel::{Cloth, Motion};
use cuesight::{Error, Field, FrictionLaw, Model, Params, Vec3};

use crate::finite;
use crate::input::Input;

/// Most object balls an input places (the scene holds [`MAX_BALLS`] − 1).
pub const MAX_OBJECT_BALLS: u8 = 20;

/// What one input reached (for checking seeds).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// Balls in the scene (0 if the table or the cue ball was refused).
    pub balls: usize,
    /// `play` returned a shot.
    pub played: bool,
    /// The cue ball hit a ball.
    pub contact: bool,
    /// The object ball reached a pocket.
    pub pocketed: bool,
    /// `solve_aim` found an aim.
    pub aimed: bool,
    /// `guide` answered.
    pub guided: bool,
}

/// Decodes `data` and plays it (see the module docs).
pub fn run(data: &[u8]) -> Report {
    let mut input = Input::new(data);
    let mut report = Report::default();
    let Some(mut scene) = scene(&mut input) else {
        return report;
    };
    add_balls(&mut input, &mut scene);
    report.balls = scene.balls().len();
    let Some(setup) = setup(&mut input, scene.radius()) else {
        return report;
    };
    let radius = scene.radius();
    let cue_speed = input.real(0.0, 8.0);
    let tip = if input.flag() {
        TipOffset::from_radius_fraction(input.real(-0.6, 0.6), input.real(-0.6, 0.6), radius)
    } else {
        TipOffset::new(
            input.real(-0.6, 0.6) * radius,
            input.real(-0.6, 0.6) * radius,
        )
    };
    let Ok(tip) = tip else {
        return report;
    };
    if let Some(stroke) = stroke(&mut input, &scene, cue_speed, tip) {
        let played = play(&scene, &stroke, &setup);
        assert_ne!(
            played.err(),
            Some(Error::NumericalFailure),
            "play {stroke:?} with {setup:?} on {scene:?}"
        );
        if let Ok(shot) = played {
            report.played = true;
            finite::shot(&shot);
            probe(&mut input, &shot.cue_before, stroke.aim(), &scene);
            if let Some(contact) = &shot.contact {
                report.contact = true;
                let index = contact.object_ball;
                assert!(
                    index >= 1 && index < scene.balls().len(),
                    "hit ball {index} of {}",
                    scene.balls().len()
                );
                assert!(contact.time >= 0.0, "contact at {}", contact.time);
                if let Some((pocket, t)) = contact.pocket {
                    report.pocketed = true;
                    assert!(pocket < scene.table().pockets().len(), "pocket {pocket}");
                    assert!(t >= 0.0, "pocketed at {t}");
                }
                probe(
                    &mut input,
                    &contact.object_after,
                    contact.line_of_centres,
                    &scene,
                );
            }
        }
    }
    free_motion(&mut input);
    let object = usize::from(input.choice(MAX_BALLS as u8 + 1));
    let pocket = usize::from(input.choice(7));
    let solved = solve_aim(&scene, object, pocket, cue_speed, tip, &setup);
    no_numerical_failure("solve_aim", solved.as_ref().err());
    if let Ok(aim) = solved {
        report.aimed = true;
        finite::aim(&aim);
        assert!(
            aim.residual.abs() <= TOLERANCE,
            "aim residual {}",
            aim.residual
        );
        assert!(aim.evaluations <= MAX_ITERATIONS, "{}", aim.evaluations);
    }
    let target = Target { object, pocket };
    let aim = match input.choice(3) {
        0 => Aim::Solve(target),
        k => Aim::Degrees {
            aim_deg: input.real(-180.0, 180.0),
            target: (k == 1).then_some(target),
        },
    };
    let guided = guide(&scene, cue_speed, tip, aim, &setup);
    no_numerical_failure("guide", guided.as_ref().err());
    if let Ok(guidance) = guided {
        report.guided = true;
        finite::debug("guidance", &guidance);
    }
    report
}

/// The core's numerical guard is for outputs valid input cannot produce: it must not
/// trip here, where every input went through its constructor.
fn no_numerical_failure(what: &str, error: Option<&AimError>) {
    assert!(
        error != Some(&AimError::Invalid(Error::NumericalFailure)),
        "{what}: numerical failure"
    );
}

/// A table, a ball radius and the cue ball.
fn scene(input: &mut Input) -> Option<Scene> {
    let (table, set) = match input.choice(4) {
        0 => (Table::pool(), BallSet::POOL),
        1 => (Table::snooker(), BallSet::SNOOKER),
        2 => (Table::carom(), BallSet::CAROM),
        _ => {
            let length = input.real(0.5, 4.0);
            let width = input.real(0.25, length);
            let corner = input.real(0.0, 0.25 * width);
            let side = input.real(0.0, 0.25 * width);
            let radius = input.real(0.001, 0.1);
            let table = Table::new(length, width, corner, side, radius).ok()?;
            (table, BallSet { radius, mass: 0.17 })
        }
    };
    for (i, p) in table.pockets().iter().enumerate() {
        finite::vector(&format!("pocket {i}.a"), p.a);
        finite::vector(&format!("pocket {i}.b"), p.b);
    }
    // Mostly the set's radius; sometimes another one (then the pockets were laid out
    // for other balls, which is allowed).
    let radius = if input.choice(8) == 0 {
        input.real(0.0005, 0.1)
    } else {
        set.radius
    };
    let cue_ball = position(input, &table);
    Scene::new(table, radius, cue_ball).ok()
}

/// A position on or just off `table`.
fn position(input: &mut Input, table: &Table) -> [f32; 2] {
    [
        input.real(-0.1, table.length() + 0.1),
        input.real(-0.1, table.width() + 0.1),
    ]
}

/// Up to [`MAX_OBJECT_BALLS`] more balls, checking `add_ball`'s bookkeeping.
fn add_balls(input: &mut Input, scene: &mut Scene) {
    for _ in 0..input.choice(MAX_OBJECT_BALLS + 1) {
        let p = position(input, scene.table());
        let before = scene.balls().len();
        match scene.add_ball(p) {
            Ok(index) => {
                assert_eq!(index, before, "add_ball's index");
                assert_eq!(scene.balls().len(), before + 1);
            }
            Err(error) => {
                assert_eq!(scene.balls().len(), before, "a refused ball was kept");
                let field = error.field();
                assert!(field.is_some(), "add_ball({p:?}): {error}");
                if field == Some(Field::BallCount) {
                    assert_eq!(before, MAX_BALLS, "refused as full with {before} balls");
                }
            }
        }
        assert!(scene.balls().len() <= MAX_BALLS);
    }
}

/// Collision parameters (usually for the scene's balls), cue, cloth and model.
fn setup(input: &mut Input, radius: f32) -> Option<ShotSetup> {
    let params_radius = if input.choice(8) == 0 {
        input.real(0.0005, 0.1)
    } else {
        radius
    };
    let mut params = Params::new(
        input.real(0.0, 0.2),
        input.real(0.5, 1.0),
        input.real(0.0, 0.5),
        params_radius,
        input.real(0.05, 1.0),
    )
    .ok()?;
    if input.flag() {
        let law = FrictionLaw::speed_dependent(
            input.real(1e-6, 0.05),
            input.real(0.0, 0.2),
            input.real(0.0, 5.0),
        )
        .ok()?;
        params = params.with_friction_law(law);
    }
    if input.flag() {
        params = params.with_cue_table_friction(input.real(0.0, 0.3)).ok()?;
    }
    let cue = if input.flag() {
        Cue::new(input.real(0.1, 2.0), input.real(0.0, 1.0)).ok()?
    } else {
        Cue::TYPICAL
    };
    let cloth = if input.flag() {
        Cloth::new(input.real(0.0, 1.0), input.real(0.0, 0.5)).ok()?
    } else {
        Cloth::TYPICAL
    };
    let model = match input.choice(5) {
        0 => Model::Ideal,
        1 => Model::Kim,
        2 => Model::KimGrip,
        3 => Model::Exact,
        _ => Model::Auto {
            tolerance: input.real(1e-4, 0.1),
        },
    };
    Some(ShotSetup {
        params,
        cue,
        cloth,
        model,
    })
}

/// A stroke aimed along a direction, at an angle, or at a ball with an offset (the
/// last reaches contacts far more often than a random aim).
fn stroke(input: &mut Input, scene: &Scene, cue_speed: f32, tip: TipOffset) -> Option<Stroke> {
    let stroke = match input.choice(3) {
        0 => Stroke::new(cue_speed, tip, input.pair(-1.0, 1.0)),
        1 => Stroke::at_angle(cue_speed, tip, input.real(-PI, PI)),
        _ => {
            let balls = scene.balls();
            let target = balls[usize::from(input.choice(MAX_BALLS as u8)) % balls.len()];
            let to = target - balls[0];
            let across = Vec3::new(-to.y, to.x, 0.0) * (1.0 / to.length().max(1e-6));
            let offset = input.real(-2.0, 2.0) * scene.radius();
            let direction = to + across * offset;
            Stroke::new(cue_speed, tip, [direction.x, direction.y])
        }
    };
    stroke.ok()
}

/// Queries `motion` at a decoded time, distance along `direction` and each pocket.
fn probe(input: &mut Input, motion: &Motion, direction: Vec3, scene: &Scene) {
    finite::at("probe", motion, input.real(0.0, 10.0));
    if let Some(t) = motion.time_to_reach(direction, input.real(0.0, 3.0)) {
        finite::numbers("time_to_reach", &[t]);
        assert!(t >= 0.0, "time_to_reach {t}");
    }
    for p in scene.table().pockets() {
        if let Some(t) = motion.crossing(p.a, p.b) {
            finite::numbers("crossing", &[t]);
            assert!(t >= 0.0, "crossing at {t}");
        }
    }
}

/// `Motion::new` from a decoded state anywhere in (and just past) the range it accepts:
/// every number of an accepted motion finite.
fn free_motion(input: &mut Input) {
    let position = input.pair(-1e3, 1e3);
    let velocity = input.triple(-1e3, 1e3);
    let spin = input.triple(-1e6, 1e6);
    let radius = input.real(0.001, 1.0);
    let Ok(cloth) = Cloth::new(input.real(0.0, 1.0), input.real(0.0, 0.5)) else {
        return;
    };
    let t = input.real(0.0, 100.0);
    if let Ok(motion) = Motion::new(
        Vec3::new(position[0], position[1], 0.0),
        Vec3::from_array(velocity),
        Vec3::from_array(spin),
        radius,
        &cloth,
    ) {
        finite::motion("Motion::new", &motion);
        finite::at("Motion::new", &motion, t);
    }
}
