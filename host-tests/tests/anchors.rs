//! Published anchors (physics-notes §6 and erratum E1), checked against the reference
//! solver and the closed-form models. Expected values are the published numbers.

use cuesight::{collide, Impact, Model, Params};
use cuesight_host::reference::{solve, ReferenceConfig, ReferenceOutcome, ReferenceParams};
use glam::DVec3;

const G: f64 = 9.81;

fn reference(params: &Params, impact: &Impact) -> ReferenceOutcome {
    let v = impact.velocity();
    let w = impact.spin();
    solve(
        &ReferenceParams::from_core(params),
        DVec3::new(v.x as f64, v.y as f64, 0.0),
        DVec3::new(w.x as f64, w.y as f64, w.z as f64),
        &ReferenceConfig::default(),
    )
    .unwrap()
}

fn close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{what}: {actual} vs expected {expected} (± {tolerance})"
    );
}

/// Erratum E1 example: head-on natural roll, U = 2 m/s, R = 28.6 mm, M = 0.17 kg,
/// μ = 0.05, e* = 0.95, μ_s = 0.3 → object-ball Ω_y ≈ −6.0 rad/s (the paper's sign
/// gives −11.1).
#[test]
fn erratum_e1_object_ball_spin() {
    let params = Params::new(0.05, 0.95, 0.3, 0.0286, 0.17).unwrap();
    let impact = Impact::rolling([2.0, 0.0], 0.0286).unwrap();
    let r = reference(&params, &impact);
    close(r.object_ball.spin.y, -6.0, 0.05, "reference Ω_y");
    cuesight_figures::record!(
        "physics-e1-reference-spin",
        "{}",
        format!("{:.2}", r.object_ball.spin.y).replace('-', "−")
    );
    for model in [Model::Kim, Model::KimGrip] {
        let out = collide(&params, &impact, model).unwrap();
        close(out.object_ball.spin.y as f64, -6.0, 0.05, model.name());
        cuesight_figures::record!(
            &format!("physics-e1-{}-spin", model.name()),
            "{}",
            format!("{:.2}", out.object_ball.spin.y).replace('-', "−")
        );
        assert!(
            (out.object_ball.spin.y as f64 + 11.1).abs() > 4.0,
            "{model:?} reproduces the uncorrected sign"
        );
    }
}

/// TP A.5: φ = 30°, e = 0.94, μ = 0.06, stun: cue-ball deviation 3.307°, throw 3.434°,
/// separation 83.259°.
#[test]
fn tp_a5_stun_cut() {
    let params = Params::new(0.06, 0.94, 0.3, 0.028575, 0.17).unwrap();
    let impact = Impact::from_cut_degrees(1.0, 30.0, [0.0; 3]).unwrap();
    let r = reference(&params, &impact);
    close(r.cue_deflection_deg(), 3.307, 0.0015, "reference deviation");
    close(r.throw_angle_deg(), 3.434, 0.0015, "reference throw");
    for model in [Model::Kim, Model::KimGrip] {
        let out = collide(&params, &impact, model).unwrap();
        close(out.cue_deflection_deg() as f64, 3.307, 0.0015, "deviation");
        close(out.throw_angle_deg() as f64, 3.434, 0.0015, "throw");
        close(
            out.separation_angle_deg() as f64,
            83.259,
            0.002,
            "separation",
        );
    }
}

/// Seed §5, μ = 0: cue-ball deviation tan⁻¹[cot φ (1 − e)/2]: 45° → 2.29° (e = 0.92),
/// 0.573° (e = 0.98); 30° → 3.96°, 0.99°; 10°, e = 0.92 → ≈ 12.8°.
#[test]
fn seed_frictionless_deviation_table() {
    for (cut, e, expected, tolerance) in [
        (45.0, 0.92, 2.29, 0.005),
        (45.0, 0.98, 0.573, 0.001),
        (30.0, 0.92, 3.96, 0.005),
        (30.0, 0.98, 0.99, 0.005),
        (10.0, 0.92, 12.8, 0.05),
    ] {
        let params = Params::new(0.0, e, 0.3, 0.028575, 0.17).unwrap();
        let impact = Impact::from_cut_degrees(2.0, cut, [0.0, 30.0, 0.0]).unwrap();
        close(
            reference(&params, &impact).cue_deflection_deg(),
            expected,
            tolerance,
            "reference",
        );
        for model in [Model::Kim, Model::KimGrip] {
            let out = collide(&params, &impact, model).unwrap();
            close(
                out.cue_deflection_deg() as f64,
                expected,
                tolerance,
                model.name(),
            );
        }
    }
}

/// Seed eq. (3) text: hop height h = μ² U² / (2g): U = 10 m/s, μ = 0.05 → 1.27 cm
/// (head-on natural roll, e = 1; TP B.5: v_z = μ(1 + e)U/2). Both are leading-order
/// estimates without table friction, so μ_s = 0 here; the object-ball table friction
/// raises the normal impulse and the hop speed by the factor (1 + μ μ_s / 2).
#[test]
fn hop_height() {
    let params = Params::new(0.05, 1.0, 0.0, 0.028575, 0.17).unwrap();
    let impact = Impact::rolling([10.0, 0.0], 0.028575).unwrap();
    let r = reference(&params, &impact);
    let height = r.cue_ball.velocity.z.powi(2) / (2.0 * G);
    close(height * 100.0, 1.27, 0.005, "reference hop height (cm)");
    cuesight_figures::record!("physics-hop-height", "{:.3}", height * 100.0);
    for e in [0.9f32, 0.95] {
        let params = params.with_restitution(e).unwrap();
        let r = reference(&params, &impact);
        close(
            r.cue_ball.velocity.z,
            0.05 * (1.0 + e as f64) * 10.0 / 2.0,
            1e-7,
            "TP B.5 hop speed",
        );
    }
    let with_table = reference(&params.with_mu_s(0.3).unwrap(), &impact);
    cuesight_figures::record!(
        "physics-hop-height-with-table",
        "{:.2}",
        with_table.cue_ball.velocity.z.powi(2) / (2.0 * G) * 100.0
    );
    close(
        with_table.cue_ball.velocity.z,
        0.5 * (1.0 + 0.05 * 0.3 / 2.0),
        2e-4,
        "hop speed with μ_s",
    );
}

/// Seed §5: head-on natural roll, e = 1: U_f ≈ μU(−μ_s/2, 0, 1), V_f ≈ U(1 − μμ_s/2, 0, 0)
/// (first order in μ: the reference agrees to the next order, μ² μ_s U).
#[test]
fn head_on_roll_first_order() {
    let (mu, mu_s, u) = (0.05, 0.3, 3.0);
    let params = Params::new(mu as f32, 1.0, mu_s as f32, 0.028575, 0.17).unwrap();
    let impact = Impact::rolling([u as f32, 0.0], 0.028575).unwrap();
    let r = reference(&params, &impact);
    let next_order = mu * mu * mu_s * u;
    close(
        r.cue_ball.velocity.x,
        -mu * mu_s / 2.0 * u,
        next_order,
        "U_x",
    );
    close(r.cue_ball.velocity.z, mu * u, next_order, "U_z");
    close(
        r.object_ball.velocity.x,
        (1.0 - mu * mu_s / 2.0) * u,
        next_order,
        "V_x",
    );
    close(
        r.object_ball.velocity.y.abs() + r.object_ball.velocity.z.abs(),
        0.0,
        1e-12,
        "V_y, V_z",
    );
}
