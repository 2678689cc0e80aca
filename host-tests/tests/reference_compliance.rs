//! The reference solver's compliant contact (`ReferenceConfig::tangential_stiffness`,
//! issue 19 deliverable 3) against what the physics fixes: the closed form of a stuck
//! linear spring contact, energy, and the rigid and frictionless limits. No expected
//! value comes from the solver itself.

use cuesight_host::reference::{solve, ReferenceConfig, ReferenceOutcome, ReferenceParams};
use glam::DVec3;

const R: f64 = 0.028575;
const M: f64 = 0.17;

fn compliant(kappa: f64) -> ReferenceConfig {
    ReferenceConfig {
        tangential_stiffness: Some(kappa),
        ..ReferenceConfig::default()
    }
}

fn stun(
    params: &ReferenceParams,
    speed: f64,
    cut_deg: f64,
    config: &ReferenceConfig,
) -> ReferenceOutcome {
    let phi = cut_deg.to_radians();
    let v = DVec3::new(speed * phi.cos(), speed * phi.sin(), 0.0);
    solve(params, v, DVec3::ZERO, config).unwrap()
}

/// κ for a frequency ratio η = ω_t/ω_n: η² = 7κ/2 (module docs of
/// `reference/compliant.rs`: ω_t² = 7 k_t/M, ω_n² = 2 k_n/M).
fn kappa_for(eta: f64) -> f64 {
    2.0 * eta * eta / 7.0
}

/// A stuck contact with e* = 1 returns the tangential relative velocity as
/// `v_t0 cos(π η)`; at η = 1 it is reversed (β = 1), so the object ball gets twice
/// the gripping impulse: `V_y = 2 U sin φ / 7`, `V_x = U cos φ`, throw
/// `atan(2 tan φ / 7)` — twice the rigid ceiling's tangent `tan φ / 7` at e* = 1. The
/// slider sticks throughout when μ ≥ κ tan φ (`|u|/F` is constant at η = 1).
#[test]
fn eta_one_reverses_the_slip_and_doubles_the_rigid_ceiling() {
    let params = ReferenceParams::constant(0.5, 1.0, 0.3, R, M);
    // docs/calibration.md §7's checks: the throws, closed form and solver, and the
    // largest relative change of kinetic energy.
    let (mut throws, mut closed_forms, mut energy) = (Vec::new(), Vec::new(), 0.0_f64);
    for cut in [10.0_f64, 20.0, 30.0] {
        let out = stun(&params, 2.0, cut, &compliant(kappa_for(1.0)));
        let t = f64::to_radians(cut).tan();
        let expected = (2.0 * t / 7.0).atan().to_degrees();
        let rigid_ceiling = (t / 7.0).atan().to_degrees();
        println!(
            "cut {cut}: throw {:.5} deg, closed form {expected:.5}, rigid ceiling {rigid_ceiling:.5}",
            out.throw_angle_deg()
        );
        assert!((out.throw_angle_deg() - expected).abs() < 1e-3, "{cut}");
        let v = out.object_ball.velocity;
        let phi = f64::to_radians(cut);
        assert!(
            (v.y - 2.0 * 2.0 * phi.sin() / 7.0).abs() < 1e-4 * 2.0,
            "{v:?}"
        );
        // No slider motion: the springs are conservative and e* = 1, so no energy is lost.
        let before = 0.5 * M * 4.0;
        let after = out.kinetic_energy(M, R);
        // (Störmer–Verlet at ω_t dt ≤ 0.01: second-order error ~1e-5.)
        assert!((after - before).abs() < 1e-5 * before, "{before} {after}");
        throws.push(format!("{:.5}°", out.throw_angle_deg()));
        closed_forms.push(format!("{expected:.5}°"));
        energy = energy.max((after - before).abs() / before);
    }
    cuesight_figures::record!(
        "calibration-compliance-eta-1-throw",
        "{}",
        throws.join(" / ")
    );
    cuesight_figures::record!(
        "calibration-compliance-eta-1-closed-form",
        "{}",
        closed_forms.join(" / ")
    );
    cuesight_figures::record!("calibration-compliance-eta-1-energy", "{energy:.1e}");
}

/// At η = 2 the stuck tangential oscillator makes a whole period over the impact
/// (e* = 1): `v_t(T) = v_t0`, no net tangential impulse, no throw (μ ≥ κ tan φ keeps
/// it stuck: `|u|/F ≤ κ tan φ`).
#[test]
fn eta_two_gives_no_net_friction_impulse() {
    let params = ReferenceParams::constant(1.0, 1.0, 0.3, R, M);
    let mut worst = 0.0_f64;
    for cut in [10.0_f64, 20.0, 30.0] {
        let out = stun(&params, 3.0, cut, &compliant(kappa_for(2.0)));
        println!("cut {cut}: throw {:.6} deg", out.throw_angle_deg());
        worst = worst.max(out.throw_angle_deg().abs());
        assert!(
            out.throw_angle_deg().abs() < 2e-3,
            "{cut}: {}",
            out.throw_angle_deg()
        );
    }
    cuesight_figures::record!("calibration-compliance-eta-2-throw", "{worst:.0e}");
}

/// With e* < 1 the restitution spring is stiffer (`k_n/e*²`): the impact lasts
/// `T = (π/2)(1 + e*)/ω_n`, and a stuck contact leaves `v_t(T) = v_t0 cos(η π (1 + e*)/2)`.
/// The spring is unloaded at the end (so the slider can stick throughout) where
/// `η (1 + e*)/2` is a whole number: at e* = 0.5, η = 4/3 reverses the slip
/// (`V_y = 2 U sin φ / 7` whatever e*), η = 8/3 gives no net tangential impulse; with
/// e* = 1, η = 3 reverses it again.
#[test]
fn stuck_contact_follows_the_tangential_restitution_closed_form() {
    let cut: f64 = 15.0;
    let phi = cut.to_radians();
    let speed = 2.0;
    let (mut solver, mut closed_forms) = (Vec::new(), Vec::new());
    for (e, eta) in [(0.5, 4.0 / 3.0), (0.5, 8.0 / 3.0), (1.0, 3.0)] {
        let params = ReferenceParams::constant(5.0, e, 0.3, R, M);
        let out = stun(&params, speed, cut, &compliant(kappa_for(eta)));
        let beta = -(std::f64::consts::PI * eta * (1.0 + e) / 2.0).cos();
        // Slip change per tangential impulse 7/M: V_y = (1 + β) v_t0 / 7.
        let expected = (1.0 + beta) * speed * phi.sin() / 7.0;
        let vy = out.object_ball.velocity.y;
        println!("e* {e}, eta {eta:.4}: V_y {vy:.6} m/s, closed form {expected:.6}");
        assert!(
            (vy - expected).abs() < 2e-4 * speed,
            "{e} {eta}: {vy} {expected}"
        );
        // The normal impulse is the rigid one: V_x = (1 + e*) U cos φ / 2.
        let vx = out.object_ball.velocity.x;
        assert!(
            (vx - 0.5 * (1.0 + e) * speed * phi.cos()).abs() < 1e-9 * speed,
            "{vx}"
        );
        solver.push(format!("{vy:.6}"));
        closed_forms.push(format!("{expected:.6}"));
    }
    cuesight_figures::record!("calibration-compliance-stuck-vy", "{}", solver.join(" / "));
    cuesight_figures::record!(
        "calibration-compliance-stuck-closed-form",
        "{}",
        closed_forms.join(" / ")
    );
}

fn scenes() -> Vec<(DVec3, DVec3)> {
    let mut out = Vec::new();
    for (speed, cut) in [(1.0, 5.0), (2.0, 20.0), (3.0, 45.0), (5.0, 60.0)] {
        let phi: f64 = f64::to_radians(cut);
        let v = DVec3::new(speed * phi.cos(), speed * phi.sin(), 0.0);
        for spin in [
            DVec3::ZERO,
            DVec3::new(0.0, speed / R, 0.0),
            DVec3::new(0.0, -speed / R, 0.0),
            DVec3::new(0.0, 0.0, 0.5 * speed / R),
        ] {
            out.push((v, spin));
        }
    }
    out
}

/// κ → ∞ is the rigid contact: the stored tangential energy `(μF)²/(2 k_t)` and the
/// slip oscillation after sticking vanish as 1/√κ.
#[test]
fn stiff_tangential_spring_is_the_rigid_contact() {
    let params = ReferenceParams {
        mu_b: 0.1,
        mu_c: 0.44,
        ..ReferenceParams::constant(0.02, 0.95, 0.3, R, M)
    };
    let mut worst = [0.0f64; 2];
    for (v, w) in scenes() {
        let rigid = solve(&params, v, w, &ReferenceConfig::default()).unwrap();
        for (k, kappa) in [1e2, 1e4].into_iter().enumerate() {
            let c = solve(&params, v, w, &compliant(kappa)).unwrap();
            let dv = (c.object_ball.velocity - rigid.object_ball.velocity).length()
                + (c.cue_ball.velocity - rigid.cue_ball.velocity).length();
            worst[k] = worst[k].max(dv / v.length());
        }
    }
    println!(
        "largest velocity difference / U: kappa 1e2 {:.2e}, 1e4 {:.2e}",
        worst[0], worst[1]
    );
    cuesight_figures::record!("calibration-compliance-scenes", "{}", scenes().len());
    cuesight_figures::record!("calibration-compliance-kappa-1e4", "{:.1e}", worst[1]);
    cuesight_figures::record!("calibration-compliance-kappa-1e2", "{:.1e}", worst[0]);
    assert!(worst[1] < 2e-3, "{worst:?}");
    assert!(worst[1] < 0.3 * worst[0], "{worst:?}");
}

/// Without friction the tangential spring carries no force: the compliant contact is
/// the rigid frictionless one.
#[test]
fn frictionless_compliant_contact_is_the_rigid_one() {
    let params = ReferenceParams::constant(0.0, 0.9, 0.3, R, M);
    for (v, w) in scenes() {
        let rigid = solve(&params, v, w, &ReferenceConfig::default()).unwrap();
        let c = solve(&params, v, w, &compliant(0.7)).unwrap();
        let dv = (c.object_ball.velocity - rigid.object_ball.velocity).length();
        assert!(dv < 1e-9 * v.length(), "{v:?} {w:?}: {dv}");
        assert_eq!(c.object_ball.spin, DVec3::ZERO);
    }
}

/// Energy is never created (e* ≤ 1, the slider dissipates), over a spread of κ.
#[test]
fn compliant_contact_creates_no_energy() {
    let params = ReferenceParams {
        mu_b: 0.1,
        mu_c: 0.44,
        ..ReferenceParams::constant(0.05, 0.95, 0.3, R, M)
    };
    for (v, w) in scenes() {
        let before = 0.5 * M * v.length_squared() + 0.5 * 0.4 * M * R * R * w.length_squared();
        for kappa in [0.05, 0.1, 0.3, 0.7, 2.0, 10.0] {
            let c = solve(&params, v, w, &compliant(kappa)).unwrap();
            let after = c.kinetic_energy(M, R);
            assert!(
                after <= before * (1.0 + 1e-6),
                "{kappa} {v:?} {w:?}: {before} -> {after}"
            );
        }
    }
}

#[test]
fn a_bad_tangential_stiffness_is_refused() {
    let params = ReferenceParams::constant(0.05, 0.95, 0.3, R, M);
    for kappa in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let out = solve(
            &params,
            DVec3::new(1.0, 0.2, 0.0),
            DVec3::ZERO,
            &compliant(kappa),
        );
        assert!(out.is_err(), "{kappa}");
    }
}
