//! What `cuesight calibrate` prints: a human report or one JSON object.

use std::fmt::Write as _;

use serde_json::{json, Map, Value};

use super::fit::{Estimate, Fit, Fold};

fn parameter_line(out: &mut String, name: &str, value: f64, estimate: Option<&Estimate>) {
    let unit = match name {
        "mu_c" => " s/m",
        _ => "",
    };
    let _ = match estimate {
        Some(e) => writeln!(
            out,
            "  {name:<12} = {value:>10.5}{unit}  95 % interval [{:.5}, {:.5}]  (standard error {:.5}, linearised ± {:.5})",
            e.lower, e.upper, e.stderr, e.ci95
        ),
        None => writeln!(out, "  {name:<12} = {value:>10.5}{unit} (fixed)"),
    };
}

/// The human report: parameters with uncertainties, fit quality, per-point residuals.
pub fn text(fit: &Fit, source: &str) -> String {
    let mut out = String::new();
    let n = fit.points.len();
    let series = super::fit::series(
        &fit.points
            .iter()
            .map(|p| p.measurement.clone())
            .collect::<Vec<_>>(),
    );
    let _ = writeln!(
        out,
        "calibrate: {n} points from {source} ({} series: {}), fit {}, throw by {}",
        series.len(),
        series.join(", "),
        fit.kind.name(),
        fit.solver.name()
    );
    let fitted = |name: &str| fit.estimates.iter().find(|e| e.name == name);
    let ph = fit.physics;
    let compliance = ph.tangential_stiffness.map(|k| ("tangential_stiffness", k));
    for (name, value) in [
        ("mu", ph.mu),
        ("mu_b", ph.mu_b),
        ("mu_c", ph.mu_c),
        ("restitution", ph.restitution),
        ("mu_s", ph.mu_s),
    ]
    .into_iter()
    .chain(compliance)
    {
        parameter_line(&mut out, name, value, fitted(name));
    }
    let (max, at) = fit.max_deg;
    let _ = writeln!(
        out,
        "rms {:.3} deg, max {:.3} deg ({}), {n} points, {} parameters, weighted rms {:.3}, {} model evaluations, {:.2} s",
        fit.rms_deg,
        max,
        fit.points[at].measurement.id,
        fit.estimates.len(),
        fit.reduced_chi,
        fit.evaluations,
        fit.seconds
    );
    let _ = writeln!(
        out,
        "rigid ceiling atan(2 (U sin φ + R ω_z) / (7 (1 + e*) U cos φ)) at e* = {:.4}: {} of {n} points above it (no friction law reaches them)",
        ph.restitution,
        fit.above_ceiling()
    );
    if fit.estimates.len() > 1 {
        let p = fit.estimates.len();
        let _ = write!(out, "correlation:");
        for a in 0..p {
            let _ = write!(out, "\n  {:<12}", fit.estimates[a].name);
            for b in 0..p {
                let _ = write!(out, " {:>6.3}", fit.correlation[a * p + b]);
            }
        }
        out.push('\n');
    }
    let _ = writeln!(
        out,
        "residuals (model − measured, degrees):\n  {:<22} {:>6} {:>7} {:>8} {:>9} {:>7} {:>8} {:>8}",
        "id", "cut", "speed", "spin", "measured", "model", "residual", "ceiling"
    );
    for p in &fit.points {
        let m = &p.measurement;
        let _ = writeln!(
            out,
            "  {:<22} {:>6.1} {:>7.3} {:>8} {:>9.3} {:>7.3} {:>+8.3} {:>8.3}{}",
            m.id,
            m.cut_deg,
            m.speed_mps,
            m.spin.label(),
            m.throw_deg,
            p.model_deg,
            p.residual_deg,
            p.ceiling_deg,
            if m.throw_deg > p.ceiling_deg {
                "  above ceiling"
            } else {
                ""
            }
        );
    }
    out.pop();
    out
}

/// The cross-validation report.
pub fn cross_validation_text(folds: &[Fold]) -> String {
    let mut out = String::from(
        "leave-one-series-out cross-validation (fit the others, predict the series):\n",
    );
    let _ = writeln!(
        out,
        "  {:<10} {:>6} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "held out", "points", "mu", "mu_b", "mu_c", "e*", "fit rms", "pred rms", "pred max"
    );
    for f in folds {
        let p = f.fit.physics;
        let _ = writeln!(
            out,
            "  {:<10} {:>6} {:>10.5} {:>10.5} {:>10.4} {:>10.4} {:>10.3} {:>10.3} {:>10.3}",
            f.series,
            f.held_out.len(),
            p.mu,
            p.mu_b,
            p.mu_c,
            p.restitution,
            f.fit.rms_deg,
            f.rms_deg,
            f.max_deg
        );
        if let Some(kappa) = p.tangential_stiffness {
            out.pop();
            let _ = writeln!(out, "  (kappa {kappa:.4})");
        }
    }
    let (rms, max, n) = pooled(folds);
    let _ = write!(
        out,
        "pooled prediction over all {n} held-out points: rms {rms:.3} deg, max {max:.3} deg"
    );
    out
}

/// Pooled RMS, max and count of the held-out residuals.
pub fn pooled(folds: &[Fold]) -> (f64, f64, usize) {
    let residuals: Vec<f64> = folds
        .iter()
        .flat_map(|f| f.held_out.iter().map(|p| p.residual_deg))
        .collect();
    let n = residuals.len();
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / n.max(1) as f64).sqrt();
    let max = residuals.iter().map(|r| r.abs()).fold(0.0, f64::max);
    (rms, max, n)
}

/// One JSON object: the parameters under `collide`'s names (so that the object is a
/// `--params` file), their uncertainties, the fit quality and the residuals.
pub fn json(fit: &Fit, folds: Option<&[Fold]>) -> Value {
    let ph = fit.physics;
    let mut stderr = Map::new();
    let mut ci95 = Map::new();
    let mut interval = Map::new();
    for e in &fit.estimates {
        stderr.insert(e.name.to_owned(), json!(e.stderr));
        ci95.insert(e.name.to_owned(), json!(e.ci95));
        interval.insert(e.name.to_owned(), json!([e.lower, e.upper]));
    }
    let residuals: Vec<Value> = fit
        .points
        .iter()
        .map(|p| {
            json!({
                "id": p.measurement.id,
                "cut_deg": p.measurement.cut_deg,
                "speed_mps": p.measurement.speed_mps,
                "throw_deg": p.measurement.throw_deg,
                "model_deg": p.model_deg,
                "residual_deg": p.residual_deg,
                "ceiling_deg": p.ceiling_deg,
            })
        })
        .collect();
    let mut v = json!({
        "mu": ph.mu,
        "mu_b": ph.mu_b,
        "mu_c": ph.mu_c,
        "restitution": ph.restitution,
        "mu_s": ph.mu_s,
        "fit": fit.kind.name(),
        "model": fit.solver.name(),
        "stderr": stderr,
        "ci95": ci95,
        "interval95": interval,
        "intervals": fit.intervals.name(),
        "rms_deg": fit.rms_deg,
        "max_deg": fit.max_deg.0,
        "points": fit.points.len(),
        "above_ceiling": fit.above_ceiling(),
        "residuals": residuals,
    });
    if let (Some(kappa), Some(map)) = (ph.tangential_stiffness, v.as_object_mut()) {
        // Not a `--params` key: `collide` and `shot` have no compliant contact.
        map.insert("tangential_stiffness".to_owned(), json!(kappa));
    }
    if let (Some(folds), Some(map)) = (folds, v.as_object_mut()) {
        let (rms, max, n) = pooled(folds);
        let list: Vec<Value> = folds
            .iter()
            .map(|f| {
                let mut fold = json!({
                    "series": f.series,
                    "points": f.held_out.len(),
                    "mu": f.fit.physics.mu,
                    "mu_b": f.fit.physics.mu_b,
                    "mu_c": f.fit.physics.mu_c,
                    "restitution": f.fit.physics.restitution,
                    "fit_rms_deg": f.fit.rms_deg,
                    "rms_deg": f.rms_deg,
                    "max_deg": f.max_deg,
                });
                if let (Some(kappa), Some(map)) =
                    (f.fit.physics.tangential_stiffness, fold.as_object_mut())
                {
                    map.insert("tangential_stiffness".to_owned(), json!(kappa));
                }
                fold
            })
            .collect();
        map.insert(
            "cross_validation".to_owned(),
            json!({ "folds": list, "rms_deg": rms, "max_deg": max, "points": n }),
        );
    }
    v
}
