//! Logic behind the `cuesight` command line (the binary only declares the clap
//! interface and calls into here).
//!
//! Exit codes: 0 success; 1 an invalid physical value (rejected by the core's
//! validating constructors) or a solver failure; 2 a usage error (unparsable number,
//! malformed `--spin`, unknown model, conflicting or missing options). Every error is
//! reported as exactly one line on stderr, `error: <message>`, naming the field.
//!
//! Output ([`write_output`], [`output_error`]): every subcommand writes stdout through
//! one place, which never panics. A closed stdout (a broken pipe: `| head`) ends the
//! command quietly with exit 0; any other write error (a full disk) is one line on
//! stderr, `error: writing the output: <cause>`, and exit 1. Lines on stderr
//! ([`error_line`]) ignore a failed stderr.

use core::fmt;
use std::io::{self, Write};
use std::process::ExitCode;

use cuesight::{Impact, Model, Outcome, Params};
use cuesight_link::response::InputEcho;
use cuesight_link::{Collide, Defaults, LinkError, ModelName};

use crate::report::Report;

/// Exit code for an invalid physical value or a solver failure.
pub const EXIT_INVALID: u8 = 1;
/// Exit code for a usage error (what clap rejects).
pub const EXIT_USAGE: u8 = 2;

/// The most any input file may hold (scene, params, throw, session): 1 MiB.
pub const MAX_INPUT_BYTES: u64 = 1 << 20;

/// Reads `path` whole, at most [`MAX_INPUT_BYTES`]: a larger file, or a source without
/// end (`/dev/zero`), is refused after reading one byte more than the limit. The error
/// is the cause alone (the caller names the file).
pub fn read_input(path: &std::path::Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    file.take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(format!(
            "larger than {MAX_INPUT_BYTES} bytes (1 MiB), refused"
        ));
    }
    Ok(bytes)
}

/// Writes one line on stderr, `error: <message>`; a failed stderr is ignored (there is
/// nowhere left to report it).
pub fn error_line(message: impl fmt::Display) {
    let _ = writeln!(io::stderr().lock(), "error: {message}");
}

/// The exit code for a failed write to stdout: 0 for a closed pipe (the reader has all
/// it wanted), [`EXIT_INVALID`] for anything else.
pub fn output_exit_code(error: &io::Error) -> u8 {
    if error.kind() == io::ErrorKind::BrokenPipe {
        0
    } else {
        EXIT_INVALID
    }
}

/// Handles a failed write to stdout, the one place that does: a closed pipe is quiet,
/// anything else is reported on stderr as `error: writing the output: <cause>`.
/// Returns the exit code ([`output_exit_code`]).
pub fn output_error(error: &io::Error) -> u8 {
    let code = output_exit_code(error);
    if code != 0 {
        error_line(format_args!("writing the output: {error}"));
    }
    code
}

/// Runs `write` on the locked stdout and flushes it; the exit code is success, or what
/// [`output_error`] makes of a failed write.
pub fn write_output(write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> ExitCode {
    let mut out = io::stdout().lock();
    match write(&mut out).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => ExitCode::from(output_error(&error)),
    }
}

/// [`write_output`] of `text` and a newline.
pub fn print_line(text: impl fmt::Display) -> ExitCode {
    write_output(|out| writeln!(out, "{text}"))
}

/// Parse a `--model` value: a core model (`ideal`, `kim`, `kim-grip`, ...) or
/// `reference`, by the link's [`ModelName`] (the names a request's `model` takes).
pub fn parse_model(name: &str) -> Result<ModelName, String> {
    ModelName::ALL
        .into_iter()
        .find(|model| model.name() == name)
        .ok_or_else(|| {
            format!(
                "unknown model, expected one of {}",
                ModelName::ALL.map(ModelName::name).join(", ")
            )
        })
}

/// Parse a `--spin` value `WX,WY,WZ` (rad/s, collision frame). Only the syntax is
/// checked here; the range (and NaN) is left to the core, which names the component.
pub fn parse_spin(text: &str) -> Result<[f32; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "spin needs three comma-separated numbers WX,WY,WZ (rad/s), got {}",
            parts.len()
        ));
    }
    let mut spin = [0.0; 3];
    for ((value, part), axis) in spin.iter_mut().zip(&parts).zip(["x", "y", "z"]) {
        *value = part
            .parse::<f32>()
            .map_err(|_| format!("spin.{axis} '{part}' is not a number"))?;
    }
    Ok(spin)
}

/// Parse a `--tip` value `SIDE,HEIGHT` (ball radii, as `shot --tip`). Only the syntax
/// is checked here; the bound (`|b| ≤ 0.5 R`) is the core's strike's.
pub fn parse_tip(text: &str) -> Result<[f32; 2], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        return Err(format!(
            "tip needs two comma-separated numbers SIDE,HEIGHT (ball radii), got {}",
            parts.len()
        ));
    }
    let mut tip = [0.0; 2];
    for ((value, part), name) in tip.iter_mut().zip(&parts).zip(["side", "height"]) {
        *value = part
            .parse::<f32>()
            .map_err(|_| format!("tip {name} '{part}' is not a number"))?;
    }
    Ok(tip)
}

/// The spin (rad/s, collision frame) of a cue ball that arrives at the request's speed
/// and cut with the state a cue strike at `tip` gives it (`SIDE,HEIGHT` in ball radii:
/// side > 0 right english, height > 0 follow; `0,0.4` is natural roll). The core's
/// [`cuesight::strike::strike`] gives the spin per unit of ball speed, which depends on
/// neither the cue nor its speed (TP A.30: `ω = 5 v b / 2R²`), scaled to the speed, and
/// [`cuesight::strike::Strike::to_impact`] turns it into the collision frame. As there,
/// what the cloth does between the strike and the impact is not applied. Errors: the
/// request's own (speed, cut, radius), a tip beyond `0.5 R`.
pub fn tip_spin(request: &Collide, tip: [f32; 2]) -> Result<[f32; 3], CliError> {
    use cuesight::strike::{strike, Cue, Strike, TipOffset};
    let stun = Collide {
        spin: None,
        roll: false,
        ..*request
    };
    let prepared = stun.prepare(&Defaults::POOL)?;
    let params = &prepared.params;
    let offset = TipOffset::from_radius_fraction(tip[0], tip[1], params.radius())?;
    let unit = strike(params, &Cue::TYPICAL, offset, 1.0)?;
    let speed = prepared.impact.speed();
    let arriving = Strike {
        speed,
        spin: unit.spin * (speed / unit.speed),
    };
    let impact = arriving.to_impact(request.cut.to_radians())?;
    Ok(impact.spin().to_array())
}

/// Why a well-formed request produced no prediction.
#[derive(Clone, Debug, PartialEq)]
pub enum CliError {
    /// The core rejected an input value (or reported a numerical failure).
    Core(cuesight::Error),
    /// The reference solver panicked or returned non-finite numbers.
    Reference(String),
    /// A request the options cannot express (`spin` with `roll`; clap refuses it first).
    Usage(String),
}

impl CliError {
    /// Process exit code for this error.
    pub const fn exit_code(&self) -> u8 {
        match self {
            CliError::Usage(_) => EXIT_USAGE,
            _ => EXIT_INVALID,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Core(error) => fmt::Display::fmt(error, f),
            CliError::Reference(message) => write!(f, "model reference: {message}"),
            CliError::Usage(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for CliError {}

impl From<cuesight::Error> for CliError {
    fn from(error: cuesight::Error) -> Self {
        CliError::Core(error)
    }
}

impl From<LinkError> for CliError {
    fn from(error: LinkError) -> Self {
        match error {
            LinkError::Invalid(error) => CliError::Core(error),
            other => CliError::Usage(crate::device::text::Sentence(&other).to_string()),
        }
    }
}

/// Validate the request through the core's constructors (the link's
/// [`Collide::prepare`], as the firmware does, from the pool defaults and `kim-grip`),
/// run the chosen solver and report the result.
pub fn collide(request: &Collide) -> Result<Report, CliError> {
    collide_within(request, None).map(|(report, _)| report)
}

/// As [`collide`], with `auto`'s tolerance (`None`: the link's default, 1e-3; checked
/// by the core, in `(0, 1]`), and for `auto` the tier it picked
/// ([`cuesight::select_model`], the function `Model::Auto` evaluates). A tolerance
/// with another model is a usage error.
pub fn collide_within(
    request: &Collide,
    tolerance: Option<f32>,
) -> Result<(Report, Option<AutoPick>), CliError> {
    let prepared = request.prepare(&Defaults::POOL)?;
    let model = match (prepared.model.core(), tolerance) {
        (Some(Model::Auto { .. }), Some(tolerance)) => Some(Model::Auto { tolerance }),
        (_, Some(_)) => {
            return Err(CliError::Usage(format!(
                "--tolerance is for --model auto, not {}",
                prepared.model.name()
            )))
        }
        (model, None) => model,
    };
    let (params, impact) = (&prepared.params, &prepared.impact);
    let outcome = match model {
        Some(model) => cuesight::collide(params, impact, model)?,
        None => reference_collide(params, impact)?,
    };
    // After `collide`, which has checked the tolerance.
    let pick = match model {
        Some(Model::Auto { tolerance }) => {
            let (tier, estimate) = cuesight::select_model(params, impact, tolerance);
            Some(AutoPick {
                tolerance,
                tier,
                estimate,
            })
        }
        _ => None,
    };
    let report = Report::new(prepared.model, InputEcho::of(request, &prepared), &outcome);
    Ok((report, pick))
}

/// What `Model::Auto` did: the tier it evaluated and that tier's a-priori error
/// estimate (`max(|Δv|, R|Δω|) / U`), for its tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoPick {
    /// The tolerance asked for.
    pub tolerance: f32,
    /// The tier evaluated: the cheapest whose estimate is within the tolerance, `exact`
    /// if none is.
    pub tier: Model,
    /// The tier's estimate.
    pub estimate: f32,
}

/// Run the reference solver, turning a panic into an error instead of a trace.
///
/// Swaps the process-wide panic hook for the duration of the call, so this is meant
/// for the single-threaded CLI, not for concurrent tests.
fn reference_collide(params: &Params, impact: &Impact) -> Result<Outcome, CliError> {
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(|| cuesight_host::reference::collide(params, impact));
    std::panic::set_hook(previous_hook);
    match result {
        Ok(outcome) if outcome.is_finite() => Ok(outcome),
        Ok(_) => Err(CliError::Reference("non-finite result".to_owned())),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_owned());
            Err(CliError::Reference(format!("solver panicked: {message}")))
        }
    }
}

/// Compress a clap error into one line (without the `error: ` prefix): its message
/// plus any detail lines clap puts under it (missing arguments, possible values),
/// but not the usage block or the `--help` hint.
pub fn usage_error_message(error: &clap::Error) -> String {
    let rendered = error.to_string();
    let mut parts = Vec::new();
    for line in rendered.lines() {
        let line = line.trim();
        if line.starts_with("Usage:") || line.starts_with("For more information") {
            break;
        }
        if !line.is_empty() {
            parts.push(line);
        }
    }
    let joined = parts.join(" ");
    joined
        .strip_prefix("error:")
        .map(str::trim)
        .unwrap_or(&joined)
        .to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight::Field;

    #[test]
    fn spin_parses_negative_and_spaced_components() {
        assert_eq!(parse_spin("-10,0,5"), Ok([-10.0, 0.0, 5.0]));
        assert_eq!(parse_spin(" 1.5 , -2e1 ,0"), Ok([1.5, -20.0, 0.0]));
    }

    #[test]
    fn spin_rejects_wrong_arity_and_junk() {
        assert!(parse_spin("1,2").unwrap_err().contains("three"));
        assert!(parse_spin("1,2,3,4").unwrap_err().contains("three"));
        assert!(parse_spin("1,x,3").unwrap_err().contains("spin.y"));
        assert!(parse_spin("").is_err());
    }

    #[test]
    fn tip_parses_and_gives_the_strikes_spin() {
        assert_eq!(parse_tip("-0.2, 0.3"), Ok([-0.2, 0.3]));
        assert!(parse_tip("0.1").unwrap_err().contains("two"));
        assert!(parse_tip("0.1,up").unwrap_err().contains("tip height"));
        let request = Collide::new(2.0, 0.0);
        let r = Defaults::POOL.params.radius();
        // 2R/5 above centre: natural roll, w_y = U / R.
        let roll = tip_spin(&request, [0.0, 0.4]).unwrap();
        assert!((roll[1] - 2.0 / r).abs() < 1e-5 * roll[1], "{roll:?}");
        assert_eq!([roll[0], roll[2]], [0.0, 0.0]);
        // Right english: counter-clockwise from above (the strike's sign).
        let right = tip_spin(&request, [0.3, 0.0]).unwrap();
        assert!(right[2] > 0.0 && right[1] == 0.0, "{right:?}");
        // Centre: stun. Beyond R/2: the core's tip error.
        assert_eq!(tip_spin(&request, [0.0, 0.0]).unwrap(), [0.0; 3]);
        let CliError::Core(e) = tip_spin(&request, [0.0, 0.6]).unwrap_err() else {
            panic!("not the core's error")
        };
        assert_eq!(e.field(), Some(Field::TipOffset));
    }

    #[test]
    fn model_names_round_trip() {
        for model in ModelName::ALL {
            assert_eq!(parse_model(model.name()), Ok(model));
        }
        assert_eq!(parse_model("reference"), Ok(ModelName::Reference));
        assert!(parse_model("kimgrip").unwrap_err().contains("kim-grip"));
    }

    #[test]
    fn invalid_values_name_their_field() {
        let base = Collide::new(1.0, 0.0);
        let cases = [
            (
                Collide {
                    mu: Some(-0.1),
                    ..base
                },
                Field::Friction,
            ),
            (
                Collide {
                    mu_b: Some(2.0),
                    ..base
                },
                Field::FrictionAmplitude,
            ),
            (
                Collide {
                    restitution: Some(1.5),
                    ..base
                },
                Field::Restitution,
            ),
            (
                Collide {
                    mu_s: Some(f32::NAN),
                    ..base
                },
                Field::TableFriction,
            ),
            (
                Collide {
                    radius: Some(0.0),
                    ..base
                },
                Field::Radius,
            ),
            (
                Collide {
                    mass: Some(1e6),
                    ..base
                },
                Field::Mass,
            ),
            (Collide { speed: 0.0, ..base }, Field::Speed),
            (Collide { cut: 90.0, ..base }, Field::CutAngle),
            (
                Collide {
                    cut: -90.0,
                    roll: true,
                    ..base
                },
                Field::CutAngle,
            ),
            (
                Collide {
                    spin: Some([0.0, f32::INFINITY, 0.0]),
                    ..base
                },
                Field::SpinY,
            ),
        ];
        for (request, field) in cases {
            let error = collide(&request).unwrap_err();
            let CliError::Core(core_error) = &error else {
                panic!("{request:?}: {error}")
            };
            assert_eq!(core_error.field(), Some(field), "{request:?}");
            assert!(error.to_string().starts_with(field.name()), "{error}");
        }
        let both = Collide {
            spin: Some([0.0; 3]),
            roll: true,
            ..base
        };
        assert_eq!(collide(&both).unwrap_err().exit_code(), EXIT_USAGE);
    }
}
