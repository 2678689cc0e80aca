//! The weighted least-squares problem that Levenberg–Marquardt minimises: residuals
//! `(model − measured)/u` plus one bound penalty per parameter, and their
//! finite-difference Jacobian. One parameter may be held fixed (profile likelihood,
//! [`super::profile`]).

use std::cell::Cell;
use std::io::Write;
use std::time::Instant;

use levenberg_marquardt::LeastSquaresProblem;
use nalgebra::{DMatrix, DVector, Dyn, Owned};

use super::fit::{FitKind, FitOptions};
use super::input::Measurement;
use super::model::model_throw_with;

/// Typical size of each parameter (finite-difference steps and penalty scale).
const TYPICAL: [f64; 4] = [0.01, 0.1, 1.0, 0.1];
/// Bounds the core accepts: a ∈ [1e-6, 1], b ∈ [0, 1], c ∈ [0, 100], e* ∈ [0, 1].
const LOWER: [f64; 4] = [1e-6, 0.0, 0.0, 0.0];
const UPPER: [f64; 4] = [1.0, 1.0, 100.0, 1.0];
/// The tangential compliance κ = k_t/k_n (fourth parameter of `mu-v-k`): typical size
/// and range (0.05: η = 0.42; 100: η = 18.7, within 0.01° of the rigid contact).
const KAPPA: (f64, f64, f64) = (0.1, 0.05, 100.0);

/// Typical size of parameter `k` of `kind`.
pub(super) fn typical(kind: FitKind, k: usize) -> f64 {
    if kind == FitKind::MuVK && k == 3 {
        KAPPA.0
    } else {
        TYPICAL[k]
    }
}

/// Lower bound of parameter `k` of `kind`.
pub(super) fn lower(kind: FitKind, k: usize) -> f64 {
    if kind == FitKind::MuVK && k == 3 {
        KAPPA.1
    } else {
        LOWER[k]
    }
}

/// Upper bound of parameter `k` of `kind`.
pub(super) fn upper(kind: FitKind, k: usize) -> f64 {
    if kind == FitKind::MuVK && k == 3 {
        KAPPA.2
    } else {
        UPPER[k]
    }
}
/// Weight of a bound violation of one `TYPICAL` unit, in weighted-residual units.
const PENALTY: f64 = 1e3;

/// The fit's least-squares problem. `theta` holds the free parameters: all of
/// `options.kind`'s, or all but `fixed.0`, which is held at `fixed.1`.
pub(super) struct Problem<'a> {
    pub(super) points: &'a [Measurement],
    pub(super) sigma: Vec<f64>,
    pub(super) options: &'a FitOptions,
    pub(super) theta: DVector<f64>,
    pub(super) fixed: Option<(usize, f64)>,
    /// What the progress line says is running: `fitting` or `profiling <name> at <x>`.
    pub(super) stage: &'a str,
    pub(super) evaluations: &'a Cell<usize>,
    pub(super) start: Instant,
    pub(super) last_print: &'a Cell<f64>,
    pub(super) failure: &'a Cell<Option<String>>,
}

impl Problem<'_> {
    /// The full parameter vector for free parameters `free`.
    pub(super) fn full(&self, free: &[f64]) -> Vec<f64> {
        let mut t = free.to_vec();
        if let Some((k, x)) = self.fixed {
            t.insert(k, x);
        }
        t
    }

    /// Index in the full vector of free parameter `f`.
    fn full_index(&self, f: usize) -> usize {
        match self.fixed {
            Some((k, _)) if f >= k => f + 1,
            _ => f,
        }
    }

    /// The full vector clamped to the core's bounds.
    pub(super) fn clamped(&self, theta: &[f64]) -> Vec<f64> {
        let mut t: Vec<f64> = theta
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let kind = self.options.kind;
                x.clamp(lower(kind, k), upper(kind, k))
            })
            .collect();
        // a + b ≤ 1 (core's FrictionLaw).
        if t.len() > 1 && t[0] + t[1] > 1.0 {
            t[1] = 1.0 - t[0];
        }
        t
    }

    /// Model throws at the full vector `theta` (clamped to the bounds), or the first
    /// error.
    pub(super) fn throws(&self, theta: &[f64]) -> Result<Vec<f64>, String> {
        let physics = self
            .options
            .physics
            .with(self.options.kind, &self.clamped(theta));
        let out = self
            .points
            .iter()
            .map(|m| {
                model_throw_with(
                    self.options.solver,
                    &physics,
                    m,
                    self.options.compliant_steps,
                )
            })
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
                "calibrate: {} {} by {}: {n} evaluations, {elapsed:.1} s, rms {rms:.3} deg",
                self.stage,
                self.options.kind.name(),
                self.options.solver.name()
            );
        }
        out
    }

    /// Weighted χ² (no penalties) at the full vector `theta` (clamped).
    pub(super) fn chi2(&self, theta: &[f64]) -> Result<f64, String> {
        Ok(self
            .throws(theta)?
            .iter()
            .zip(self.points)
            .zip(&self.sigma)
            .map(|((t, m), s)| ((t - m.throw_deg) / s).powi(2))
            .sum())
    }

    fn penalties(&self, theta: &[f64]) -> Vec<f64> {
        theta
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let kind = self.options.kind;
                let below = (lower(kind, k) - x).max(0.0);
                let above = (x - upper(kind, k)).max(0.0);
                let sum = if k == 1 {
                    (theta[0] + x - 1.0).max(0.0)
                } else {
                    0.0
                };
                PENALTY * (below + above + sum) / typical(self.options.kind, k)
            })
            .collect()
    }

    pub(super) fn record(&self, error: String) {
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
        let theta = self.full(self.theta.as_slice());
        let throws = match self.throws(&theta) {
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
        r.extend(self.penalties(&theta));
        Some(DVector::from_vec(r))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let n = self.points.len();
        let free = self.theta.len();
        let theta = self.full(self.theta.as_slice());
        let p = theta.len();
        let mut j = DMatrix::zeros(n + p, free);
        for f in 0..free {
            let k = self.full_index(f);
            let h = 1e-4 * theta[k].abs().max(typical(self.options.kind, k));
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
                j[(i, f)] = (tu[i] - td[i]) / (cu - cd) / self.sigma[i];
            }
            let (pu, pd) = (self.penalties(&up), self.penalties(&down));
            for (row, (a, b)) in pu.iter().zip(&pd).enumerate() {
                j[(n + row, f)] = (a - b) / (2.0 * h);
            }
        }
        Some(j)
    }
}
