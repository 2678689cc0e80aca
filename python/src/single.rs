//! `collide`: one collision, the dict of `cuesight collide --json`.

use cuesight_cli::cli::{AutoPick, CliError};
use cuesight_cli::report::Report;
use cuesight_link::ModelName;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::request::{self, Contact};
use crate::value_error;

/// `[x, y, z]` as a Python tuple of exactly widened floats.
fn vector(py: Python<'_>, v: [f32; 3]) -> PyResult<Bound<'_, PyAny>> {
    Ok((v[0], v[1], v[2]).into_pyobject(py)?.into_any())
}

/// The answer as a dict with the keys of `cuesight collide --json`.
fn answer_dict<'py>(
    py: Python<'py>,
    answer: &Report,
    pick: Option<AutoPick>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("model", answer.model.name())?;
    dict.set_item("regime", answer.regime.name())?;
    let i = &answer.input;
    let input = PyDict::new(py);
    input.set_item("speed", i.speed)?;
    input.set_item("cut_deg", i.cut_deg)?;
    input.set_item("spin", vector(py, i.spin)?)?;
    input.set_item("roll", i.roll)?;
    for (key, value) in [
        ("mu", i.mu),
        ("mu_b", i.mu_b),
        ("mu_c", i.mu_c),
        ("restitution", i.restitution),
        ("mu_s", i.mu_s),
        ("radius", i.radius),
        ("mass", i.mass),
    ] {
        input.set_item(key, value)?;
    }
    dict.set_item("input", input)?;
    for (key, ball) in [("cue", &answer.cue), ("object", &answer.object)] {
        let b = PyDict::new(py);
        b.set_item("v", vector(py, ball.v)?)?;
        b.set_item("w", vector(py, ball.w)?)?;
        dict.set_item(key, b)?;
    }
    dict.set_item("throw_deg", answer.throw_deg)?;
    dict.set_item("cue_deflection_deg", answer.cue_deflection_deg)?;
    dict.set_item("separation_deg", answer.separation_deg)?;
    let impulses = PyDict::new(py);
    impulses.set_item("normal", answer.impulses.normal)?;
    impulses.set_item("friction", vector(py, answer.impulses.friction)?)?;
    impulses.set_item("table_friction", answer.impulses.table_friction)?;
    dict.set_item("impulses", impulses)?;
    if let Some(pick) = pick {
        dict.set_item("tolerance", pick.tolerance)?;
        dict.set_item("model_used", pick.tier.name())?;
        dict.set_item("error_estimate", pick.estimate)?;
    }
    Ok(dict)
}

/// One collision: the dict of `cuesight collide --json`. The reference solver runs
/// without the GIL (about 0.3 ms a scene).
#[pyfunction]
#[pyo3(signature = (speed, cut_deg, spin, roll, tip, mu, mu_b, mu_c, restitution, mu_s, radius, mass, model, tolerance))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _collide<'py>(
    py: Python<'py>,
    speed: f32,
    cut_deg: f32,
    spin: Option<[f32; 3]>,
    roll: bool,
    tip: Option<[f32; 2]>,
    mu: Option<f32>,
    mu_b: Option<f32>,
    mu_c: Option<f32>,
    restitution: Option<f32>,
    mu_s: Option<f32>,
    radius: Option<f32>,
    mass: Option<f32>,
    model: &str,
    tolerance: Option<f32>,
) -> PyResult<Bound<'py, PyDict>> {
    let contact = Contact {
        mu,
        mu_b,
        mu_c,
        restitution,
        mu_s,
        radius,
        mass,
    };
    let model = request::model(model).map_err(value_error)?;
    let predict = || -> Result<_, CliError> {
        let request = request::request(speed, cut_deg, spin, roll, tip, contact, model)?;
        let _lock = request::reference_lock(model);
        request::predict(&request, tolerance)
    };
    let (answer, pick) = if model == ModelName::Reference {
        py.detach(predict)
    } else {
        predict()
    }
    .map_err(value_error)?;
    answer_dict(py, &answer, pick)
}
