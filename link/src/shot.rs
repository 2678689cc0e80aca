//! The answer to `shot` (shot guidance; the device computes it in `cuesight-device`'s
//! `guide.rs`). It holds the keys of `cuesight shot --json` but the echo of the scene,
//! which the host has; both are built by [`cuesight::guidance::guide`], so the numbers
//! are the same. Units: SI in the table frame, degrees in the keys ending in `_deg`
//! (`docs/protocol.md`).

use serde::{Deserialize, Serialize};

use crate::names::{EndName, ModelName, RegimeName, ShotMode};

/// The answer to `shot`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ShotAnswer {
    /// Whether the aim was given or solved.
    pub mode: ShotMode,
    /// The stroke played.
    pub stroke: StrokePart,
    /// The inverse aim (solve only).
    pub solve: Option<SolvePart>,
    /// The first collision; `None` when the cue ball hits nothing.
    pub contact: Option<ContactPart>,
    /// The cue ball's path.
    pub cue_ball: BallPart,
    /// The object ball's path after the impact.
    pub object_ball: Option<BallPart>,
    /// The target, if one was given.
    pub target: Option<TargetPart>,
}

/// The stroke played.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct StrokePart {
    /// Cue speed at the tip impact (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cue_speed: f32,
    /// Tip offset asked for (ball radii, right and up).
    pub tip: [f32; 2],
    /// Aim (degrees counter-clockwise from `+x`).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub aim_deg: f32,
    /// Aim as a unit vector.
    pub aim: [f32; 2],
    /// Cue-ball speed after the strike (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub launch_speed: f32,
    /// Cue-ball spin after the strike (rad/s, table frame).
    pub launch_spin: [f32; 3],
}

/// The inverse aim.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct SolvePart {
    /// The ball to pocket.
    pub object: u16,
    /// The pocket.
    pub pocket: u16,
    /// The aim that pockets it, throw included (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub aim_deg: f32,
    /// The ghost-ball aim (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub naive_aim_deg: f32,
    /// `aim_deg − naive_aim_deg` (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub correction_deg: f32,
    /// The correction as a shift of the contact point (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub correction_offset: f32,
    /// Whether the corrected aim hits the object ball thinner.
    pub thinner: bool,
    /// Cut angle at the corrected aim (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cut_deg: f32,
    /// Ghost-ball centre at the corrected aim (m).
    pub ghost_ball: [f32; 2],
    /// Ghost-ball centre at the naive aim (m).
    pub naive_ghost_ball: [f32; 2],
    /// Shot evaluations the solver made.
    pub evaluations: u32,
    /// Miss at the pocket's mouth at the solution (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub residual: f32,
}

/// The first collision.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ContactPart {
    /// The ball hit.
    pub ball: u16,
    /// When (s after the strike).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub time: f32,
    /// Cue-ball centre at contact (m).
    pub cue_position: [f32; 2],
    /// Unit vector from the cue ball to the object ball.
    pub line_of_centres: [f32; 2],
    /// Cut angle (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cut_deg: f32,
    /// Cue-ball speed at contact (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub speed: f32,
    /// Cue-ball spin at contact (rad/s, collision frame).
    pub spin: [f32; 3],
    /// The model asked for.
    pub model: ModelName,
    /// The model that ran (`auto` picks one).
    pub model_used: ModelName,
    /// `auto`'s error estimate, when it ran.
    pub error_estimate: Option<f32>,
    /// Contact regime.
    pub regime: RegimeName,
    /// Throw of the object ball (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub throw_deg: f32,
}

/// One ball's path from its launch to its end.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct BallPart {
    /// The ball (0: the cue ball).
    pub ball: u16,
    /// Launch position (m).
    pub start: [f32; 2],
    /// Launch velocity (m/s).
    pub velocity: [f32; 3],
    /// Launch spin (rad/s).
    pub spin: [f32; 3],
    /// Highest hop (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub hop_height: f32,
    /// Time in the air (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub air_time: f32,
    /// Where it lands (m).
    pub landing: [f32; 2],
    /// Time sliding (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub sliding_time: f32,
    /// Where it starts to roll (m).
    pub rolling_start: [f32; 2],
    /// Rolling velocity (m/s).
    pub rolling_velocity: [f32; 2],
    /// Rolling speed (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub rolling_speed: f32,
    /// Rolling direction (degrees).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub rolling_direction_deg: f32,
    /// When it would stop on an endless table (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub stop_time: f32,
    /// Where it would stop on an endless table (m).
    pub rest: [f32; 2],
    /// How the path ends.
    pub end: EndName,
    /// When (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub end_time: f32,
    /// Where (m).
    pub end_position: [f32; 2],
    /// The pocket, when it drops.
    pub pocket: Option<u16>,
}

/// The target's outcome.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct TargetPart {
    /// The ball.
    pub object: u16,
    /// The pocket.
    pub pocket: u16,
    /// Whether it drops.
    pub pocketed: bool,
    /// Miss at the mouth (m), when it reaches the mouth line.
    pub miss: Option<f32>,
}
