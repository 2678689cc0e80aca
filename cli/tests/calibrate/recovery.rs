//! Recovery of known parameters: synthetic throw from the reference solver plus noise,
//! fitted, and each parameter's 95 % interval checked against the truth.

use cuesight_cli::calibrate::fit::{model_throw, stun};
use cuesight_cli::calibrate::{fit, FitKind, FitOptions, Intervals, Measurement, Physics, Solver};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The shared set's design: cuts 5..60 every 5 at the three assumed speeds, stun.
fn design() -> Vec<Measurement> {
    let mut points = Vec::new();
    for (label, speed) in [("slow", 1.341), ("medium", 3.129), ("fast", 5.364)] {
        for k in 1..=12 {
            let cut = 5.0 * k as f64;
            points.push(stun(&format!("{label}-{cut}"), label, cut, speed, 0.0));
        }
    }
    points
}

/// A standard normal deviate (Box–Muller).
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Fit `trials` synthetic data sets — throw by the reference solver at `truth`, plus
/// Gaussian noise of `sigma` degrees, seeds 0, 1, ... — and count, per parameter, the
/// trials whose 95 % interval (as reported: profile likelihood) holds the true value.
fn coverage(kind: FitKind, truth: Physics, sigma: f64, trials: u64) -> Vec<usize> {
    coverage_of(kind, Intervals::Profile, truth, sigma, trials)
}

/// [`coverage`] with the given kind of interval.
fn coverage_of(
    kind: FitKind,
    intervals: Intervals,
    truth: Physics,
    sigma: f64,
    trials: u64,
) -> Vec<usize> {
    let clean: Vec<Measurement> = design()
        .into_iter()
        .map(|mut m| {
            m.throw_deg = model_throw(Solver::Reference, &truth, &m).unwrap();
            m
        })
        .collect();
    let true_values = [truth.mu, truth.mu_b, truth.mu_c, truth.restitution];
    let mut options = FitOptions::new(kind);
    options.physics.restitution = truth.restitution;
    options.intervals = intervals;
    let mut inside = vec![0; kind.len()];
    let mut worst = vec![0.0_f64; kind.len()];
    let mut failed = 0;
    for seed in 0..trials {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let noisy: Vec<Measurement> = clean
            .iter()
            .map(|m| Measurement {
                throw_deg: m.throw_deg + sigma * normal(&mut rng),
                ..m.clone()
            })
            .collect();
        let fitted = match fit(&noisy, &options) {
            Ok(fitted) => fitted,
            Err(e) => {
                // Counted as outside for every parameter.
                println!("seed {seed}: {e}");
                failed += 1;
                continue;
            }
        };
        for (k, e) in fitted.estimates.iter().enumerate() {
            // Distance to the truth in units of the interval's half on the truth's side.
            let truth = true_values[k];
            let half = if truth >= e.value {
                e.upper - e.value
            } else {
                e.value - e.lower
            };
            worst[k] = worst[k].max((truth - e.value).abs() / half);
            if e.contains(truth) {
                inside[k] += 1;
            }
        }
    }
    println!(
        "{} recovery, {trials} trials, noise {sigma} deg, {} intervals: {failed} fits failed; inside the 95 % interval {:?} (of {:?}); largest |error|/half-width {:?}",
        kind.name(),
        intervals.name(),
        inside,
        kind.parameter_names(),
        worst
    );
    // docs/calibration.md §4's table: a count of 100 trials, else a percentage.
    let key = format!(
        "calibration-recovery-{}-{}-{trials}",
        kind.name(),
        intervals.name()
    );
    for (name, n) in kind.parameter_names().iter().zip(&inside) {
        let name = name.replace('_', "-");
        if trials == 100 {
            cuesight_figures::record!(&format!("{key}-{name}"), "{n}");
        } else {
            let percent = 100.0 * *n as f64 / trials as f64;
            cuesight_figures::record!(&format!("{key}-{name}"), "{percent:.1} %");
        }
    }
    cuesight_figures::record!(&format!("{key}-failed"), "{failed}");
    inside
}

/// The parameters the shared set gives (its μ(v) fit, rounded), e* 0.95.
fn shared_like() -> Physics {
    Physics {
        mu: 0.0212,
        mu_b: 0.0985,
        mu_c: 0.44,
        ..Physics::pool()
    }
}

/// A true 95 % interval holds the truth in at most 89 of 100 trials with probability
/// 1.2 % (binomial): below that the reported interval is not a 95 % interval.
const NOMINAL_95_OF_100: usize = 90;

/// Issue 19's acceptance: each parameter inside its reported 95 % interval in at least
/// 95 of 100 seeded trials — for μ(v), the fit `calibrate` makes by default. With the
/// profile-likelihood intervals: 99, 98, 98 of 100 (the linearised ones gave 91, 98,
/// 99: `mu` is 0.97-correlated with `mu_c` and often near its bound).
#[test]
fn issue_19_mu_v_each_parameter_inside_in_95_of_100_trials() {
    let inside = coverage(FitKind::MuV, shared_like(), 0.45, 100);
    for (k, n) in inside.iter().enumerate() {
        assert!(*n >= 95, "parameter {k}: {n} of 100 inside");
    }
}

/// The constant μ's interval is a 95 % interval (94 of 100 on these seeds, 94.7 % of
/// 1,000): with one parameter the profile interval is the linearised one to within
/// the model's curvature, and a correct 95 % interval holds the truth in ≥ 95 of 100
/// trials only 62 % of the time (binomial). Checked at the nominal level.
#[test]
fn constant_mu_interval_is_a_95_percent_interval_on_100_reference_trials() {
    let truth = Physics {
        mu: 0.06,
        ..Physics::pool()
    };
    let inside = coverage(FitKind::Mu, truth, 0.45, 100);
    assert!(inside[0] >= NOMINAL_95_OF_100, "{inside:?}");
}

/// Issue 19's criterion with e* fitted as well (about a minute in release: run with
/// `--ignored`): 100, 98, 97, 95 of 100 with profile intervals (88, 99, 99, 95 with
/// the linearised ones).
#[test]
#[ignore = "about a minute in release: run with --ignored"]
fn issue_19_mu_v_e_each_parameter_inside_in_95_of_100_trials() {
    let truth = Physics {
        restitution: 0.92,
        ..shared_like()
    };
    let inside = coverage(FitKind::MuVE, truth, 0.45, 100);
    for (k, n) in inside.iter().enumerate() {
        assert!(*n >= 95, "parameter {k}: {n} of 100 inside");
    }
}

/// The intervals' coverage over 1,000 trials, profile and linearised (the figures of
/// docs/calibration.md), one test per fit.
fn coverage_1000(kind: FitKind, truth: Physics) {
    for intervals in [Intervals::Profile, Intervals::Linearised] {
        coverage_of(kind, intervals, truth, 0.45, 1000);
    }
}

#[test]
#[ignore = "figure: 1,000 trials, run with --ignored --nocapture"]
fn coverage_over_1000_trials_mu() {
    coverage_1000(
        FitKind::Mu,
        Physics {
            mu: 0.06,
            ..Physics::pool()
        },
    );
}

#[test]
#[ignore = "figure: 1,000 trials (minutes), run with --ignored --nocapture"]
fn coverage_over_1000_trials_mu_v() {
    coverage_1000(FitKind::MuV, shared_like());
}

#[test]
#[ignore = "figure: 1,000 trials (minutes), run with --ignored --nocapture"]
fn coverage_over_1000_trials_mu_v_e() {
    coverage_1000(
        FitKind::MuVE,
        Physics {
            restitution: 0.92,
            ..shared_like()
        },
    );
}

/// The linearised intervals on the same 100 trials, for comparison (figures only).
#[test]
#[ignore = "figure: run with --ignored --nocapture"]
fn linearised_coverage_on_100_trials() {
    let with_e = Physics {
        restitution: 0.92,
        ..shared_like()
    };
    coverage_of(
        FitKind::MuV,
        Intervals::Linearised,
        shared_like(),
        0.45,
        100,
    );
    coverage_of(FitKind::MuVE, Intervals::Linearised, with_e, 0.45, 100);
}
