//! Profile-likelihood confidence intervals of the fitted parameters.
//!
//! The linearised interval `θ̂_k ± t·se` assumes the model is linear in the parameters
//! over the interval and ignores the bounds. μ(v)'s `mu` is neither: it is
//! 0.97-correlated with the weakly determined decay rate `mu_c`, along a curved valley
//! of χ², and sits about one standard error above its bound `mu ≥ 1e-6`. The profile
//! interval follows the valley and the bound instead.
//!
//! For parameter `k` held at `x`, the profile `S_k(x) = min over the others of χ²`
//! (the same weighted least squares, by Levenberg–Marquardt from the neighbouring
//! profile point's optimum). With the scale estimated from the residuals,
//! `s² = S(θ̂)/(n − p)`, the profile t statistic is
//!
//! ```text
//! τ_k(x) = sign(x − θ̂_k) · √(S_k(x) − S(θ̂)) / s
//! ```
//!
//! and the 95 % interval is `{x : |τ_k(x)| ≤ t_{n−p, 0.975}}` — D. M. Bates & D. G.
//! Watts, *Nonlinear Regression Analysis and Its Applications* (Wiley 1988), §6.1.1,
//! eqs. (6.3)–(6.4), the likelihood-ratio interval with the F(1, n−p) quantile `t²`
//! (Venzon & Moolgavkar, Appl. Statist. 37 (1988) 87, for the search). For a model
//! linear in its parameters it is exactly `θ̂_k ± t·se`. Where `S_k` stays below the
//! threshold up to a bound of the parameter, the interval ends at the bound.
//!
//! Search, each side: the first trial is the linearised end `θ̂_k ± t·se`; the step
//! grows by 2 until `|τ|` passes `t` (or the bound is reached); then regula falsi
//! (Illinois variant) on `|τ(x)| − t`, which is nearly linear in `x`, to
//! `10⁻³ se`.

use std::cell::Cell;
use std::time::Instant;

use levenberg_marquardt::{LevenbergMarquardt, TerminationReason};
use nalgebra::DVector;

use super::fit::{t95, uncertainties, Fit, FitError, FitOptions};
use super::input::Measurement;
use super::problem::{lower, typical, upper, Problem};

/// The profile t statistic `τ_k(x)` of parameter `k` of `fitted` (eq. 6.3 above), the
/// fit of `points` with `options`: `x` lies in the parameter's 95 % profile interval
/// exactly when `|τ_k(x)| ≤ t_{n−p, 0.975}` ([`t95`]), which one profile fit at `x`
/// decides — where [`Intervals::Profile`](super::fit::Intervals::Profile) searches for
/// both ends (tens of profile fits). For coverage studies: whether a known truth lies
/// in the interval, without computing the interval.
///
/// The profile fit starts from the optimum's other parameters (the interval search
/// starts from its neighbouring profile point), so the two can differ where the χ²
/// valley has more than one minimum over the others; a test compares them
/// (`cli/tests/calibrate/recovery.rs`).
pub fn profile_t(
    points: &[Measurement],
    options: &FitOptions,
    fitted: &Fit,
    k: usize,
    x: f64,
) -> Result<f64, FitError> {
    let p = options.kind.len();
    if fitted.kind != options.kind || fitted.points.len() != points.len() || k >= p {
        return Err(FitError(format!(
            "profile_t: parameter {k} of a {} fit of {} points, asked of a {} fit with {} points",
            options.kind.name(),
            points.len(),
            fitted.kind.name(),
            fitted.points.len()
        )));
    }
    let sigma = uncertainties(points, options);
    let dof = points.len() - p;
    let profiler = Profiler {
        points,
        sigma: &sigma,
        options,
        theta: fitted.estimates.iter().map(|e| e.value).collect(),
        chi2: fitted.chi2,
        s2: fitted.chi2 / dof as f64,
        t: t95(dof),
        evaluations: Cell::new(0),
        total: Cell::new(0),
        start: Instant::now(),
        last_print: Cell::new(f64::INFINITY),
        failure: Cell::new(None),
    };
    let centre = profiler.theta[k];
    let mut others = profiler.theta.clone();
    others.remove(k);
    let (s, _) = profiler.profile(k, x, (centre, &others))?;
    let tau = ((s - profiler.chi2).max(0.0) / profiler.s2).sqrt();
    Ok(if x < centre { -tau } else { tau })
}

/// Steps of [`Profiler::profile`]'s walk along the χ² valley to a point it found
/// outside the interval.
const CONTINUATION: usize = 4;

/// What a profile search needs of the fit.
pub(super) struct Profiler<'a> {
    pub(super) points: &'a [Measurement],
    pub(super) sigma: &'a [f64],
    pub(super) options: &'a FitOptions,
    /// The optimum (full vector, inside the bounds).
    pub(super) theta: Vec<f64>,
    /// χ² at the optimum.
    pub(super) chi2: f64,
    /// `s² = χ²/(n − p)`.
    pub(super) s2: f64,
    /// Student t quantile (two-sided 95 %, `n − p` degrees of freedom).
    pub(super) t: f64,
    /// Model evaluations of the current profile fit (each has the fit's budget,
    /// `max_evaluations`).
    pub(super) evaluations: Cell<usize>,
    /// Model evaluations of all profile fits.
    pub(super) total: Cell<usize>,
    pub(super) start: Instant,
    /// No progress lines from the profile fits (the fit printed its own).
    pub(super) last_print: Cell<f64>,
    /// The first failure of a profile fit.
    pub(super) failure: Cell<Option<String>>,
}

impl Profiler<'_> {
    fn problem<'s>(&'s self, k: usize, x: f64, warm: Vec<f64>, stage: &'s str) -> Problem<'s> {
        Problem {
            points: self.points,
            sigma: self.sigma.to_vec(),
            options: self.options,
            theta: DVector::from_vec(warm),
            fixed: Some((k, x)),
            stage,
            evaluations: &self.evaluations,
            start: self.start,
            last_print: &self.last_print,
            failure: &self.failure,
        }
    }

    /// `S_k(x)` and the other parameters at its minimum, from `warm`: a profile point
    /// `(x_w, others)` already found (the optimum, or the search's last inside point).
    ///
    /// A profile fit's χ² bounds `S_k(x)` from above, so a verdict inside the interval
    /// stands. A fit may stop above the valley's floor, though: on Levenberg–Marquardt's
    /// evaluation limit (`LostPatience`: it crawls along a kink of the model, where a
    /// point changes between gripping and sliding; then it is restarted once from the
    /// optimum's other parameters), or from a start far up the valley's side, which
    /// puts `x` outside when it is inside (seed 52 of the `mu-v-e` recovery trials: the
    /// search ended `mu_c`'s interval at 0.425 where the profile at 0.44 is 1.49
    /// t-units from the optimum, below t = 2.04). So an outside verdict is checked by
    /// walking from `x_w` to `x` in [`CONTINUATION`] steps, each fit started from the
    /// last one's optimum; the lowest χ² found is kept, an upper bound on `S_k(x)`
    /// within the last accepted step of it.
    fn profile(
        &self,
        k: usize,
        x: f64,
        (warm_x, warm): (f64, &[f64]),
    ) -> Result<(f64, Vec<f64>), FitError> {
        let fail = |e: String| FitError(format!("profile of {}: {e}", self.name(k)));
        if warm.is_empty() {
            let problem = self.problem(k, x, Vec::new(), "");
            self.total.set(self.total.get() + self.points.len());
            return Ok((problem.chi2(&[x]).map_err(fail)?, Vec::new()));
        }
        let (mut chi2, mut others, patience_lost) = self.minimize(k, x, warm).map_err(fail)?;
        if patience_lost {
            let mut optimum = self.theta.clone();
            optimum.remove(k);
            let (chi2_b, others_b, _) = self.minimize(k, x, &optimum).map_err(fail)?;
            if chi2_b < chi2 {
                (chi2, others) = (chi2_b, others_b);
            }
        }
        if self.excess(chi2) > 0.0 {
            let mut start = warm.to_vec();
            for step in 1..=CONTINUATION {
                let at = warm_x + (x - warm_x) * step as f64 / CONTINUATION as f64;
                let (chi2_at, others_at, _) = self.minimize(k, at, &start).map_err(fail)?;
                start = others_at;
                if step == CONTINUATION && chi2_at < chi2 {
                    (chi2, others) = (chi2_at, start.clone());
                }
            }
        }
        Ok((chi2, others))
    }

    /// One Levenberg–Marquardt run of the profile at `x` from `warm`: χ² at its best
    /// point, that point, and whether it stopped on the evaluation limit.
    fn minimize(&self, k: usize, x: f64, warm: &[f64]) -> Result<(f64, Vec<f64>, bool), String> {
        let stage = format!("profiling {} at {x:.5} in", self.name(k));
        let problem = self.problem(k, x, warm.to_vec(), &stage);
        let before = self.evaluations.replace(0);
        // LM's limit is `patience × (free + 1)` residual evaluations, each with up to a
        // Jacobian (`2 free` more): stop on it before the budget of model evaluations.
        let free = warm.len();
        let per_call = self.points.len() * (1 + 2 * free) * (free + 1);
        let patience = (self.options.max_evaluations / per_call).clamp(1, 200);
        let (solved, report) = LevenbergMarquardt::new()
            .with_patience(patience)
            .minimize(problem);
        self.total.set(self.total.get() + self.evaluations.get());
        self.evaluations.set(before);
        let patience_lost = report.termination == TerminationReason::LostPatience;
        let usable = report.termination.was_successful() || patience_lost;
        if !(usable && report.objective_function.is_finite()) {
            return Err(self
                .failure
                .take()
                .unwrap_or_else(|| format!("{:?}", report.termination)));
        }
        let others: Vec<f64> = solved.theta.iter().copied().collect();
        let full = solved.clamped(&solved.full(&others));
        Ok((solved.chi2(&full)?, others, patience_lost))
    }

    fn name(&self, k: usize) -> &'static str {
        self.options.kind.parameter_names()[k]
    }

    /// `|τ_k(x)| − t` for a profile value `S`.
    fn excess(&self, s: f64) -> f64 {
        ((s - self.chi2).max(0.0) / self.s2).sqrt() - self.t
    }

    /// One end of parameter `k`'s 95 % profile interval: `direction` −1 (lower) or +1
    /// (upper); `se` the linearised standard error (sets the first step).
    pub(super) fn end(&self, k: usize, direction: f64, se: f64) -> Result<f64, FitError> {
        let kind = self.options.kind;
        let (low, high) = (lower(kind, k), upper(kind, k));
        let bound = if direction < 0.0 { low } else { high };
        let centre = self.theta[k];
        if centre == bound {
            return Ok(bound);
        }
        let mut others: Vec<f64> = self.theta.clone();
        others.remove(k);
        let step0 = if se.is_finite() && se > 0.0 {
            self.t * se
        } else {
            0.1 * typical(kind, k)
        };
        // Bracket: `inside` has |τ| ≤ t, `outside` |τ| > t.
        let mut inside = (centre, -self.t, others.clone());
        let mut step = step0;
        let mut outside = None;
        for _ in 0..40 {
            let x = (centre + direction * step).clamp(low, high);
            let (s, o) = self.profile(k, x, (inside.0, &inside.2))?;
            let g = self.excess(s);
            if g > 0.0 {
                outside = Some((x, g));
                break;
            }
            inside = (x, g, o);
            if x == bound {
                return Ok(bound);
            }
            step *= 2.0;
        }
        let Some(mut outside) = outside else {
            return Ok(inside.0);
        };
        // Illinois regula falsi on g(x) = |τ(x)| − t.
        let tolerance = 1e-3 * step0;
        let mut last_side = 0;
        for _ in 0..60 {
            if (outside.0 - inside.0).abs() <= tolerance {
                break;
            }
            let (xi, gi, xo, go) = (inside.0, inside.1, outside.0, outside.1);
            let mut x = xi - gi * (xo - xi) / (go - gi);
            if !(x.is_finite() && (x - xi) * (x - xo) < 0.0) {
                x = 0.5 * (xi + xo);
            }
            let (s, o) = self.profile(k, x, (inside.0, &inside.2))?;
            let g = self.excess(s);
            if g > 0.0 {
                outside = (x, g);
                if last_side == 1 {
                    inside.1 *= 0.5;
                }
                last_side = 1;
            } else {
                inside = (x, g, o);
                if last_side == -1 {
                    outside.1 *= 0.5;
                }
                last_side = -1;
            }
        }
        // The crossing lies in the bracket; report the interpolated point.
        let (xi, gi, xo, go) = (inside.0, inside.1, outside.0, outside.1);
        let x = xi - gi * (xo - xi) / (go - gi);
        Ok(if x.is_finite() && (x - xi) * (x - xo) <= 0.0 {
            x
        } else {
            0.5 * (xi + xo)
        })
    }
}
