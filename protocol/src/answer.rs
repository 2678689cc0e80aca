//! Answers: one JSON line per request, tagged like the request it answers
//! (`{"collide":{...}}`, `{"error":{...}}`).
//!
//! [`CollideAnswer`] is also what `cuesight collide --json` prints (untagged): the CLI
//! and the firmware produce the same struct, serialized by serde_json on the host and
//! written by hand on the device ([`Answer::write`], byte for byte what serde-json-core
//! wrote). Both print `f32` with `ryu`'s shortest round-trip form, so the same numbers
//! give the same text. All quantities are SI (m, s, kg,
//! rad/s, N·s) in the collision frame of physics-notes §1 (`x` from the cue ball to the
//! object ball, `z` up, `y = z × x`); angles are in degrees.

use cuesight::{BallState, Impact, Impulses, Outcome, Params, Vec3};
use serde::{Deserialize, Serialize};

use crate::names::{ModelName, RegimeName};
use crate::problem::{ErrorKind, Message, Name};
use crate::request::{law_components, Defaults};

/// One answer line. (`shot`'s answer, [`crate::ShotAnswer`], is written on its own: a
/// host reads it as plain JSON, with the keys of `cuesight shot --json`.)
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Answer {
    /// To `collide`.
    Collide(CollideAnswer),
    /// To `params`: the session defaults now in force.
    Params(ParamsAnswer),
    /// To the last chunk of a `stroke`: the estimate.
    Stroke(StrokeAnswer),
    /// To a `stroke` chunk with `"more":true`: the samples held so far.
    StrokeChunk(StrokeChunkAnswer),
    /// To `version`.
    Version(VersionAnswer),
    /// To `shutdown`, just before the firmware exits.
    Shutdown(ShutdownAnswer),
    /// To anything that could not be answered.
    Error(ErrorAnswer),
}

/// The inputs of a prediction, echoed next to its result.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct InputEcho {
    /// Cue-ball speed before impact `U_i` (m/s).
    pub speed: f32,
    /// Cut angle `φ` (degrees).
    pub cut_deg: f32,
    /// Cue-ball angular velocity before impact (rad/s); for `roll` the natural roll
    /// that was derived from the velocity.
    pub spin: [f32; 3],
    /// `true` when `spin` was set to natural roll rather than given.
    pub roll: bool,
    /// Ball–ball friction μ (for a speed-dependent law, its high-speed limit `a`).
    pub mu: f32,
    /// Amplitude `b` of `μ(v) = a + b·exp(−c·v)`; 0 for constant μ.
    pub mu_b: f32,
    /// Decay rate `c` (s/m) of the speed-dependent friction; 0 for constant μ.
    pub mu_c: f32,
    /// Energetic coefficient of restitution e*.
    pub restitution: f32,
    /// Object-ball/table static friction μ_s.
    pub mu_s: f32,
    /// Ball radius R (m).
    pub radius: f32,
    /// Ball mass M (kg).
    pub mass: f32,
}

impl InputEcho {
    /// Echo of a validated `params` and `impact`; `speed` and `cut_deg` are the values
    /// the impact was built from (the impact itself stores only the velocity).
    pub fn new(speed: f32, cut_deg: f32, roll: bool, params: &Params, impact: &Impact) -> Self {
        let (mu, mu_b, mu_c) = law_components(params.friction_law());
        Self {
            speed,
            cut_deg,
            spin: plain(impact.spin()),
            roll,
            mu,
            mu_b,
            mu_c,
            restitution: params.restitution(),
            mu_s: params.mu_s(),
            radius: params.radius(),
            mass: params.mass(),
        }
    }
}

/// Components as an array, with `-0.0` shown as `0` (the sign of a zero carries no
/// physics and only clutters the output).
fn plain(v: Vec3) -> [f32; 3] {
    v.to_array().map(|c| c + 0.0)
}

/// One ball just after the impact.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BallAnswer {
    /// Centre velocity (m/s).
    pub v: [f32; 3],
    /// Angular velocity (rad/s).
    pub w: [f32; 3],
}

impl From<&BallState> for BallAnswer {
    fn from(ball: &BallState) -> Self {
        Self {
            v: plain(ball.velocity),
            w: plain(ball.spin),
        }
    }
}

/// Impulses exchanged during the impact (N·s), all acting on the object ball.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImpulsesAnswer {
    /// Ball–ball normal impulse, along `+x`.
    pub normal: f32,
    /// Ball–ball friction impulse; `x` is zero.
    pub friction: [f32; 3],
    /// Magnitude of the table friction impulse (close to `−x`).
    pub table_friction: f32,
}

impl From<&Impulses> for ImpulsesAnswer {
    fn from(impulses: &Impulses) -> Self {
        Self {
            normal: impulses.normal + 0.0,
            friction: plain(impulses.friction),
            table_friction: impulses.table_friction + 0.0,
        }
    }
}

/// A complete prediction: which model, what went in, what came out. The JSON of
/// `cuesight collide --json`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CollideAnswer {
    /// Model.
    pub model: ModelName,
    /// Contact regime.
    pub regime: RegimeName,
    /// The inputs.
    pub input: InputEcho,
    /// Cue ball after the impact.
    pub cue: BallAnswer,
    /// Object ball after the impact.
    pub object: BallAnswer,
    /// Throw angle of the object ball from the line of centres (degrees, positive
    /// towards `+y`).
    pub throw_deg: f32,
    /// Cue-ball deflection from the tangent line towards the line of centres
    /// (degrees).
    pub cue_deflection_deg: f32,
    /// Angle between the balls' horizontal directions of travel (degrees).
    pub separation_deg: f32,
    /// Impulses exchanged.
    pub impulses: ImpulsesAnswer,
}

impl CollideAnswer {
    /// The answer for `outcome`, produced by `model` from `input`.
    pub fn new(model: ModelName, input: InputEcho, outcome: &Outcome) -> Self {
        Self {
            model,
            regime: outcome.regime.into(),
            input,
            cue: BallAnswer::from(&outcome.cue_ball),
            object: BallAnswer::from(&outcome.object_ball),
            throw_deg: outcome.throw_angle_deg() + 0.0,
            cue_deflection_deg: outcome.cue_deflection_deg() + 0.0,
            separation_deg: outcome.separation_angle_deg() + 0.0,
            impulses: ImpulsesAnswer::from(&outcome.impulses),
        }
    }
}

/// The session defaults (answer to `params`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParamsAnswer {
    /// Ball–ball friction μ (high-speed limit `a` of a speed-dependent law).
    pub mu: f32,
    /// Amplitude `b` of the speed-dependent friction; 0 for constant μ.
    pub mu_b: f32,
    /// Decay rate `c` (s/m) of the speed-dependent friction; 0 for constant μ.
    pub mu_c: f32,
    /// Energetic restitution e*.
    pub restitution: f32,
    /// Object-ball/table friction μ_s.
    pub mu_s: f32,
    /// Ball radius R (m).
    pub radius: f32,
    /// Ball mass M (kg).
    pub mass: f32,
    /// Model.
    pub model: ModelName,
}

impl From<&Defaults> for ParamsAnswer {
    fn from(defaults: &Defaults) -> Self {
        let p = &defaults.params;
        let (mu, mu_b, mu_c) = law_components(p.friction_law());
        Self {
            mu,
            mu_b,
            mu_c,
            restitution: p.restitution(),
            mu_s: p.mu_s(),
            radius: p.radius(),
            mass: p.mass(),
            model: defaults.model,
        }
    }
}

/// A stroke estimate (answer to the last `stroke` chunk): the cue speed at the tip
/// impact (`cuesight_sensors::estimate_raw`) and the cue ball it produces
/// (`cuesight::strike`, TP A.30) with the session's ball, in the ball's travel frame
/// (`x` along the cue, `z` up; follow `w.y > 0`, right english `w.z > 0`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StrokeAnswer {
    /// Estimated cue speed just before the tip impact (m/s).
    pub cue_speed: f32,
    /// Cue-ball speed after the strike (m/s).
    pub ball_speed: f32,
    /// Cue-ball angular velocity after the strike (rad/s).
    pub ball_spin: [f32; 3],
    /// Samples in the window (all chunks).
    pub samples: u32,
    /// Index of the first sample touched by the impact.
    pub impact_index: u32,
    /// Integration time from the end of the rest to the impact (s).
    pub stroke_duration: f32,
    /// Standard deviation of the rest window (m/s²): the sensor noise as seen.
    pub rest_noise: f32,
}

/// Samples held so far (answer to a `stroke` chunk with `"more":true`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StrokeChunkAnswer {
    /// Samples received for the stroke in progress.
    pub samples: u32,
    /// [`crate::STROKE_CAPACITY`].
    pub capacity: u32,
}

/// Versions and limits (answer to `version`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VersionAnswer {
    /// [`crate::PROTOCOL_VERSION`].
    pub protocol: u32,
    /// Firmware name and version, e.g. `cuesight-firmware 0.1.0`.
    pub firmware: Name,
    /// Board, e.g. `qemu-mps2-an386`.
    pub board: Name,
    /// Longest request line accepted, in bytes without the newline ([`crate::MAX_LINE`]).
    pub max_line: u32,
    /// Most samples in one `stroke` chunk ([`crate::MAX_SAMPLES`]).
    pub max_samples: u32,
    /// Most samples in one stroke, all chunks ([`crate::STROKE_CAPACITY`]).
    pub stroke_capacity: u32,
}

/// Session statistics (answer to `shutdown`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShutdownAnswer {
    /// Request lines answered in the session, this one included.
    pub requests: u32,
    /// How many of them were answered with an error.
    pub errors: u32,
}

/// What went wrong with a line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrorAnswer {
    /// The class of problem.
    pub kind: ErrorKind,
    /// The field (or request name) it concerns, when there is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<Name>,
    /// One line for a human.
    pub message: Message,
}

impl ErrorAnswer {
    /// The `internal` error: an answer that did not fit the answer buffer (a bug: sizes
    /// are checked by tests).
    pub fn internal() -> Self {
        let mut message = Message::new();
        let _ = message.push_str("the answer did not fit the answer buffer");
        Self {
            kind: ErrorKind::Internal,
            field: None,
            message,
        }
    }
}
