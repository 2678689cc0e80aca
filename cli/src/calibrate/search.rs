//! The search for the least-squares optimum: Levenberg–Marquardt from several starting
//! points, the lowest χ² kept.
//!
//! For the compliant contact (`--fit mu-v-k`: every evaluation a reference solve) the
//! starts are searched with the solver at [`COARSE_STEPS`] steps, where a throw costs a
//! tenth of one at the fit's own steps (`FitOptions::compliant_steps`, 1,000 by default)
//! and is within 5e-4° of the converged one for κ ≤ 0.3 and 2e-3° above (docs/
//! calibration.md §7). The starts' optima differ by far more than that in χ² (on the
//! shared set 3.33, 3.50 and 5.01), so the coarse search picks the valley; then every
//! distinct coarse optimum whose χ² is within [`REFINE_WITHIN`] of the lowest is refitted
//! at the fit's own steps from where it stopped, and the lowest refined one is the answer.

use std::cell::Cell;
use std::time::Instant;

use levenberg_marquardt::LevenbergMarquardt;
use nalgebra::DVector;

use super::fit::{FitError, FitKind, FitOptions};
use super::input::Measurement;
use super::model::Physics;
use super::problem::{typical, Problem};

/// Steps of the compliant reference solver while searching from every start.
pub const COARSE_STEPS: usize = 100;
/// Coarse optima within this fraction of the lowest χ² are refined.
const REFINE_WITHIN: f64 = 0.01;

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
        // The throw oscillates with η = √(3.5 κ) (β = −cos(π η) for a stuck contact):
        // starts in the first two lobes, near Mindlin's elastic value and rigid-like.
        FitKind::MuVK => [0.1, 0.15, 1.0, 30.0]
            .iter()
            .map(|&kappa| vec![0.02, 0.1, 0.44, kappa])
            .collect(),
    }
}

/// What every Levenberg–Marquardt run of one fit shares.
pub(super) struct Search<'a> {
    pub(super) points: &'a [Measurement],
    pub(super) sigma: &'a [f64],
    pub(super) evaluations: &'a Cell<usize>,
    pub(super) start: Instant,
    pub(super) last_print: &'a Cell<f64>,
}

/// Converged optima (parameters, objective) and the failed runs' reasons.
type Found = (Vec<(DVector<f64>, f64)>, Vec<String>);

impl Search<'_> {
    /// Levenberg–Marquardt from each of `starts` with `options`.
    fn run(&self, options: &FitOptions, starts: Vec<Vec<f64>>) -> Found {
        let failure = Cell::new(None);
        let (mut found, mut reasons) = (Vec::new(), Vec::new());
        for theta0 in starts {
            let problem = Problem {
                points: self.points,
                sigma: self.sigma.to_vec(),
                options,
                theta: DVector::from_vec(theta0),
                fixed: None,
                stage: "fitting",
                evaluations: self.evaluations,
                start: self.start,
                last_print: self.last_print,
                failure: &failure,
            };
            let (solved, report) = LevenbergMarquardt::new()
                .with_patience(200)
                .minimize(problem);
            if report.termination.was_successful() && report.objective_function.is_finite() {
                found.push((solved.theta.clone(), report.objective_function));
            } else {
                reasons.push(
                    failure
                        .take()
                        .unwrap_or_else(|| format!("{:?}", report.termination)),
                );
            }
            if self.evaluations.get() >= options.max_evaluations {
                break;
            }
        }
        (found, reasons)
    }

    /// The optimum over all starts (coarse search, then refinement, for the compliant
    /// contact: module docs).
    pub(super) fn best(&self, options: &FitOptions) -> Result<DVector<f64>, FitError> {
        let starts = starts(options.kind, &options.physics);
        let coarse = options.kind == FitKind::MuVK && options.compliant_steps > COARSE_STEPS;
        let (found, reasons) = if coarse {
            let coarse_options = FitOptions {
                compliant_steps: COARSE_STEPS,
                ..*options
            };
            let (mut found, mut reasons) = self.run(&coarse_options, starts);
            found.sort_by(|a, b| a.1.total_cmp(&b.1));
            let lowest = found.first().map_or(f64::INFINITY, |f| f.1);
            let mut refine: Vec<Vec<f64>> = Vec::new();
            for (theta, objective) in &found {
                // The same optimum reached from two starts is refined once.
                let seen = refine.iter().any(|r| {
                    r.iter()
                        .zip(theta.iter())
                        .enumerate()
                        .all(|(k, (a, b))| (a - b).abs() <= 1e-2 * typical(options.kind, k))
                });
                if *objective <= lowest * (1.0 + REFINE_WITHIN) && !seen {
                    refine.push(theta.iter().copied().collect());
                }
            }
            let (refined, more) = self.run(options, refine);
            reasons.extend(more);
            (refined, reasons)
        } else {
            self.run(options, starts)
        };
        found
            .into_iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(theta, _)| theta)
            .ok_or_else(|| {
                FitError(format!(
                    "the fit did not converge: {}",
                    reasons.first().map_or("no start succeeded", String::as_str)
                ))
            })
    }
}
