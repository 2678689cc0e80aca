//! Logic behind `cuesight shot`: shot guidance from a scene (a TOML or JSON file, flags,
//! or both) — the inverse aim that pockets a chosen ball, or the given aim played
//! forward — as human-readable guidance, one JSON object, and an SVG drawing.
//!
//! Exit codes, as for `cuesight collide`: 0 success; 1 an invalid value (off the table,
//! overlapping balls, too many balls, no such ball or pocket, a physical parameter out of
//! range), no aim found, or the SVG file not written; 2 a usage error (unreadable or
//! malformed scene file, a scene or params file over 1 MiB, unknown key or name,
//! unparsable number, missing input). Every error is one line on stderr,
//! `error: <message>`.

pub mod input;
pub mod report;
pub mod table_report;

use std::fmt;
use std::process::ExitCode;

use cuesight::aim::{AimError, AimSolution};
use cuesight::guidance::{guide, Aim, Guidance, Target};
use cuesight::shot::{play, Shot, Stroke};
use cuesight::travel::Motion;

pub use cuesight::guidance::{End, PathEnd};
pub use input::{Flags, Request};
pub use report::{to_json, ShotReport};
pub use table_report::TableOutcome;

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
    /// The core's guidance, which the report presents.
    pub guidance: Guidance,
    /// The whole table after the shot.
    pub table: TableOutcome,
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
/// at the aim and report. The numbers come from the core's [`guide`], as the firmware's
/// `shot` answer does; this adds the scene echo and the pocket names.
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
    let target = request
        .pocket
        .zip(object)
        .map(|(pocket, object)| Target { object, pocket });
    let aim = match request.aim_deg {
        Some(aim_deg) => Aim::Degrees { aim_deg, target },
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
            Aim::Solve(Target { object, pocket })
        }
    };
    let guidance = guide(scene, request.speed, request.tip, aim, setup).map_err(|e| {
        let target = target.unwrap_or(Target {
            object: object.unwrap_or(1),
            pocket: request.pocket.unwrap_or(0),
        });
        aim_error(e, target.object, input::pocket_phrase(table, target.pocket))
    })?;
    let stroke = Stroke::new(request.speed, request.tip, guidance.stroke.aim).map_err(invalid)?;
    let shot = play(scene, &stroke, setup).map_err(invalid)?;
    let table = table_report::simulate(&request, &stroke, &shot.cue_before)?;
    let report = ShotReport::new(&request, &guidance, &table);
    Ok(Played {
        table,
        stroke,
        solution: guidance.solve.map(|s| s.solution),
        shot,
        cue_motion: guidance.cue_ball.motion,
        cue_end: guidance.cue_ball.end,
        object_end: guidance.object_ball.map(|b| b.end),
        guidance,
        report,
        request,
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

/// Run `cuesight shot`: print the guidance (or JSON), write the SVG if asked; errors as
/// one line on stderr, output as [`crate::cli::write_output`] (never a panic).
pub fn main(flags: &Flags) -> ExitCode {
    let played = match run(flags) {
        Ok(played) => played,
        Err(error) => {
            crate::cli::error_line(&error);
            return ExitCode::from(error.code);
        }
    };
    if let Some(path) = &flags.svg {
        if let Err(e) = std::fs::write(path, crate::svg::render(&played)) {
            crate::cli::error_line(format_args!("svg file {}: {e}", path.display()));
            return ExitCode::from(EXIT_INVALID);
        }
    }
    crate::cli::write_output(|out| {
        if flags.json {
            writeln!(out, "{}", to_json(&played.report))
        } else {
            writeln!(out, "{}", played.report)?;
            match &flags.svg {
                Some(path) => writeln!(out, "drawing: {}", path.display()),
                None => Ok(()),
            }
        }
    })
}
