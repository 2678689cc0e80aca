//! Requests: what a line sent to the firmware asks for.
//!
//! On the wire each request is one JSON object with exactly one key, the request's
//! name, whose value is an object of its fields (externally tagged, the form
//! serde-json-core can read): `{"collide":{"speed":2,"cut":30}}`, `{"version":{}}`.
//! Decoding is in [`crate::decode`]; the serializers here are what a host uses to
//! write requests (`serde_json::to_string(&request)` or [`serde_json_core::to_slice`]).

use cuesight::{FrictionLaw, Impact, Params};
use heapless::Vec;
use serde::ser::{Serialize, SerializeStruct, Serializer};

use crate::answer::InputEcho;
use crate::names::ModelName;
#[cfg(feature = "shot")]
use crate::shot::Shot;
use crate::MAX_SAMPLES;

/// One request.
#[derive(Clone, Debug, PartialEq)]
// No heap to box into: a stroke's samples live inline (2.4 KB), on the caller's stack.
#[allow(clippy::large_enum_variant)]
pub enum Request {
    /// Predict a collision (`cuesight collide`).
    Collide(Collide),
    /// Change the session defaults used by later requests; `{"params":{}}` only reads
    /// them.
    Params(Overrides),
    /// Estimate a stroke from raw accelerometer samples.
    Stroke(Stroke),
    /// Shot guidance: aim, throw correction, both balls' paths (`cuesight shot`).
    #[cfg(feature = "shot")]
    Shot(Shot),
    /// Protocol and firmware versions, buffer limits.
    Version,
    /// End the session: the firmware answers, then exits (QEMU exits 0).
    Shutdown,
}

impl Request {
    /// Every request name, as on the wire.
    #[cfg(feature = "shot")]
    pub const NAMES: &'static [&'static str] =
        &["collide", "params", "stroke", "shot", "version", "shutdown"];
    /// Every request name, as on the wire.
    #[cfg(not(feature = "shot"))]
    pub const NAMES: &'static [&'static str] =
        &["collide", "params", "stroke", "version", "shutdown"];

    /// The request's wire name.
    pub const fn name(&self) -> &'static str {
        match self {
            Request::Collide(_) => "collide",
            Request::Params(_) => "params",
            Request::Stroke(_) => "stroke",
            #[cfg(feature = "shot")]
            Request::Shot(_) => "shot",
            Request::Version => "version",
            Request::Shutdown => "shutdown",
        }
    }
}

/// Cue-ball spin in a `collide` request.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spin {
    /// `"spin": [wx, wy, wz]` (rad/s, collision frame); stun `[0, 0, 0]` when absent.
    Given([f32; 3]),
    /// `"roll": true`: natural roll for the cue-ball velocity.
    Roll,
}

/// Parameters a request may set; `None` keeps the session default. Shared by
/// `collide` (for that one prediction) and `params` (for every later request).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Ball–ball friction μ; with `mu_b`/`mu_c`, the high-speed limit `a` of
    /// `μ(v) = a + b·exp(−c·v)`.
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

impl Overrides {
    /// Field names, in wire order.
    pub const FIELDS: [&'static str; 8] = [
        "mu",
        "mu_b",
        "mu_c",
        "restitution",
        "mu_s",
        "radius",
        "mass",
        "model",
    ];

    /// `defaults` with these values replaced, validated by the core's constructors.
    ///
    /// Checked in the order μ (and its law), e*, μ_s, R, M, so an error names the first
    /// bad field in that order, as `cuesight collide` does. The friction law is
    /// `(mu, mu_b, mu_c)`, each component kept from `defaults` when absent: constant μ
    /// when `mu_b` and `mu_c` are both zero, `μ(v) = mu + mu_b·exp(−mu_c·v)` otherwise.
    pub fn apply(&self, defaults: &Defaults) -> cuesight::Result<Defaults> {
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
        let params = p
            .with_friction_law(law)
            .with_restitution(self.restitution.unwrap_or(p.restitution()))?
            .with_mu_s(self.mu_s.unwrap_or(p.mu_s()))?
            .with_ball(
                self.radius.unwrap_or(p.radius()),
                self.mass.unwrap_or(p.mass()),
            )?;
        Ok(Defaults {
            params,
            model: self.model.unwrap_or(defaults.model),
        })
    }

    pub(crate) fn serialize_fields<S: SerializeStruct>(&self, s: &mut S) -> Result<(), S::Error> {
        let numbers = [
            ("mu", self.mu),
            ("mu_b", self.mu_b),
            ("mu_c", self.mu_c),
            ("restitution", self.restitution),
            ("mu_s", self.mu_s),
            ("radius", self.radius),
            ("mass", self.mass),
        ];
        for (key, value) in numbers {
            match value {
                Some(value) => s.serialize_field(key, &value)?,
                None => s.skip_field(key)?,
            }
        }
        match self.model {
            Some(model) => s.serialize_field("model", &model),
            None => s.skip_field("model"),
        }
    }

    pub(crate) fn count(&self) -> usize {
        [
            self.mu,
            self.mu_b,
            self.mu_c,
            self.restitution,
            self.mu_s,
            self.radius,
            self.mass,
        ]
        .iter()
        .filter(|v| v.is_some())
        .count()
            + usize::from(self.model.is_some())
    }
}

/// `(a, b, c)` of `μ(v) = a + b·exp(−c·v)`; a constant μ is `(μ, 0, 0)`.
pub fn law_components(law: FrictionLaw) -> (f32, f32, f32) {
    match law {
        FrictionLaw::Constant(mu) => (mu, 0.0, 0.0),
        FrictionLaw::SpeedDependent { a, b, c } => (a, b, c),
    }
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
    /// The pool parameters ([`Params::POOL`]) and `kim-grip`, what a session starts with.
    pub const POOL: Self = Self {
        params: Params::POOL,
        model: ModelName::DEFAULT,
    };
}

impl Default for Defaults {
    fn default() -> Self {
        Self::POOL
    }
}

/// `collide`: the fields of `cuesight collide`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collide {
    /// Cue-ball speed `U` before impact (m/s).
    pub speed: f32,
    /// Cut angle φ (degrees, |φ| < 90).
    pub cut: f32,
    /// Cue-ball spin.
    pub spin: Spin,
    /// Parameters for this prediction only.
    pub with: Overrides,
}

impl Collide {
    /// Field names, in wire order (the [`Overrides::FIELDS`] follow).
    pub const FIELDS: [&'static str; 4] = ["speed", "cut", "spin", "roll"];

    /// A stun shot at `speed` (m/s) and `cut` (degrees) with the session defaults.
    pub const fn new(speed: f32, cut: f32) -> Self {
        Self {
            speed,
            cut,
            spin: Spin::Given([0.0; 3]),
            with: Overrides {
                mu: None,
                mu_b: None,
                mu_c: None,
                restitution: None,
                mu_s: None,
                radius: None,
                mass: None,
                model: None,
            },
        }
    }

    /// Validate against `defaults` through the core's constructors: parameters first
    /// (μ, e*, μ_s, R, M), then speed and cut, then spin. Errors name the field.
    pub fn prepare(&self, defaults: &Defaults) -> cuesight::Result<Prepared> {
        let Defaults { params, model } = self.with.apply(defaults)?;
        let (impact, roll) = match self.spin {
            Spin::Given(spin) => (Impact::from_cut_degrees(self.speed, self.cut, spin)?, false),
            Spin::Roll => {
                // Validate speed and cut first so errors name them, then spin up.
                let v = Impact::from_cut_degrees(self.speed, self.cut, [0.0; 3])?.velocity();
                (Impact::rolling([v.x, v.y], params.radius())?, true)
            }
        };
        Ok(Prepared {
            params,
            impact,
            model,
            input: InputEcho::new(self.speed, self.cut, roll, &params, &impact),
        })
    }
}

/// A validated `collide` request, ready for a solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prepared {
    /// Parameters.
    pub params: Params,
    /// The cue ball at contact.
    pub impact: Impact,
    /// The model to run.
    pub model: ModelName,
    /// The input echo of the answer.
    pub input: InputEcho,
}

/// `stroke`: raw accelerometer samples of a stroke, in one or more chunks, and the cue.
///
/// `samples` are the raw signed 16-bit words of the accelerometer axis along the cue
/// (forward, towards the tip, positive; a negative `scale` flips a sensor mounted the
/// other way), oldest first, at `rate_hz`. The window must start with the cue held
/// still (≥ 150 ms) and contain the tip impact (`cuesight_sensors::stroke`). A window
/// longer than one line is sent in chunks: every chunk but the last has `"more":true`
/// and carries only `samples`; the last carries the rest of the fields and gets the
/// estimate. A session holds [`crate::STROKE_CAPACITY`] samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Stroke {
    /// This chunk's raw samples.
    pub samples: Vec<i16, MAX_SAMPLES>,
    /// More chunks follow.
    pub more: bool,
    /// Output data rate (Hz), the part's trimmed ODR; required in the last chunk.
    pub rate_hz: Option<f32>,
    /// m/s² per LSB; the LSM6DSOX at ±16 g when absent. The sensor's full scale is
    /// taken as `32768·|scale|`.
    pub scale: Option<f32>,
    /// Tip offset `[side, height]` from the ball centre (m, side > 0 right, height > 0
    /// above); a centre-ball hit when absent.
    pub tip_offset: Option<[f32; 2]>,
    /// Cue mass (kg); the typical cue (0.54 kg) when absent.
    pub cue_mass: Option<f32>,
    /// Tip restitution; the typical tip (0.75) when absent.
    pub tip_restitution: Option<f32>,
}

impl Stroke {
    /// Field names, in wire order.
    pub const FIELDS: [&'static str; 7] = [
        "samples",
        "more",
        "rate_hz",
        "scale",
        "tip_offset",
        "cue_mass",
        "tip_restitution",
    ];

    /// A chunk of `samples` with more to follow.
    pub fn chunk(samples: Vec<i16, MAX_SAMPLES>) -> Self {
        Self {
            samples,
            more: true,
            rate_hz: None,
            scale: None,
            tip_offset: None,
            cue_mass: None,
            tip_restitution: None,
        }
    }

    /// The last (or only) chunk: `samples` at `rate_hz`, the other fields at their
    /// defaults.
    pub fn last(samples: Vec<i16, MAX_SAMPLES>, rate_hz: f32) -> Self {
        Self {
            more: false,
            rate_hz: Some(rate_hz),
            ..Self::chunk(samples)
        }
    }
}

/// `{}`, the body of `version` and `shutdown`.
struct Empty;

impl Serialize for Empty {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_struct("Empty", 0)?.end()
    }
}

impl Serialize for Request {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let name = self.name();
        match self {
            Request::Collide(body) => {
                serializer.serialize_newtype_variant("Request", 0, name, body)
            }
            Request::Params(body) => serializer.serialize_newtype_variant("Request", 1, name, body),
            Request::Stroke(body) => serializer.serialize_newtype_variant("Request", 2, name, body),
            #[cfg(feature = "shot")]
            Request::Shot(body) => serializer.serialize_newtype_variant("Request", 3, name, body),
            Request::Version => serializer.serialize_newtype_variant("Request", 4, name, &Empty),
            Request::Shutdown => serializer.serialize_newtype_variant("Request", 5, name, &Empty),
        }
    }
}

impl Serialize for Overrides {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut s = serializer.serialize_struct("Params", self.count())?;
        self.serialize_fields(&mut s)?;
        s.end()
    }
}

impl Serialize for Collide {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut s = serializer.serialize_struct("Collide", 3 + self.with.count())?;
        s.serialize_field("speed", &self.speed)?;
        s.serialize_field("cut", &self.cut)?;
        match self.spin {
            Spin::Given(spin) => s.serialize_field("spin", &spin)?,
            Spin::Roll => s.serialize_field("roll", &true)?,
        }
        self.with.serialize_fields(&mut s)?;
        s.end()
    }
}

impl Serialize for Stroke {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let numbers = [
            ("rate_hz", self.rate_hz),
            ("scale", self.scale),
            ("cue_mass", self.cue_mass),
            ("tip_restitution", self.tip_restitution),
        ];
        let given = numbers.iter().filter(|(_, v)| v.is_some()).count()
            + usize::from(self.tip_offset.is_some())
            + usize::from(self.more);
        let mut s = serializer.serialize_struct("Stroke", 1 + given)?;
        s.serialize_field("samples", self.samples.as_slice())?;
        if self.more {
            s.serialize_field("more", &true)?;
        } else {
            s.skip_field("more")?;
        }
        for (key, value) in &numbers[..2] {
            match value {
                Some(value) => s.serialize_field(key, value)?,
                None => s.skip_field(key)?,
            }
        }
        match self.tip_offset {
            Some(tip) => s.serialize_field("tip_offset", &tip)?,
            None => s.skip_field("tip_offset")?,
        }
        for (key, value) in &numbers[2..] {
            match value {
                Some(value) => s.serialize_field(key, value)?,
                None => s.skip_field(key)?,
            }
        }
        s.end()
    }
}
