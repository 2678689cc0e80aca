//! The names of models and contact regimes as they appear on the wire.

use core::fmt;

use cuesight::{Model, Regime};
use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize, Serializer};

use crate::text::{list, Fmt, Sink};

/// A collision model, by its wire name: a core model by [`Model::name`] (`ideal`, `kim`,
/// `kim-grip`, ...), or `reference`.
///
/// `reference` is the host's f64 first-principles solver: the `cuesight` CLI runs it,
/// the firmware answers it with an `unsupported` error. Core models are looked up with
/// [`Model::from_name`], so a model the core adds is on the wire at once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModelName {
    /// A model of the core.
    Core(Model),
    /// The host-only f64 reference solver.
    Reference,
}

impl ModelName {
    /// `kim-grip`, the default.
    pub const DEFAULT: Self = ModelName::Core(Model::KimGrip);

    /// The wire name.
    pub const fn name(self) -> &'static str {
        match self {
            ModelName::Core(model) => model.name(),
            ModelName::Reference => "reference",
        }
    }

    /// Parse a wire name.
    pub fn from_name(name: &str) -> Option<Self> {
        if name == "reference" {
            return Some(ModelName::Reference);
        }
        Model::from_name(name).map(ModelName::Core)
    }

    /// The core model, or `None` for the host-only `reference`.
    pub const fn core(self) -> Option<Model> {
        match self {
            ModelName::Core(model) => Some(model),
            ModelName::Reference => None,
        }
    }

    /// Every accepted name, in the order shown to users: the core's models, then
    /// `reference`.
    pub fn names() -> impl Iterator<Item = &'static str> + Clone {
        // `from_name` accepts a few names `Model::ALL` does not list (parametrised
        // models such as `auto`); list them too.
        let extra = ["auto"]
            .into_iter()
            .filter(|name| Model::from_name(name).is_some_and(|m| !Model::ALL.contains(&m)));
        Model::ALL
            .into_iter()
            .map(Model::name)
            .chain(extra)
            .chain(["reference"])
    }
}

impl From<Model> for ModelName {
    fn from(model: Model) -> Self {
        ModelName::Core(model)
    }
}

impl fmt::Display for ModelName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// `a, b or c` over [`ModelName::names`].
pub(crate) struct ModelNames;

impl fmt::Display for ModelNames {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Fmt::write(f, model_names)
    }
}

/// [`ModelNames`]' text.
pub(crate) fn model_names(f: &mut dyn Sink) {
    list(f, ModelName::names(), " or ");
}

impl Serialize for ModelName {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for ModelName {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NameVisitor;
        impl Visitor<'_> for NameVisitor {
            type Value = ModelName;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a model name: {ModelNames}")
            }
            fn visit_str<E: de::Error>(self, name: &str) -> Result<ModelName, E> {
                ModelName::from_name(name)
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Str(name), &self))
            }
        }
        deserializer.deserialize_str(NameVisitor)
    }
}

/// How the contact behaved, by its wire name (`frictionless`, `sliding`, `gripping`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[serde(rename_all = "lowercase")]
pub enum RegimeName {
    /// [`Regime::Frictionless`].
    Frictionless,
    /// [`Regime::Sliding`].
    Sliding,
    /// [`Regime::Gripping`].
    Gripping,
}

impl RegimeName {
    /// The wire name.
    pub const fn name(self) -> &'static str {
        match self {
            RegimeName::Frictionless => "frictionless",
            RegimeName::Sliding => "sliding",
            RegimeName::Gripping => "gripping",
        }
    }
}

impl From<Regime> for RegimeName {
    fn from(regime: Regime) -> Self {
        match regime {
            Regime::Frictionless => RegimeName::Frictionless,
            Regime::Sliding => RegimeName::Sliding,
            Regime::Gripping => RegimeName::Gripping,
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::string::ToString;

    use super::*;

    #[test]
    fn names_round_trip() {
        for name in ModelName::names() {
            let model = ModelName::from_name(name).unwrap();
            assert_eq!(model.name(), name);
            let json = serde_json::to_string(&model).unwrap();
            assert_eq!(json, std::format!("\"{name}\""));
            assert_eq!(serde_json::from_str::<ModelName>(&json).unwrap(), model);
        }
        for model in Model::ALL {
            assert_eq!(ModelName::from(model).core(), Some(model));
        }
        assert_eq!(ModelName::Reference.core(), None);
        assert!(ModelName::from_name("kimgrip").is_none());
        let listed = ModelNames.to_string();
        assert!(listed.starts_with("ideal, kim, kim-grip"), "{listed}");
        assert!(listed.ends_with(" or reference"), "{listed}");
    }

    #[test]
    fn regimes_match_the_core() {
        for regime in [Regime::Frictionless, Regime::Sliding, Regime::Gripping] {
            assert_eq!(RegimeName::from(regime).name(), regime.name());
            let json = serde_json::to_string(&RegimeName::from(regime)).unwrap();
            assert_eq!(json, std::format!("\"{}\"", regime.name()));
        }
    }
}
