//! `cuesight._cuesight`: the Rust half of the Python package. The Python half
//! (`cuesight/__init__.py`) turns its plain dicts and arrays into typed results.
//!
//! One collision is predicted exactly as `cuesight collide` does it
//! (`host-tests/src/cli.rs`, `collide_within` and `tip_spin`): the link's
//! [`Collide::prepare`] from the pool defaults, the core's [`cuesight::collide`], the
//! link's [`CollideAnswer`] (whose serde form is what `collide --json` prints) and, for
//! `auto`, [`cuesight::select_model`]. Every number is the engine's f32, widened to a
//! Python float exactly. Invalid input is a `ValueError` carrying the core's message.

use cuesight::strike::{strike, Cue, Strike, TipOffset};
use cuesight::{Model, Params, Regime};
use cuesight_link::request::law_components;
use cuesight_link::response::{CollideAnswer, InputEcho};
use cuesight_link::{Collide, Defaults, ModelName};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// The models Python may name: the core's (the link's names), not the host's f64
/// reference solver.
fn parse_model(name: &str) -> Result<ModelName, String> {
    match ModelName::ALL.into_iter().find(|m| m.name() == name) {
        Some(ModelName::Reference) => Err(
            "model reference (the f64 reference solver) is host-only: use `cuesight collide --model reference`"
                .to_owned(),
        ),
        Some(model) => Ok(model),
        None => Err(format!(
            "unknown model '{name}', expected one of {}",
            models().join(", ")
        )),
    }
}

/// The names [`parse_model`] accepts, in the core's order.
fn models() -> Vec<&'static str> {
    ModelName::ALL
        .into_iter()
        .filter(|m| m.core().is_some())
        .map(ModelName::name)
        .collect()
}

/// What `auto` did: the tolerance, the tier it evaluated and that tier's estimate.
#[derive(Clone, Copy)]
struct AutoPick {
    tolerance: f32,
    tier: Model,
    estimate: f32,
}

/// The spin a cue strike at `tip` (`[side, height]`, ball radii) gives a ball arriving
/// at the request's speed and cut: `cuesight collide --tip` (`cli::tip_spin`).
fn tip_spin(request: &Collide, tip: [f32; 2]) -> Result<[f32; 3], String> {
    let stun = Collide {
        spin: None,
        roll: false,
        ..*request
    };
    let prepared = stun.prepare(&Defaults::POOL).map_err(|e| e.to_string())?;
    let params = &prepared.params;
    let offset = TipOffset::from_radius_fraction(tip[0], tip[1], params.radius())
        .map_err(|e| e.to_string())?;
    let unit = strike(params, &Cue::TYPICAL, offset, 1.0).map_err(|e| e.to_string())?;
    let speed = prepared.impact.speed();
    let arriving = Strike {
        speed,
        spin: unit.spin * (speed / unit.speed),
    };
    let impact = arriving
        .to_impact(request.cut.to_radians())
        .map_err(|e| e.to_string())?;
    Ok(impact.spin().to_array())
}

/// One prediction, as `cuesight collide` makes it (`cli::collide_within`), the
/// reference solver aside.
fn predict(
    request: &Collide,
    tolerance: Option<f32>,
) -> Result<(CollideAnswer, Option<AutoPick>), String> {
    let prepared = request
        .prepare(&Defaults::POOL)
        .map_err(|e| e.to_string())?;
    let model = match (prepared.model.core(), tolerance) {
        (Some(Model::Auto { .. }), Some(tolerance)) => Model::Auto { tolerance },
        (_, Some(_)) => {
            return Err(format!(
                "tolerance is for model 'auto', not '{}'",
                prepared.model.name()
            ))
        }
        (Some(model), None) => model,
        (None, None) => return Err(parse_model("reference").unwrap_err()),
    };
    let (params, impact) = (&prepared.params, &prepared.impact);
    let outcome = cuesight::collide(params, impact, model).map_err(|e| e.to_string())?;
    let pick = match model {
        Model::Auto { tolerance } => {
            let (tier, estimate) = cuesight::select_model(params, impact, tolerance);
            Some(AutoPick {
                tolerance,
                tier,
                estimate,
            })
        }
        _ => None,
    };
    let answer = CollideAnswer::new(prepared.model, InputEcho::of(request, &prepared), &outcome);
    Ok((answer, pick))
}

/// The contact parameters of one request (each `None`: the pool default).
#[derive(Clone, Copy, Default)]
struct Contact {
    mu: Option<f32>,
    mu_b: Option<f32>,
    mu_c: Option<f32>,
    restitution: Option<f32>,
    mu_s: Option<f32>,
    radius: Option<f32>,
    mass: Option<f32>,
}

/// The request `cuesight collide` builds from its flags; `tip` replaces the spin as
/// `--tip` does. Spin with roll, or tip with either, is refused (clap refuses them).
fn request(
    speed: f32,
    cut: f32,
    spin: Option<[f32; 3]>,
    roll: bool,
    tip: Option<[f32; 2]>,
    contact: Contact,
    model: ModelName,
) -> Result<Collide, String> {
    if roll && spin.is_some() {
        return Err("spin and roll=True are exclusive".to_owned());
    }
    if tip.is_some() && (roll || spin.is_some()) {
        return Err("tip is exclusive with spin and roll=True".to_owned());
    }
    let mut request = Collide {
        speed,
        cut,
        spin,
        roll,
        mu: contact.mu,
        mu_b: contact.mu_b,
        mu_c: contact.mu_c,
        restitution: contact.restitution,
        mu_s: contact.mu_s,
        radius: contact.radius,
        mass: contact.mass,
        model: Some(model),
    };
    if let Some(tip) = tip {
        request.spin = Some(tip_spin(&request, tip)?);
    }
    Ok(request)
}

/// `[x, y, z]` as a Python tuple of exactly widened floats.
fn vector(py: Python<'_>, v: [f32; 3]) -> PyResult<Bound<'_, PyAny>> {
    Ok((v[0], v[1], v[2]).into_pyobject(py)?.into_any())
}

/// The answer as a dict with the keys of `cuesight collide --json`.
fn answer_dict<'py>(
    py: Python<'py>,
    answer: &CollideAnswer,
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

/// One collision: the dict of `cuesight collide --json`.
#[pyfunction]
#[pyo3(signature = (speed, cut_deg, spin, roll, tip, mu, mu_b, mu_c, restitution, mu_s, radius, mass, model, tolerance))]
#[allow(clippy::too_many_arguments)]
fn _collide<'py>(
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
    let model = parse_model(model).map_err(PyValueError::new_err)?;
    let (answer, pick) = request(speed, cut_deg, spin, roll, tip, contact, model)
        .and_then(|request| predict(&request, tolerance))
        .map_err(PyValueError::new_err)?;
    answer_dict(py, &answer, pick)
}

/// A batch input: one value for every scene (length 1) or one per scene (length n),
/// `width` numbers each.
#[derive(Clone, Copy)]
struct Column<'a, T> {
    values: &'a [T],
    width: usize,
}

impl<'a, T: Copy> Column<'a, T> {
    fn new(name: &str, values: &'a [T], width: usize, n: usize) -> Result<Self, String> {
        if values.len() == width || values.len() == width * n {
            Ok(Self { values, width })
        } else {
            Err(format!(
                "{name} has {} values, expected {width} or {} (one per scene)",
                values.len(),
                width * n
            ))
        }
    }

    /// Scene `i`'s values.
    fn row(&self, i: usize) -> &'a [T] {
        if self.values.len() == self.width {
            self.values
        } else {
            &self.values[i * self.width..(i + 1) * self.width]
        }
    }
}

/// An optional scalar column's value for scene `i`.
fn scalar(column: Option<Column<'_, f32>>, i: usize) -> Option<f32> {
    column.map(|c| c.row(i)[0])
}

/// Output columns of a batch, flat (vectors as `3 n`).
struct Outputs {
    throw_deg: Vec<f32>,
    cue_deflection_deg: Vec<f32>,
    separation_deg: Vec<f32>,
    cue_v: Vec<f32>,
    cue_w: Vec<f32>,
    object_v: Vec<f32>,
    object_w: Vec<f32>,
    impulse_normal: Vec<f32>,
    impulse_friction: Vec<f32>,
    table_friction: Vec<f32>,
    spin: Vec<f32>,
    regime: Vec<i8>,
    valid: Vec<bool>,
    model_used: Vec<i8>,
    error_estimate: Vec<f32>,
}

impl Outputs {
    fn with_capacity(n: usize, auto: bool) -> Self {
        let auto_n = if auto { n } else { 0 };
        Self {
            throw_deg: Vec::with_capacity(n),
            cue_deflection_deg: Vec::with_capacity(n),
            separation_deg: Vec::with_capacity(n),
            cue_v: Vec::with_capacity(3 * n),
            cue_w: Vec::with_capacity(3 * n),
            object_v: Vec::with_capacity(3 * n),
            object_w: Vec::with_capacity(3 * n),
            impulse_normal: Vec::with_capacity(n),
            impulse_friction: Vec::with_capacity(3 * n),
            table_friction: Vec::with_capacity(n),
            spin: Vec::with_capacity(3 * n),
            regime: Vec::with_capacity(n),
            valid: Vec::with_capacity(n),
            model_used: Vec::with_capacity(auto_n),
            error_estimate: Vec::with_capacity(auto_n),
        }
    }

    fn push(&mut self, answer: &CollideAnswer, pick: Option<AutoPick>) {
        self.throw_deg.push(answer.throw_deg);
        self.cue_deflection_deg.push(answer.cue_deflection_deg);
        self.separation_deg.push(answer.separation_deg);
        self.cue_v.extend_from_slice(&answer.cue.v);
        self.cue_w.extend_from_slice(&answer.cue.w);
        self.object_v.extend_from_slice(&answer.object.v);
        self.object_w.extend_from_slice(&answer.object.w);
        self.impulse_normal.push(answer.impulses.normal);
        self.impulse_friction
            .extend_from_slice(&answer.impulses.friction);
        self.table_friction.push(answer.impulses.table_friction);
        self.spin.extend_from_slice(&answer.input.spin);
        self.regime.push(regime_code(answer.regime));
        self.valid.push(true);
        if let Some(pick) = pick {
            self.model_used.push(model_code(ModelName::of(pick.tier)));
            self.error_estimate.push(pick.estimate);
        }
    }

    /// A scene that was refused: NaN everywhere, regime and model −1.
    fn push_invalid(&mut self, auto: bool) {
        let nan = f32::NAN;
        for column in [
            &mut self.throw_deg,
            &mut self.cue_deflection_deg,
            &mut self.separation_deg,
            &mut self.impulse_normal,
            &mut self.table_friction,
        ] {
            column.push(nan);
        }
        for column in [
            &mut self.cue_v,
            &mut self.cue_w,
            &mut self.object_v,
            &mut self.object_w,
            &mut self.impulse_friction,
            &mut self.spin,
        ] {
            column.extend_from_slice(&[nan; 3]);
        }
        self.regime.push(-1);
        self.valid.push(false);
        if auto {
            self.model_used.push(-1);
            self.error_estimate.push(nan);
        }
    }
}

/// The regimes, in the order of their codes in a batch (`cuesight.REGIMES`).
const REGIMES: [Regime; 3] = [Regime::Frictionless, Regime::Sliding, Regime::Gripping];

/// A regime's index in [`REGIMES`].
fn regime_code(regime: Regime) -> i8 {
    REGIMES
        .iter()
        .position(|&r| r == regime)
        .map_or(-1, |p| p as i8)
}

/// A model's index in [`models`] (`cuesight.MODELS`).
fn model_code(model: ModelName) -> i8 {
    models()
        .iter()
        .position(|&m| m == model.name())
        .map_or(-1, |p| p as i8)
}

/// An optional f32 array as a [`Column`] of `width` numbers a scene.
fn column_of<'a>(
    name: &str,
    array: &'a Option<PyReadonlyArray1<'_, f32>>,
    width: usize,
    n: usize,
) -> PyResult<Option<Column<'a, f32>>> {
    let Some(array) = array else {
        return Ok(None);
    };
    let values = array
        .as_slice()
        .map_err(|e| PyValueError::new_err(format!("{name}: {e}")))?;
    Column::new(name, values, width, n)
        .map(Some)
        .map_err(PyValueError::new_err)
}

/// Many collisions over arrays: each input one value or one per scene (vectors
/// flattened). Returns a dict of numpy arrays (f32; vectors `(n, 3)`).
#[pyfunction]
#[pyo3(signature = (n, speed, cut_deg, spin, roll, tip, mu, mu_b, mu_c, restitution, mu_s, radius, mass, model, tolerance, raise_errors))]
#[allow(clippy::too_many_arguments)]
fn _collide_many<'py>(
    py: Python<'py>,
    n: usize,
    speed: PyReadonlyArray1<'py, f32>,
    cut_deg: PyReadonlyArray1<'py, f32>,
    spin: Option<PyReadonlyArray1<'py, f32>>,
    roll: PyReadonlyArray1<'py, bool>,
    tip: Option<PyReadonlyArray1<'py, f32>>,
    mu: Option<PyReadonlyArray1<'py, f32>>,
    mu_b: Option<PyReadonlyArray1<'py, f32>>,
    mu_c: Option<PyReadonlyArray1<'py, f32>>,
    restitution: Option<PyReadonlyArray1<'py, f32>>,
    mu_s: Option<PyReadonlyArray1<'py, f32>>,
    radius: Option<PyReadonlyArray1<'py, f32>>,
    mass: Option<PyReadonlyArray1<'py, f32>>,
    model: &str,
    tolerance: Option<f32>,
    raise_errors: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let model = parse_model(model).map_err(PyValueError::new_err)?;
    let auto = model == ModelName::Auto;
    if tolerance.is_some() && !auto {
        // One model and tolerance for the batch: refused once, not per scene.
        return Err(PyValueError::new_err(format!(
            "tolerance is for model 'auto', not '{}'",
            model.name()
        )));
    }
    let speed = Some(speed);
    let cut_deg = Some(cut_deg);
    let scalars = [
        ("speed", &speed),
        ("cut_deg", &cut_deg),
        ("mu", &mu),
        ("mu_b", &mu_b),
        ("mu_c", &mu_c),
        ("restitution", &restitution),
        ("mu_s", &mu_s),
        ("radius", &radius),
        ("mass", &mass),
    ];
    let mut columns = [None; 9];
    for ((name, array), column) in scalars.into_iter().zip(&mut columns) {
        *column = column_of(name, array, 1, n)?;
    }
    let [speed_c, cut_c, mu_col, mu_b_col, mu_c_col, e_col, mu_s_col, r_col, m_col] = columns;
    let (Some(speed_c), Some(cut_c)) = (speed_c, cut_c) else {
        unreachable!("speed and cut_deg are always given")
    };
    let spin_c = column_of("spin", &spin, 3, n)?;
    let tip_c = column_of("tip", &tip, 2, n)?;
    let roll_s = roll
        .as_slice()
        .map_err(|e| PyValueError::new_err(format!("roll: {e}")))?;
    let roll_c = Column::new("roll", roll_s, 1, n).map_err(PyValueError::new_err)?;

    let result = py.detach(|| -> Result<Outputs, String> {
        let mut out = Outputs::with_capacity(n, auto);
        for i in 0..n {
            let contact = Contact {
                mu: scalar(mu_col, i),
                mu_b: scalar(mu_b_col, i),
                mu_c: scalar(mu_c_col, i),
                restitution: scalar(e_col, i),
                mu_s: scalar(mu_s_col, i),
                radius: scalar(r_col, i),
                mass: scalar(m_col, i),
            };
            let spin = spin_c.map(|c| {
                let s = c.row(i);
                [s[0], s[1], s[2]]
            });
            let tip = tip_c.map(|c| {
                let t = c.row(i);
                [t[0], t[1]]
            });
            let scene = request(
                speed_c.row(i)[0],
                cut_c.row(i)[0],
                spin,
                roll_c.row(i)[0],
                tip,
                contact,
                model,
            )
            .and_then(|request| predict(&request, tolerance));
            match scene {
                Ok((answer, pick)) => out.push(&answer, pick),
                Err(message) if raise_errors => return Err(format!("scene {i}: {message}")),
                Err(_) => out.push_invalid(auto),
            }
        }
        Ok(out)
    });
    let out = result.map_err(PyValueError::new_err)?;

    let dict = PyDict::new(py);
    let vec3 = |v: Vec<f32>| PyArray1::from_vec(py, v).reshape([n, 3]);
    for (key, values) in [
        ("throw_deg", out.throw_deg),
        ("cue_deflection_deg", out.cue_deflection_deg),
        ("separation_deg", out.separation_deg),
        ("impulse_normal", out.impulse_normal),
        ("table_friction", out.table_friction),
    ] {
        dict.set_item(key, PyArray1::from_vec(py, values))?;
    }
    for (key, values) in [
        ("cue_v", out.cue_v),
        ("cue_w", out.cue_w),
        ("object_v", out.object_v),
        ("object_w", out.object_w),
        ("impulse_friction", out.impulse_friction),
        ("spin", out.spin),
    ] {
        dict.set_item(key, vec3(values)?)?;
    }
    dict.set_item("regime", PyArray1::from_vec(py, out.regime))?;
    dict.set_item("valid", PyArray1::from_vec(py, out.valid))?;
    if auto {
        dict.set_item("model_used", PyArray1::from_vec(py, out.model_used))?;
        dict.set_item("error_estimate", PyArray1::from_vec(py, out.error_estimate))?;
    }
    Ok(dict)
}

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
    m.add_function(wrap_pyfunction!(_collide, m)?)?;
    m.add_function(wrap_pyfunction!(_collide_many, m)?)?;
    m.add_function(wrap_pyfunction!(_defaults, m)?)?;
    let py = m.py();
    m.add("MODELS", PyTuple::new(py, models())?)?;
    m.add("REGIMES", PyTuple::new(py, REGIMES.map(Regime::name))?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
