//! Requests: what the host asks the device. The same types are the JSON vocabulary a
//! person types into `cuesight device` (externally tagged: `{"collide":{"speed":2,"cut":30}}`,
//! the field names of `cuesight collide` and `cuesight shot`) and the postcard body of a
//! frame.

use cuesight::strike::Cue;
use cuesight::{FrictionLaw, Impact, Params};
use heapless::Vec;
use serde::{Deserialize, Serialize};

use crate::error::LinkError;
use crate::limits::{MAX_OBJECT_BALLS, MAX_SAMPLES};
use crate::names::{ModelName, TableName};

/// One request.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
// No heap to box into: a stroke chunk's samples live inline (512 B).
#[allow(clippy::large_enum_variant)]
pub enum Request {
    /// Schema, firmware and limits; also (re)starts the frame count.
    Version(Empty),
    /// Predict a collision (`cuesight collide`).
    Collide(Collide),
    /// Change the session defaults of later requests; with no field, only read them.
    Params(Overrides),
    /// One chunk of a stroke's raw accelerometer samples.
    Stroke(StrokeChunk),
    /// Shot guidance (`cuesight shot`).
    Shot(ShotRequest),
    /// The planned shot for the live cue, kept for the strokes that follow (its `speed`
    /// is replaced by each stroke's); `null` forgets it.
    Plan(Option<ShotRequest>),
    /// End the session: the device answers, then exits.
    Shutdown(Empty),
}

impl Request {
    /// The request's JSON name.
    pub const fn name(&self) -> &'static str {
        match self {
            Request::Version(_) => "version",
            Request::Collide(_) => "collide",
            Request::Params(_) => "params",
            Request::Stroke(_) => "stroke",
            Request::Shot(_) => "shot",
            Request::Plan(_) => "plan",
            Request::Shutdown(_) => "shutdown",
        }
    }
}

/// No fields (`{}` in JSON, nothing in postcard).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(deny_unknown_fields)]
pub struct Empty {}

/// Contact parameters and model a request may set; `None` keeps the session default.
/// The body of `params`; `collide` and `shot` carry the same fields for one request.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(deny_unknown_fields)]
pub struct Overrides {
    /// Ball–ball friction μ; with `mu_b`/`mu_c` the high-speed limit `a` of
    /// `μ(v) = a + b·exp(−c·v)` (TP A.14).
    pub mu: Option<f32>,
    /// Amplitude `b` of the speed-dependent friction (0: constant μ).
    pub mu_b: Option<f32>,
    /// Decay rate `c` (s/m) of the speed-dependent friction.
    pub mu_c: Option<f32>,
    /// Energetic restitution e*.
    pub restitution: Option<f32>,
    /// Object-ball/table friction μ_s.
    pub mu_s: Option<f32>,
    /// Ball radius R (m).
    pub radius: Option<f32>,
    /// Ball mass M (kg).
    pub mass: Option<f32>,
    /// Model.
    pub model: Option<ModelName>,
}

/// The parameters and model a session uses when a request does not say.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Defaults {
    /// Ball and contact parameters.
    pub params: Params,
    /// Model.
    pub model: ModelName,
}

impl Defaults {
    /// [`Params::POOL`] and `kim-grip`: what a session starts with.
    pub const POOL: Self = Self {
        params: Params::POOL,
        model: ModelName::KimGrip,
    };
}

/// The cue of a `stroke` or `shot`: its mass (kg) and tip restitution, each
/// [`Cue::TYPICAL`]'s when absent; validated by the core (TP A.30's ranges).
pub fn cue(mass: Option<f32>, tip_restitution: Option<f32>) -> cuesight::Result<Cue> {
    let typical = Cue::TYPICAL;
    Cue::new(
        mass.unwrap_or(typical.mass()),
        tip_restitution.unwrap_or(typical.tip_restitution()),
    )
}

/// `(a, b, c)` of `μ(v) = a + b·exp(−c·v)`; a constant μ is `(μ, 0, 0)`.
pub fn law_components(law: FrictionLaw) -> (f32, f32, f32) {
    match law {
        FrictionLaw::Constant(mu) => (mu, 0.0, 0.0),
        FrictionLaw::SpeedDependent { a, b, c } => (a, b, c),
    }
}

impl Overrides {
    /// `defaults` with these values, validated by the core's constructors in the order
    /// μ (and its law), e*, μ_s, R, M, so an error names the first bad field as
    /// `cuesight collide` does. Constant μ when `mu_b` and `mu_c` are both zero.
    pub fn apply(&self, defaults: &Defaults) -> Result<Defaults, LinkError> {
        let p = defaults.params;
        let (a, b, c) = law_components(p.friction_law());
        let (a, b, c) = (
            self.mu.unwrap_or(a),
            self.mu_b.unwrap_or(b),
            self.mu_c.unwrap_or(c),
        );
        let law = if b == 0.0 && c == 0.0 {
            FrictionLaw::constant(a)?
        } else {
            FrictionLaw::speed_dependent(a, b, c)?
        };
        let params = p.with_contact(
            law,
            self.restitution.unwrap_or(p.restitution()),
            self.mu_s.unwrap_or(p.mu_s()),
            self.radius.unwrap_or(p.radius()),
            self.mass.unwrap_or(p.mass()),
        )?;
        Ok(Defaults {
            params,
            model: self.model.unwrap_or(defaults.model),
        })
    }
}

/// `collide`: the fields of `cuesight collide`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(deny_unknown_fields)]
pub struct Collide {
    /// Cue-ball speed `U` before impact (m/s), in (0, 100].
    pub speed: f32,
    /// Cut angle φ (degrees), in (−90, 90).
    pub cut: f32,
    /// Cue-ball spin `[wx, wy, wz]` (rad/s, collision frame); stun when absent.
    pub spin: Option<[f32; 3]>,
    /// Natural roll for the velocity instead of `spin`.
    #[serde(default)]
    pub roll: bool,
    /// See [`Overrides::mu`].
    pub mu: Option<f32>,
    /// See [`Overrides::mu_b`].
    pub mu_b: Option<f32>,
    /// See [`Overrides::mu_c`].
    pub mu_c: Option<f32>,
    /// See [`Overrides::restitution`].
    pub restitution: Option<f32>,
    /// See [`Overrides::mu_s`].
    pub mu_s: Option<f32>,
    /// See [`Overrides::radius`].
    pub radius: Option<f32>,
    /// See [`Overrides::mass`].
    pub mass: Option<f32>,
    /// See [`Overrides::model`].
    pub model: Option<ModelName>,
}

/// A validated `collide`, ready for a solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreparedCollide {
    /// Parameters.
    pub params: Params,
    /// The cue ball at contact.
    pub impact: Impact,
    /// The model asked for.
    pub model: ModelName,
}

impl Collide {
    /// A stun shot at `speed` (m/s) and `cut` (degrees) with the session defaults.
    pub fn new(speed: f32, cut: f32) -> Self {
        Self {
            speed,
            cut,
            ..Self::default()
        }
    }

    /// The parameter fields.
    pub const fn overrides(&self) -> Overrides {
        Overrides {
            mu: self.mu,
            mu_b: self.mu_b,
            mu_c: self.mu_c,
            restitution: self.restitution,
            mu_s: self.mu_s,
            radius: self.radius,
            mass: self.mass,
            model: self.model,
        }
    }

    /// Validates against `defaults`: parameters (μ, e*, μ_s, R, M), then speed and
    /// cut, then spin; errors name the field.
    pub fn prepare(&self, defaults: &Defaults) -> Result<PreparedCollide, LinkError> {
        let Defaults { params, model } = self.overrides().apply(defaults)?;
        if self.roll && self.spin.is_some() {
            return Err(LinkError::SpinAndRoll);
        }
        // Speed and cut first, so errors name them; then, for a rolling ball, spin up.
        let cut = Impact::from_cut_degrees(self.speed, self.cut, self.spin.unwrap_or([0.0; 3]))?;
        let impact = if self.roll {
            let v = cut.velocity();
            Impact::rolling([v.x, v.y], params.radius())?
        } else {
            cut
        };
        Ok(PreparedCollide {
            params,
            impact,
            model,
        })
    }
}

/// One chunk of a stroke upload.
///
/// A stroke is the raw signed 16-bit words of the accelerometer axis along the cue
/// (forward positive), oldest first, from a rest of at least 150 ms through the tip
/// impact, sent as `count` chunks numbered `index` 0, 1, ..., `count − 1` under one
/// `stroke` id. Chunk 0 starts the stroke (dropping any unfinished one); each later
/// chunk must be the next one of the same stroke; the last carries the `setup` and
/// gets the estimate. Any error drops the upload.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(deny_unknown_fields)]
pub struct StrokeChunk {
    /// The stroke's id, chosen by the host.
    pub stroke: u16,
    /// This chunk's index, from 0.
    pub index: u16,
    /// Chunks in the stroke, 1 to [`crate::limits::MAX_CHUNKS`].
    pub count: u16,
    /// This chunk's raw words, 1 to [`MAX_SAMPLES`].
    pub samples: Vec<i16, MAX_SAMPLES>,
    /// How to read the samples; required in the last chunk, ignored in the others.
    pub setup: Option<StrokeSetup>,
}

/// How to read a stroke's samples, and the cue that struck.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(deny_unknown_fields)]
pub struct StrokeSetup {
    /// Sample rate (Hz), the part's trimmed output data rate, in [500, 100000].
    pub rate_hz: f32,
    /// m/s² per LSB; the LSM6DSOX at ±16 g (0.488 mg/LSB) when absent. Negative flips
    /// the axis; the full scale is taken as `32768·|scale|`.
    pub scale: Option<f32>,
    /// Tip offset `[side, height]` from the ball centre (m, right and up positive);
    /// centre when absent.
    pub tip_offset: Option<[f32; 2]>,
    /// Cue mass (kg); 0.54 when absent.
    pub cue_mass: Option<f32>,
    /// Tip restitution; 0.75 when absent.
    pub tip_restitution: Option<f32>,
}

/// `shot`: a scene, a stroke, and an aim, given (`aim`) or solved for (`pocket`).
/// The keys of a `cuesight shot` scene file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(deny_unknown_fields)]
pub struct ShotRequest {
    /// Table preset and its ball set.
    #[serde(default)]
    pub table: TableName,
    /// Cue-ball centre (m, table frame: origin at a corner, `x` along the length).
    pub cue: [f32; 2],
    /// The other balls' centres (m), numbered 1, 2, ...
    #[serde(default)]
    pub balls: Vec<[f32; 2], MAX_OBJECT_BALLS>,
    /// Cue speed at the tip impact (m/s), in (0, 20].
    pub speed: f32,
    /// Tip offset `[side right, height up]` in ball radii; centre when absent.
    #[serde(default)]
    pub tip: [f32; 2],
    /// Aim (degrees counter-clockwise from `+x`); absent: solve for `pocket`.
    pub aim: Option<f32>,
    /// The ball to pocket (default 1).
    pub object: Option<u16>,
    /// The pocket (index in the table's pocket list).
    pub pocket: Option<u16>,
    /// Ball–cloth sliding friction; 0.2 when absent.
    pub mu_cloth: Option<f32>,
    /// Rolling resistance; 0.01 when absent.
    pub mu_roll: Option<f32>,
    /// Cue mass (kg); 0.54 when absent.
    pub cue_mass: Option<f32>,
    /// Tip restitution; 0.75 when absent.
    pub tip_restitution: Option<f32>,
    /// See [`Overrides::mu`].
    pub mu: Option<f32>,
    /// See [`Overrides::mu_b`].
    pub mu_b: Option<f32>,
    /// See [`Overrides::mu_c`].
    pub mu_c: Option<f32>,
    /// See [`Overrides::restitution`].
    pub restitution: Option<f32>,
    /// See [`Overrides::mu_s`].
    pub mu_s: Option<f32>,
    /// Ball mass (kg); the table's ball set when absent (the radius is always the set's).
    pub mass: Option<f32>,
    /// See [`Overrides::model`].
    pub model: Option<ModelName>,
}
