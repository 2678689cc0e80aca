use super::*;
use crate::friction::FrictionLaw;
use crate::outcome::Regime;

/// A friction law built from the enum's variant bypasses `FrictionLaw::constant`'s
/// range check; the fast path's guard assumes μ ≤ 1, so such laws take the general
/// path, whose guard reports the error (found by the `collide` fuzz target: μ = ∞
/// gave a NaN velocity through the fast path).
#[test]
fn unvalidated_friction_never_gives_a_non_finite_outcome() {
    extern crate std;
    let impacts = [
        // Topspin (object ball pressed), stun with side spin, draw.
        Impact::from_velocity([2.0, -10.0], [340.9, 68.6, 0.0]),
        Impact::from_velocity([2.0, 0.3], [0.0, -20.0, 10.0]),
        Impact::from_velocity([3.0, 0.0], [0.0, -90.0, 0.0]),
    ];
    // The last laws: speed-dependent ones outside the validated ranges (the `collide`
    // fuzz target's crash-10fb3cbe: a = −0.92 through the speed-dependent fast path
    // gave an infinite velocity).
    let laws = [f32::INFINITY, 1e30, 1.5, f32::NAN, -0.5, f32::MIN_POSITIVE]
        .map(FrictionLaw::Constant)
        .into_iter()
        .chain([
            FrictionLaw::SpeedDependent {
                a: -0.922_656_24,
                b: 1.248_962_7e-37,
                c: 32.0,
            },
            FrictionLaw::SpeedDependent {
                a: 0.01,
                b: 0.1,
                c: 1e3,
            },
            FrictionLaw::SpeedDependent {
                a: 1e-9,
                b: 0.1,
                c: 1.0,
            },
            FrictionLaw::SpeedDependent {
                a: 0.01,
                b: f32::NAN,
                c: 1.0,
            },
        ]);
    let impacts = impacts.into_iter().chain([Impact::from_velocity(
        [6.666_666_5, 2.438_196_8e-9],
        [40.0, 4.656_613e-8, 0.0],
    )]);
    let impacts: std::vec::Vec<_> = impacts.collect();
    // The pool defaults, and the crash's own parameters.
    let crash = Params::new(0.05, 1.0, 0.079_998_925, 0.04, 0.100_000_08).unwrap();
    for (mu, params) in laws.flat_map(|law| {
        [
            (law, Params::POOL.with_friction_law(law)),
            (law, crash.with_friction_law(law)),
        ]
    }) {
        for impact in &impacts {
            let impact = impact.as_ref().expect("valid impact");
            let results = [
                collide::<f32>(&params, impact),
                collide::<f64>(&params, impact),
            ];
            for outcome in results.iter().flatten() {
                assert!(outcome.is_finite(), "{mu:?}: {outcome:?}");
            }
        }
    }
}

/// The fast path's topspin branch has no zero-length branch for the table-contact
/// slip: a slip whose square underflows (a vanishing approach speed) gives an
/// infinite or NaN table friction there, which its guard must hand to the general
/// path. Without that guard these scenes come out NaN.
#[test]
fn underflowing_table_slip_takes_the_general_path() {
    let params = Params::POOL;
    let mut declined = 0;
    for approach in [f32::from_bits(1), 1e-44, 1e-40, 1e-38, 1e-30, 1e-22, 1e-19] {
        for side in [0.0, 1e-30, 0.5] {
            // Topspin: the object ball is pressed into the cloth.
            let impact =
                Impact::from_velocity([approach, side], [0.0, 70.0, 0.0]).expect("valid impact");
            let fast = fast_path::collide::<f32>(&params, &impact);
            if let Some(outcome) = fast {
                assert!(outcome.is_finite(), "a = {approach:e}: {outcome:?}");
            } else {
                declined += 1;
            }
            let outcome = collide::<f32>(&params, &impact).expect("a finite outcome");
            assert!(outcome.is_finite(), "a = {approach:e}: {outcome:?}");
        }
    }
    assert!(declined > 0, "no scene reached the table-slip guard");
}

/// The shots of the instruction gate (`bench-firmware/src/bin/kimgrip_count.rs`,
/// same table) take the branches their labels claim, so that the gate's largest
/// fast-path count covers every branch of the fast path. Classified here in f64
/// from the model's own conditions: pressed (`v_z0 > 0`), `(1+e)a/2 ≥ p*`, the
/// sliding end `(1+e)a/(2 − ρ)` against `p*`, and `p*` against `p_c = a/(2 − ρ)`.
#[test]
fn gate_shots_take_their_branches() {
    #[derive(Debug, PartialEq)]
    enum Branch {
        Slides,
        CertainGripRestitution,
        CertainGripCompression,
        BandGrip,
        GripRestitution,
        GripCompression,
        General,
    }
    use Branch::*;
    /// `(label, branch, μ (< 0: TP A.14's speed-dependent law), v, ω)`.
    type Shot = (&'static str, Branch, f32, [f32; 2], [f32; 3]);
    let shots: [Shot; 12] = [
        ("topspin-slides", Slides, 0.05, [2.0, 0.0], [0.0, 70.0, 0.0]),
        (
            "topspin-grips-restitution",
            CertainGripRestitution,
            0.05,
            [2.0, 0.3],
            [0.0, 7.0, 0.0],
        ),
        (
            "topspin-grips-compression",
            CertainGripCompression,
            0.05,
            [2.0, 0.1],
            [0.0, 3.0, 0.0],
        ),
        (
            "topspin-band-grips",
            BandGrip,
            0.05,
            [2.0, 0.0],
            [0.0, 17.98, 0.0],
        ),
        (
            "stun-cut-slides",
            Slides,
            0.05,
            [1.732, 1.0],
            [0.0, 0.0, 0.0],
        ),
        (
            "draw-grips-restitution",
            GripRestitution,
            0.05,
            [2.0, 0.3],
            [0.0, -7.0, 0.0],
        ),
        (
            "draw-grips-compression",
            GripCompression,
            0.05,
            [2.0, 0.1],
            [0.0, -3.0, 0.0],
        ),
        (
            "near-gearing",
            GripCompression,
            0.05,
            [0.866, 0.5],
            [0.0, 0.0, -17.497_813],
        ),
        (
            "speed-dependent-mu",
            General,
            -1.0,
            [16.0, 3.0],
            [0.0, 30.0, 0.0],
        ),
        ("frictionless", General, 0.0, [1.0, 0.5], [0.0, 10.0, 0.0]),
        ("gearing-side", General, 0.05, [1.0, 1e-13], [0.0, 0.0, 0.0]),
        (
            "gearing-topspin",
            General,
            0.05,
            [1.0, 0.0],
            [0.0, 1e-12, 0.0],
        ),
    ];
    for (label, expected, mu, v, w) in shots {
        let params = if mu < 0.0 {
            Params::POOL.with_friction_law(FrictionLaw::MARLOW)
        } else {
            Params::POOL.with_mu(mu).expect("valid μ")
        };
        let impact = Impact::from_velocity(v, w).expect("valid impact");
        let Some(outcome) = fast_path::collide::<f32>(&params, &impact) else {
            assert_eq!(General, expected, "{label}");
            continue;
        };
        let (e, mu_s, radius) = (
            f64::from(params.restitution()),
            f64::from(params.mu_s()),
            f64::from(params.radius()),
        );
        let (mu, a) = (f64::from(mu), f64::from(v[0]));
        let slip_y = -f64::from(v[1]) - radius * f64::from(w[2]);
        let slip_z = radius * f64::from(w[1]);
        let pressed = slip_z > 0.0;
        let k_z = if pressed { 6.0 - 2.5 * mu_s } else { 6.0 };
        let stick = (slip_y / 7.0).hypot(slip_z / k_z);
        let grip = stick / mu;
        let first = 0.5 * (1.0 + e) * a;
        let rho = if pressed {
            let (start, end) = (slip_z / slip_y.hypot(slip_z), slip_z / k_z / stick);
            mu * mu_s * (start + (first / grip).min(1.0) * (end - start))
        } else {
            0.0
        };
        let compression_end = a / (2.0 - rho);
        let restitution_or_compression = |restitution, compression| {
            if grip >= compression_end {
                restitution
            } else {
                compression
            }
        };
        let branch = if pressed && first >= grip {
            restitution_or_compression(CertainGripRestitution, CertainGripCompression)
        } else if first / (1.0 - 0.5 * rho) <= grip {
            Slides
        } else if pressed {
            BandGrip
        } else {
            restitution_or_compression(GripRestitution, GripCompression)
        };
        assert_eq!(branch, expected, "{label}");
        let sliding = outcome.regime == Regime::Sliding;
        assert_eq!(sliding, branch == Slides, "{label}: {:?}", outcome.regime);
    }
}

/// The fast path evaluates the straight general path's equations specialised (diagonal
/// `K`, constant μ, unscaled slip; `straight`, its test oracle), so both must agree to
/// rounding wherever the fast path applies. Differences are in units of the scene's speed scale
/// `S = max(U, R|ω|)`: `f32` within 2e-6 S (a few ulps of the largest term), `f64`
/// within 3e-7 S (the outcome is rounded to `f32`: a difference of 1e-16 can still
/// round to neighbouring `f32` values, 1.2e-7 S apart at most), and the same regime
/// away from the slide/grip boundary.
#[test]
fn fast_path_agrees_with_the_straight_general_path() {
    fn largest_difference<R: Real>(params: &Params, impact: &Impact) -> Option<(f32, bool)> {
        let fast = fast_path::collide::<R>(params, impact)?;
        let general = crate::kim_grip::straight::general::<R>(params, impact).ok()?;
        let scale = impact.speed().max(params.radius() * impact.spin().length());
        let mut worst = 0.0f32;
        for (a, b) in [
            (fast.cue_ball, general.cue_ball),
            (fast.object_ball, general.object_ball),
        ] {
            let dv = a.velocity - b.velocity;
            let dw = a.spin - b.spin;
            worst = worst
                .max(dv.length() / scale)
                .max(params.radius() * dw.length() / scale);
        }
        Some((worst, fast.regime == general.regime))
    }
    let mut uniform = uniform_from(0x9e37_79b9_7f4a_7c15);
    let (mut checked, mut regime_differs) = (0, 0);
    let (mut worst32, mut worst64) = (0.0f32, 0.0f32);
    for _ in 0..20_000 {
        // Where the fast path applies: μ ≤ 0.15, μ_s ≤ 0.4, μ·μ_s ≤ 0.04.
        let mu = uniform(1e-4, crate::kim_grip::CURVED_MIN_MU);
        let restitution = uniform(0.0, 1.0);
        let mu_s = uniform(
            0.0,
            (crate::kim_grip::CURVED_MIN_MU_MU_S / mu).min(CURVED_MIN_MU_S),
        );
        let params =
            Params::new(mu, restitution, mu_s, uniform(0.01, 0.1), uniform(0.1, 1.0)).unwrap();
        let speed = uniform(0.01, 10.0);
        let cut = uniform(-1.5, 1.5);
        let spin = [
            uniform(-300.0, 300.0),
            uniform(-300.0, 300.0),
            uniform(-300.0, 300.0),
        ];
        let impact = Impact::from_velocity(
            [speed * crate::math::cos(cut), speed * crate::math::sin(cut)],
            spin,
        )
        .unwrap();
        if let Some((d32, same32)) = largest_difference::<f32>(&params, &impact) {
            let (d64, _) = largest_difference::<f64>(&params, &impact).unwrap();
            checked += 1;
            worst32 = worst32.max(d32);
            worst64 = worst64.max(d64);
            regime_differs += usize::from(!same32);
        }
    }
    assert!(checked > 19_000, "fast path taken in only {checked} scenes");
    assert!(
        worst32 <= 2e-6,
        "f32: fast and general differ by {worst32:e} S"
    );
    assert!(
        worst64 <= 3e-7,
        "f64: fast and general differ by {worst64:e} S"
    );
    assert!(
        regime_differs <= 2,
        "regime differs in {regime_differs} scenes"
    );
}

/// Above `CURVED_MIN_MU_S` the fast paths decline every scene (the general path follows
/// a pressed object ball's slide in pieces), at and below it they take it.
#[test]
fn fast_path_declines_a_cloth_of_large_friction() {
    let impact = Impact::from_velocity([2.0, 0.3], [0.0, 40.0, 0.0]).unwrap();
    let params = |mu_s: f32| Params::new(0.05, 0.9, mu_s, 0.028575, 0.17).unwrap();
    let edge = params(CURVED_MIN_MU_S);
    assert!(fast_path::collide::<f32>(&edge, &impact).is_some());
    let above = params(f32::from_bits(CURVED_MIN_MU_S.to_bits() + 1));
    assert!(fast_path::collide::<f32>(&above, &impact).is_none());
    assert!(fast_path::collide::<f64>(&above, &impact).is_none());
    // The general path answers it, the slide followed in pieces.
    assert!(collide::<f32>(&above, &impact).is_ok());
}

/// A small deterministic generator (no dev-dependency in the unit tests): a 64-bit LCG
/// from `state`, each call a number uniform in `[lo, hi)` from its top 24 bits.
pub(super) fn uniform_from(mut state: u64) -> impl FnMut(f32, f32) -> f32 {
    move |lo: f32, hi: f32| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
    }
}
