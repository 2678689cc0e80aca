//! `cuesight._cuesight`: the Rust half of the Python package. The Python half
//! (`cuesight/__init__.py`) turns its plain dicts and arrays into typed results.
//!
//! Nothing here predicts anything by itself: every function calls the `cuesight` CLI's
//! own code in `cuesight-cli` (`cli/`), without its argument parsing, so that
//! Python and the CLI cannot drift apart:
//!
//! * [`single`], [`many`]: `cuesight collide` ([`cuesight_cli::cli::collide_within`],
//!   `tip_spin`, `parse_model`), one scene or arrays of them;
//! * [`shot`]: `cuesight shot --json` ([`cuesight_cli::shot_cli`]);
//! * [`calibrate`]: `cuesight calibrate --json` ([`cuesight_cli::calibrate`]).
//!
//! Numbers keep the engine's precision: `collide` gives its f32 results widened to
//! Python floats exactly; `shot` and `calibrate` give the CLI's JSON text, which
//! Python parses. Every error is a `ValueError` carrying the message the CLI prints
//! after `error: `.

mod calibrate;
mod many;
mod request;
mod shot;
mod single;

use cuesight::{Model, Params, Regime};
use cuesight_link::request::law_components;
use cuesight_link::{Defaults, ModelName};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// A `ValueError` with `error`'s message (the CLI's, without `error: `).
fn value_error(error: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(error.to_string())
}

/// The core's models, cheapest first (`cuesight.MODELS`; a batch's `model_used`
/// indexes them). `model="reference"`, the host's f64 solver, is accepted besides.
fn models() -> Vec<&'static str> {
    ModelName::ALL
        .into_iter()
        .filter(|m| m.core().is_some())
        .map(ModelName::name)
        .collect()
}

/// The regimes, in the order of their codes in a batch (`cuesight.REGIMES`).
const REGIMES: [Regime; 3] = [Regime::Frictionless, Regime::Sliding, Regime::Gripping];

/// The pool defaults a parameter left out takes ([`Params::POOL`], model `kim-grip`).
#[pyfunction]
fn _defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let p = Params::POOL;
    let (mu, mu_b, mu_c) = law_components(p.friction_law());
    let dict = PyDict::new(py);
    for (key, value) in [
        ("mu", mu),
        ("mu_b", mu_b),
        ("mu_c", mu_c),
        ("restitution", p.restitution()),
        ("mu_s", p.mu_s()),
        ("radius", p.radius()),
        ("mass", p.mass()),
    ] {
        dict.set_item(key, value)?;
    }
    dict.set_item("model", Defaults::POOL.model.name())?;
    dict.set_item("tolerance", auto_tolerance())?;
    Ok(dict)
}

/// `auto`'s tolerance when none is given (the link's, 1e-3).
fn auto_tolerance() -> f32 {
    match ModelName::Auto.core() {
        Some(Model::Auto { tolerance }) => tolerance,
        _ => unreachable!("auto is a core model"),
    }
}

#[pymodule]
fn _cuesight(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(single::_collide, m)?)?;
    m.add_function(wrap_pyfunction!(many::_collide_many, m)?)?;
    m.add_function(wrap_pyfunction!(shot::_shot, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate::_calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(_defaults, m)?)?;
    let py = m.py();
    m.add("MODELS", PyTuple::new(py, models())?)?;
    m.add("REGIMES", PyTuple::new(py, REGIMES.map(Regime::name))?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
