//! Names on the wire: models, contact regimes, tables, how a path ends. Each is a
//! plain enum (a varint in postcard, a lower-case string in JSON).

use cuesight::Model;
use serde::{Deserialize, Serialize};

/// How a ball's path ends (`rest`, `pocket`, `cushion`): the core's own type.
pub use cuesight::guidance::End as EndName;
/// The contact regime of a collision (physics.md §1): the core's own type, which
/// derives serde (`frictionless`, `sliding`, `gripping`).
pub use cuesight::Regime as RegimeName;

/// A collision model: one of the core's ([`Model`], `auto` with its default tolerance
/// 1e-3), or the host's f64 reference solver.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "kebab-case")]
pub enum ModelName {
    /// [`Model::Ideal`].
    Ideal,
    /// [`Model::Kim`].
    Kim,
    /// [`Model::KimGrip`], the default.
    #[default]
    KimGrip,
    /// [`Model::SeedExact`].
    SeedExact,
    /// [`Model::Exact`].
    Exact,
    /// [`Model::Auto`] with tolerance 1e-3.
    Auto,
    /// The f64 reference solver: host only (the device answers `unsupported`).
    Reference,
}

impl ModelName {
    /// Every name, as written in JSON.
    pub const ALL: [ModelName; 7] = [
        ModelName::Ideal,
        ModelName::Kim,
        ModelName::KimGrip,
        ModelName::SeedExact,
        ModelName::Exact,
        ModelName::Auto,
        ModelName::Reference,
    ];

    /// The JSON name (`kim-grip`).
    pub const fn name(self) -> &'static str {
        match self.core() {
            Some(Model::Auto { .. }) => "auto",
            Some(model) => model.name(),
            None => "reference",
        }
    }

    /// The core's model; `None` for the reference solver.
    pub const fn core(self) -> Option<Model> {
        match self {
            ModelName::Ideal => Some(Model::Ideal),
            ModelName::Kim => Some(Model::Kim),
            ModelName::KimGrip => Some(Model::KimGrip),
            ModelName::SeedExact => Some(Model::SeedExact),
            ModelName::Exact => Some(Model::Exact),
            ModelName::Auto => Some(Model::Auto { tolerance: 1e-3 }),
            ModelName::Reference => None,
        }
    }

    /// The name of a core model (any `auto` tolerance is `auto`).
    pub const fn of(model: Model) -> Self {
        match model {
            Model::Ideal => ModelName::Ideal,
            Model::Kim => ModelName::Kim,
            Model::KimGrip => ModelName::KimGrip,
            Model::SeedExact => ModelName::SeedExact,
            Model::Exact => ModelName::Exact,
            Model::Auto { .. } => ModelName::Auto,
        }
    }
}

/// A table preset with its ball set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "lowercase")]
pub enum TableName {
    /// 9-ft pool table, pool balls.
    #[default]
    Pool,
    /// Snooker table, snooker balls.
    Snooker,
    /// Carom table (no pockets), carom balls.
    Carom,
}

/// Whether a `shot` played a given aim or solved for one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "lowercase")]
pub enum ShotMode {
    /// The aim was given.
    Play,
    /// The aim was solved for a pocket.
    Solve,
}
