//! Degenerate and extreme inputs: no panic, no error, finite outputs for every model
//! and the reference; KimGrip continuous across the slide/grip boundary; exact mirror
//! symmetry φ → −φ.

use cuesight::{collide, Impact, Model, Outcome, Params, Regime};
use cuesight_host::reference::{solve, ReferenceConfig, ReferenceParams};
use cuesight_host::validity::{answer, declared};
use glam::DVec3;

const R: f32 = 0.028575;

fn all_models_and_reference(params: &Params, impact: &Impact, what: &str) {
    for model in Model::ALL {
        // Answered, or refused as the model's validity domain declares.
        let Some(out) = answer(params, impact, model, what) else {
            continue;
        };
        assert!(out.is_finite(), "{what}: {model:?} not finite: {out:?}");
        assert!(
            out.throw_angle_deg().is_finite() && out.cue_deflection_deg().is_finite(),
            "{what}: angles"
        );
    }
    let v = impact.velocity();
    let w = impact.spin();
    let r = solve(
        &ReferenceParams::from_core(params),
        DVec3::new(v.x as f64, v.y as f64, 0.0),
        DVec3::new(w.x as f64, w.y as f64, w.z as f64),
        &ReferenceConfig::default(),
    )
    .unwrap_or_else(|e| panic!("{what}: reference -> {e:?}"));
    assert!(
        r.cue_ball.velocity.is_finite() && r.object_ball.spin.is_finite(),
        "{what}: reference not finite"
    );
}

fn spins(speed: f32, cut_deg: f32) -> Vec<(&'static str, [f32; 3])> {
    let (s, c) = (cut_deg.to_radians().sin(), cut_deg.to_radians().cos());
    vec![
        ("zero spin", [0.0, 0.0, 0.0]),
        ("natural roll", [-speed * s / R, speed * c / R, 0.0]),
        ("draw", [speed * s / R, -speed * c / R, 0.0]),
        ("exact gearing", [0.0, 0.0, -speed * s / R]),
        (
            "gearing with topspin",
            [0.0, 0.3 * speed / R, -speed * s / R],
        ),
        ("max side", [0.0, 0.0, 10_000.0]),
    ]
}

#[test]
fn extremes_are_finite_everywhere() {
    let mut count = 0;
    for cut in [0.0f32, 89.9, -89.9, 45.0, 1e-6] {
        for speed in [0.2f32, 2.0, 8.0] {
            for (name, spin) in spins(speed, cut) {
                for (mu, e, mu_s) in [
                    (0.0, 0.95, 0.3),
                    (0.05, 0.0, 0.3),
                    (0.05, 1.0, 0.3),
                    (0.05, 0.95, 0.0),
                    (0.1, 1.0, 0.0),
                ] {
                    let params = Params::new(mu, e, mu_s, R, 0.17).unwrap();
                    let impact = Impact::from_cut_degrees(speed, cut, spin).unwrap();
                    all_models_and_reference(
                        &params,
                        &impact,
                        &format!("{name} cut {cut} U {speed} μ {mu} e {e} μs {mu_s}"),
                    );
                    count += 1;
                }
            }
        }
    }
    assert_eq!(count, 5 * 3 * 6 * 5);
}

#[test]
fn exact_gearing_grips_with_no_friction() {
    // R = 1/32 m and v_y = 1 m/s make R ω_z = −v_y exact in f32: zero initial slip.
    let params = Params::POOL.with_ball(0.03125, 0.17).unwrap();
    let impact = Impact::from_velocity([1.5, 1.0], [3.0, 0.0, -32.0]).unwrap();
    let out = collide(&params, &impact, Model::KimGrip).unwrap();
    assert_eq!(out.regime, Regime::Gripping);
    assert_eq!(out.impulses.friction.y, 0.0);
    assert_eq!(out.impulses.friction.z, 0.0);
}

fn max_difference(a: &Outcome, b: &Outcome, speed: f32) -> f32 {
    let d = |x: cuesight::Vec3, y: cuesight::Vec3| (x - y).length();
    [
        d(a.cue_ball.velocity, b.cue_ball.velocity),
        d(a.object_ball.velocity, b.object_ball.velocity),
        R * d(a.cue_ball.spin, b.cue_ball.spin),
        R * d(a.object_ball.spin, b.object_ball.spin),
    ]
    .into_iter()
    .fold(0.0, f32::max)
        / speed
}

/// For 300 scenes, bisect μ to two adjacent f32 values on either side of the
/// slide/grip boundary: outputs there differ by less than 2e-5 U (a few f32 ulps
/// amplified by the formulas), i.e. no jump.
#[test]
fn kim_grip_is_continuous_across_the_grip_boundary() {
    let grid = cuesight_host::grid::scenes(5, 300);
    let mut crossings = 0;
    let mut worst = 0.0f32;
    for s in &grid {
        let impact = s.impact();
        let regime =
            |mu: f32| collide(&s.params().with_mu(mu).unwrap(), &impact, Model::KimGrip).unwrap();
        // μ up to the edge of KimGrip's validity domain: μ ≤ 1, μ·μ_s ≤ 0.2.
        let (mu_s, limit) = (s.params().mu_s(), cuesight::validity::KIM_GRIP_MAX_MU_MU_S);
        let (mut lo, mut hi) = (
            1e-4f32,
            (limit / mu_s).min(cuesight::validity::KIM_GRIP_MAX_MU),
        );
        while hi * mu_s > limit {
            hi = f32::from_bits(hi.to_bits() - 1);
        }
        if regime(lo).regime == regime(hi).regime {
            continue;
        }
        crossings += 1;
        while f32::from_bits(lo.to_bits() + 1) < hi {
            let mid = 0.5 * (lo + hi);
            let mid = if mid <= lo || mid >= hi {
                f32::from_bits(lo.to_bits() + 1)
            } else {
                mid
            };
            if regime(mid).regime == regime(lo).regime {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (a, b) = (regime(lo), regime(hi));
        assert_ne!(a.regime, b.regime);
        let jump = max_difference(&a, &b, s.speed() as f32);
        worst = worst.max(jump);
        assert!(jump < 2e-5, "jump {jump} at μ = {lo}..{hi} for {s:?}");
    }
    println!("{crossings} boundary crossings, largest jump {worst:e} U");
    cuesight_figures::record!("physics-kim-grip-boundary-crossings", "{crossings}");
    cuesight_figures::record!("physics-kim-grip-boundary-jump", "{worst:.1e}");
    assert!(
        crossings > 100,
        "only {crossings} scenes cross the boundary"
    );
}

/// Mirror y → −y: velocity (x, y, z) → (x, −y, z), angular velocity (a pseudovector)
/// (x, y, z) → (−x, y, −z). Every model must mirror exactly, bit for bit.
/// `KimGrip` changes method where its fast path ends (μ = 0.15, μ_s = 0.4, μ·μ_s = 0.04:
/// the single mid-point direction there, the slide in pieces beyond, `docs/physics.md`
/// §4 item 8): on 200,000 seeded scenes (speeds 0.1–10 m/s, cuts to ±86°, spins to three
/// times rolling, e* 0–1) the answer either side of each edge (adjacent f32 values) moves
/// by less than twice the declared bound (each side is within 0.5 % of U of the
/// reference), and the largest moves are recorded.
#[test]
fn kim_grip_method_edges_move_it_within_its_bound() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let next = |x: f32| f32::from_bits(x.to_bits() + 1);
    let mut worst = [0.0f32; 3];
    for _ in 0..200_000 {
        let speed: f32 = rng.random_range(0.1f32.ln()..=10f32.ln()).exp();
        let cut: f32 = rng.random_range(-1.5..1.5);
        let spin: [f32; 3] = std::array::from_fn(|_| rng.random_range(-3.0..=3.0) * speed / R);
        let restitution: f32 = rng.random_range(0.0..=1.0);
        let impact = Impact::from_velocity([speed * cut.cos(), speed * cut.sin()], spin).unwrap();
        let mu_s: f32 = rng.random_range(0.0..=0.26);
        let mu: f32 = rng.random_range(0.001..=0.1);
        // μ·μ_s = 0.04 at μ = 0.1 (μ_s 0.4) up to 0.15 (μ_s 0.2667).
        let edge_mu = rng.random_range(0.1f32..=0.15);
        let edge_mu_s = 0.04 / edge_mu;
        let edges = [
            ((0.15, mu_s), (next(0.15), mu_s)),
            ((mu, 0.4), (mu, next(0.4))),
            ((edge_mu, edge_mu_s), (edge_mu, next(edge_mu_s))),
        ];
        for (w, (below, above)) in worst.iter_mut().zip(edges) {
            let answer = |(mu, mu_s): (f32, f32)| {
                let params = Params::new(mu, restitution, mu_s, R, 0.17).unwrap();
                collide(&params, &impact, Model::KimGrip).unwrap()
            };
            *w = w.max(max_difference(&answer(below), &answer(above), speed));
        }
    }
    println!(
        "KimGrip's method edges: {:.3} % of U at mu 0.15, {:.3} % at mu_s 0.4, {:.3} % at \
         mu mu_s 0.04",
        100.0 * worst[0],
        100.0 * worst[1],
        100.0 * worst[2]
    );
    cuesight_figures::record!("physics-kimgrip-edge-jump-mu", "{:.2}", 100.0 * worst[0]);
    cuesight_figures::record!("physics-kimgrip-edge-jump-mu-s", "{:.2}", 100.0 * worst[1]);
    cuesight_figures::record!(
        "physics-kimgrip-edge-jump-mu-mu-s",
        "{:.2}",
        100.0 * worst[2]
    );
    for w in worst {
        assert!(w < 2.0 * cuesight::KIM_GRIP_DECLARED_BOUND, "{w}");
    }
}

#[test]
fn mirror_symmetry_is_exact() {
    for s in cuesight_host::grid::scenes(11, 2000) {
        let mirrored = Impact::from_velocity(
            [s.velocity[0], -s.velocity[1]],
            [-s.spin[0], s.spin[1], -s.spin[2]],
        )
        .unwrap();
        for model in Model::ALL {
            let a = collide(&s.params(), &s.impact(), model);
            let b = collide(&s.params(), &mirrored, model);
            // A refusal mirrors too: the same error.
            let (Ok(a), Ok(b)) = (a, b) else {
                assert_eq!(a.err(), b.err(), "{model:?} {s:?}");
                assert!(
                    declared(&s.params(), model, &a.unwrap_err()),
                    "{model:?} {s:?}"
                );
                continue;
            };
            let mirror_v = |v: cuesight::Vec3| cuesight::Vec3::new(v.x, -v.y, v.z);
            let mirror_w = |w: cuesight::Vec3| cuesight::Vec3::new(-w.x, w.y, -w.z);
            assert_eq!(
                mirror_v(a.cue_ball.velocity),
                b.cue_ball.velocity,
                "{model:?} {s:?}"
            );
            assert_eq!(
                mirror_v(a.object_ball.velocity),
                b.object_ball.velocity,
                "{model:?} {s:?}"
            );
            assert_eq!(
                mirror_w(a.cue_ball.spin),
                b.cue_ball.spin,
                "{model:?} {s:?}"
            );
            assert_eq!(
                mirror_w(a.object_ball.spin),
                b.object_ball.spin,
                "{model:?} {s:?}"
            );
            assert_eq!(a.throw_angle_deg(), -b.throw_angle_deg());
            assert_eq!(a.regime, b.regime);
        }
    }
}
