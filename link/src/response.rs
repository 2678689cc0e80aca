//! Answers: what the device sends back, one per request, in order. All quantities SI
//! (m, s, kg, rad/s, N·s); angles in degrees in the fields ending in `_deg`. A
//! [`CollideAnswer`] is also what `cuesight collide --json` prints.

use cuesight::{BallState, Impulses, Outcome, Params, Vec3};
use heapless::String;
use serde::{Deserialize, Serialize};

use crate::error::LinkError;
use crate::live::LiveReport;
use crate::names::{ModelName, RegimeName};
use crate::request::{law_components, Collide, Defaults, PreparedCollide};
use crate::shot::ShotAnswer;

/// Longest firmware or board name, in bytes.
pub const NAME_LEN: usize = 32;

/// One answer.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
#[allow(clippy::large_enum_variant)]
pub enum Response {
    /// To `version`; also sent unprompted at boot.
    Version(VersionAnswer),
    /// To `collide`.
    Collide(CollideAnswer),
    /// To `params`: the defaults now in force.
    Params(ParamsAnswer),
    /// To a stroke chunk that is not the last: the upload so far.
    StrokeChunk(StrokeProgress),
    /// To the last stroke chunk: the estimate.
    Stroke(StrokeAnswer),
    /// To `shot`.
    Shot(ShotAnswer),
    /// To `plan`: whether a plan is now set.
    Plan(bool),
    /// Sent unprompted by the live cue: a stroke, a fault, the end of a trace.
    Live(LiveReport),
    /// To `shutdown`, just before the device exits.
    Shutdown(ShutdownAnswer),
    /// To anything that could not be answered.
    Error(LinkError),
}

/// Schema, firmware and limits.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct VersionAnswer {
    /// The device's [`crate::SCHEMA_HASH`].
    pub schema: u32,
    /// Firmware name and version.
    pub firmware: String<NAME_LEN>,
    /// Board.
    pub board: String<NAME_LEN>,
    /// Longest encoded frame accepted ([`crate::frame::MAX_FRAME`]).
    pub max_frame: u16,
    /// Most samples in one stroke chunk ([`crate::MAX_SAMPLES`]).
    pub max_samples: u16,
    /// Most samples in one stroke ([`crate::STROKE_CAPACITY`]).
    pub stroke_capacity: u16,
    /// Whether `shot` is served.
    pub shot: bool,
}

/// The inputs of a prediction, echoed next to its result.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct InputEcho {
    /// Cue-ball speed before impact `U` (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub speed: f32,
    /// Cut angle φ (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cut_deg: f32,
    /// Cue-ball spin before impact (rad/s); for `roll`, the natural roll derived.
    pub spin: [f32; 3],
    /// Whether `spin` is the natural roll.
    pub roll: bool,
    /// Ball–ball friction μ (a speed-dependent law's high-speed limit `a`).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu: f32,
    /// Amplitude `b` of `μ(v) = a + b·exp(−c·v)`; 0 for constant μ.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu_b: f32,
    /// Decay rate `c` (s/m); 0 for constant μ.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu_c: f32,
    /// Energetic restitution e*.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub restitution: f32,
    /// Object-ball/table friction μ_s.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu_s: f32,
    /// Ball radius R (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub radius: f32,
    /// Ball mass M (kg).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mass: f32,
}

impl InputEcho {
    /// The echo of `request` as validated (`prepared`): speed and cut as given, the spin
    /// and parameters as used.
    pub fn of(request: &Collide, prepared: &PreparedCollide) -> Self {
        let params = &prepared.params;
        let (mu, mu_b, mu_c) = law_components(params.friction_law());
        Self {
            speed: request.speed,
            cut_deg: request.cut,
            spin: plain(prepared.impact.spin()),
            roll: request.roll,
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

/// Components of `v`, with `-0.0` as `0` (a zero's sign carries no physics): how every
/// vector of an answer is written (the device's stroke estimate uses it too).
pub fn plain(v: Vec3) -> [f32; 3] {
    v.to_array().map(|c| c + 0.0)
}

/// One ball just after the impact.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
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

/// Impulses of the impact (N·s), on the object ball.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ImpulsesAnswer {
    /// Ball–ball normal impulse, along `+x`.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub normal: f32,
    /// Ball–ball friction impulse `[0, y, z]`.
    pub friction: [f32; 3],
    /// Magnitude of the table friction impulse.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub table_friction: f32,
}

/// A prediction, in the collision frame (physics-notes §1: `x` from the cue ball to the
/// object ball, `z` up).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct CollideAnswer {
    /// The model that was asked for.
    pub model: ModelName,
    /// Contact regime.
    pub regime: RegimeName,
    /// The inputs.
    pub input: InputEcho,
    /// Cue ball after the impact.
    pub cue: BallAnswer,
    /// Object ball after the impact.
    pub object: BallAnswer,
    /// Throw of the object ball from the line of centres (degrees, towards `+y`).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub throw_deg: f32,
    /// Cue-ball deflection from the tangent line towards the line of centres (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cue_deflection_deg: f32,
    /// Angle between the balls' horizontal directions (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub separation_deg: f32,
    /// Impulses.
    pub impulses: ImpulsesAnswer,
}

impl CollideAnswer {
    /// The answer for `outcome`, produced by `model` from `input`.
    pub fn new(model: ModelName, input: InputEcho, outcome: &Outcome) -> Self {
        let impulses: &Impulses = &outcome.impulses;
        Self {
            model,
            regime: outcome.regime,
            input,
            cue: BallAnswer::from(&outcome.cue_ball),
            object: BallAnswer::from(&outcome.object_ball),
            throw_deg: outcome.throw_angle_deg() + 0.0,
            cue_deflection_deg: outcome.cue_deflection_deg() + 0.0,
            separation_deg: outcome.separation_angle_deg() + 0.0,
            impulses: ImpulsesAnswer {
                normal: impulses.normal + 0.0,
                friction: plain(impulses.friction),
                table_friction: impulses.table_friction + 0.0,
            },
        }
    }
}

/// Contact parameters and model (the answer to `params`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ParamsAnswer {
    /// Ball–ball friction μ (the high-speed limit `a` of a speed-dependent law).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu: f32,
    /// Amplitude `b` of the speed-dependent friction; 0 for constant μ.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu_b: f32,
    /// Decay rate `c` (s/m); 0 for constant μ.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu_c: f32,
    /// Energetic restitution e*.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub restitution: f32,
    /// Object-ball/table friction μ_s.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mu_s: f32,
    /// Ball radius R (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub radius: f32,
    /// Ball mass M (kg).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub mass: f32,
    /// Model.
    pub model: ModelName,
}

impl From<&Defaults> for ParamsAnswer {
    fn from(defaults: &Defaults) -> Self {
        let p: &Params = &defaults.params;
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

/// A stroke upload in progress.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct StrokeProgress {
    /// Stroke id.
    pub stroke: u16,
    /// Chunks received.
    pub chunks: u16,
    /// Chunks in the stroke.
    pub count: u16,
    /// Samples held.
    pub samples: u16,
}

/// A stroke's estimate: the cue speed at the tip impact (`cuesight_sensors::estimate_raw`)
/// and the cue ball it gives (`cuesight::strike`, TP A.30) in the ball's travel frame
/// (`x` along the cue, `z` up; follow `w.y > 0`, right english `w.z > 0`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct StrokeAnswer {
    /// Stroke id.
    pub stroke: u16,
    /// Cue speed just before the impact (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cue_speed: f32,
    /// Cue-ball speed after the strike (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub ball_speed: f32,
    /// Cue-ball spin after the strike (rad/s).
    pub ball_spin: [f32; 3],
    /// Samples in the stroke.
    pub samples: u16,
    /// Index of the first sample touched by the impact.
    pub impact_index: u16,
    /// Integration time from the end of the rest to the impact (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub stroke_duration: f32,
    /// Standard deviation at rest (m/s²): the sensor noise as seen.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub rest_noise: f32,
}

/// Session statistics (the answer to `shutdown`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ShutdownAnswer {
    /// Frames answered, this one included.
    pub requests: u32,
    /// How many of them with an error.
    pub errors: u32,
}
