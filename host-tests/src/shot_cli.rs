//! Logic behind `cuesight shot`: shot guidance from a scene (a TOML or JSON file, flags,
//! or both) — the inverse aim that pockets a chosen ball, or the given aim played
//! forward — as human-readable guidance, one JSON object, and an SVG drawing.
//!
//! Exit codes, as for `cuesight collide`: 0 success; 1 an invalid value (off the table,
//! overlapping balls, too many balls, no such ball or pocket, a physical parameter out of
//! range), no aim found, or the SVG file not written; 2 a usage error (unreadable or
//! malformed scene file, unknown key or name, unparsable number, missing input). Every
//! error is one line on stderr, `error: <message>`.

pub mod input;
pub mod report;

use std::fmt;
use std::process::ExitCode;

use cuesight::aim::{solve_aim, AimError, AimSolution};
use cuesight::shot::{play, Shot, Stroke};
use cuesight::travel::{Motion, GRAVITY};
use cuesight::{select_model, Model, Vec3};

pub use input::{Flags, Request};
pub use report::{to_json, End, PathEnd, ShotReport};

use report::{BallReport, ContactReport, SolveReport, StrokeReport, TableReport, TargetReport};

/// Exit code for an invalid value, no solution, or an output file not written.
pub const EXIT_INVALID: u8 = crate::cli::EXIT_INVALID;
/// Exit code for a usage error.
pub const EXIT_USAGE: u8 = crate::cli::EXIT_USAGE;

/// Why `cuesight shot` gave no answer: a one-line message and the exit code.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShotError {
    /// What is wrong, naming the input.
    pub message: String,
    /// [`EXIT_INVALID`] or [`EXIT_USAGE`].
    pub code: u8,
}

impl ShotError {
    /// A usage error (exit 2).
    pub fn usage(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            code: EXIT_USAGE,
        }
    }

    /// An invalid value or no solution (exit 1).
    pub fn invalid(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            code: EXIT_INVALID,
        }
    }
}

impl fmt::Display for ShotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ShotError {}

/// A played shot: the request, the core's answer, and the report.
#[derive(Clone, Debug)]
pub struct Played {
    /// The validated request.
    pub request: Request,
    /// The stroke played (the solved aim in solve mode).
    pub stroke: Stroke,
    /// The inverse aim, in solve mode.
    pub solution: Option<AimSolution>,
    /// The forward chain at the played aim.
    pub shot: Shot,
    /// The cue ball's motion after the impact, or from the strike without contact.
    pub cue_motion: Motion,
    /// How far the cue ball's path goes.
    pub cue_end: PathEnd,
    /// How far the object ball's path goes.
    pub object_end: Option<PathEnd>,
    /// The answer.
    pub report: ShotReport,
}

/// Resolve the flags (and scene file) and play the shot.
pub fn run(flags: &Flags) -> Result<Played, ShotError> {
    play_request(Request::resolve(flags)?)
}

fn aim_error(error: AimError, object: usize, pocket: String) -> ShotError {
    ShotError::invalid(match error {
        AimError::Invalid(e) => e.to_string(),
        AimError::ObjectBallNotHit => format!(
            "no aim: at the ghost-ball aim the cue ball does not reach ball {object} first (another ball in the way, or too slow)"
        ),
        AimError::PocketUnreachable => format!(
            "no aim: ball {object} cannot reach {pocket} (it stops short, or the cut is too thin)"
        ),
        AimError::NotConverged => format!(
            "no aim: the solver did not converge for ball {object} into {pocket} (the cut may be too thin)"
        ),
    })
}

/// Play a validated request: solve the aim if none is given, then run the forward chain
/// at the aim and report.
pub fn play_request(request: Request) -> Result<Played, ShotError> {
    let scene = &request.scene;
    let table = scene.table();
    let setup = &request.setup;
    let invalid = |e: cuesight::Error| ShotError::invalid(e.to_string());
    let ball_count = scene.balls().len();
    // The ball the chosen pocket is for.
    let object = request
        .object
        .or((ball_count > 1).then_some(1))
        .filter(|&o| o < ball_count);
    let (stroke, solution) = match request.aim_deg {
        Some(deg) => (
            Stroke::at_angle(request.speed, request.tip, deg.to_radians()).map_err(invalid)?,
            None,
        ),
        None => {
            let pocket = request.pocket.ok_or_else(|| {
                ShotError::usage(if table.pockets().is_empty() {
                    format!(
                        "no aim: the {} table has no pockets to solve for, give --aim DEG",
                        request.table_name
                    )
                } else {
                    "no aim: give --aim DEG, or --pocket N (and --object N) to solve for one"
                        .to_owned()
                })
            })?;
            let object = object.ok_or_else(|| {
                ShotError::invalid("nothing to pocket: the scene has no ball besides the cue ball")
            })?;
            check_cut(scene, object, pocket)?;
            let solution = solve_aim(scene, object, pocket, request.speed, request.tip, setup)
                .map_err(|e| aim_error(e, object, input::pocket_phrase(table, pocket)))?;
            let stroke = Stroke::new(request.speed, request.tip, [solution.aim.x, solution.aim.y])
                .map_err(invalid)?;
            (stroke, Some(solution))
        }
    };
    let shot = play(scene, &stroke, setup).map_err(invalid)?;
    let radius = scene.radius();

    let contact = shot.contact.as_ref();
    let cue_motion = contact.map_or(shot.cue_before, |c| c.cue_after);
    let cue_end = PathEnd::of(&cue_motion, table, radius);
    let object_end = contact.map(|c| PathEnd::of(&c.object_after, table, radius));
    let start_velocity = |m: &Motion| {
        let v = m.initial_velocity;
        Vec3::new(v.x, v.y, 0.5 * GRAVITY * m.air_time)
    };

    let aim = stroke.aim();
    let aim_deg = request
        .aim_deg
        .unwrap_or_else(|| aim.y.atan2(aim.x).to_degrees());
    let launch = &shot.cue_before;
    let stroke_report = StrokeReport {
        cue_speed: request.speed,
        tip: request.tip_radii,
        aim_deg,
        aim: [aim.x, aim.y],
        launch_speed: launch.initial_velocity.length(),
        launch_spin: launch.initial_spin.to_array(),
    };
    let solve_report = solution.as_ref().map(|s| SolveReport {
        object: object.unwrap_or(1),
        pocket: request.pocket.unwrap_or(0),
        pocket_name: input::pocket_name(table, request.pocket.unwrap_or(0)),
        aim_deg,
        naive_aim_deg: s.naive_aim.y.atan2(s.naive_aim.x).to_degrees(),
        correction_deg: s.correction_deg,
        correction_offset: 1e-3 * s.correction_mm,
        thinner: s.thinner,
        cut_deg: s.cut_angle_deg,
        ghost_ball: [s.ghost_ball.x, s.ghost_ball.y],
        naive_ghost_ball: [s.naive_ghost_ball.x, s.naive_ghost_ball.y],
        evaluations: s.evaluations,
        residual: s.residual,
    });
    let contact_report = contact.map(|c| {
        let (used, estimate) = match setup.model {
            Model::Auto { tolerance } => {
                let (tier, estimate) = select_model(&setup.params, &c.impact, tolerance);
                (tier, Some(estimate))
            }
            model => (model, None),
        };
        ContactReport {
            ball: c.object_ball,
            time: c.time,
            cue_position: [c.cue_position.x, c.cue_position.y],
            line_of_centres: [c.line_of_centres.x, c.line_of_centres.y],
            cut_deg: c.cut_angle.to_degrees(),
            speed: shot.cue_before.velocity_at(c.time).length(),
            spin: shot.cue_before.spin_at(c.time).to_array(),
            model: setup.model.name(),
            model_used: used.name(),
            error_estimate: estimate,
            regime: c.outcome.regime.name(),
            throw_deg: c.outcome.throw_angle_deg(),
        }
    });
    let cue_ball = BallReport::new(0, &cue_motion, start_velocity(&cue_motion), cue_end, table);
    let object_ball = contact.zip(object_end).map(|(c, end)| {
        BallReport::new(
            c.object_ball,
            &c.object_after,
            start_velocity(&c.object_after),
            end,
            table,
        )
    });
    let target = request.pocket.zip(object).map(|(pocket, object)| {
        let hit = contact.filter(|c| c.object_ball == object);
        let miss = hit.and_then(|c| mouth_miss(&c.object_after, table, pocket));
        let pocketed = hit.is_some()
            && object_end.is_some_and(|e| e.end == End::Pocket && e.pocket == Some(pocket));
        TargetReport {
            object,
            pocket,
            pocket_name: input::pocket_name(table, pocket),
            pocketed,
            miss,
        }
    });
    let report = ShotReport {
        mode: if solution.is_some() { "solve" } else { "play" },
        table: TableReport::new(request.table_name, table, radius, request.mass),
        balls: scene.balls().iter().map(|b| [b.x, b.y]).collect(),
        mu_cloth: setup.cloth.sliding(),
        mu_roll: setup.cloth.rolling(),
        stroke: stroke_report,
        solve: solve_report,
        contact: contact_report,
        cue_ball,
        object_ball,
        target,
    };
    Ok(Played {
        request,
        stroke,
        solution,
        shot,
        cue_motion,
        cue_end,
        object_end,
        report,
    })
}

/// Reject a pocket the object ball cannot be cut into: the ghost-ball cut is 90° or
/// more (the solver would only report that the ball is not hit).
fn check_cut(
    scene: &cuesight::table::Scene,
    object: usize,
    pocket: usize,
) -> Result<(), ShotError> {
    let (cue, ball) = (scene.balls()[0], scene.balls()[object]);
    let Some(target) = scene.table().pockets().get(pocket) else {
        return Ok(());
    };
    let to_pocket = target.centre() - ball;
    let ghost = ball - to_pocket * (2.0 * scene.radius() / to_pocket.length());
    let (aim, centres) = (ghost - cue, ball - ghost);
    let cut = (centres.x * aim.y - centres.y * aim.x)
        .atan2(centres.dot(aim))
        .to_degrees();
    if cut.abs() >= 89.0 {
        return Err(ShotError::invalid(format!(
            "no aim: ball {object} cannot be cut into {}: the ghost-ball cut would be {:.1}° (90° or more)",
            input::pocket_phrase(scene.table(), pocket),
            cut.abs()
        )));
    }
    Ok(())
}

/// Where `motion`'s centre crosses pocket `pocket`'s mouth line (its target segment
/// extended), from the target centre along the segment (m, signed) — the miss the aim
/// solver drives to zero. Cushions are ignored.
fn mouth_miss(motion: &Motion, table: &cuesight::table::Table, pocket: usize) -> Option<f32> {
    let p = table.pockets().get(pocket)?;
    let centre = p.centre();
    let along = p.b - p.a;
    let along = along * (1.0 / along.length());
    let t = motion.crossing(centre - along * 20.0, centre + along * 20.0)?;
    Some(along.dot(motion.position_at(t) - centre))
}

/// Run `cuesight shot`: print the guidance (or JSON), write the SVG if asked; errors as
/// one line on stderr.
pub fn main(flags: &Flags) -> ExitCode {
    let played = match run(flags) {
        Ok(played) => played,
        Err(error) => {
            eprintln!("error: {error}");
            return ExitCode::from(error.code);
        }
    };
    if let Some(path) = &flags.svg {
        if let Err(e) = std::fs::write(path, crate::svg::render(&played)) {
            eprintln!("error: svg file {}: {e}", path.display());
            return ExitCode::from(EXIT_INVALID);
        }
    }
    if flags.json {
        println!("{}", to_json(&played.report));
    } else {
        println!("{}", played.report);
        if let Some(path) = &flags.svg {
            println!("drawing: {}", path.display());
        }
    }
    ExitCode::SUCCESS
}
