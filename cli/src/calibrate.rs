//! `cuesight calibrate`: fit the ball–ball friction law `μ(v) = a + b·exp(−c·v)` (TP
//! A.14; and e* if asked) to measured throw by weighted least squares.
//!
//! * **Input** ([`input`]): JSON (the shared calibration set's schema, or a bare array of
//!   its points) or CSV with `cut_deg`, `speed_mps`, `spin` (stun / follow / draw, or a
//!   spin ratio; or `wx_rad_s`, `wy_rad_s`, `wz_rad_s`), `throw_deg` and an optional
//!   `uncertainty_deg`; at most 1 MiB, every value range-checked, errors naming the line
//!   (CSV), the line and column (JSON) or the cause.
//! * **Model** ([`fit::model_throw`]): the throw of each point through the core's
//!   `collide` — `KimGrip` by default, evaluated in f64 (`collide_f64`) so that the
//!   finite-difference Jacobian is not f32 rounding — or the core's `Exact` tier, or the
//!   f64 reference solver (`--model`). `KimGrip` is within 0.037° of the reference in
//!   throw with Marlow's μ(v) on the 3,000-scene grid (docs/physics.md §6); on the shared
//!   set the fits by `kim-grip` and by `reference` are compared in docs/calibration.md.
//! * **Fit** ([`fit::fit`]): residuals `(model − measured)/u`, `u` the point's
//!   uncertainty or `--default-uncertainty` (1°), minimised by Levenberg–Marquardt from
//!   three starting points, the lowest kept. The optimiser is the `levenberg-marquardt`
//!   crate (rust-cv; a port of MINPACK's `lmder`, the routine behind SciPy's
//!   `least_squares(method="lm")` and `curve_fit`): a trust-region LM with column
//!   scaling and MINPACK's termination tests, on nalgebra, maintained, with no C or
//!   Fortran to build. `argmin` was the alternative: a general framework whose
//!   least-squares solver is Gauss–Newton with a line search, without MINPACK's
//!   scaling and trust region, which this problem (parameters from 0.01 to 1, a decay
//!   rate weakly determined) needs. The core's parameter bounds (`a ∈ [1e-6, 1]`,
//!   `b ∈ [0, 1]`, `a + b ≤ 1`, `c ∈ [0, 100]`, `e* ∈ [0, 1]`) are kept by evaluating
//!   the model at the clamped point and adding a penalty residual per bound, zero
//!   inside the bounds.
//! * **Uncertainties**: covariance `s² (JᵀJ)⁻¹` from the weighted Jacobian at the
//!   optimum (central differences), `s² = χ²/(n − p)` — the residual scatter sets the
//!   scale, as SciPy's `curve_fit` does by default, so only the ratios of the given
//!   uncertainties matter. Printed: the standard error and the 95 % half-width
//!   (Student t with `n − p` degrees of freedom × standard error).
//! * **Cross-validation** (`--cross-validate`): leave one series out (the `series`
//!   key, the shared file's `speed_label`, or the speed), fit the rest, predict it.

mod cross_validate;
pub mod fit;
pub mod input;
pub mod model;
pub mod params_file;
mod problem;
pub mod profile;
pub mod report;
mod search;

use std::path::PathBuf;
use std::process::ExitCode;

pub use fit::{
    cross_validate, fit, Fit, FitError, FitKind, FitOptions, Fold, Intervals, Physics, Solver,
};
pub use input::{read_file, InputError, Measurement, Spin};
pub use params_file::ParamsFile;

/// Flags of `cuesight calibrate`.
#[derive(Clone, Debug, clap::Args)]
pub struct Flags {
    /// Measured throw: JSON (the shared calibration set's schema) or CSV with columns
    /// cut_deg, speed_mps, spin, throw_deg[, uncertainty_deg]; see docs/calibration.md.
    #[arg(long, value_name = "FILE")]
    pub throw: PathBuf,
    /// Parameters to fit: mu (constant μ), mu-v (μ(v) = mu + mu_b·exp(−mu_c·v)), mu-v-e
    /// (μ(v) and e*), mu-v-k (μ(v) and the contact's tangential compliance
    /// κ = k_t/k_n; always by the reference solver).
    #[arg(long, value_enum, default_value = "mu-v")]
    pub fit: FitKind,
    /// Model of the throw: kim-grip (the core's tier, f64 evaluation), exact, or
    /// reference (the f64 first-principles solver; slower).
    #[arg(long, value_enum, default_value = "kim-grip")]
    pub model: Solver,
    /// Energetic restitution e* when not fitted (the start value with mu-v-e).
    #[arg(long, default_value_t = 0.95)]
    pub restitution: f64,
    /// Object-ball/table friction μ_s (not fitted).
    #[arg(long, default_value_t = 0.3)]
    pub mu_s: f64,
    /// Uncertainty (degrees) of points that give none.
    #[arg(long, value_name = "DEG", default_value_t = 1.0)]
    pub default_uncertainty: f64,
    /// Also fit each series left out in turn and report how well it is predicted.
    #[arg(long)]
    pub cross_validate: bool,
    /// 95 % intervals: profile (profile likelihood, follows the curved χ² valley and
    /// the bounds; one refit per trial value) or linearised (θ̂ ± t·se).
    #[arg(long, value_enum, default_value = "profile")]
    pub intervals: Intervals,
    /// Give up after this many model evaluations (one per point and parameter set).
    #[arg(long, value_name = "N", default_value_t = 100_000)]
    pub max_evaluations: usize,
    /// Print one JSON object (parameters under collide's names, so it is a --params
    /// file) instead of the report.
    #[arg(long)]
    pub json: bool,
}

/// Why `calibrate` failed: the message and the exit code.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CalibrateError {
    /// One line.
    pub message: String,
    /// Exit code: 1 (bad data, no convergence) or 2 (usage: unreadable file).
    pub code: u8,
}

impl std::fmt::Display for CalibrateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for CalibrateError {}

fn invalid(message: impl Into<String>) -> CalibrateError {
    CalibrateError {
        message: message.into(),
        code: crate::cli::EXIT_INVALID,
    }
}

/// Options for the flags (checked).
pub fn options(flags: &Flags) -> Result<FitOptions, CalibrateError> {
    let mut options = FitOptions::new(flags.fit);
    options.solver = flags.model;
    options.physics.restitution = flags.restitution;
    options.physics.mu_s = flags.mu_s;
    options.default_uncertainty_deg = flags.default_uncertainty;
    options.max_evaluations = flags.max_evaluations;
    options.progress = true;
    options.intervals = flags.intervals;
    if flags.fit == FitKind::MuVK {
        // The compliant contact exists in the reference solver only.
        options.solver = Solver::Reference;
    }
    if !(flags.restitution.is_finite() && (0.0..=1.0).contains(&flags.restitution)) {
        return Err(invalid(format!(
            "restitution = {} is outside [0, 1]",
            flags.restitution
        )));
    }
    if !(flags.mu_s.is_finite() && (0.0..=1.0).contains(&flags.mu_s)) {
        return Err(invalid(format!("mu_s = {} is outside [0, 1]", flags.mu_s)));
    }
    if !(flags.default_uncertainty.is_finite() && flags.default_uncertainty > 0.0) {
        return Err(invalid(format!(
            "default uncertainty = {} must be > 0 degrees",
            flags.default_uncertainty
        )));
    }
    Ok(options)
}

/// Read, fit (and cross-validate) and render the output.
pub fn run(flags: &Flags) -> Result<String, CalibrateError> {
    // The flags are checked before the file is read.
    options(flags)?;
    let points = read_file(&flags.throw).map_err(|e| invalid(e.to_string()))?;
    run_points(&points, flags, &flags.throw.display().to_string())
}

/// [`run`] on points already read (`flags.throw` is not read): fit (and
/// cross-validate) and render the output; `source` names the points in messages and
/// in the report (`run` gives the file's path).
pub fn run_points(
    points: &[Measurement],
    flags: &Flags,
    source: &str,
) -> Result<String, CalibrateError> {
    let options = options(flags)?;
    if points.is_empty() {
        return Err(invalid(format!("{source}: no points")));
    }
    let fitted = fit(points, &options).map_err(|e| invalid(e.to_string()))?;
    let folds = if flags.cross_validate {
        Some(cross_validate(points, &options).map_err(|e| invalid(e.to_string()))?)
    } else {
        None
    };
    Ok(if flags.json {
        report::json(&fitted, folds.as_deref()).to_string()
    } else {
        let mut text = report::text(&fitted, source);
        if let Some(folds) = &folds {
            text.push('\n');
            text.push_str(&report::cross_validation_text(folds));
        }
        text
    })
}

/// Run `cuesight calibrate`: the report on stdout, errors as one line on stderr. Writes
/// never panic ([`crate::cli::write_output`]): a closed stdout (broken pipe) drops the
/// output and exits 0, any other write error (a full disk) is reported and exits 1.
pub fn main(flags: &Flags) -> ExitCode {
    match run(flags) {
        Ok(text) => crate::cli::print_line(text),
        Err(error) => {
            crate::cli::error_line(&error);
            ExitCode::from(error.code)
        }
    }
}
