//! Input validation of the shot entry points, table-driven (issue 6, item 2, extended to
//! `travel`, `table`, `shot`, `aim` and `guidance`): every invalid input — NaN, ±Inf,
//! zero or negative sizes, cloth friction below its floor, tables that cannot hold their
//! pockets, balls off the table or overlapping, a scene over its 16 balls, a degenerate
//! aim, a tip beyond the miscue limit, a setup for another ball size, out-of-range ball
//! and pocket indices, bad motion states — returns its typed error (`cuesight::Error`
//! with the field and the rejected value bit for bit, or the `AimError`), with the exact
//! message `Display` gives; the accepted edges are accepted; the query methods that
//! return no `Result` degrade gracefully (no panic, no NaN). docs/reliability.md lists
//! the table. `-- --nocapture` prints every row.

mod shot_common;

use cuesight::aim::{solve_aim, solve_aim_with, AimError};
use cuesight::guidance::{guide, Aim, Target};
use cuesight::shot::{play, play_with, ShotSetup, Stroke};
use cuesight::strike::TipOffset;
use cuesight::table::{BallSet, Scene, Table, MAX_BALLS};
use cuesight::travel::{Cloth, Motion};
use cuesight::{collide, Error, Field, Model, Vec3};
use shot_common::*;

const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;
const R: f32 = BallSet::POOL.radius;

/// What a row expects.
#[derive(Clone, Copy, Debug)]
enum Expect {
    NotFinite(Field),
    OutOfRange(Field, f32),
    /// An `AimError` other than `Invalid`.
    Aim(AimError),
}

type Call = Box<dyn Fn() -> Result<(), AimError>>;

fn row(
    what: &'static str,
    call: impl Fn() -> Result<(), AimError> + 'static,
    expect: Expect,
) -> (&'static str, Call, Expect) {
    (what, Box::new(call), expect)
}

fn ok<T>(r: cuesight::Result<T>) -> Result<(), AimError> {
    r.map(|_| ()).map_err(AimError::Invalid)
}

fn ok_aim<T>(r: Result<T, AimError>) -> Result<(), AimError> {
    r.map(|_| ())
}

fn setup() -> ShotSetup {
    shot_common::setup(BallSet::POOL, Model::KimGrip)
}

/// Pool table, cue ball at (0.5, 0.6), object ball at (1.5, 0.6).
fn two_balls() -> Scene {
    scene(&Table::pool(), R, [0.5, 0.6], &[[1.5, 0.6]])
}

fn stroke() -> Stroke {
    Stroke::new(2.0, TipOffset::CENTRE, [1.0, 0.0]).unwrap()
}

fn motion(position: Vec3, velocity: Vec3, spin: Vec3, radius: f32) -> Result<(), AimError> {
    ok(Motion::new(
        position,
        velocity,
        spin,
        radius,
        &Cloth::TYPICAL,
    ))
}

/// Every invalid input of the travel and table entry points.
fn travel_and_table_rows() -> Vec<(&'static str, Call, Expect)> {
    use Expect::{NotFinite as Nf, OutOfRange as Or};
    let p = Vec3::new(1.0, 0.5, 0.0);
    let v = Vec3::new(1.0, 0.0, 0.0);
    let z = Vec3::ZERO;
    vec![
        // Cloth::new(μ_c, μ_r)
        row(
            "Cloth::new μ_c NaN",
            || ok(Cloth::new(NAN, 0.01)),
            Nf(Field::ClothFriction),
        ),
        row(
            "Cloth::new μ_c +Inf",
            || ok(Cloth::new(INF, 0.01)),
            Nf(Field::ClothFriction),
        ),
        row(
            "Cloth::new μ_c 0",
            || ok(Cloth::new(0.0, 0.01)),
            Or(Field::ClothFriction, 0.0),
        ),
        row(
            "Cloth::new μ_c < 0",
            || ok(Cloth::new(-0.2, 0.01)),
            Or(Field::ClothFriction, -0.2),
        ),
        row(
            "Cloth::new μ_c subnormal",
            || ok(Cloth::new(1e-40, 0.01)),
            Or(Field::ClothFriction, 1e-40),
        ),
        row(
            "Cloth::new μ_c below 0.001",
            || ok(Cloth::new(9.9e-4, 0.01)),
            Or(Field::ClothFriction, 9.9e-4),
        ),
        row(
            "Cloth::new μ_c > 1",
            || ok(Cloth::new(1.01, 0.01)),
            Or(Field::ClothFriction, 1.01),
        ),
        row(
            "Cloth::new μ_r NaN",
            || ok(Cloth::new(0.2, NAN)),
            Nf(Field::RollingResistance),
        ),
        row(
            "Cloth::new μ_r -Inf",
            || ok(Cloth::new(0.2, -INF)),
            Nf(Field::RollingResistance),
        ),
        row(
            "Cloth::new μ_r 0",
            || ok(Cloth::new(0.2, 0.0)),
            Or(Field::RollingResistance, 0.0),
        ),
        row(
            "Cloth::new μ_r < 0",
            || ok(Cloth::new(0.2, -0.01)),
            Or(Field::RollingResistance, -0.01),
        ),
        row(
            "Cloth::new μ_r smallest subnormal",
            || ok(Cloth::new(0.2, f32::from_bits(1))),
            Or(Field::RollingResistance, f32::from_bits(1)),
        ),
        row(
            "Cloth::new μ_r > 0.5",
            || ok(Cloth::new(0.2, 0.6)),
            Or(Field::RollingResistance, 0.6),
        ),
        // Motion::new(position, velocity, spin, R, cloth)
        row(
            "Motion::new position NaN",
            move || motion(Vec3::new(NAN, 0.5, 0.0), v, z, R),
            Nf(Field::Position),
        ),
        row(
            "Motion::new position y +Inf",
            move || motion(Vec3::new(1.0, INF, 0.0), v, z, R),
            Nf(Field::Position),
        ),
        row(
            "Motion::new velocity NaN",
            move || motion(p, Vec3::new(NAN, 0.0, 0.0), z, R),
            Nf(Field::Velocity),
        ),
        row(
            "Motion::new velocity z -Inf",
            move || motion(p, Vec3::new(1.0, 0.0, -INF), z, R),
            Nf(Field::Velocity),
        ),
        row(
            "Motion::new velocity beyond 1000 m/s",
            move || motion(p, Vec3::new(1.0, 1e4, 0.0), z, R),
            Or(Field::Velocity, 1e4),
        ),
        row(
            "Motion::new velocity 1e30 (would overflow)",
            move || motion(p, Vec3::new(1e30, 0.0, 0.0), z, R),
            Or(Field::Velocity, 1e30),
        ),
        row(
            "Motion::new spin NaN",
            move || motion(p, v, Vec3::new(0.0, NAN, 0.0), R),
            Nf(Field::Spin),
        ),
        row(
            "Motion::new spin +Inf",
            move || motion(p, v, Vec3::new(0.0, 0.0, INF), R),
            Nf(Field::Spin),
        ),
        row(
            "Motion::new spin beyond 1e6 rad/s",
            move || motion(p, v, Vec3::new(-2e6, 0.0, 0.0), R),
            Or(Field::Spin, -2e6),
        ),
        row(
            "Motion::new R NaN",
            move || motion(p, v, z, NAN),
            Nf(Field::Radius),
        ),
        row(
            "Motion::new R 0",
            move || motion(p, v, z, 0.0),
            Or(Field::Radius, 0.0),
        ),
        row(
            "Motion::new R < 0",
            move || motion(p, v, z, -R),
            Or(Field::Radius, -R),
        ),
        row(
            "Motion::new R > 1 m",
            move || motion(p, v, z, 1.5),
            Or(Field::Radius, 1.5),
        ),
        // Table::new(length, width, corner mouth, side mouth, R)
        row(
            "Table::new length NaN",
            || ok(Table::new(NAN, 1.27, 0.116, 0.13, R)),
            Nf(Field::Table),
        ),
        row(
            "Table::new length +Inf",
            || ok(Table::new(INF, 1.27, 0.116, 0.13, R)),
            Nf(Field::Table),
        ),
        row(
            "Table::new length 0",
            || ok(Table::new(0.0, 1.27, 0.116, 0.13, R)),
            Or(Field::Table, 0.0),
        ),
        row(
            "Table::new length < 0",
            || ok(Table::new(-2.54, 1.27, 0.116, 0.13, R)),
            Or(Field::Table, -2.54),
        ),
        row(
            "Table::new length > 10 m",
            || ok(Table::new(12.0, 1.27, 0.116, 0.13, R)),
            Or(Field::Table, 12.0),
        ),
        row(
            "Table::new width NaN",
            || ok(Table::new(2.54, NAN, 0.116, 0.13, R)),
            Nf(Field::Table),
        ),
        row(
            "Table::new width 0",
            || ok(Table::new(2.54, 0.0, 0.116, 0.13, R)),
            Or(Field::Table, 0.0),
        ),
        row(
            "Table::new width > length",
            || ok(Table::new(2.54, 3.0, 0.116, 0.13, R)),
            Or(Field::Table, 3.0),
        ),
        row(
            "Table::new corner mouth NaN",
            || ok(Table::new(2.54, 1.27, NAN, 0.13, R)),
            Nf(Field::Table),
        ),
        row(
            "Table::new corner mouth < 0",
            || ok(Table::new(2.54, 1.27, -0.1, 0.13, R)),
            Or(Field::Table, -0.1),
        ),
        row(
            "Table::new corner mouth > width/2",
            || ok(Table::new(2.54, 1.27, 0.7, 0.13, R)),
            Or(Field::Table, 0.7),
        ),
        row(
            "Table::new side mouth -Inf",
            || ok(Table::new(2.54, 1.27, 0.116, -INF, R)),
            Nf(Field::Table),
        ),
        row(
            "Table::new side mouth > length/2",
            || ok(Table::new(2.54, 1.27, 0.116, 1.5, R)),
            Or(Field::Table, 1.5),
        ),
        row(
            "Table::new R NaN",
            || ok(Table::new(2.54, 1.27, 0.116, 0.13, NAN)),
            Nf(Field::Radius),
        ),
        row(
            "Table::new R 0",
            || ok(Table::new(2.54, 1.27, 0.116, 0.13, 0.0)),
            Or(Field::Radius, 0.0),
        ),
        row(
            "Table::new R < 0",
            || ok(Table::new(2.54, 1.27, 0.116, 0.13, -R)),
            Or(Field::Radius, -R),
        ),
        row(
            "Table::new R > 1 m",
            || ok(Table::new(2.54, 1.27, 0.116, 0.13, 2.0)),
            Or(Field::Radius, 2.0),
        ),
        // Scene::new(table, R, cue ball)
        row(
            "Scene::new R NaN",
            || ok(Scene::new(Table::pool(), NAN, [0.5, 0.6])),
            Nf(Field::Radius),
        ),
        row(
            "Scene::new R 0",
            || ok(Scene::new(Table::pool(), 0.0, [0.5, 0.6])),
            Or(Field::Radius, 0.0),
        ),
        row(
            "Scene::new R < 0",
            || ok(Scene::new(Table::pool(), -R, [0.5, 0.6])),
            Or(Field::Radius, -R),
        ),
        row(
            "Scene::new cue ball x NaN",
            || ok(Scene::new(Table::pool(), R, [NAN, 0.6])),
            Nf(Field::Position),
        ),
        row(
            "Scene::new cue ball y -Inf",
            || ok(Scene::new(Table::pool(), R, [0.5, -INF])),
            Nf(Field::Position),
        ),
        row(
            "Scene::new cue ball into the near cushion (x < R)",
            || ok(Scene::new(Table::pool(), R, [0.02, 0.6])),
            Or(Field::Position, 0.02),
        ),
        row(
            "Scene::new cue ball off the far side (y > W − R)",
            || ok(Scene::new(Table::pool(), R, [0.5, 1.25])),
            Or(Field::Position, 1.25),
        ),
        row(
            "Scene::new cue ball far off (x = -5e3)",
            || ok(Scene::new(Table::pool(), R, [-5e3, 0.6])),
            Or(Field::Position, -5e3),
        ),
        row(
            "Scene::new ball bigger than the table",
            || ok(Scene::new(Table::pool(), 0.7, [0.7, 0.6])),
            Or(Field::Position, 0.6),
        ),
        // Scene::add_ball
        row(
            "add_ball x NaN",
            || ok(two_balls().add_ball([NAN, 0.3])),
            Nf(Field::Position),
        ),
        row(
            "add_ball y +Inf",
            || ok(two_balls().add_ball([1.0, INF])),
            Nf(Field::Position),
        ),
        row(
            "add_ball off the table (x > L − R)",
            || ok(two_balls().add_ball([2.53, 0.3])),
            Or(Field::Position, 2.53),
        ),
        row(
            "add_ball off the table (y < R)",
            || ok(two_balls().add_ball([1.0, 0.0])),
            Or(Field::Position, 0.0),
        ),
        row(
            "add_ball on top of the cue ball",
            || ok(two_balls().add_ball([0.5, 0.6])),
            Or(Field::Spacing, 0.0),
        ),
        row(
            "add_ball overlapping the object ball (1.5R apart)",
            || ok(two_balls().add_ball([1.5 + 1.5 * R, 0.6])),
            Or(Field::Spacing, (1.5 + 1.5 * R) - 1.5),
        ),
        row(
            "add_ball a 17th ball",
            || {
                let mut s = two_balls();
                for i in 2..MAX_BALLS {
                    s.add_ball([0.2 + 0.1 * i as f32, 1.0]).unwrap();
                }
                ok(s.add_ball([2.0, 0.3]))
            },
            Or(Field::BallCount, (MAX_BALLS + 1) as f32),
        ),
    ]
}

/// Every invalid input of the stroke, shot, aim and guidance entry points.
fn shot_rows() -> Vec<(&'static str, Call, Expect)> {
    use Expect::{Aim as A, NotFinite as Nf, OutOfRange as Or};
    let centre = TipOffset::CENTRE;
    let beyond = TipOffset::new(0.0, 0.6 * R).unwrap();
    let solve = |object: usize, pocket: usize, speed: f32, tip: TipOffset, setup: ShotSetup| {
        ok_aim(solve_aim(&two_balls(), object, pocket, speed, tip, &setup))
    };
    let with_model = |model: Model| {
        let mut s = setup();
        s.model = model;
        s
    };
    let snooker_setup = shot_common::setup(BallSet::SNOOKER, Model::KimGrip);
    vec![
        // Stroke::new(cue speed, tip, direction)
        row(
            "Stroke::new direction x NaN",
            move || ok(Stroke::new(2.0, centre, [NAN, 1.0])),
            Nf(Field::Aim),
        ),
        row(
            "Stroke::new direction y -Inf",
            move || ok(Stroke::new(2.0, centre, [1.0, -INF])),
            Nf(Field::Aim),
        ),
        row(
            "Stroke::new direction [0, 0]",
            move || ok(Stroke::new(2.0, centre, [0.0, 0.0])),
            Or(Field::Aim, 0.0),
        ),
        row(
            "Stroke::new direction [-0, -0]",
            move || ok(Stroke::new(2.0, centre, [-0.0, -0.0])),
            Or(Field::Aim, 0.0),
        ),
        row(
            "Stroke::new cue speed NaN",
            move || ok(Stroke::new(NAN, centre, [1.0, 0.0])),
            Nf(Field::CueSpeed),
        ),
        row(
            "Stroke::new cue speed 0",
            move || ok(Stroke::new(0.0, centre, [1.0, 0.0])),
            Or(Field::CueSpeed, 0.0),
        ),
        row(
            "Stroke::new cue speed < 0",
            move || ok(Stroke::new(-1.0, centre, [1.0, 0.0])),
            Or(Field::CueSpeed, -1.0),
        ),
        row(
            "Stroke::new cue speed > 20 m/s",
            move || ok(Stroke::new(25.0, centre, [1.0, 0.0])),
            Or(Field::CueSpeed, 25.0),
        ),
        // Stroke::at_angle(cue speed, tip, angle)
        row(
            "Stroke::at_angle angle NaN",
            move || ok(Stroke::at_angle(2.0, centre, NAN)),
            Nf(Field::AimAngle),
        ),
        row(
            "Stroke::at_angle angle +Inf",
            move || ok(Stroke::at_angle(2.0, centre, INF)),
            Nf(Field::AimAngle),
        ),
        row(
            "Stroke::at_angle angle beyond 1000 rad",
            move || ok(Stroke::at_angle(2.0, centre, -1500.0)),
            Or(Field::AimAngle, -1500.0),
        ),
        row(
            "Stroke::at_angle cue speed +Inf",
            move || ok(Stroke::at_angle(INF, centre, 0.3)),
            Nf(Field::CueSpeed),
        ),
        // play / play_with
        row(
            "play tip beyond 0.5 R",
            move || {
                let s = Stroke::new(2.0, beyond, [1.0, 0.0]).unwrap();
                ok(play(&two_balls(), &s, &setup()))
            },
            Or(Field::TipOffset, 0.6 * R),
        ),
        row(
            "play cue speed set NaN after construction",
            || {
                let mut s = stroke();
                s.cue_speed = NAN;
                ok(play(&two_balls(), &s, &setup()))
            },
            Nf(Field::CueSpeed),
        ),
        row(
            "play cue speed set to 30 m/s after construction",
            || {
                let mut s = stroke();
                s.cue_speed = 30.0;
                ok(play(&two_balls(), &s, &setup()))
            },
            Or(Field::CueSpeed, 30.0),
        ),
        row(
            "play setup for another ball size (snooker on pool)",
            move || ok(play(&two_balls(), &stroke(), &snooker_setup)),
            Or(Field::SetupRadius, BallSet::SNOOKER.radius),
        ),
        row(
            "play Auto tolerance 0 (ball hit)",
            move || {
                ok(play(
                    &two_balls(),
                    &stroke(),
                    &with_model(Model::Auto { tolerance: 0.0 }),
                ))
            },
            Or(Field::Tolerance, 0.0),
        ),
        row(
            "play Auto tolerance NaN (nothing hit)",
            move || {
                let s = Stroke::new(2.0, centre, [0.0, 1.0]).unwrap();
                ok(play(
                    &two_balls(),
                    &s,
                    &with_model(Model::Auto { tolerance: NAN }),
                ))
            },
            Nf(Field::Tolerance),
        ),
        row(
            "play_with setup for another ball size",
            move || {
                ok(play_with(
                    &two_balls(),
                    &stroke(),
                    &snooker_setup,
                    |p, i| collide(p, i, Model::Ideal),
                ))
            },
            Or(Field::SetupRadius, BallSet::SNOOKER.radius),
        ),
        // solve_aim(scene, object, pocket, cue speed, tip, setup)
        row(
            "solve_aim object 0 (the cue ball)",
            move || solve(0, 3, 2.0, centre, setup()),
            Or(Field::BallIndex, 0.0),
        ),
        row(
            "solve_aim object out of range",
            move || solve(2, 3, 2.0, centre, setup()),
            Or(Field::BallIndex, 2.0),
        ),
        row(
            "solve_aim pocket out of range",
            move || solve(1, 6, 2.0, centre, setup()),
            Or(Field::Pocket, 6.0),
        ),
        row(
            "solve_aim pocket on a carom table (no pockets)",
            || {
                let s = scene(
                    &Table::carom(),
                    BallSet::CAROM.radius,
                    [0.5, 0.6],
                    &[[1.5, 0.6]],
                );
                let setup = shot_common::setup(BallSet::CAROM, Model::KimGrip);
                ok_aim(solve_aim(&s, 1, 0, 2.0, TipOffset::CENTRE, &setup))
            },
            Or(Field::Pocket, 0.0),
        ),
        row(
            "solve_aim cue speed NaN",
            move || solve(1, 3, NAN, centre, setup()),
            Nf(Field::CueSpeed),
        ),
        row(
            "solve_aim cue speed 0",
            move || solve(1, 3, 0.0, centre, setup()),
            Or(Field::CueSpeed, 0.0),
        ),
        row(
            "solve_aim tip beyond 0.5 R",
            move || solve(1, 3, 2.0, beyond, setup()),
            Or(Field::TipOffset, 0.6 * R),
        ),
        row(
            "solve_aim setup for another ball size",
            move || solve(1, 3, 2.0, centre, snooker_setup),
            Or(Field::SetupRadius, BallSet::SNOOKER.radius),
        ),
        row(
            "solve_aim Auto tolerance -1",
            move || {
                solve(
                    1,
                    3,
                    2.0,
                    centre,
                    with_model(Model::Auto { tolerance: -1.0 }),
                )
            },
            Or(Field::Tolerance, -1.0),
        ),
        row(
            "solve_aim_with object out of range",
            move || {
                ok_aim(solve_aim_with(
                    &two_balls(),
                    9,
                    3,
                    2.0,
                    centre,
                    &setup(),
                    |p, i| collide(p, i, Model::Ideal),
                ))
            },
            Or(Field::BallIndex, 9.0),
        ),
        row(
            "solve_aim another ball in the way",
            || {
                let s = scene(&Table::pool(), R, [0.5, 0.6], &[[1.5, 0.6], [1.0, 0.6]]);
                ok_aim(solve_aim(&s, 1, 3, 2.0, TipOffset::CENTRE, &setup()))
            },
            A(AimError::ObjectBallNotHit),
        ),
        row(
            "solve_aim too slow to reach the ball",
            move || solve(1, 3, 0.05, centre, setup()),
            A(AimError::ObjectBallNotHit),
        ),
        row(
            "solve_aim object ball stops before the pocket",
            || {
                let s = scene(&Table::pool(), R, [0.5, 0.6], &[[0.6, 0.6]]);
                ok_aim(solve_aim(&s, 1, 3, 0.3, TipOffset::CENTRE, &setup()))
            },
            A(AimError::PocketUnreachable),
        ),
        // guidance::guide(scene, cue speed, tip, aim, setup)
        row(
            "guide aim NaN degrees",
            move || {
                let aim = Aim::Degrees {
                    aim_deg: NAN,
                    target: None,
                };
                ok_aim(guide(&two_balls(), 2.0, centre, aim, &setup()))
            },
            Nf(Field::AimAngle),
        ),
        row(
            "guide cue speed -Inf",
            move || {
                let aim = Aim::Degrees {
                    aim_deg: 0.0,
                    target: None,
                };
                ok_aim(guide(&two_balls(), -INF, centre, aim, &setup()))
            },
            Nf(Field::CueSpeed),
        ),
        row(
            "guide target object out of range",
            move || {
                let target = Some(Target {
                    object: 5,
                    pocket: 0,
                });
                let aim = Aim::Degrees {
                    aim_deg: 0.0,
                    target,
                };
                ok_aim(guide(&two_balls(), 2.0, centre, aim, &setup()))
            },
            Or(Field::BallIndex, 5.0),
        ),
        row(
            "guide target pocket out of range",
            move || {
                let target = Some(Target {
                    object: 1,
                    pocket: 7,
                });
                let aim = Aim::Degrees {
                    aim_deg: 0.0,
                    target,
                };
                ok_aim(guide(&two_balls(), 2.0, centre, aim, &setup()))
            },
            Or(Field::Pocket, 7.0),
        ),
        row(
            "guide solve for pocket out of range",
            move || {
                let aim = Aim::Solve(Target {
                    object: 1,
                    pocket: 6,
                });
                ok_aim(guide(&two_balls(), 2.0, centre, aim, &setup()))
            },
            Or(Field::Pocket, 6.0),
        ),
        row(
            "guide solve with the tip beyond 0.5 R",
            move || {
                let aim = Aim::Solve(Target {
                    object: 1,
                    pocket: 3,
                });
                ok_aim(guide(&two_balls(), 2.0, beyond, aim, &setup()))
            },
            Or(Field::TipOffset, 0.6 * R),
        ),
    ]
}

/// The message of an `AimError` other than `Invalid`.
fn aim_message(e: AimError) -> &'static str {
    match e {
        AimError::ObjectBallNotHit => {
            "no aim: at the ghost-ball aim the cue ball does not reach the object ball \
             first (another ball is in the way, or the cue ball stops short)"
        }
        AimError::PocketUnreachable => {
            "no aim: the object ball cannot reach the pocket (it stops short, or the cut \
             is too thin)"
        }
        AimError::NotConverged => {
            "no aim: the solver did not converge in 24 forward evaluations (the cut may be \
             too thin)"
        }
        AimError::Invalid(_) => unreachable!(),
    }
}

fn check_rows(rows: Vec<(&'static str, Call, Expect)>) -> usize {
    let mut failures = Vec::new();
    let n = rows.len();
    for (what, call, expect) in rows {
        let got = call();
        let good = match (expect, got) {
            (
                Expect::NotFinite(field),
                Err(e @ AimError::Invalid(Error::NotFinite { field: f })),
            ) => f == field && e.to_string() == format!("{} must be a finite number", field.name()),
            (
                Expect::OutOfRange(field, value),
                Err(e @ AimError::Invalid(Error::OutOfRange { field: f, value: v })),
            ) => {
                f == field
                    && v.to_bits() == value.to_bits()
                    && e.to_string()
                        == format!(
                            "{} = {} is outside {}",
                            field.name(),
                            value,
                            field.valid_range()
                        )
            }
            (Expect::Aim(a), Err(b)) => a == b && b.to_string() == aim_message(a),
            _ => false,
        };
        if good {
            println!("{what:52} -> {}", got.unwrap_err());
        } else {
            failures.push(format!("{what}: expected {expect:?}, got {got:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    n
}

#[test]
fn every_invalid_travel_and_table_input_names_its_field() {
    let n = check_rows(travel_and_table_rows());
    assert_eq!(n, 59, "rows");
    cuesight_figures::record!("reliability-shot-validation-travel-rows", "{n}");
}

#[test]
fn every_invalid_shot_aim_and_guidance_input_names_its_field() {
    let n = check_rows(shot_rows());
    assert_eq!(n, 38, "rows");
    cuesight_figures::record!("reliability-shot-validation-shot-rows", "{n}");
}

/// The `Display` of an invalid input inside `AimError` is the input error's message.
#[test]
fn aim_error_messages() {
    let e = AimError::Invalid(Error::OutOfRange {
        field: Field::Pocket,
        value: 6.0,
    });
    assert_eq!(
        e.to_string(),
        "pocket = 6 is outside an index of a pocket of the table"
    );
    for e in [
        AimError::ObjectBallNotHit,
        AimError::PocketUnreachable,
        AimError::NotConverged,
    ] {
        assert_eq!(e.to_string(), aim_message(e));
    }
}

/// The edges of every accepted range are accepted and give finite shots.
#[test]
fn range_edges_are_accepted() {
    // Cloth at its floor and ceiling.
    for (mu_c, mu_r) in [(0.001, 0.001), (1.0, 0.5)] {
        let mut setup = setup();
        setup.cloth = Cloth::new(mu_c, mu_r).unwrap();
        let shot = play(&two_balls(), &stroke(), &setup).unwrap();
        shot_finite(&shot).unwrap();
    }
    // Tables: the largest, the smallest that holds a ball, pocketless, mouths at the
    // largest (half the rail), radius 1 mm and 1 m.
    assert!(Table::new(10.0, 10.0, 5.0, 5.0, 1.0).is_ok());
    assert!(Table::new(0.05, 0.02, 0.0, 0.0, 0.001).is_ok());
    let small = Table::new(0.05, 0.02, 0.01, 0.025, 0.001).unwrap();
    assert!(Scene::new(small, 0.001, [0.001, 0.001]).is_ok());
    // Balls exactly touching each other and the cushions (corner at (R, R)).
    let t = Table::pool();
    let mut s = Scene::new(t.clone(), R, [R, R]).unwrap();
    s.add_ball([R + 2.0 * R, R]).unwrap();
    s.add_ball([t.length() - R, t.width() - R]).unwrap();
    // Sixteen balls.
    let mut full = Scene::new(t, R, [0.1, 0.1]).unwrap();
    for i in 1..MAX_BALLS {
        full.add_ball([0.1 + 0.12 * i as f32, 0.6]).unwrap();
    }
    assert_eq!(full.balls().len(), MAX_BALLS);
    // Strokes: any finite non-zero direction, the cue speed limits, the angle limits.
    let tiny_speed = f32::from_bits(1);
    for (speed, direction) in [(tiny_speed, [f32::MAX, -f32::MAX]), (20.0, [1e-45, 0.0])] {
        let stroke = Stroke::new(speed, TipOffset::CENTRE, direction).unwrap();
        shot_finite(&play(&full, &stroke, &setup()).unwrap()).unwrap();
    }
    assert!(Stroke::at_angle(2.0, TipOffset::CENTRE, 1000.0).is_ok());
    assert!(Stroke::at_angle(2.0, TipOffset::CENTRE, -1000.0).is_ok());
    // Motions at the limits of their state.
    for (v, w, r) in [
        (
            Vec3::new(1000.0, -1000.0, 1000.0),
            Vec3::new(1e6, -1e6, 1e6),
            1.0,
        ),
        (
            Vec3::new(-1000.0, 1000.0, -1000.0),
            Vec3::new(-1e6, 1e6, -1e6),
            0.001,
        ),
    ] {
        let cloth = Cloth::new(0.001, 0.001).unwrap();
        let m = Motion::new(Vec3::new(1e3, -1e3, 0.0), v, w, r, &cloth).unwrap();
        motion_finite(&m).unwrap();
    }
}

/// The query methods that return no `Result` never panic and never return NaN:
/// `Motion` at a NaN, infinite or negative time (NaN and negative times are the start,
/// +∞ the rest position), `time_to_reach` and `crossing` with NaN or infinite
/// arguments (nothing reached), `contact_distance` with a NaN aim or a ball index out
/// of range (no contact), `Pocket::centre`.
#[test]
fn unvalidated_queries_degrade_gracefully() {
    let m = Motion::new(
        Vec3::new(1.0, 0.5, 0.0),
        Vec3::new(1.0, 0.3, 0.2),
        Vec3::new(3.0, -20.0, 5.0),
        R,
        &Cloth::TYPICAL,
    )
    .unwrap();
    for t in [NAN, -INF, -1.0, 0.0] {
        assert_eq!(m.displacement_at(t), Vec3::ZERO, "{t}");
        assert_eq!(m.position_at(t), m.start, "{t}");
        assert_eq!(m.velocity_at(t), m.initial_velocity, "{t}");
        assert_eq!(m.spin_at(t), m.initial_spin, "{t}");
    }
    assert_eq!(m.position_at(INF), m.rest());
    assert_eq!(m.velocity_at(INF), Vec3::ZERO);
    assert!(m.spin_at(INF).is_finite());
    let x = Vec3::new(1.0, 0.0, 0.0);
    for (dir, d) in [(x, NAN), (x, INF), (Vec3::new(NAN, 0.0, 0.0), 0.5)] {
        assert_eq!(m.time_to_reach(dir, d), None, "{dir:?} {d}");
    }
    let a = Vec3::new(1.5, -1.0, 0.0);
    for (p, q) in [
        (Vec3::new(NAN, 0.0, 0.0), a),
        (a, Vec3::new(1.5, INF, 0.0)),
        (a, a),
    ] {
        assert_eq!(m.crossing(p, q), None, "{p:?} {q:?}");
        assert_eq!(m.crossing_line(p, q - p), None, "{p:?} {q:?}");
    }
    let s = two_balls();
    assert_eq!(s.contact_distance(Vec3::new(NAN, 0.0, 0.0), 1), None);
    assert_eq!(s.contact_distance(x, 0), None);
    assert_eq!(s.contact_distance(x, 17), None);
    for p in Table::pool().pockets() {
        assert!(p.centre().is_finite());
    }
}
