//! `calibrate`: the friction-law fit, the JSON text `cuesight calibrate --json` prints
//! ([`cuesight_cli::calibrate`]: `run` for a file, `run_points` for points given as
//! the JSON point schema, read by the CLI's `parse_json`).

use std::path::PathBuf;

use clap::ValueEnum;
use cuesight_cli::calibrate::input::parse_json;
use cuesight_cli::calibrate::{run, run_points, CalibrateError, FitKind, Flags, Intervals, Solver};
use pyo3::prelude::*;

use crate::value_error;

/// What the measured throw is: a file (`--throw`), or points as JSON objects.
enum Throw {
    File(PathBuf),
    Points(Vec<String>),
}

/// The name `source` gives points that come as a list (in messages: `throw list: ...`).
const LIST_SOURCE: &str = "throw list";

/// A `--fit` or `--model` value by its CLI name.
fn value<T: ValueEnum>(flag: &str, name: &str) -> Result<T, CalibrateError> {
    T::from_str(name, false).map_err(|_| {
        let names: Vec<String> = T::value_variants()
            .iter()
            .filter_map(|v| v.to_possible_value())
            .map(|v| v.get_name().to_owned())
            .collect();
        CalibrateError {
            message: format!(
                "invalid value '{name}' for {flag} [possible values: {}]",
                names.join(", ")
            ),
            code: 2,
        }
    })
}

/// Points given one JSON object each, read by the CLI's JSON reader as one array with
/// point `i` on line `i` (1-based), so that a point's error, which serde_json places at
/// a line and column, names the point: `throw list: point 3: cut_deg = 95 is outside
/// [0, 90) degrees`.
fn read_points(points: &[String]) -> Result<Vec<cuesight_cli::calibrate::Measurement>, String> {
    let text = format!("[{}]", points.join(",\n"));
    parse_json(&text).map_err(|e| {
        let message = e.to_string();
        let located = message.rsplit_once(" at line ").and_then(|(head, place)| {
            let (line, _column) = place.split_once(" column ")?;
            Some(format!("point {line}: {head}"))
        });
        format!("{LIST_SOURCE}: {}", located.unwrap_or(message))
    })
}

/// The fit: `cuesight calibrate --json` with these flags, on a file or on points (each
/// a JSON object of docs/calibration.md's point schema). Returns the JSON text.
#[pyfunction]
#[pyo3(signature = (throw_file, throw_points, fit, model, restitution, mu_s, default_uncertainty, cross_validate, max_evaluations))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _calibrate(
    py: Python<'_>,
    throw_file: Option<PathBuf>,
    throw_points: Option<Vec<String>>,
    fit: &str,
    model: &str,
    restitution: f64,
    mu_s: f64,
    default_uncertainty: f64,
    cross_validate: bool,
    max_evaluations: usize,
) -> PyResult<String> {
    let throw = match (throw_file, throw_points) {
        (Some(path), None) => Throw::File(path),
        (None, Some(points)) => Throw::Points(points),
        _ => unreachable!("the Python wrapper passes one of a file and points"),
    };
    let fit: FitKind = value("fit", fit).map_err(value_error)?;
    let model: Solver = value("model", model).map_err(value_error)?;
    py.detach(|| {
        let mut flags = Flags {
            throw: PathBuf::new(),
            fit,
            model,
            restitution,
            mu_s,
            default_uncertainty,
            cross_validate,
            intervals: Intervals::Profile,
            max_evaluations,
            json: true,
        };
        match throw {
            Throw::File(path) => {
                flags.throw = path;
                run(&flags)
            }
            Throw::Points(points) => {
                // The flags are checked before the points are read, as `run` does.
                cuesight_cli::calibrate::options(&flags)?;
                let points =
                    read_points(&points).map_err(|message| CalibrateError { message, code: 1 })?;
                run_points(&points, &flags, LIST_SOURCE)
            }
        }
    })
    .map_err(value_error)
}
