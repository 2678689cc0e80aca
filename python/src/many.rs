//! `collide_many`: `collide` over numpy arrays, one row per scene, on one core without
//! the GIL. Each row is [`request::predict`] of the row's request, what `collide` and
//! the CLI run for it.

use cuesight::Regime;
use cuesight_cli::cli::AutoPick;
use cuesight_cli::report::Report;
use cuesight_link::ModelName;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::request::{self, Contact};
use crate::{models, REGIMES};

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

    fn push(&mut self, answer: &Report, pick: Option<AutoPick>) {
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
pub(crate) fn _collide_many<'py>(
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
    let model = request::model(model).map_err(PyValueError::new_err)?;
    let auto = model == ModelName::Auto;
    if tolerance.is_some() && !auto {
        // One model and tolerance for the batch: refused once, not per scene, with the
        // message `collide_within` gives.
        return Err(PyValueError::new_err(format!(
            "--tolerance is for --model auto, not {}",
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
        // Taken and released without the GIL (see `request::REFERENCE`).
        let _lock = request::reference_lock(model);
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
            let scene = request::request(
                speed_c.row(i)[0],
                cut_c.row(i)[0],
                spin,
                roll_c.row(i)[0],
                tip,
                contact,
                model,
            )
            .and_then(|request| request::predict(&request, tolerance));
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
