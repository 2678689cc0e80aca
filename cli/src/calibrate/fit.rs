//! The weighted least-squares fit of the friction law (and e*) to measured throw and its
//! covariance.

use std::cell::Cell;
use std::time::Instant;

use levenberg_marquardt::LeastSquaresProblem;
use nalgebra::DVector;

use super::input::Measurement;
use super::problem::Problem;
use super::profile::Profiler;
use super::search::Search;

pub use super::cross_validate::{cross_validate, series, Fold};
pub use super::model::{model_throw, rigid_ceiling_deg, stun, FitKind, Physics, Solver};
pub use super::profile::profile_t;

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
    /// How the 95 % intervals are computed.
    pub intervals: Intervals,
    /// Steps of the compliant reference solver (`--fit mu-v-k`; `ReferenceConfig::steps`)
    /// for the fit's answer; the search from every start runs at 100 steps first
    /// (`COARSE_STEPS` in `calibrate/search.rs`).
    pub compliant_steps: usize,
}

/// How the 95 % confidence intervals are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Intervals {
    /// Profile likelihood (Bates & Watts 1988, §6.1; [`super::profile`]): follows the
    /// curved χ² valley and the parameter bounds. The default.
    Profile,
    /// Linearised: `θ̂ ± t·se` from the covariance `s² (JᵀJ)⁻¹` only (no extra fits).
    Linearised,
}

impl Intervals {
    /// The `--intervals` name.
    pub const fn name(self) -> &'static str {
        match self {
            Intervals::Profile => "profile",
            Intervals::Linearised => "linearised",
        }
    }
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
            intervals: Intervals::Profile,
            compliant_steps: cuesight_host::reference::ReferenceConfig::default().steps,
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
    /// Half-width of the linearised 95 % confidence interval (Student t × standard
    /// error).
    pub ci95: f64,
    /// Lower end of the 95 % confidence interval ([`FitOptions::intervals`]: profile
    /// likelihood by default, else `value − ci95`).
    pub lower: f64,
    /// Upper end of the 95 % confidence interval.
    pub upper: f64,
}

impl Estimate {
    /// Whether `x` lies in the 95 % interval.
    pub fn contains(&self, x: f64) -> bool {
        self.lower <= x && x <= self.upper
    }
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
    /// How their intervals were computed.
    pub intervals: Intervals,
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
    /// χ² = Σ ((model − measured)/u)² at the optimum (the profile statistic's origin,
    /// [`profile_t`]).
    pub chi2: f64,
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

/// Each point's uncertainty (degrees): its own, else `options.default_uncertainty_deg`.
pub(super) fn uncertainties(points: &[Measurement], options: &FitOptions) -> Vec<f64> {
    points
        .iter()
        .map(|m| m.uncertainty_deg.unwrap_or(options.default_uncertainty_deg))
        .collect()
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
    let sigma = uncertainties(points, options);
    let evaluations = Cell::new(0);
    let last_print = Cell::new(0.0);
    let start = Instant::now();
    let search = Search {
        points,
        sigma: &sigma,
        evaluations: &evaluations,
        start,
        last_print: &last_print,
    };
    let theta = search.best(options)?;
    finish(
        points,
        &sigma,
        options,
        theta,
        (evaluations.get(), &last_print),
        start,
    )
}

fn finish(
    points: &[Measurement],
    sigma: &[f64],
    options: &FitOptions,
    theta: DVector<f64>,
    (evaluations, last_print): (usize, &Cell<f64>),
    start: Instant,
) -> Result<Fit, FitError> {
    let (n, p) = (points.len(), theta.len());
    let failure = Cell::new(None);
    let problem = Problem {
        points,
        sigma: sigma.to_vec(),
        options,
        theta: theta.clone(),
        fixed: None,
        stage: "fitting",
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
    let profiler = Profiler {
        points,
        sigma,
        options,
        theta: clamped.clone(),
        chi2,
        s2,
        t,
        evaluations: Cell::new(0),
        total: Cell::new(0),
        start,
        last_print: Cell::new(last_print.get()),
        failure: Cell::new(None),
    };
    let estimates: Vec<Estimate> = (0..p)
        .map(|k| {
            let se = covariance[(k, k)].max(0.0).sqrt();
            let (lower, upper) = match options.intervals {
                Intervals::Linearised => (clamped[k] - t * se, clamped[k] + t * se),
                Intervals::Profile => (profiler.end(k, -1.0, se)?, profiler.end(k, 1.0, se)?),
            };
            Ok(Estimate {
                name: names[k],
                value: clamped[k],
                stderr: se,
                ci95: t * se,
                lower,
                upper,
            })
        })
        .collect::<Result<Vec<Estimate>, FitError>>()?;
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
        intervals: options.intervals,
        correlation,
        points: fitted,
        rms_deg: rms,
        max_deg: max,
        reduced_chi: s2.sqrt(),
        chi2,
        evaluations: evaluations + profiler.total.get(),
        seconds: start.elapsed().as_secs_f64(),
    })
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
