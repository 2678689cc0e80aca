//! The weighted least-squares fit of the friction law (and e*) to measured throw, its
//! covariance, and leave-one-series-out cross-validation.

use std::cell::Cell;
use std::io::Write;
use std::time::Instant;

use cuesight::{FrictionLaw, Impact, Model, Params};
use glam::DVec3;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Owned};

use super::input::{Measurement, Spin};
use crate::reference::{self, ReferenceConfig, ReferenceParams};

/// Which parameters are fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FitKind {
    /// A constant μ.
    Mu,
    /// `μ(v) = a + b·exp(−c·v)` (TP A.14), `v` the slip speed.
    #[value(name = "mu-v")]
    MuV,
    /// μ(v) and the energetic restitution e*.
    #[value(name = "mu-v-e")]
    MuVE,
}

impl FitKind {
    /// The `--fit` name.
    pub const fn name(self) -> &'static str {
        match self {
            FitKind::Mu => "mu",
            FitKind::MuV => "mu-v",
            FitKind::MuVE => "mu-v-e",
        }
    }

    /// Names of the fitted parameters, as `collide` takes them.
    pub const fn parameter_names(self) -> &'static [&'static str] {
        match self {
            FitKind::Mu => &["mu"],
            FitKind::MuV => &["mu", "mu_b", "mu_c"],
            FitKind::MuVE => &["mu", "mu_b", "mu_c", "restitution"],
        }
    }

    /// Number of fitted parameters.
    pub const fn len(self) -> usize {
        self.parameter_names().len()
    }

    /// Always false (every kind fits at least μ); for clippy's `len_without_is_empty`.
    pub const fn is_empty(self) -> bool {
        false
    }
}

/// What computes the model's throw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Solver {
    /// The core's `KimGrip` tier, evaluated in f64 (`cuesight::collide_f64`).
    KimGrip,
    /// The core's `Exact` tier, evaluated in f64.
    Exact,
    /// The f64 first-principles reference solver (`reference::solve`, 1,000 steps).
    Reference,
}

impl Solver {
    /// The `--model` name.
    pub const fn name(self) -> &'static str {
        match self {
            Solver::KimGrip => "kim-grip",
            Solver::Exact => "exact",
            Solver::Reference => "reference",
        }
    }
}

/// Parameters that are not fitted (and the fitted ones' values outside a fit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Physics {
    /// μ(v)'s high-speed limit `a` (the constant μ when `b = 0`).
    pub mu: f64,
    /// Amplitude `b`.
    pub mu_b: f64,
    /// Decay rate `c` (s/m).
    pub mu_c: f64,
    /// Energetic restitution e*.
    pub restitution: f64,
    /// Object-ball/table friction μ_s.
    pub mu_s: f64,
    /// Ball radius (m).
    pub radius: f64,
    /// Ball mass (kg).
    pub mass: f64,
}

impl Physics {
    /// The core's pool defaults (μ = 0.05 constant, e* = 0.95, μ_s = 0.3).
    pub fn pool() -> Self {
        let p = Params::POOL;
        Self {
            mu: p.mu() as f64,
            mu_b: 0.0,
            mu_c: 0.0,
            restitution: p.restitution() as f64,
            mu_s: p.mu_s() as f64,
            radius: p.radius() as f64,
            mass: p.mass() as f64,
        }
    }

    fn with(mut self, kind: FitKind, theta: &[f64]) -> Self {
        self.mu = theta[0];
        match kind {
            FitKind::Mu => {
                self.mu_b = 0.0;
                self.mu_c = 0.0;
            }
            FitKind::MuV | FitKind::MuVE => {
                self.mu_b = theta[1];
                self.mu_c = theta[2];
            }
        }
        if kind == FitKind::MuVE {
            self.restitution = theta[3];
        }
        self
    }

    fn core(&self) -> Result<Params, String> {
        let law = if self.mu_b == 0.0 && self.mu_c == 0.0 {
            FrictionLaw::constant(self.mu as f32)
        } else {
            FrictionLaw::speed_dependent(self.mu as f32, self.mu_b as f32, self.mu_c as f32)
        }
        .map_err(|e| e.to_string())?;
        Params::POOL
            .with_friction_law(law)
            .with_restitution(self.restitution as f32)
            .and_then(|p| p.with_mu_s(self.mu_s as f32))
            .and_then(|p| p.with_ball(self.radius as f32, self.mass as f32))
            .map_err(|e| e.to_string())
    }
}

/// The model's throw (degrees) for one measurement.
pub fn model_throw(solver: Solver, physics: &Physics, m: &Measurement) -> Result<f64, String> {
    let w = m.spin.vector(m.speed_mps, m.cut_deg, physics.radius);
    match solver {
        Solver::KimGrip | Solver::Exact => {
            let params = physics.core()?;
            let impact =
                Impact::from_cut_degrees(m.speed_mps as f32, m.cut_deg as f32, w.map(|x| x as f32))
                    .map_err(|e| e.to_string())?;
            let model = match solver {
                Solver::KimGrip => Model::KimGrip,
                _ => Model::Exact,
            };
            let out = cuesight::collide_f64(&params, &impact, model).map_err(|e| e.to_string())?;
            Ok(out.throw_angle_deg() as f64)
        }
        Solver::Reference => {
            let p = ReferenceParams {
                mu: physics.mu,
                mu_b: physics.mu_b,
                mu_c: physics.mu_c,
                restitution: physics.restitution,
                mu_s: physics.mu_s,
                cue_table_friction: 0.0,
                radius: physics.radius,
                mass: physics.mass,
            };
            let phi = m.cut_deg.to_radians();
            let v = DVec3::new(m.speed_mps * phi.cos(), m.speed_mps * phi.sin(), 0.0);
            reference::solve(&p, v, DVec3::from(w), &ReferenceConfig::default())
                .map(|o| o.throw_angle_deg())
                .map_err(|e| format!("reference solver: {e:?}"))
        }
    }
}

/// The rigid-ball ceiling on throw (degrees): the contact grips and the friction
/// impulse is the one that stops the slip (`ΔV_y = v_y0/7`, TP A.14's 1/7 cap) over the
/// frictionless normal impulse, `atan(2 (U sin φ + R ω_z) / (7 (1 + e*) U cos φ))`; for
/// a stun ball `atan(2 tan φ / (7 (1 + e*)))`. No friction law exceeds it (the
/// object ball's table friction only adds to `V_x`).
pub fn rigid_ceiling_deg(m: &Measurement, restitution: f64, radius: f64) -> f64 {
    let w = m.spin.vector(m.speed_mps, m.cut_deg, radius);
    let phi = m.cut_deg.to_radians();
    let side = m.speed_mps * phi.sin() + radius * w[2];
    (2.0 * side)
        .atan2(7.0 * (1.0 + restitution) * m.speed_mps * phi.cos())
        .to_degrees()
}

/// Settings of a fit.
#[derive(Clone, Copy, Debug)]
pub struct FitOptions {
    /// Parameters to fit.
    pub kind: FitKind,
    /// Model of the throw.
    pub solver: Solver,
    /// Fixed parameters (and the fitted ones' values when not fitted).
    pub physics: Physics,
    /// Uncertainty (degrees) of points that give none.
    pub default_uncertainty_deg: f64,
    /// Limit on model evaluations over the whole fit (all starts).
    pub max_evaluations: usize,
    /// Print a progress line on stderr every second once a fit has run for one.
    pub progress: bool,
}

impl FitOptions {
    /// Defaults: μ(v), `KimGrip`, pool physics, 1° for missing uncertainties.
    pub fn new(kind: FitKind) -> Self {
        Self {
            kind,
            solver: Solver::KimGrip,
            physics: Physics::pool(),
            default_uncertainty_deg: 1.0,
            max_evaluations: 100_000,
            progress: false,
        }
    }
}

/// A fitted parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// `collide`'s name.
    pub name: &'static str,
    /// Best-fit value.
    pub value: f64,
    /// Standard error (from the Jacobian covariance).
    pub stderr: f64,
    /// Half-width of the 95 % confidence interval (Student t × standard error).
    pub ci95: f64,
}

/// One point after the fit.
#[derive(Clone, Debug, PartialEq)]
pub struct PointFit {
    /// The measurement.
    pub measurement: Measurement,
    /// The model's throw at the fitted parameters (degrees).
    pub model_deg: f64,
    /// Model − measured (degrees).
    pub residual_deg: f64,
    /// The rigid ceiling at the fitted (or fixed) e* (degrees).
    pub ceiling_deg: f64,
}

/// The result of a fit.
#[derive(Clone, Debug)]
pub struct Fit {
    /// What was fitted.
    pub kind: FitKind,
    /// The throw model used.
    pub solver: Solver,
    /// All parameters at the optimum (fixed ones as given).
    pub physics: Physics,
    /// The fitted parameters.
    pub estimates: Vec<Estimate>,
    /// Correlation matrix of the fitted parameters (row-major, `len × len`).
    pub correlation: Vec<f64>,
    /// Per-point results, in file order.
    pub points: Vec<PointFit>,
    /// RMS of the residuals (degrees, unweighted).
    pub rms_deg: f64,
    /// Largest |residual| (degrees) and its point index.
    pub max_deg: (f64, usize),
    /// Weighted RMS √(χ²/(n − p)) (1 when the uncertainties are the scatter).
    pub reduced_chi: f64,
    /// Model evaluations (one per point and parameter vector).
    pub evaluations: usize,
    /// Wall time (s).
    pub seconds: f64,
}

impl Fit {
    /// Points above their rigid ceiling.
    pub fn above_ceiling(&self) -> usize {
        self.points
            .iter()
            .filter(|p| p.measurement.throw_deg > p.ceiling_deg)
            .count()
    }
}

/// Why a fit gave no answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FitError(pub String);

impl std::fmt::Display for FitError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for FitError {}

/// Typical size of each parameter (finite-difference steps and penalty scale).
const TYPICAL: [f64; 4] = [0.01, 0.1, 1.0, 0.1];
/// Bounds the core accepts: a ∈ [1e-6, 1], b ∈ [0, 1], c ∈ [0, 100], e* ∈ [0, 1].
const LOWER: [f64; 4] = [1e-6, 0.0, 0.0, 0.0];
const UPPER: [f64; 4] = [1.0, 1.0, 100.0, 1.0];
/// Weight of a bound violation of one `TYPICAL` unit, in weighted-residual units.
const PENALTY: f64 = 1e3;

struct Problem<'a> {
    points: &'a [Measurement],
    sigma: Vec<f64>,
    options: &'a FitOptions,
    theta: DVector<f64>,
    evaluations: &'a Cell<usize>,
    start: Instant,
    last_print: &'a Cell<f64>,
    failure: &'a Cell<Option<String>>,
}

impl Problem<'_> {
    fn clamped(&self, theta: &[f64]) -> Vec<f64> {
        let mut t: Vec<f64> = theta
            .iter()
            .enumerate()
            .map(|(k, &x)| x.clamp(LOWER[k], UPPER[k]))
            .collect();
        // a + b ≤ 1 (core's FrictionLaw).
        if t.len() > 1 && t[0] + t[1] > 1.0 {
            t[1] = 1.0 - t[0];
        }
        t
    }

    /// Model throws at `theta` (clamped to the bounds), or the first error.
    fn throws(&self, theta: &[f64]) -> Result<Vec<f64>, String> {
        let physics = self
            .options
            .physics
            .with(self.options.kind, &self.clamped(theta));
        let out = self
            .points
            .iter()
            .map(|m| model_throw(self.options.solver, &physics, m))
            .collect::<Result<Vec<f64>, String>>();
        let n = self.evaluations.get() + self.points.len();
        self.evaluations.set(n);
        let elapsed = self.start.elapsed().as_secs_f64();
        if self.options.progress && elapsed >= 1.0 && elapsed - self.last_print.get() >= 1.0 {
            self.last_print.set(elapsed);
            let rms = out.as_ref().ok().map_or(f64::NAN, |t| {
                let s: f64 = t
                    .iter()
                    .zip(self.points)
                    .map(|(t, m)| (t - m.throw_deg).powi(2))
                    .sum();
                (s / t.len() as f64).sqrt()
            });
            let _ = writeln!(
                std::io::stderr(),
                "calibrate: fitting {} by {}: {n} evaluations, {elapsed:.1} s, rms {rms:.3} deg",
                self.options.kind.name(),
                self.options.solver.name()
            );
        }
        out
    }

    fn penalties(&self, theta: &[f64]) -> Vec<f64> {
        theta
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let below = (LOWER[k] - x).max(0.0);
                let above = (x - UPPER[k]).max(0.0);
                let sum = if k == 1 {
                    (theta[0] + x - 1.0).max(0.0)
                } else {
                    0.0
                };
                PENALTY * (below + above + sum) / TYPICAL[k]
            })
            .collect()
    }

    fn record(&self, error: String) {
        let previous = self.failure.take();
        self.failure.set(previous.or(Some(error)));
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.theta.copy_from(x);
    }

    fn params(&self) -> DVector<f64> {
        self.theta.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        if self.evaluations.get() >= self.options.max_evaluations {
            self.record(format!(
                "the fit did not converge within {} model evaluations",
                self.options.max_evaluations
            ));
            return None;
        }
        let theta = self.theta.as_slice();
        let throws = match self.throws(theta) {
            Ok(t) => t,
            Err(e) => {
                self.record(format!("the model failed: {e}"));
                return None;
            }
        };
        let mut r: Vec<f64> = throws
            .iter()
            .zip(self.points)
            .zip(&self.sigma)
            .map(|((t, m), s)| (t - m.throw_deg) / s)
            .collect();
        r.extend(self.penalties(theta));
        Some(DVector::from_vec(r))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let n = self.points.len();
        let p = self.theta.len();
        let theta: Vec<f64> = self.theta.iter().copied().collect();
        let mut j = DMatrix::zeros(n + p, p);
        for k in 0..p {
            let h = 1e-4 * theta[k].abs().max(TYPICAL[k]);
            let (mut up, mut down) = (theta.clone(), theta.clone());
            up[k] += h;
            down[k] -= h;
            let (cu, cd) = (self.clamped(&up)[k], self.clamped(&down)[k]);
            if cu - cd <= 0.0 {
                continue;
            }
            let (tu, td) = match (self.throws(&up), self.throws(&down)) {
                (Ok(tu), Ok(td)) => (tu, td),
                (Err(e), _) | (_, Err(e)) => {
                    self.record(format!("the model failed: {e}"));
                    return None;
                }
            };
            for i in 0..n {
                j[(i, k)] = (tu[i] - td[i]) / (cu - cd) / self.sigma[i];
            }
            let (pu, pd) = (self.penalties(&up), self.penalties(&down));
            for (row, (a, b)) in pu.iter().zip(&pd).enumerate() {
                j[(n + row, k)] = (a - b) / (2.0 * h);
            }
        }
        Some(j)
    }
}

/// Two-sided 95 % quantile of Student's t with `dof` degrees of freedom (Cornish–Fisher
/// expansion about the normal quantile, Abramowitz & Stegun 26.7.5: error below 1e-3
/// from 4 degrees of freedom; exact values for 1–3).
pub fn t95(dof: usize) -> f64 {
    match dof {
        0 => f64::INFINITY,
        1 => 12.706_204_736,
        2 => 4.302_652_730,
        3 => 3.182_446_305,
        _ => {
            let z: f64 = 1.959_963_985;
            let v = dof as f64;
            let (z3, z5, z7, z9) = (z.powi(3), z.powi(5), z.powi(7), z.powi(9));
            z + (z3 + z) / (4.0 * v)
                + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * v * v)
                + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * v.powi(3))
                + (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z)
                    / (92_160.0 * v.powi(4))
        }
    }
}

/// Starting points: TP A.14's Marlow fit and two others spread in the decay rate.
fn starts(kind: FitKind, physics: &Physics) -> Vec<Vec<f64>> {
    let e = physics.restitution;
    match kind {
        FitKind::Mu => vec![vec![0.05]],
        FitKind::MuV => vec![
            vec![0.00995, 0.108, 1.088],
            vec![0.03, 0.1, 0.3],
            vec![0.02, 0.2, 3.0],
        ],
        FitKind::MuVE => vec![
            vec![0.00995, 0.108, 1.088, e],
            vec![0.03, 0.1, 0.3, e],
            vec![0.02, 0.2, 3.0, e],
        ],
    }
}

/// Fit `options.kind` to `points` by weighted least squares (Levenberg–Marquardt).
pub fn fit(points: &[Measurement], options: &FitOptions) -> Result<Fit, FitError> {
    let p = options.kind.len();
    if points.len() <= p {
        return Err(FitError(format!(
            "{} points for {p} parameters ({}): need at least {} to fit and estimate uncertainties",
            points.len(),
            options.kind.parameter_names().join(", "),
            p + 1
        )));
    }
    if !(options.default_uncertainty_deg.is_finite() && options.default_uncertainty_deg > 0.0) {
        return Err(FitError(
            "the default uncertainty must be > 0 degrees".to_owned(),
        ));
    }
    let sigma: Vec<f64> = points
        .iter()
        .map(|m| m.uncertainty_deg.unwrap_or(options.default_uncertainty_deg))
        .collect();
    let evaluations = Cell::new(0);
    let last_print = Cell::new(0.0);
    let failure = Cell::new(None);
    let start = Instant::now();
    let mut best: Option<(DVector<f64>, f64)> = None;
    let mut reasons = Vec::new();
    for theta0 in starts(options.kind, &options.physics) {
        let problem = Problem {
            points,
            sigma: sigma.clone(),
            options,
            theta: DVector::from_vec(theta0),
            evaluations: &evaluations,
            start,
            last_print: &last_print,
            failure: &failure,
        };
        let (solved, report) = LevenbergMarquardt::new()
            .with_patience(200)
            .minimize(problem);
        if report.termination.was_successful() && report.objective_function.is_finite() {
            let better = best
                .as_ref()
                .is_none_or(|(_, f)| report.objective_function < *f);
            if better {
                best = Some((solved.theta.clone(), report.objective_function));
            }
        } else {
            reasons.push(
                failure
                    .take()
                    .unwrap_or_else(|| format!("{:?}", report.termination)),
            );
        }
        if evaluations.get() >= options.max_evaluations {
            break;
        }
    }
    let Some((theta, _)) = best else {
        return Err(FitError(format!(
            "the fit did not converge: {}",
            reasons.first().map_or("no start succeeded", String::as_str)
        )));
    };
    finish(points, &sigma, options, theta, evaluations.get(), start)
}

fn finish(
    points: &[Measurement],
    sigma: &[f64],
    options: &FitOptions,
    theta: DVector<f64>,
    evaluations: usize,
    start: Instant,
) -> Result<Fit, FitError> {
    let (n, p) = (points.len(), theta.len());
    let failure = Cell::new(None);
    let problem = Problem {
        points,
        sigma: sigma.to_vec(),
        options,
        theta: theta.clone(),
        evaluations: &Cell::new(0),
        start,
        last_print: &Cell::new(f64::INFINITY),
        failure: &failure,
    };
    let theta_v: Vec<f64> = theta.iter().copied().collect();
    let clamped = problem.clamped(&theta_v);
    let physics = options.physics.with(options.kind, &clamped);
    let throws = problem
        .throws(&theta_v)
        .map_err(|e| FitError(format!("the model failed at the optimum: {e}")))?;
    let jacobian = problem
        .jacobian()
        .ok_or_else(|| FitError(failure.take().unwrap_or_default()))?;
    let j = jacobian.rows(0, n).into_owned();
    let chi2: f64 = throws
        .iter()
        .zip(points)
        .zip(sigma)
        .map(|((t, m), s)| ((t - m.throw_deg) / s).powi(2))
        .sum();
    let dof = n - p;
    let s2 = chi2 / dof as f64;
    let normal = j.transpose() * &j;
    let inverse = normal
        .clone()
        .cholesky()
        .map(|c| c.inverse())
        .filter(|inv| inv.iter().all(|x| x.is_finite()));
    let Some(inverse) = inverse else {
        return Err(FitError(
            "the data do not determine every parameter (singular normal matrix): fit fewer parameters (--fit mu) or add points at other speeds and cuts".to_owned(),
        ));
    };
    let covariance = inverse * s2;
    let t = t95(dof);
    let names = options.kind.parameter_names();
    let estimates: Vec<Estimate> = (0..p)
        .map(|k| {
            let se = covariance[(k, k)].max(0.0).sqrt();
            Estimate {
                name: names[k],
                value: clamped[k],
                stderr: se,
                ci95: t * se,
            }
        })
        .collect();
    let mut correlation = vec![0.0; p * p];
    for a in 0..p {
        for b in 0..p {
            let d = (covariance[(a, a)] * covariance[(b, b)]).sqrt();
            correlation[a * p + b] = if d > 0.0 { covariance[(a, b)] / d } else { 0.0 };
        }
    }
    let fitted: Vec<PointFit> = points
        .iter()
        .zip(&throws)
        .map(|(m, &t)| PointFit {
            measurement: m.clone(),
            model_deg: t,
            residual_deg: t - m.throw_deg,
            ceiling_deg: rigid_ceiling_deg(m, physics.restitution, physics.radius),
        })
        .collect();
    let rms = (fitted.iter().map(|f| f.residual_deg.powi(2)).sum::<f64>() / n as f64).sqrt();
    let max = fitted
        .iter()
        .enumerate()
        .map(|(i, f)| (f.residual_deg.abs(), i))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
    Ok(Fit {
        kind: options.kind,
        solver: options.solver,
        physics,
        estimates,
        correlation,
        points: fitted,
        rms_deg: rms,
        max_deg: max,
        reduced_chi: s2.sqrt(),
        evaluations,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// One fold of leave-one-series-out cross-validation.
#[derive(Clone, Debug)]
pub struct Fold {
    /// The series held out.
    pub series: String,
    /// The fit on the other series.
    pub fit: Fit,
    /// The held-out points with the fold's predictions.
    pub held_out: Vec<PointFit>,
    /// RMS of the held-out residuals (degrees).
    pub rms_deg: f64,
    /// Largest |held-out residual| (degrees).
    pub max_deg: f64,
}

/// Series in first-appearance order.
pub fn series(points: &[Measurement]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for m in points {
        if !names.contains(&m.series) {
            names.push(m.series.clone());
        }
    }
    names
}

/// Leave-one-series-out: for each series, fit the others and predict it.
pub fn cross_validate(points: &[Measurement], options: &FitOptions) -> Result<Vec<Fold>, FitError> {
    let names = series(points);
    if names.len() < 2 {
        return Err(FitError(
            "cross-validation needs at least two series (the `series` key, or different speeds)"
                .to_owned(),
        ));
    }
    names
        .into_iter()
        .map(|name| {
            let train: Vec<Measurement> = points
                .iter()
                .filter(|m| m.series != name)
                .cloned()
                .collect();
            let fit = fit(&train, options)
                .map_err(|e| FitError(format!("without series {name}: {e}")))?;
            let held_out = points
                .iter()
                .filter(|m| m.series == name)
                .map(|m| {
                    let t = model_throw(options.solver, &fit.physics, m)
                        .map_err(|e| FitError(format!("predicting series {name}: {e}")))?;
                    Ok(PointFit {
                        measurement: m.clone(),
                        model_deg: t,
                        residual_deg: t - m.throw_deg,
                        ceiling_deg: rigid_ceiling_deg(
                            m,
                            fit.physics.restitution,
                            fit.physics.radius,
                        ),
                    })
                })
                .collect::<Result<Vec<PointFit>, FitError>>()?;
            let rms = (held_out.iter().map(|p| p.residual_deg.powi(2)).sum::<f64>()
                / held_out.len() as f64)
                .sqrt();
            let max = held_out
                .iter()
                .map(|p| p.residual_deg.abs())
                .fold(0.0, f64::max);
            Ok(Fold {
                series: name,
                fit,
                held_out,
                rms_deg: rms,
                max_deg: max,
            })
        })
        .collect()
}

/// Measurements with the given spin labelled stun (for tests and examples).
pub fn stun(id: &str, series: &str, cut_deg: f64, speed_mps: f64, throw_deg: f64) -> Measurement {
    Measurement {
        id: id.to_owned(),
        series: series.to_owned(),
        cut_deg,
        speed_mps,
        spin: Spin::Ratio(0.0),
        throw_deg,
        uncertainty_deg: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_quantiles() {
        // Tabulated two-sided 95 % values.
        for (dof, t) in [
            (4, 2.776_445),
            (10, 2.228_139),
            (33, 2.034_515),
            (1000, 1.962_339),
        ] {
            assert!((t95(dof) - t).abs() < 1e-3, "{dof}: {}", t95(dof));
        }
    }
}
