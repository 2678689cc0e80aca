//! The reference solver against exact analytic limits and its own step-size
//! convergence.

use cuesight_host::compare::reference_with;
use cuesight_host::grid::scenes;
use cuesight_host::reference::{solve, ReferenceConfig, ReferenceParams, ReferenceRegime};
use glam::DVec3;

fn params(mu: f64, restitution: f64, mu_s: f64) -> ReferenceParams {
    ReferenceParams::constant(mu, restitution, mu_s, 0.028575, 0.17)
}

/// Halving the step changes no output by more than 1e-6 relative (velocities to U,
/// spins to U/R), on 300 grid scenes of every spin kind.
#[test]
fn step_size_convergence() {
    let coarse = ReferenceConfig::default();
    let fine = ReferenceConfig {
        steps: 2 * coarse.steps,
        ..coarse
    };
    let mut worst = 0.0f64;
    for scene in scenes(99, 300) {
        let a = reference_with(&scene, &coarse).unwrap();
        let b = reference_with(&scene, &fine).unwrap();
        let r = scene.radius as f64;
        let change = [
            a.cue_ball.velocity.distance(b.cue_ball.velocity),
            a.object_ball.velocity.distance(b.object_ball.velocity),
            r * a.cue_ball.spin.distance(b.cue_ball.spin),
            r * a.object_ball.spin.distance(b.object_ball.spin),
        ]
        .into_iter()
        .fold(0.0, f64::max)
            / scene.speed();
        worst = worst.max(change);
    }
    println!("largest change when halving the step: {worst:.3e}");
    cuesight_figures::record!("physics-reference-step-halving", "{worst:.1e}");
    assert!(worst < 1e-6, "step-size change {worst}");
}

/// μ = 0: the exact inelastic result for equal spheres (normal velocity shared with
/// Newton's e, which equals Stronge's energetic e* without friction), spins untouched.
#[test]
fn frictionless_is_the_exact_inelastic_result() {
    for (e, mu_s) in [(0.0, 0.3), (0.5, 0.0), (0.95, 0.4), (1.0, 0.2)] {
        let v = DVec3::new(1.7, -0.8, 0.0);
        let w = DVec3::new(10.0, 40.0, -25.0);
        let out = solve(&params(0.0, e, mu_s), v, w, &ReferenceConfig::default()).unwrap();
        assert_eq!(out.regime, ReferenceRegime::Frictionless);
        let expect_cue = DVec3::new(v.x * (1.0 - e) / 2.0, v.y, 0.0);
        let expect_object = DVec3::new(v.x * (1.0 + e) / 2.0, 0.0, 0.0);
        assert!(
            out.cue_ball.velocity.distance(expect_cue) < 1e-12,
            "{:?}",
            out.cue_ball.velocity
        );
        assert!(out.object_ball.velocity.distance(expect_object) < 1e-12);
        assert!(out.cue_ball.spin.distance(w) < 1e-12);
        assert!(out.object_ball.spin.length() < 1e-12);
    }
}

/// Peskin limit (μ_s = 0, e* = 1), head-on natural roll: the slip stays vertical, so
/// the first-order results are exact: U_f = (0, 0, μU), V_f = (U, 0, 0),
/// ω_y = (U/R)(1 − μ/ν), Ω_y = −(μ/ν)(U/R).
#[test]
fn peskin_limit_head_on_roll() {
    let (mu, u, r) = (0.06, 2.5, 0.028575);
    let out = solve(
        &params(mu, 1.0, 0.0),
        DVec3::new(u, 0.0, 0.0),
        DVec3::new(0.0, u / r, 0.0),
        &ReferenceConfig::default(),
    )
    .unwrap();
    assert_eq!(out.regime, ReferenceRegime::Sliding);
    let tol = 1e-9 * u;
    assert!(
        out.cue_ball.velocity.distance(DVec3::new(0.0, 0.0, mu * u)) < tol,
        "{:?}",
        out.cue_ball.velocity
    );
    assert!(out.object_ball.velocity.distance(DVec3::new(u, 0.0, 0.0)) < tol);
    assert!((out.cue_ball.spin.y - u / r * (1.0 - mu / 0.4)).abs() * r < tol);
    assert!((out.object_ball.spin.y + mu / 0.4 * u / r).abs() * r < tol);
}

/// A stun shot slides along y only, with the exact sliding result; with near-zero
/// initial slip the contact grips and the friction impulse is exactly the one that
/// cancels the slip (y: M v_y0 / 7).
#[test]
fn stick_cap_is_one_seventh_of_the_slip() {
    let (u, cut) = (2.0f64, 3.0f64.to_radians());
    let v = DVec3::new(u * cut.cos(), u * cut.sin(), 0.0);
    let out = solve(
        &params(0.08, 0.95, 0.3),
        v,
        DVec3::ZERO,
        &ReferenceConfig::default(),
    )
    .unwrap();
    assert_eq!(out.regime, ReferenceRegime::Gripping);
    let slip_y = -v.y;
    assert!(
        (out.friction_impulse.y - (-0.17 * slip_y / 7.0)).abs() < 1e-12,
        "{:?}",
        out.friction_impulse
    );
    // And the final tangential slip is zero: (V_y − R Ω_z) − (U_y + R ω_z) = 0.
    let r = 0.028575;
    let slip_after = out.object_ball.velocity.y
        - r * out.object_ball.spin.z
        - out.cue_ball.velocity.y
        - r * out.cue_ball.spin.z;
    assert!(slip_after.abs() < 1e-10, "slip after {slip_after}");
}

/// Restitution bounds: e* = 0 ends the impact at maximum compression (equal normal
/// velocities); e* = 1 with μ = 0 conserves energy exactly.
#[test]
fn restitution_extremes() {
    let v = DVec3::new(2.0, 0.5, 0.0);
    let w = DVec3::new(0.0, 30.0, 10.0);
    let out = solve(&params(0.05, 0.0, 0.3), v, w, &ReferenceConfig::default()).unwrap();
    let relative_normal = out.object_ball.velocity.x - out.cue_ball.velocity.x;
    assert!(
        relative_normal.abs() < 1e-9,
        "e=0 leaves normal relative velocity {relative_normal}"
    );
    let out = solve(&params(0.0, 1.0, 0.3), v, w, &ReferenceConfig::default()).unwrap();
    let before = 0.5 * 0.17 * v.length_squared()
        + 0.5 * 0.4 * 0.17 * 0.028575f64.powi(2) * w.length_squared();
    assert!((out.kinetic_energy(0.17, 0.028575) - before).abs() < 1e-12 * before);
}
