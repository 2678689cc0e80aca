//! The fit on the shared calibration set and its cross-validation.

use cuesight_cli::calibrate::{
    cross_validate, fit, read_file, FitKind, FitOptions, Intervals, Solver,
};

use cuesight_figures::{signed, thousands};

use super::shared_set;

/// CPU time of the calling thread (s), from `/proc/thread-self/stat` (utime + stime,
/// fields 14 and 15, in clock ticks of 1/100 s: proc(5)); `None` elsewhere.
fn thread_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    // Fields after the command name, which is in parentheses and may hold spaces.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i)?.parse::<f64>().ok();
    // `rest` starts at field 3 (state): utime is field 14, stime 15.
    Some((ticks(11)? + ticks(12)?) / 100.0)
}

/// `x` with `decimals` decimals, or as an integer when they are all zero (an interval
/// that ends at a bound: `[0, 0.0454]`, `[0.675, 1]`), as docs/calibration.md prints it.
fn figure(x: f64, decimals: usize) -> String {
    let text = format!("{x:.decimals$}");
    if text.contains('.') && text.trim_end_matches('0').ends_with('.') {
        format!("{x:.0}")
    } else {
        text
    }
}

/// `x` with `decimals` decimals, an explicit sign and the typographic minus.
fn plus_minus(x: f64, decimals: usize) -> String {
    format!("{x:+.decimals$}").replace('-', "\u{2212}")
}

/// `x` to `digits` significant digits (`0.214`, `2.51`), as docs/calibration.md prints
/// the folds' `mu_c`.
fn significant(x: f64, digits: i32) -> String {
    let decimals = (digits - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// The series and cut of a point (`slow-20`), as the docs name it.
fn point_name(m: &cuesight_cli::calibrate::Measurement) -> String {
    format!("{}-{:.0}", m.series, m.cut_deg)
}

/// Records a fit's row of the table of docs/calibration.md §3 (`calibration-KIND-…`):
/// each fitted parameter as `value [lower, upper]` (its 95 % interval), the RMS and the
/// worst point (`max`, with its series and cut).
fn record_row(kind: &str, f: &cuesight_cli::calibrate::Fit) {
    for e in &f.estimates {
        let decimals = if e.name == "mu_c" || e.name == "restitution" {
            3
        } else {
            4
        };
        cuesight_figures::record!(
            &format!("calibration-{kind}-{}", e.name.replace('_', "-")),
            "{} [{}, {}]",
            figure(e.value, decimals),
            figure(e.lower, decimals),
            figure(e.upper, decimals)
        );
        cuesight_figures::record!(
            &format!("calibration-{kind}-{}-value", e.name.replace('_', "-")),
            "{}",
            figure(e.value, decimals)
        );
    }
    let worst = &f.points[f.max_deg.1].measurement;
    cuesight_figures::record!(&format!("calibration-{kind}-rms"), "{:.3}°", f.rms_deg);
    cuesight_figures::record!(
        &format!("calibration-{kind}-max"),
        "{:.2}° ({} {:.0}°)",
        f.max_deg.0,
        worst.series,
        worst.cut_deg
    );
}

fn shared_fit(kind: FitKind, solver: Solver) -> cuesight_cli::calibrate::Fit {
    shared_fit_with(kind, solver, Intervals::Profile)
}

fn shared_fit_with(
    kind: FitKind,
    solver: Solver,
    intervals: Intervals,
) -> cuesight_cli::calibrate::Fit {
    let points = read_file(&shared_set()).unwrap();
    let mut options = FitOptions::new(kind);
    options.solver = solver;
    options.intervals = intervals;
    fit(&points, &options).unwrap()
}

#[test]
fn shared_set_constant_mu_is_the_issues_best_constant() {
    // Issue 19 (with the Exact model): best constant μ 0.0696, 0.98° RMS.
    let f = shared_fit(FitKind::Mu, Solver::KimGrip);
    println!("constant mu {:.5}, rms {:.4}", f.physics.mu, f.rms_deg);
    record_row("mu", &f);
    assert!((f.physics.mu - 0.0696).abs() < 5e-4, "{}", f.physics.mu);
    assert!((f.rms_deg - 0.98).abs() < 5e-3, "{}", f.rms_deg);
}

#[test]
fn shared_set_mu_v_by_kim_grip_is_the_reference_fit() {
    // The fit itself (the optimum and its time); the reference's profile intervals
    // are another ~6 fits per parameter (docs/calibration.md §2, cost).
    let started = std::time::Instant::now();
    let cpu_started = thread_cpu_seconds();
    let reference = shared_fit_with(FitKind::MuV, Solver::Reference, Intervals::Linearised);
    let wall = started.elapsed().as_secs_f64();
    // The issue's limit is for one core: the thread's CPU time where Linux gives it
    // (the wall time on a loaded shared machine is not the fit's cost).
    let seconds = match (cpu_started, thread_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => wall,
    };
    let kim_grip = shared_fit_with(FitKind::MuV, Solver::KimGrip, Intervals::Linearised);
    println!(
        "mu-v: reference ({seconds:.2} s CPU, {wall:.2} s wall) {:?} rms {:.5} max {:.4}; kim-grip {:?} rms {:.5} max {:.4}",
        [reference.physics.mu, reference.physics.mu_b, reference.physics.mu_c],
        reference.rms_deg,
        reference.max_deg.0,
        [kim_grip.physics.mu, kim_grip.physics.mu_b, kim_grip.physics.mu_c],
        kim_grip.rms_deg,
        kim_grip.max_deg.0
    );
    // docs/calibration.md §2: how far the fast tier's optimum is from the reference's.
    for (a, b) in kim_grip.estimates.iter().zip(&reference.estimates) {
        cuesight_figures::record!(
            &format!(
                "calibration-kim-grip-vs-reference-{}",
                a.name.replace('_', "-")
            ),
            "{:.1e}",
            (a.value - b.value).abs()
        );
    }
    cuesight_figures::record!(
        "calibration-kim-grip-vs-reference-rms",
        "{:.0e}",
        (kim_grip.rms_deg - reference.rms_deg).abs()
    );
    cuesight_figures::record!("calibration-mu-v-rms-reference", "{:.6}", reference.rms_deg);
    cuesight_figures::record!("calibration-mu-v-rms-kim-grip", "{:.6}", kim_grip.rms_deg);
    cuesight_figures::record!("calibration-above-ceiling", "{}", reference.above_ceiling());
    // Issue 19: today's μ(v) fit, 0.45° RMS (max 1.48°), with the Exact model.
    assert!(
        (reference.rms_deg - 0.45).abs() < 5e-3,
        "{}",
        reference.rms_deg
    );
    assert!((reference.max_deg.0 - 1.48).abs() < 5e-3);
    // The fast model finds the same optimum: within a tenth of each standard error.
    for (k, (a, b)) in kim_grip
        .estimates
        .iter()
        .zip(&reference.estimates)
        .enumerate()
    {
        assert!(
            (a.value - b.value).abs() < 0.1 * b.stderr,
            "parameter {k}: {a:?} {b:?}"
        );
    }
    assert!((kim_grip.rms_deg - reference.rms_deg).abs() < 1e-4);
    assert!(seconds < 10.0, "the reference fit took {seconds} s");
    // 12 of the 36 points are above the rigid ceiling at e* = 0.95.
    assert_eq!(reference.above_ceiling(), 12);
}

#[test]
fn shared_set_mu_v_e_reaches_0_45_deg() {
    let f = shared_fit(FitKind::MuVE, Solver::KimGrip);
    println!(
        "mu-v-e: {:?} e* {:.4} rms {:.4} max {:.4}",
        [f.physics.mu, f.physics.mu_b, f.physics.mu_c],
        f.physics.restitution,
        f.rms_deg,
        f.max_deg.0
    );
    record_row("mu-v-e", &f);
    // The points above the rigid ceiling at the fitted e* (docs/calibration.md §6).
    cuesight_figures::record!("calibration-mu-v-e-above-ceiling", "{}", f.above_ceiling());
    assert!(f.rms_deg <= 0.45, "{}", f.rms_deg);
}

#[test]
fn cross_validation_holds_out_each_speed_series() {
    let points = read_file(&shared_set()).unwrap();
    let folds = cross_validate(&points, &FitOptions::new(FitKind::MuV)).unwrap();
    assert_eq!(
        folds.iter().map(|f| f.series.as_str()).collect::<Vec<_>>(),
        ["slow", "medium", "fast"]
    );
    for f in &folds {
        println!(
            "held out {}: fit rms {:.3}, predicted rms {:.3}, max {:.3}",
            f.series, f.fit.rms_deg, f.rms_deg, f.max_deg
        );
        // docs/calibration.md §5's table: `mu` at its bound prints as 1e-6.
        let p = f.fit.physics;
        let mu = if p.mu < 1e-4 {
            format!("{:.0e}", p.mu)
        } else {
            format!("{:.4}", p.mu)
        };
        let key = |what: &str| format!("calibration-cv-mu-v-{}-{what}", f.series);
        cuesight_figures::record!(&key("mu"), "{mu}");
        cuesight_figures::record!(&key("mu-b"), "{:.4}", p.mu_b);
        cuesight_figures::record!(&key("mu-c"), "{}", significant(p.mu_c, 3));
        cuesight_figures::record!(&key("fit-rms"), "{:.3}°", f.fit.rms_deg);
        cuesight_figures::record!(&key("rms"), "{:.3}°", f.rms_deg);
        cuesight_figures::record!(&key("max"), "{:.2}°", f.max_deg);
        assert_eq!(f.held_out.len(), 12);
        assert_eq!(f.fit.points.len(), 24);
        // Predicting unseen data cannot beat fitting it.
        assert!(f.rms_deg >= f.fit.rms_deg * 0.5);
    }
    let (rms, max, n) = cuesight_cli::calibrate::report::pooled(&folds);
    cuesight_figures::record!("calibration-cv-mu-v-pooled-n", "{n}");
    cuesight_figures::record!("calibration-cv-mu-v-pooled-rms", "{rms:.3}°");
    cuesight_figures::record!("calibration-cv-mu-v-pooled-max", "{max:.2}°");
    let mu_c = folds.iter().map(|f| f.fit.physics.mu_c);
    cuesight_figures::record!(
        "calibration-cv-mu-v-mu-c-range",
        "{} to {}",
        significant(mu_c.clone().fold(f64::INFINITY, f64::min), 2),
        significant(mu_c.fold(0.0, f64::max), 2)
    );
}

/// The profile interval of the constant μ, checked by its definition (Bates & Watts
/// 1988, §6.1) with χ² computed here from the model's throw: at each end
/// `(χ²(end) − χ²_min)/s² = t²`, `s² = χ²_min/(n − 1)`, t the two-sided 95 % quantile
/// of Student's t with 35 degrees of freedom (2.030108, tables).
#[test]
fn constant_mu_profile_interval_ends_where_chi2_rises_by_t_squared() {
    let points = read_file(&shared_set()).unwrap();
    let f = shared_fit(FitKind::Mu, Solver::KimGrip);
    let chi2 = |mu: f64| -> f64 {
        let physics = cuesight_cli::calibrate::Physics { mu, ..f.physics };
        points
            .iter()
            .map(|m| {
                let t = cuesight_cli::calibrate::fit::model_throw(Solver::KimGrip, &physics, m)
                    .unwrap();
                (t - m.throw_deg).powi(2)
            })
            .sum()
    };
    let minimum = chi2(f.physics.mu);
    let s2 = minimum / 35.0;
    let e = f.estimates[0];
    println!("constant mu {} in [{}, {}]", e.value, e.lower, e.upper);
    assert!(e.lower < e.value && e.value < e.upper);
    for end in [e.lower, e.upper] {
        let tau2 = (chi2(end) - minimum) / s2;
        assert!((tau2 - 2.030_108_f64.powi(2)).abs() < 2e-3, "{end}: {tau2}");
    }
}

/// μ(v)'s `mu` is about one standard error above its bound on the shared set: its
/// profile interval ends at the bound (1e-6), where the linearised one would cross it.
#[test]
fn mu_v_profile_interval_of_mu_ends_at_its_bound() {
    let f = shared_fit(FitKind::MuV, Solver::KimGrip);
    record_row("mu-v", &f);
    record_mu_v_details(&f);
    let mu = f.estimates[0];
    assert_eq!(mu.lower, 1e-6, "{mu:?}");
    assert!(mu.value - mu.ci95 < 0.0, "{mu:?}");
    for e in &f.estimates {
        assert!(e.lower < e.value && e.value < e.upper, "{e:?}");
    }
}

/// The figures of docs/calibration.md §3 and §6 about the μ(v) fit (profile
/// intervals): standard errors, linearised intervals, correlations, μ at three slip
/// speeds, the fit's cost, the residuals by series and of the points above the rigid
/// ceiling, and the worst points.
fn record_mu_v_details(f: &cuesight_cli::calibrate::Fit) {
    let joined = |value: &dyn Fn(&cuesight_cli::calibrate::fit::Estimate) -> String| {
        f.estimates
            .iter()
            .map(value)
            .collect::<Vec<_>>()
            .join(" / ")
    };
    let decimals =
        |e: &cuesight_cli::calibrate::fit::Estimate| if e.name == "mu_c" { 3 } else { 4 };
    cuesight_figures::record!(
        "calibration-mu-v-stderr",
        "{}",
        joined(&|e| format!("{:.*}", decimals(e), e.stderr))
    );
    cuesight_figures::record!(
        "calibration-mu-v-linearised-half-width",
        "{}",
        joined(&|e| format!("±{:.*}", decimals(e), e.ci95))
    );
    let mu = f.estimates[0];
    cuesight_figures::record!(
        "calibration-mu-v-linearised-mu-lower",
        "{}",
        signed(mu.value - mu.ci95, 3)
    );
    let n = f.estimates.len();
    cuesight_figures::record!(
        "calibration-mu-v-correlation-mu-mu-c",
        "{}",
        signed(f.correlation[2], 2)
    );
    cuesight_figures::record!(
        "calibration-mu-v-correlation-mu-mu-b",
        "{}",
        signed(f.correlation[1], 2)
    );
    assert_eq!(n * n, f.correlation.len());
    let p = f.physics;
    for slip in [1, 2, 5] {
        let mu_at = p.mu + p.mu_b * (-p.mu_c * slip as f64).exp();
        cuesight_figures::record!(&format!("calibration-mu-v-mu-at-{slip}"), "{mu_at:.3}");
    }
    cuesight_figures::record!(
        "calibration-mu-v-profile-evaluations",
        "{}",
        thousands(f.evaluations)
    );
    let rms = |points: &[&cuesight_cli::calibrate::fit::PointFit]| {
        let sum: f64 = points.iter().map(|p| p.residual_deg.powi(2)).sum();
        (sum / points.len() as f64).sqrt()
    };
    for series in ["slow", "medium", "fast"] {
        let of: Vec<_> = f
            .points
            .iter()
            .filter(|p| p.measurement.series == series)
            .collect();
        let mean = of.iter().map(|p| p.residual_deg).sum::<f64>() / of.len() as f64;
        cuesight_figures::record!(
            &format!("calibration-mu-v-{series}-rms"),
            "{:.2}°",
            rms(&of)
        );
        cuesight_figures::record!(
            &format!("calibration-mu-v-{series}-mean"),
            "{}°",
            plus_minus(mean, 2)
        );
    }
    // The points above the rigid ceiling (§6): each one's ceiling and excess, and the
    // residuals of those points, of the others, and of the whole set without them.
    let (above, below): (Vec<_>, Vec<_>) = f
        .points
        .iter()
        .partition(|p| p.measurement.throw_deg > p.ceiling_deg);
    for p in &above {
        let name = point_name(&p.measurement);
        cuesight_figures::record!(
            &format!("calibration-ceiling-{name}"),
            "{:.3}°",
            p.ceiling_deg
        );
        cuesight_figures::record!(
            &format!("calibration-above-{name}"),
            "{:.3}°",
            p.measurement.throw_deg - p.ceiling_deg
        );
    }
    for cut in [20.0, 30.0] {
        let ceiling = f
            .points
            .iter()
            .find(|p| p.measurement.cut_deg == cut)
            .unwrap()
            .ceiling_deg;
        cuesight_figures::record!(&format!("calibration-ceiling-{cut:.0}"), "{ceiling:.2}°");
    }
    cuesight_figures::record!("calibration-mu-v-above-rms", "{:.3}°", rms(&above));
    cuesight_figures::record!("calibration-mu-v-below-rms", "{:.3}°", rms(&below));
    let without = (below.len() as f64 / f.points.len() as f64).sqrt() * rms(&below);
    cuesight_figures::record!("calibration-mu-v-above-at-zero-rms", "{without:.3}°");
    // §6: the 5° points (the contact grips: the ceiling, whatever the speed) and the
    // medium series' curvature in cut.
    let at_5: Vec<_> = f
        .points
        .iter()
        .filter(|p| p.measurement.cut_deg == 5.0)
        .collect();
    cuesight_figures::record!("calibration-mu-v-model-5", "{:.2}°", at_5[0].model_deg);
    let residual = |p: &&cuesight_cli::calibrate::fit::PointFit| p.residual_deg;
    cuesight_figures::record!(
        "calibration-mu-v-residual-5",
        "{}° to {}°",
        plus_minus(at_5.iter().map(residual).fold(f64::INFINITY, f64::min), 2),
        plus_minus(
            at_5.iter().map(residual).fold(f64::NEG_INFINITY, f64::max),
            2
        )
    );
    for p in &f.points {
        let name = point_name(&p.measurement);
        if p.measurement.series == "medium"
            && [30.0, 35.0, 55.0, 60.0].contains(&p.measurement.cut_deg)
        {
            cuesight_figures::record!(
                &format!("calibration-mu-v-residual-{name}"),
                "{}°",
                plus_minus(p.residual_deg, 2)
            );
        }
    }
}

/// Why μ(v)'s RMS on the shared set is 0.4511°, not ≤ 0.45° (docs/calibration.md §3):
/// the fit is the global least-squares optimum — a brute-force grid over the whole
/// parameter range (`mu` 0–0.1, `mu_b` 0–0.3, `mu_c` 0.01–100 s/m, 27,000 points)
/// finds nothing lower — and e* = 0.95 is fixed: only a lower e* lowers it.
#[test]
fn mu_v_fit_is_the_global_optimum_on_the_shared_set() {
    use cuesight_cli::calibrate::fit::model_throw;
    use cuesight_cli::calibrate::Physics;
    let points = read_file(&shared_set()).unwrap();
    let rms = |physics: &Physics| -> f64 {
        let sum: f64 = points
            .iter()
            .map(|m| (model_throw(Solver::KimGrip, physics, m).unwrap() - m.throw_deg).powi(2))
            .sum();
        (sum / points.len() as f64).sqrt()
    };
    let f = shared_fit_with(FitKind::MuV, Solver::KimGrip, Intervals::Linearised);
    let mut grid_min = (f64::INFINITY, [0.0; 3]);
    let mut grid_points = 0;
    // The grid's best RMS at a fixed decay rate `mu_c` (the valley's floor along it).
    let mut along_mu_c = Vec::new();
    for ic in 0..=16 {
        let mu_c = 0.01 * 10f64.powf(ic as f64 / 4.0);
        let mut best_here = f64::INFINITY;
        for ia in 0..=25 {
            let mu = 1e-6 + 0.004 * ia as f64;
            for ib in 0..=60 {
                let mu_b = 0.005 * ib as f64;
                let physics = Physics {
                    mu,
                    mu_b,
                    mu_c,
                    ..f.physics
                };
                let r = rms(&physics);
                grid_points += 1;
                best_here = best_here.min(r);
                if r < grid_min.0 {
                    grid_min = (r, [mu, mu_b, mu_c]);
                }
            }
        }
        along_mu_c.push((mu_c, best_here));
    }
    let valley: Vec<String> = along_mu_c
        .iter()
        .filter(|(mu_c, _)| (0.1..=40.0).contains(mu_c))
        .step_by(2)
        .map(|(mu_c, r)| format!("{r:.3}° at {mu_c:.2}"))
        .collect();
    cuesight_figures::record!("calibration-grid-valley", "{}", valley.join(", "));
    println!(
        "mu-v fit rms {:.6} at {:?}; grid minimum {:.6} at {:?}",
        f.rms_deg,
        [f.physics.mu, f.physics.mu_b, f.physics.mu_c],
        grid_min.0,
        grid_min.1
    );
    cuesight_figures::record!("calibration-grid-points", "{}", thousands(grid_points));
    cuesight_figures::record!("calibration-grid-rms", "{:.4}°", grid_min.0);
    cuesight_figures::record!("calibration-mu-v-rms-4", "{:.4}°", f.rms_deg);
    cuesight_figures::record!("calibration-mu-v-over-0-45", "{:.4}°", f.rms_deg - 0.45);
    cuesight_figures::record!(
        "calibration-mu-v-fit-evaluations",
        "{}",
        thousands(f.evaluations)
    );
    assert!(grid_min.0 >= f.rms_deg - 1e-9, "{grid_min:?}");
    // `exact` at the same optimum gives the same RMS (calibration.md, "Model tier").
    let exact_rms = (points
        .iter()
        .map(|m| (model_throw(Solver::Exact, &f.physics, m).unwrap() - m.throw_deg).powi(2))
        .sum::<f64>()
        / points.len() as f64)
        .sqrt();
    cuesight_figures::record!("calibration-mu-v-rms-exact-at-optimum", "{exact_rms:.6}");
    assert!(
        (exact_rms - f.rms_deg).abs() < 1e-5,
        "{exact_rms} vs {}",
        f.rms_deg
    );
    // The optimum is interior: no bound is active.
    assert!(f.physics.mu > 0.01 && f.physics.mu_c > 0.1 && f.physics.mu_c < 10.0);
    // With e* fitted the optimum moves to e* ≈ 0.87 (RMS 0.443°); with e* fixed at
    // 0.95 μ(v) alone cannot go below 0.451°.
    let mut lower_e = FitOptions::new(FitKind::MuV);
    lower_e.intervals = Intervals::Linearised;
    for (e, expect_below) in [
        (0.90, true),
        (0.92, true),
        (0.93, true),
        (0.94, true),
        (0.95, false),
        (0.96, false),
        (0.98, false),
    ] {
        lower_e.physics.restitution = e;
        let g = fit(&points, &lower_e).unwrap();
        println!("e* {e} fixed: mu-v rms {:.5}", g.rms_deg);
        cuesight_figures::record!(
            &format!("calibration-mu-v-rms-e-{:.0}", e * 100.0),
            "{:.4}",
            g.rms_deg
        );
        assert_eq!(g.rms_deg <= 0.45, expect_below, "e* {e}: {}", g.rms_deg);
    }
}

/// The compliant contact (`--fit mu-v-k`, reference solver) reaches the points above
/// the rigid ceiling: docs/calibration.md §7 (about 6 s of CPU).
#[test]
fn mu_v_k_reaches_points_above_the_rigid_ceiling() {
    let points = read_file(&shared_set()).unwrap();
    let mut options = FitOptions::new(FitKind::MuVK);
    options.solver = Solver::Reference;
    options.intervals = Intervals::Linearised;
    options.max_evaluations = 400_000;
    let f = fit(&points, &options).unwrap();
    let above: Vec<_> = f
        .points
        .iter()
        .filter(|p| p.measurement.throw_deg > p.ceiling_deg)
        .collect();
    let reached = above.iter().filter(|p| p.model_deg > p.ceiling_deg).count();
    println!(
        "mu-v-k: {:?} kappa {:?} rms {:.4} max {:.4}; model above the rigid ceiling at {reached} of the {} points above it",
        [f.physics.mu, f.physics.mu_b, f.physics.mu_c],
        f.physics.tangential_stiffness,
        f.rms_deg,
        f.max_deg.0,
        above.len()
    );
    // docs/calibration.md §7's table (± the linearised 95 % half-width).
    for e in &f.estimates {
        let decimals = if e.name == "mu" || e.name == "mu_b" {
            4
        } else {
            3
        };
        let key = match e.name {
            "tangential_stiffness" => "kappa".to_owned(),
            name => name.replace('_', "-"),
        };
        cuesight_figures::record!(
            &format!("calibration-mu-v-k-{key}"),
            "{:.decimals$} ± {:.3}",
            e.value,
            e.ci95
        );
    }
    let kappa = f.physics.tangential_stiffness.unwrap();
    cuesight_figures::record!("calibration-mu-v-k-kappa-value", "{kappa:.3}");
    cuesight_figures::record!("calibration-mu-v-k-eta", "{:.2}", (3.5 * kappa).sqrt());
    cuesight_figures::record!("calibration-mu-v-k-rms", "{:.3}°", f.rms_deg);
    let worst = &f.points[f.max_deg.1].measurement;
    cuesight_figures::record!(
        "calibration-mu-v-k-max",
        "{:.2}° ({} {:.0}°)",
        f.max_deg.0,
        worst.series,
        worst.cut_deg
    );
    cuesight_figures::record!("calibration-mu-v-k-reached", "{reached}");
    let above_rms =
        (above.iter().map(|p| p.residual_deg.powi(2)).sum::<f64>() / above.len() as f64).sqrt();
    cuesight_figures::record!("calibration-mu-v-k-above-rms", "{above_rms:.2}°");
    assert_eq!(above.len(), 12);
    assert!(reached >= 10, "{reached}");
    // Better than μ(v) with the rigid contact (0.4511°).
    assert!(f.rms_deg < 0.44, "{}", f.rms_deg);
}

/// The compliant contact exists in the reference solver only: the fast tiers refuse it.
#[test]
fn compliance_needs_the_reference_solver() {
    let points = read_file(&shared_set()).unwrap();
    let physics = cuesight_cli::calibrate::Physics {
        tangential_stiffness: Some(0.7),
        ..cuesight_cli::calibrate::Physics::pool()
    };
    let e = cuesight_cli::calibrate::fit::model_throw(Solver::KimGrip, &physics, &points[0])
        .unwrap_err();
    assert!(e.contains("--model reference"), "{e}");
    assert!(
        cuesight_cli::calibrate::fit::model_throw(Solver::Reference, &physics, &points[0]).is_ok()
    );
}
