use super::*;
use crate::friction::FrictionLaw;
use crate::kim_grip::speed_path;
use crate::kim_grip::straight::general;

/// The speed-dependent fast path (`speed_path`, f32) against the straight general path's
/// Newton solution of the same equations in f64 (`straight`, its test oracle), on 20,000 scenes with laws `μ(v) = a + b e^{−cv}`
/// inside `KimGrip`'s validity domain.
#[cfg(feature = "speed-path")]
#[test]
fn speed_path_agrees_with_the_straight_general_path() {
    extern crate std;
    let mut uniform = crate::kim_grip::tests::uniform_from(0x2545_f491_4f6c_dd1d);
    let (mut checked, mut regime_differs, mut sliding) = (0, 0, 0);
    let (mut worst, mut worst_general32) = (0.0f32, 0.0f32);
    for _ in 0..20_000 {
        let a = uniform(1e-3, 0.05);
        let b = uniform(1e-3, crate::kim_grip::CURVED_MIN_MU - a);
        let c = uniform(0.05, 5.0);
        let law = FrictionLaw::speed_dependent(a, b, c).unwrap();
        let mu_s = uniform(
            0.0,
            (crate::kim_grip::CURVED_MIN_MU_MU_S / (a + b)).min(crate::kim_grip::CURVED_MIN_MU_S),
        );
        let params = Params::new(0.05, uniform(0.0, 1.0), mu_s, 0.028575, 0.17)
            .unwrap()
            .with_friction_law(law);
        let speed = uniform(0.01, 8.0);
        let cut = uniform(-1.5, 1.5);
        // Spins from 3e-4 to 300 rad/s (log-uniform size): large slips slide, small
        // grip; with a cut near 0 the slip goes down to 1e-5 m/s.
        let size = crate::math::exp(uniform(-13.8, 0.0));
        let spin = [
            size * uniform(-300.0, 300.0),
            size * uniform(-300.0, 300.0),
            size * uniform(-300.0, 300.0),
        ];
        let impact = Impact::from_velocity(
            [speed * crate::math::cos(cut), speed * crate::math::sin(cut)],
            spin,
        )
        .unwrap();
        let Some(fast) = speed_path::collide(&params, &impact) else {
            continue;
        };
        let reference = general::<f64>(&params, &impact).unwrap();
        let general32 = general::<f32>(&params, &impact).unwrap();
        let scale = impact.speed().max(params.radius() * impact.spin().length());
        let difference = |x: &Outcome, y: &Outcome| {
            let mut worst = 0.0f32;
            for (p, q) in [(x.cue_ball, y.cue_ball), (x.object_ball, y.object_ball)] {
                worst = worst
                    .max((p.velocity - q.velocity).length() / scale)
                    .max(params.radius() * (p.spin - q.spin).length() / scale);
            }
            worst
        };
        checked += 1;
        sliding += usize::from(fast.regime == Regime::Sliding);
        worst = worst.max(difference(&fast, &reference));
        worst_general32 = worst_general32.max(difference(&general32, &reference));
        regime_differs += usize::from(fast.regime != reference.regime);
    }
    std::println!(
        "speed path: {checked} scenes ({sliding} sliding), worst {worst:e} of the larger of U \
         and R|ω| from the f64 general path (the f32 general path: {worst_general32:e}); \
         regime differs in {regime_differs}"
    );
    cuesight_figures::record!("physics-speed-path-vs-general", "{worst:.1e}");
    cuesight_figures::record!(
        "physics-speed-path-general32-vs-general",
        "{worst_general32:.1e}"
    );
    assert!(
        checked > 14_000,
        "speed path taken in only {checked} scenes"
    );
    assert!(
        sliding > 1_000 && checked - sliding > 1_000,
        "{sliding} of {checked} sliding"
    );
    // Closer to the f64 solution than the general path's own f32 evaluation (1.95e-6).
    assert!(
        worst <= 5e-7,
        "speed path and f64 general path differ by {worst:e}"
    );
    assert!(
        regime_differs <= 2,
        "regime differs in {regime_differs} scenes"
    );
}

/// Which branch of the speed-dependent fast path each `mu-v-*` shot of
/// `bench-firmware/src/bin/kimgrip_count.rs` takes, decided here in f64 from the closed
/// form (`speed_path` module docs) with TP A.14's law and the pool parameters; the
/// general-path shot `speed-dependent-mu` lies beyond the path's range.
#[cfg(feature = "speed-path")]
#[test]
fn speed_gate_shots_take_their_branches() {
    extern crate std;
    let shots: [(&str, &str, [f32; 2], [f32; 3]); 9] = [
        (
            "mu-v-topspin-slides",
            "slides",
            [2.0, 0.0],
            [0.0, 70.0, 0.0],
        ),
        (
            "mu-v-topspin-grips-restitution",
            "certain-restitution",
            [5.0, 0.0],
            [0.0, 40.0, 0.0],
        ),
        (
            "mu-v-topspin-grips-compression",
            "certain-compression",
            [8.0, 0.0],
            [0.0, 40.0, 0.0],
        ),
        (
            "mu-v-topspin-band-grips",
            "band",
            [3.4, 0.0],
            [0.0, 40.0, 0.0],
        ),
        (
            "mu-v-topspin-band-grips-small-slip",
            "band",
            [2.0, 0.0],
            [0.0, 28.13, 0.0],
        ),
        (
            "mu-v-stun-cut-slides",
            "slides",
            [1.732, 1.0],
            [0.0, 0.0, 0.0],
        ),
        (
            "mu-v-draw-grips-restitution",
            "restitution",
            [4.4, 0.0],
            [0.0, -40.0, 0.0],
        ),
        (
            "mu-v-draw-grips-compression",
            "compression",
            [8.0, 0.0],
            [0.0, -40.0, 0.0],
        ),
        (
            "speed-dependent-mu",
            "general",
            [16.0, 3.0],
            [0.0, 30.0, 0.0],
        ),
    ];
    let params = Params::POOL.with_friction_law(FrictionLaw::MARLOW);
    let FrictionLaw::SpeedDependent { a, b, c } = FrictionLaw::MARLOW else {
        unreachable!()
    };
    let (a, b, c) = (f64::from(a), f64::from(b), f64::from(c));
    let (e, mu_s, radius) = (
        f64::from(params.restitution()),
        f64::from(params.mu_s()),
        f64::from(params.radius()),
    );
    for (label, expected, v, w) in shots {
        let impact = Impact::from_velocity(v, w).unwrap();
        let outcome = speed_path::collide(&params, &impact);
        let approach = f64::from(v[0]);
        let slip_y = -f64::from(v[1]) - radius * f64::from(w[2]);
        let slip_z = radius * f64::from(w[1]);
        let pressed = slip_z > 0.0;
        let k_z = if pressed { 6.0 - 2.5 * mu_s } else { 6.0 };
        let slip = slip_y.hypot(slip_z);
        let stick = (slip_y / 7.0).hypot(slip_z / k_z);
        let decay = c * slip / stick;
        let mu0 = a + b * (-c * slip).exp();
        let grip_progress = -(-c * slip).exp_m1();
        // y(p) and p* in f64 (module docs).
        let progress = |p: f64| mu0 / a * -(-a * decay * p).exp_m1();
        let grip = -(-(a / mu0) * grip_progress).ln_1p() / (a * decay);
        let first = 0.5 * (1.0 + e) * approach;
        let branch = if a * decay * first > 1.0 {
            "general"
        } else if !pressed {
            if progress(first) < grip_progress {
                "slides"
            } else if grip >= approach / 2.0 {
                "restitution"
            } else {
                "compression"
            }
        } else if progress(first) >= grip_progress {
            let rho = mu_s * (slip_z / k_z / stick) * stick / grip;
            if grip >= approach / (2.0 - rho) {
                "certain-restitution"
            } else {
                "certain-compression"
            }
        } else {
            let budget = -(-progress(first)).ln_1p() / decay;
            let (start, end) = (slip_z / slip, slip_z / k_z / stick);
            let rho = mu_s * (start + budget / stick * (end - start)) * budget / first;
            if progress(first / (1.0 - 0.5 * rho)) < grip_progress {
                "slides"
            } else {
                "band"
            }
        };
        assert_eq!(branch, expected, "{label}");
        // The exponential's branch (c v₀ > 1), but for the one shot that shows φ's.
        assert_eq!(c * slip > 1.0, !label.ends_with("small-slip"), "{label}");
        match outcome {
            None => assert_eq!(branch, "general", "{label}: declined"),
            Some(outcome) => assert_eq!(
                outcome.regime == Regime::Sliding,
                branch == "slides",
                "{label}: {:?}",
                outcome.regime
            ),
        }
    }
}
