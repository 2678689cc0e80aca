//! Logic behind the `cuesight` command line (the binary only declares the clap
//! interface and calls into here).
//!
//! Exit codes: 0 success; 1 an invalid physical value (rejected by the core's
//! validating constructors) or a solver failure; 2 a usage error (unparsable number,
//! malformed `--spin`, unknown model, conflicting or missing options). Every error is
//! reported as exactly one line on stderr, `error: <message>`, naming the field.

use core::fmt;

use cuesight::{Impact, Model, Outcome, Params};

use crate::report::{InputReport, Report};

/// Exit code for an invalid physical value or a solver failure.
pub const EXIT_INVALID: u8 = 1;
/// Exit code for a usage error (what clap rejects).
pub const EXIT_USAGE: u8 = 2;

/// Which solver answers a `collide` request.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModelChoice {
    /// One of the core's closed-form models.
    Core(Model),
    /// The host's f64 first-principles reference solver.
    Reference,
}

impl ModelChoice {
    /// Every accepted name, in the order shown to users.
    pub const NAMES: [&'static str; 4] = ["ideal", "kim", "kim-grip", "reference"];

    /// Name as accepted by `--model`.
    pub const fn name(self) -> &'static str {
        match self {
            ModelChoice::Core(model) => model.name(),
            ModelChoice::Reference => "reference",
        }
    }
}

/// Parse a `--model` value (`ideal`, `kim`, `kim-grip` or `reference`).
pub fn parse_model(name: &str) -> Result<ModelChoice, String> {
    if name == "reference" {
        return Ok(ModelChoice::Reference);
    }
    Model::from_name(name)
        .map(ModelChoice::Core)
        .ok_or_else(|| {
            format!(
                "unknown model, expected one of {}",
                ModelChoice::NAMES.join(", ")
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

/// Cue-ball spin before impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpinInput {
    /// Given angular velocity `[ω_x, ω_y, ω_z]` (rad/s); zero is a stun shot.
    Given([f32; 3]),
    /// Natural roll for the cue-ball velocity ([`Impact::rolling`]).
    Roll,
}

/// A `collide` request, as parsed from the command line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CollideRequest {
    /// Cue-ball speed `U_i` (m/s).
    pub speed: f32,
    /// Cut angle `φ` (degrees).
    pub cut_deg: f32,
    /// Cue-ball spin.
    pub spin: SpinInput,
    /// Ball–ball friction μ.
    pub mu: f32,
    /// Energetic restitution e*.
    pub restitution: f32,
    /// Object-ball/table friction μ_s.
    pub mu_s: f32,
    /// Ball radius R (m).
    pub radius: f32,
    /// Ball mass M (kg).
    pub mass: f32,
    /// Solver to use.
    pub model: ModelChoice,
}

impl Default for CollideRequest {
    /// A 1 m/s head-on stun shot with the pool parameters and `kim-grip`.
    fn default() -> Self {
        let p = Params::POOL;
        Self {
            speed: 1.0,
            cut_deg: 0.0,
            spin: SpinInput::Given([0.0; 3]),
            mu: p.mu(),
            restitution: p.restitution(),
            mu_s: p.mu_s(),
            radius: p.radius(),
            mass: p.mass(),
            model: ModelChoice::Core(Model::KimGrip),
        }
    }
}

/// Why a well-formed request produced no prediction.
#[derive(Clone, Debug, PartialEq)]
pub enum CliError {
    /// The core rejected an input value (or reported a numerical failure).
    Core(cuesight::Error),
    /// The reference solver panicked or returned non-finite numbers.
    Reference(String),
}

impl CliError {
    /// Process exit code for this error.
    pub const fn exit_code(&self) -> u8 {
        EXIT_INVALID
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Core(error) => fmt::Display::fmt(error, f),
            CliError::Reference(message) => write!(f, "model reference: {message}"),
        }
    }
}

impl std::error::Error for CliError {}

impl From<cuesight::Error> for CliError {
    fn from(error: cuesight::Error) -> Self {
        CliError::Core(error)
    }
}

/// Validate the request through the core's constructors, run the chosen solver and
/// report the result.
pub fn collide(request: &CollideRequest) -> Result<Report, CliError> {
    let params = Params::new(
        request.mu,
        request.restitution,
        request.mu_s,
        request.radius,
        request.mass,
    )?;
    let (impact, roll) = match request.spin {
        SpinInput::Given(spin) => (
            Impact::from_cut_degrees(request.speed, request.cut_deg, spin)?,
            false,
        ),
        SpinInput::Roll => {
            // Validate speed and cut first so errors name them, then spin up.
            let v = Impact::from_cut_degrees(request.speed, request.cut_deg, [0.0; 3])?.velocity();
            (Impact::rolling([v.x, v.y], params.radius())?, true)
        }
    };
    let outcome = match request.model {
        ModelChoice::Core(model) => cuesight::collide(&params, &impact, model)?,
        ModelChoice::Reference => reference_collide(&params, &impact)?,
    };
    let input = InputReport::new(request.speed, request.cut_deg, roll, &params, &impact);
    Ok(Report::new(request.model.name(), input, &outcome))
}

/// Run the reference solver, turning a panic into an error instead of a trace.
///
/// Swaps the process-wide panic hook for the duration of the call, so this is meant
/// for the single-threaded CLI, not for concurrent tests.
fn reference_collide(params: &Params, impact: &Impact) -> Result<Outcome, CliError> {
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(|| crate::reference::collide(params, impact));
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
    fn model_names_round_trip() {
        for name in ModelChoice::NAMES {
            assert_eq!(parse_model(name).unwrap().name(), name);
        }
        assert!(parse_model("kimgrip").is_err());
    }

    #[test]
    fn invalid_values_name_their_field() {
        let base = CollideRequest::default();
        let cases = [
            (CollideRequest { mu: -0.1, ..base }, Field::Friction),
            (
                CollideRequest {
                    restitution: 1.5,
                    ..base
                },
                Field::Restitution,
            ),
            (
                CollideRequest {
                    mu_s: f32::NAN,
                    ..base
                },
                Field::TableFriction,
            ),
            (
                CollideRequest {
                    radius: 0.0,
                    ..base
                },
                Field::Radius,
            ),
            (CollideRequest { mass: 1e6, ..base }, Field::Mass),
            (CollideRequest { speed: 0.0, ..base }, Field::Speed),
            (
                CollideRequest {
                    cut_deg: 90.0,
                    ..base
                },
                Field::CutAngle,
            ),
            (
                CollideRequest {
                    cut_deg: -90.0,
                    spin: SpinInput::Roll,
                    ..base
                },
                Field::CutAngle,
            ),
            (
                CollideRequest {
                    spin: SpinInput::Given([0.0, f32::INFINITY, 0.0]),
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
    }
}
