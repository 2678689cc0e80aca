//! `shot`: shot guidance, the JSON text `cuesight shot --json` prints
//! ([`cuesight_cli::shot_cli`]: the scene file and the flags merged by
//! `Request::from_parts`, played by `play_request`, serialized by `to_json`).

use std::path::PathBuf;

use clap::ValueEnum;
use cuesight_cli::shot_cli::input::{parse_model, PocketRef, SceneFile, TablePreset};
use cuesight_cli::shot_cli::{play_request, to_json, Flags, Request, ShotError};
use pyo3::prelude::*;

use crate::value_error;

/// The scene: a file as `--scene` reads it, or the JSON text of a scene dict.
enum Scene {
    File(PathBuf),
    Json(String),
}

/// `--table`'s preset by name.
fn table(name: &str) -> Result<TablePreset, ShotError> {
    TablePreset::from_str(name, false).map_err(|_| {
        let names: Vec<_> = TablePreset::value_variants()
            .iter()
            .map(|p| p.name())
            .collect();
        ShotError::usage(format!(
            "invalid value '{name}' for table [possible values: {}]",
            names.join(", ")
        ))
    })
}

/// The shot: the CLI's flags from the keyword arguments (each `None`: not given, the
/// scene's value or the default), resolved and played as `cuesight shot --json` does;
/// with `svg`, the drawing of `--svg` written there. Returns the JSON text.
#[pyfunction]
#[pyo3(signature = (scene_file, scene_json, params, table, cue, balls, object, pocket, speed, tip, aim, solve, model, tolerance, mu, restitution, mu_s, mu_cloth, mu_roll, radius, mass, cue_mass, tip_restitution, svg))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _shot(
    py: Python<'_>,
    scene_file: Option<PathBuf>,
    scene_json: Option<String>,
    params: Option<PathBuf>,
    table: Option<&str>,
    cue: Option<[f32; 2]>,
    balls: Option<Vec<[f32; 2]>>,
    object: Option<usize>,
    pocket: Option<&str>,
    speed: Option<f32>,
    tip: Option<[f32; 2]>,
    aim: Option<f32>,
    solve: bool,
    model: Option<&str>,
    tolerance: Option<f32>,
    mu: Option<f32>,
    restitution: Option<f32>,
    mu_s: Option<f32>,
    mu_cloth: Option<f32>,
    mu_roll: Option<f32>,
    radius: Option<f32>,
    mass: Option<f32>,
    cue_mass: Option<f32>,
    tip_restitution: Option<f32>,
    svg: Option<PathBuf>,
) -> PyResult<String> {
    let scene = match (scene_file, scene_json) {
        (Some(path), None) => Some(Scene::File(path)),
        (None, Some(text)) => Some(Scene::Json(text)),
        (None, None) => None,
        (Some(_), Some(_)) => unreachable!("the Python wrapper passes one scene"),
    };
    // What clap's value parsers do for the flags.
    let usage = |flag: &str, value: &str, e: String| {
        ShotError::usage(format!("invalid value '{value}' for {flag}: {e}"))
    };
    let table = table.map(self::table).transpose().map_err(value_error)?;
    let pocket = pocket
        .map(|p| PocketRef::parse(p).map_err(|e| usage("pocket", p, e)))
        .transpose()
        .map_err(value_error)?;
    let model = model
        .map(|m| parse_model(m).map_err(|e| usage("model", m, e)))
        .transpose()
        .map_err(value_error)?;
    let flags = Flags {
        scene: None,
        params,
        table,
        cue,
        balls: balls.unwrap_or_default(),
        object,
        pocket,
        speed,
        tip,
        aim,
        solve,
        model,
        tolerance,
        mu,
        restitution,
        mu_s,
        mu_cloth,
        mu_roll,
        radius,
        mass,
        cue_mass,
        tip_restitution,
        json: true,
        svg,
    };
    py.detach(|| play(scene, flags)).map_err(value_error)
}

/// `cuesight shot --json` (`shot_cli::main` without the printing): the JSON line, the
/// SVG written first if asked.
fn play(scene: Option<Scene>, mut flags: Flags) -> Result<String, ShotError> {
    let file = match scene {
        // Read as `--scene` reads it (extension, size bound, messages).
        Some(Scene::File(path)) => SceneFile::read(&path)?,
        Some(Scene::Json(text)) => {
            SceneFile::from_json(&text).map_err(|e| ShotError::usage(format!("scene: {e}")))?
        }
        None => SceneFile::default(),
    };
    let svg = flags.svg.take();
    let played = play_request(Request::from_parts(&file, &flags)?)?;
    if let Some(path) = svg {
        std::fs::write(&path, cuesight_cli::svg::render(&played))
            .map_err(|e| ShotError::invalid(format!("svg file {}: {e}", path.display())))?;
    }
    Ok(to_json(&played.report))
}
