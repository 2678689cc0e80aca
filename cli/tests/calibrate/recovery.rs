//! Recovery of known parameters: synthetic throw from the reference solver plus noise,
//! fitted, and each parameter's 95 % interval checked against the truth.

use cuesight_cli::calibrate::fit::{model_throw, profile_t, stun, t95};
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

/// `trials` synthetic data sets — throw by the reference solver at `truth`, plus
/// Gaussian noise of `sigma` degrees, seeds 0, 1, ... — each handed to `judge` (the
/// trial's seed and points).
fn synthetic_trials(
    truth: &Physics,
    sigma: f64,
    trials: u64,
    mut judge: impl FnMut(u64, &[Measurement]),
) {
    let clean: Vec<Measurement> = design()
        .into_iter()
        .map(|mut m| {
            m.throw_deg = model_throw(Solver::Reference, truth, &m).unwrap();
            m
        })
        .collect();
    for seed in 0..trials {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let noisy: Vec<Measurement> = clean
            .iter()
            .map(|m| Measurement {
                throw_deg: m.throw_deg + sigma * normal(&mut rng),
                ..m.clone()
            })
            .collect();
        judge(seed, &noisy);
    }
}

/// The fit options of a recovery: `kind`, e* fixed at the truth's when not fitted.
fn options(kind: FitKind, truth: &Physics, intervals: Intervals) -> FitOptions {
    let mut options = FitOptions::new(kind);
    options.physics.restitution = truth.restitution;
    options.intervals = intervals;
    options
}

/// Per parameter, the trials whose interval holds the truth, and the fits that failed
/// (counted outside for every parameter).
#[derive(Debug, Default)]
struct Tally {
    inside: Vec<usize>,
    failed: usize,
}

impl Tally {
    fn new(kind: FitKind) -> Self {
        Self {
            inside: vec![0; kind.len()],
            failed: 0,
        }
    }

    /// Prints the tally and records docs/calibration.md §4's figures (a count of 100
    /// trials, else a percentage).
    fn record(&self, kind: FitKind, intervals: Intervals, trials: u64, sigma: f64, how: &str) {
        println!(
            "{} recovery, {trials} trials, noise {sigma} deg, {} intervals ({how}): {} fits failed; inside the 95 % interval {:?} (of {:?})",
            kind.name(),
            intervals.name(),
            self.failed,
            self.inside,
            kind.parameter_names(),
        );
        let key = format!(
            "calibration-recovery-{}-{}-{trials}",
            kind.name(),
            intervals.name()
        );
        for (name, n) in kind.parameter_names().iter().zip(&self.inside) {
            let name = name.replace('_', "-");
            if trials == 100 {
                cuesight_figures::record!(&format!("{key}-{name}"), "{n}");
            } else {
                let percent = 100.0 * *n as f64 / trials as f64;
                cuesight_figures::record!(&format!("{key}-{name}"), "{percent:.1} %");
            }
        }
        cuesight_figures::record!(&format!("{key}-failed"), "{}", self.failed);
    }
}

/// [`coverage_of`] with the profile intervals `calibrate` reports by default.
fn coverage(kind: FitKind, truth: Physics, sigma: f64, trials: u64) -> Vec<usize> {
    coverage_of(kind, Intervals::Profile, truth, sigma, trials)
}

/// Coverage of the intervals `calibrate` reports ([`fit`] with `intervals`) over
/// [`synthetic_trials`]. With profile intervals each verdict is checked against the
/// profile statistic at the truth, `|τ_k(truth)| ≤ t` ([`profile_t`]), which defines
/// the interval: they must agree except within the search's tolerance of an end
/// (`10⁻³` of the first step, `t·se`) — what lets [`coverage_1000`] use the statistic.
fn coverage_of(
    kind: FitKind,
    intervals: Intervals,
    truth: Physics,
    sigma: f64,
    trials: u64,
) -> Vec<usize> {
    let options = options(kind, &truth, intervals);
    let mut tally = Tally::new(kind);
    let mut disagreements = 0;
    synthetic_trials(&truth, sigma, trials, |seed, noisy| {
        let fitted = match fit(noisy, &options) {
            Ok(fitted) => fitted,
            Err(e) => {
                println!("seed {seed}: {e}");
                tally.failed += 1;
                return;
            }
        };
        let t = t95(noisy.len() - kind.len());
        for (k, e) in fitted.estimates.iter().enumerate() {
            let truth = [truth.mu, truth.mu_b, truth.mu_c, truth.restitution][k];
            let inside = e.contains(truth);
            tally.inside[k] += usize::from(inside);
            if intervals == Intervals::Profile {
                let tau = profile_t(noisy, &options, &fitted, k, truth).unwrap();
                if inside != (tau.abs() <= t) {
                    let from_end = (truth - e.lower).abs().min((truth - e.upper).abs());
                    println!(
                        "seed {seed}, {}: interval [{}, {}] vs τ(truth) {tau:.6} (t {t:.6}), truth {from_end:.3e} from an end",
                        e.name, e.lower, e.upper
                    );
                    assert!(
                        from_end <= 2e-3 * e.ci95,
                        "seed {seed}, {}: the reported interval and the profile statistic disagree away from the interval's end",
                        e.name
                    );
                    disagreements += 1;
                }
            }
        }
    });
    tally.record(kind, intervals, trials, sigma, "as reported");
    if intervals == Intervals::Profile {
        println!("  profile statistic at the truth: {disagreements} verdicts differ, each within the search tolerance of an end");
    }
    tally.inside
}

/// Coverage of both kinds of interval over `trials` trials from one fit per trial
/// (linearised intervals, which cost no extra fit): the linearised verdict from the
/// reported interval, the profile verdict from `|τ_k(truth)| ≤ t` ([`profile_t`]: one
/// profile fit per parameter instead of the interval's search, about a sixth of
/// the time; [`coverage_of`] checks that the two verdicts agree).
fn coverage_1000(kind: FitKind, truth: Physics) {
    let (sigma, trials) = (0.45, 1000);
    let options = options(kind, &truth, Intervals::Linearised);
    let mut linearised = Tally::new(kind);
    let mut profile = Tally::new(kind);
    synthetic_trials(&truth, sigma, trials, |seed, noisy| {
        let fitted = match fit(noisy, &options) {
            Ok(fitted) => fitted,
            Err(e) => {
                println!("seed {seed}: {e}");
                linearised.failed += 1;
                profile.failed += 1;
                return;
            }
        };
        let t = t95(noisy.len() - kind.len());
        let true_values = [truth.mu, truth.mu_b, truth.mu_c, truth.restitution];
        let mut taus = Vec::new();
        for (k, e) in fitted.estimates.iter().enumerate() {
            linearised.inside[k] += usize::from(e.contains(true_values[k]));
            match profile_t(noisy, &options, &fitted, k, true_values[k]) {
                Ok(tau) => taus.push(tau),
                Err(e) => {
                    println!("seed {seed}: {e}");
                    profile.failed += 1;
                    return;
                }
            }
        }
        for (k, tau) in taus.iter().enumerate() {
            profile.inside[k] += usize::from(tau.abs() <= t);
        }
    });
    linearised.record(kind, Intervals::Linearised, trials, sigma, "as reported");
    profile.record(kind, Intervals::Profile, trials, sigma, "|τ(truth)| ≤ t");
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

/// Issue 19's criterion with e* fitted as well (about 80 s of CPU): 100, 98, 98, 95
/// of 100 with profile intervals (88, 99, 99, 95 with the linearised ones).
#[test]
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
/// docs/calibration.md §4), one test per fit: about 5, 40 and 55 s of CPU.
#[test]
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
fn coverage_over_1000_trials_mu_v() {
    coverage_1000(FitKind::MuV, shared_like());
}

#[test]
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
