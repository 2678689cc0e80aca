//! `--params FILE` of `cuesight collide` and `cuesight shot`: contact parameters from a
//! JSON object, typically what `cuesight calibrate --json` printed.
//!
//! Keys (all optional, the names `collide` and the device's `params` request take):
//! `mu`, `mu_b`, `mu_c`, `restitution`, `mu_s`, `radius`, `mass`. The other keys that
//! `calibrate --json` prints (`fit`, `model`, `stderr`, `ci95`, `interval95`, `intervals`, `rms_deg`, `max_deg`,
//! `points`, `above_ceiling`, `residuals`, `cross_validation`) are accepted and ignored;
//! any other key is an error, so a misspelt parameter is not silently dropped. A flag
//! given on the command line overrides the file's value.

use std::io::Read;
use std::path::Path;

use serde::de::IgnoredAny;
use serde::Deserialize;

use super::input::MAX_FILE_BYTES;

/// The parameters of a `--params` file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParamsFile {
    /// Ball–ball friction μ (μ(v)'s `a` with `mu_b`/`mu_c`).
    pub mu: Option<f32>,
    /// μ(v)'s amplitude `b`.
    pub mu_b: Option<f32>,
    /// μ(v)'s decay rate `c` (s/m).
    pub mu_c: Option<f32>,
    /// Energetic restitution e*.
    pub restitution: Option<f32>,
    /// Object-ball/table friction μ_s.
    pub mu_s: Option<f32>,
    /// Ball radius (m).
    pub radius: Option<f32>,
    /// Ball mass (kg).
    pub mass: Option<f32>,
    #[serde(default, rename = "fit")]
    _fit: Option<IgnoredAny>,
    #[serde(default, rename = "model")]
    _model: Option<IgnoredAny>,
    #[serde(default, rename = "stderr")]
    _stderr: Option<IgnoredAny>,
    #[serde(default, rename = "ci95")]
    _ci95: Option<IgnoredAny>,
    #[serde(default, rename = "interval95")]
    _interval: Option<IgnoredAny>,
    #[serde(default, rename = "intervals")]
    _intervals: Option<IgnoredAny>,
    #[serde(default, rename = "rms_deg")]
    _rms: Option<IgnoredAny>,
    #[serde(default, rename = "max_deg")]
    _max: Option<IgnoredAny>,
    #[serde(default, rename = "points")]
    _points: Option<IgnoredAny>,
    #[serde(default, rename = "above_ceiling")]
    _above: Option<IgnoredAny>,
    #[serde(default, rename = "residuals")]
    _residuals: Option<IgnoredAny>,
    #[serde(default, rename = "cross_validation")]
    _cross_validation: Option<IgnoredAny>,
}

impl ParamsFile {
    /// Parse JSON text; the error is one line with its line and column.
    pub fn from_json(text: &str) -> Result<Self, String> {
        serde_json::from_str(text).map_err(|e| {
            e.to_string()
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ")
        })
    }

    /// Read a params file (at most 1 MiB). The error names the file.
    pub fn read(path: &Path) -> Result<Self, String> {
        let shown = path.display();
        let file = std::fs::File::open(path).map_err(|e| format!("params file {shown}: {e}"))?;
        let mut text = String::new();
        file.take(MAX_FILE_BYTES + 1)
            .read_to_string(&mut text)
            .map_err(|e| format!("params file {shown}: {e}"))?;
        if text.len() as u64 > MAX_FILE_BYTES {
            return Err(format!("params file {shown}: larger than 1 MiB, refused"));
        }
        Self::from_json(&text).map_err(|e| format!("params file {shown}: {e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_calibrate_output_and_refuses_typos() {
        let p = ParamsFile::from_json(
            r#"{"mu":0.01,"mu_b":0.1,"mu_c":1.2,"restitution":0.95,"mu_s":0.3,"fit":"mu-v","rms_deg":0.4,"points":36,"stderr":{"mu":0.001}}"#,
        )
        .unwrap();
        assert_eq!(p.mu, Some(0.01));
        assert_eq!(p.mu_c, Some(1.2));
        assert_eq!(p.radius, None);
        let e = ParamsFile::from_json(r#"{"restituion":0.9}"#).unwrap_err();
        assert!(e.contains("restituion"), "{e}");
        // The profile intervals are read and ignored.
        let p = ParamsFile::from_json(
            r#"{"mu":0.02,"interval95":{"mu":[0.0,0.04]},"intervals":"profile"}"#,
        )
        .unwrap();
        assert_eq!(p.mu, Some(0.02));
        // A compliant fit (`--fit mu-v-k`) is not silently run as a rigid one.
        let e = ParamsFile::from_json(r#"{"mu":0.02,"tangential_stiffness":0.1}"#).unwrap_err();
        assert!(e.contains("tangential_stiffness"), "{e}");
    }
}
