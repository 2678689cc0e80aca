//! The figures of `docs/low-speed-limit.md` §5 ("What the error is"): each of the three
//! mechanisms measured against its estimate, recorded as `low-speed-limit-mech-*`.
//!
//! Measures as in the sweep: the full measure `max(|Δv|, R|Δω|)/U` over both balls
//! ([`Deviation::max`](cuesight_host::timed::Deviation)), μ = 0.05, e* = 0.95,
//! μ_s = 0.3 unless named.

use cuesight_figures::record;
use cuesight_host::timed::{
    Comparison, Scenario, SpinKind, TimedConfig, GRAVITY, POOL_MASS, POOL_RADIUS,
};

use super::{run, Row};

/// `g τ / U`: the hop speed gravity takes back during the contact, as a fraction of U
/// (τ the solver's contact duration).
fn gravity_scale(c: &Comparison, speed: f64) -> f64 {
    GRAVITY * c.timed.duration / speed
}

/// The smallest and largest of `values`.
fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}

/// A range `lo–hi` with `digits` decimals.
fn range(values: impl Iterator<Item = f64>, digits: usize) -> String {
    let (lo, hi) = bounds(values);
    let (lo, hi) = (format!("{lo:.digits$}"), format!("{hi:.digits$}"));
    if lo == hi {
        lo
    } else {
        format!("{lo}–{hi}")
    }
}

/// Least-squares slope of `ln y` against `ln x`.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(sx, sy), &(x, y)| (sx + x.ln(), sy + y.ln()));
    let (mx, my) = (sx / n, sy / n);
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(sxy, sxx), &(x, y)| {
        let dx = x.ln() - mx;
        (sxy + dx * (y.ln() - my), sxx + dx * dx)
    });
    sxy / sxx
}

/// Records §5's figures. `rows` is the sweep (every scenario at every μ, with its
/// error curve over `speeds`); `fixed` the solver's configuration.
pub fn record_mechanisms(rows: &[Row], speeds: &[f64], fixed: &TimedConfig) {
    let at = |spin: SpinKind, cut: f64, u: f64| {
        let s = Scenario::pool(spin, cut, 0.05);
        run(&s, &s.params(), u, fixed)
    };
    let mid_speeds = || speeds.iter().copied().filter(|&u| (0.5..=2.0).contains(&u));

    // 1. Hop speed lost to gravity: head-on roll, error / (g τ/U) from 0.5 to 2 m/s.
    let ratios = mid_speeds().map(|u| {
        let c = at(SpinKind::Roll, 0.0, u);
        c.deviation.max() / gravity_scale(&c, u)
    });
    record!(
        "low-speed-limit-mech-roll-gravity-ratio",
        "{}",
        range(ratios, 3)
    );
    let draw_in_plane = rows
        .iter()
        .filter(|r| {
            r.scenario.mu == 0.05 && r.scenario.spin == SpinKind::Draw && r.scenario.cut_deg <= 60.0
        })
        .filter_map(|r| r.in_plane);
    record!(
        "low-speed-limit-mech-draw-in-plane",
        "{}",
        range(draw_in_plane, 2)
    );

    // 2. The object ball's table friction under its weight: error / (g τ/U) at 2 m/s,
    // against 2.5 μ_s.
    for (spin, cut) in [(SpinKind::Side, 30.0), (SpinKind::Stun, 85.0)] {
        let c = at(spin, cut, 2.0);
        record!(
            &format!("low-speed-limit-mech-table-ratio-{}-{cut:.0}", spin.label()),
            "{:.2}",
            c.deviation.max() / gravity_scale(&c, 2.0)
        );
    }
    let longer =
        at(SpinKind::Stun, 85.0, 1.0).timed.duration / at(SpinKind::Stun, 0.0, 1.0).timed.duration;
    record!("low-speed-limit-mech-duration-85", "{longer:.2}");
    // The stuck contact shares the torque: head-on stun at 0.3 m/s, R Δω_y (% of U).
    let c = at(SpinKind::Stun, 0.0, 0.3);
    let spin_change = |t: &cuesight_host::reference::BallState,
                       r: &cuesight_host::reference::BallState| {
        100.0 * POOL_RADIUS * (t.spin.y - r.spin.y) / 0.3
    };
    record!(
        "low-speed-limit-mech-stun-shared",
        "{:+.2} % on the cue ball and {:+.2} % on the object ball",
        spin_change(&c.timed.cue_ball, &c.reference.cue_ball),
        spin_change(&c.timed.object_ball, &c.reference.object_ball)
    );

    // 3. Rolling off: the object ball's table contact does not slip below
    // (7/2) μ_s M g; with the ball–ball contact sliding, P = (1+e*) M U (1+ν)/(2+ν−μ),
    // V = R Ω_y = P (1−μ)/((1+ν) M), the cue ball U − P/M (ν = 2/5).
    let (mu, e, nu) = (0.05, 0.95, 0.4);
    record!(
        "low-speed-limit-mech-no-slip-force",
        "{:.2}",
        3.5 * 0.3 * POOL_MASS * GRAVITY
    );
    let impulse = (1.0 + e) * (1.0 + nu) / (2.0 + nu - mu);
    let object = impulse * (1.0 - mu) / (1.0 + nu);
    let cue = 1.0 - impulse;
    record!(
        "low-speed-limit-mech-rolling-off",
        "{object:.3} U for μ = 0.05, instead of {:.3} U), cue ball `U − P/M` (it rebounds at {cue:.2} U",
        (1.0 + e) / 2.0
    );
    let slow = 1e-4;
    let c = at(SpinKind::Stun, 0.0, slow);
    let o = &c.timed.object_ball;
    let differences = [
        (o.velocity.x / slow - object).abs(),
        (POOL_RADIUS * o.spin.y / slow - object).abs(),
        (c.timed.cue_ball.velocity.x / slow - cue).abs(),
    ];
    record!(
        "low-speed-limit-mech-rolling-off-solver",
        "{:.0e}",
        differences.iter().fold(0.0f64, |a, &b| a.max(b))
    );
    let plateau = |keep: &dyn Fn(f64) -> bool| {
        range(
            rows.iter()
                .filter(|r| keep(r.scenario.cut_deg))
                .map(|r| 100.0 * r.curve[0]),
            0,
        )
    };
    record!(
        "low-speed-limit-mech-plateau",
        "{}",
        plateau(&|cut| cut < 85.0)
    );
    record!(
        "low-speed-limit-mech-plateau-85",
        "{}",
        plateau(&|cut| cut >= 85.0)
    );

    // Between the regimes: slopes of ln(error) against ln U from 0.5 to 2 m/s, the
    // 16 scenarios at μ = 0.05.
    let first = speeds.iter().position(|&u| u >= 0.5).unwrap_or(0);
    let slopes = rows.iter().filter(|r| r.scenario.mu == 0.05).map(|r| {
        let points: Vec<(f64, f64)> = speeds[first..]
            .iter()
            .zip(&r.curve[first..])
            .filter(|(&u, _)| u <= 2.0)
            .map(|(&u, &err)| (u, err))
            .collect();
        log_slope(&points)
    });
    let (steepest, flattest) = bounds(slopes);
    record!(
        "low-speed-limit-mech-slopes",
        "{steepest:.2} to {flattest:.2}"
    );

    // The a-priori estimate: 1 % at U = (100 C g τ₁)^{5/6} (cos φ)^{-1/6}, τ₁ the
    // head-on contact duration at 1 m/s (τ(v) = τ₁ v^{-1/5}).
    let frictionless = Scenario {
        mu: 0.0,
        mu_s: 0.0,
        ..Scenario::pool(SpinKind::Stun, 0.0, 0.0)
    };
    let tau_1 = run(&frictionless, &frictionless.params(), 1.0, fixed)
        .timed
        .duration;
    let estimate = |c: f64, cut_deg: f64| {
        (100.0 * c * GRAVITY * tau_1).powf(5.0 / 6.0) * cut_deg.to_radians().cos().powf(-1.0 / 6.0)
    };
    record!(
        "low-speed-limit-mech-estimate-head-on",
        "{:.2}",
        estimate(1.0, 0.0)
    );
    record!(
        "low-speed-limit-mech-estimate-85",
        "{:.2}",
        estimate(0.75, 85.0)
    );
    let measured = |spin: SpinKind, cut: f64| {
        rows.iter()
            .find(|r| r.scenario.mu == 0.05 && r.scenario.spin == spin && r.scenario.cut_deg == cut)
            .and_then(|r| r.full)
            .map_or(String::from("—"), |u| format!("{u:.3}"))
    };
    record!(
        "low-speed-limit-mech-measured-head-on",
        "{}",
        measured(SpinKind::Roll, 0.0)
    );
    record!(
        "low-speed-limit-mech-measured-85",
        "{}",
        measured(SpinKind::Stun, 85.0)
    );
}
