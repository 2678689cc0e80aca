//! The fit on the shared calibration set and its cross-validation.

use cuesight_cli::calibrate::{
    cross_validate, fit, read_file, FitKind, FitOptions, Intervals, Solver,
};

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
        assert_eq!(f.held_out.len(), 12);
        assert_eq!(f.fit.points.len(), 24);
        // Predicting unseen data cannot beat fitting it.
        assert!(f.rms_deg >= f.fit.rms_deg * 0.5);
    }
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
    let mu = f.estimates[0];
    assert_eq!(mu.lower, 1e-6, "{mu:?}");
    assert!(mu.value - mu.ci95 < 0.0, "{mu:?}");
    for e in &f.estimates {
        assert!(e.lower < e.value && e.value < e.upper, "{e:?}");
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
    for ic in 0..=16 {
        let mu_c = 0.01 * 10f64.powf(ic as f64 / 4.0);
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
                if r < grid_min.0 {
                    grid_min = (r, [mu, mu_b, mu_c]);
                }
            }
        }
    }
    println!(
        "mu-v fit rms {:.6} at {:?}; grid minimum {:.6} at {:?}",
        f.rms_deg,
        [f.physics.mu, f.physics.mu_b, f.physics.mu_c],
        grid_min.0,
        grid_min.1
    );
    assert!(grid_min.0 >= f.rms_deg - 1e-9, "{grid_min:?}");
    // The optimum is interior: no bound is active.
    assert!(f.physics.mu > 0.01 && f.physics.mu_c > 0.1 && f.physics.mu_c < 10.0);
    // With e* fitted the optimum moves to e* ≈ 0.87 (RMS 0.443°); with e* fixed at
    // 0.95 μ(v) alone cannot go below 0.451°.
    let mut lower_e = FitOptions::new(FitKind::MuV);
    lower_e.intervals = Intervals::Linearised;
    for (e, expect_below) in [(0.94, true), (0.95, false), (0.96, false)] {
        lower_e.physics.restitution = e;
        let g = fit(&points, &lower_e).unwrap();
        println!("e* {e} fixed: mu-v rms {:.5}", g.rms_deg);
        assert_eq!(g.rms_deg <= 0.45, expect_below, "e* {e}: {}", g.rms_deg);
    }
}

/// The compliant contact (`--fit mu-v-k`, reference solver) reaches the points above
/// the rigid ceiling: docs/calibration.md §7 (about 6 s of CPU: run with `--ignored`).
#[test]
#[ignore = "about 6 s of CPU in release: run with --ignored --nocapture"]
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
