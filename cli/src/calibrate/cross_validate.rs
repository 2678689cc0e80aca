//! Leave-one-series-out cross-validation: each series held out in turn, the others
//! fitted, the held-out series predicted.

use super::fit::{fit, Fit, FitError, FitOptions, PointFit};
use super::input::Measurement;
use super::model::{model_throw, rigid_ceiling_deg};

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
            // The folds' intervals are not reported: linearised ones cost no extra fits.
            let options = FitOptions {
                intervals: super::fit::Intervals::Linearised,
                ..*options
            };
            let fit = fit(&train, &options)
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
