use super::*;

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

#[test]
fn normal_impulse_without_table_is_one_plus_e_half() {
    assert!(
        (final_normal_impulse::<f32, true>(2.0, 0.9, 1.9, 0.0, f32::INFINITY).0 - 1.9).abs() < 1e-6
    );
}

#[test]
fn normal_impulse_is_continuous_across_grip_cases() {
    let (a, e, rho) = (1.0f32, 0.9f32, 0.04f32);
    let p_c = a / (2.0 - rho);
    for grip in [p_c, (1.0 + e) * p_c] {
        let (below, _) =
            final_normal_impulse::<f32, true>(a, e, 0.5 * (1.0 + e) * a, rho, grip * (1.0 - 1e-6));
        let (above, _) =
            final_normal_impulse::<f32, true>(a, e, 0.5 * (1.0 + e) * a, rho, grip * (1.0 + 1e-6));
        assert!((below - above).abs() < 1e-5, "{below} vs {above} at {grip}");
    }
}

#[test]
fn early_grip_tends_to_the_frictionless_impulse() {
    // Table friction that stops immediately leaves the frictionless (1+e) a / 2.
    let (p, slides) = final_normal_impulse::<f32, true>(1.0, 0.95, 0.975, 0.04, 0.0);
    assert!(!slides);
    assert!((p - 0.975).abs() < 1e-6);
}

#[test]
fn direction_meets_stick_impulse_at_the_boundary() {
    let slip = TangentialSlip::new(-0.7f32, 0.5, 0.7, 0.0, 5.0);
    let (dy, dz) = slip.friction_direction(slip.stick_budget);
    let (sy, sz) = (
        slip.stick_y / slip.stick_budget,
        slip.stick_z / slip.stick_budget,
    );
    assert!((dy - sy).abs() < 1e-6 && (dz - sz).abs() < 1e-6);
}

/// The fast path evaluates the general path's equations specialised (diagonal `K`,
/// constant μ, unscaled slip), so both must agree to rounding wherever the fast
/// path applies. Differences are in units of the scene's speed scale
/// `S = max(U, R|ω|)`: `f32` within 2e-6 S (a few ulps of the largest term), `f64`
/// within 3e-7 S (the outcome is rounded to `f32`: a difference of 1e-16 can still
/// round to neighbouring `f32` values, 1.2e-7 S apart at most), and the same regime
/// away from the slide/grip boundary.
#[test]
fn fast_path_agrees_with_the_general_path() {
    fn largest_difference<R: Real>(params: &Params, impact: &Impact) -> Option<(f32, bool)> {
        let fast = fast_path::collide::<R>(params, impact)?;
        let general = general::<R>(params, impact).ok()?;
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
    // A small deterministic generator (no dev-dependency in the unit tests).
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut uniform = |lo: f32, hi: f32| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
    };
    let (mut checked, mut regime_differs) = (0, 0);
    let (mut worst32, mut worst64) = (0.0f32, 0.0f32);
    for _ in 0..20_000 {
        // Inside the validity domain (μ ≤ 0.15, μ·μ_s ≤ 0.08), where the fast path applies.
        let mu = uniform(1e-4, crate::validity::KIM_GRIP_MAX_MU);
        let restitution = uniform(0.0, 1.0);
        let mu_s = uniform(0.0, (crate::validity::KIM_GRIP_MAX_MU_MU_S / mu).min(1.0));
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

/// The slip's path length under sliding friction, `S = ∫₀^∞ |u(t)| dt` with `u_i(t) =
/// u_i0 e^{−k_i t}` (the slip obeys `du/dS = −K û`; with `dt = dS/|u|` each component
/// decays on its own), by composite Simpson on `[0, 40/k_min]` (the rest is below
/// `e^{−40}`).
fn sliding_path_length(k: [f64; 2], u0: [f64; 2]) -> f64 {
    const INTERVALS: usize = 4000;
    let end = 40.0 / k[0].min(k[1]);
    let h = end / INTERVALS as f64;
    let speed = |t: f64| {
        let (y, z) = (u0[0] * (-k[0] * t).exp(), u0[1] * (-k[1] * t).exp());
        (y * y + z * z).sqrt()
    };
    (0..INTERVALS)
        .map(|i| {
            let a = i as f64 * h;
            h / 6.0 * (speed(a) + 4.0 * speed(a + h / 2.0) + speed(a + h))
        })
        .sum()
}

/// The largest relative error of the grip threshold `s* = |K⁻¹ u₀|` against the
/// sliding path's length over slip directions 0°–90° (1° apart), for `K = diag(k_y,
/// k_z)`.
fn worst_grip_threshold_error(k_z: f64) -> f64 {
    let k = [k_y::<f64>(), k_z];
    (0..=90)
        .map(|degrees| {
            let angle = f64::from(degrees).to_radians();
            let u0 = [angle.cos(), angle.sin()];
            let s_star = (u0[0] / k[0]).hypot(u0[1] / k[1]);
            (s_star / sliding_path_length(k, u0) - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

/// docs/physics.md §4 item 3: `s* = |j_stick|` is the friction budget that stops the
/// slip exactly for an isotropic `K`, and within a stated error for the anisotropic
/// one of a pressed object ball (`k_z = (2+ν−μ_s)/ν`, `k_y/k_z` from 7/6 at μ_s = 0 to
/// 1.4 at μ_s = 0.4).
#[test]
fn grip_threshold_is_the_sliding_path_length_within_its_stated_error() {
    let nu = nu::<f64>();
    let k_z = |mu_s: f64| (2.0 + nu - mu_s) / nu;
    let isotropic = worst_grip_threshold_error(k_y::<f64>());
    assert!(isotropic < 1e-9, "isotropic K: {isotropic:e}");
    let at_0 = worst_grip_threshold_error(k_z(0.0));
    let at_0_4 = worst_grip_threshold_error(k_z(0.4));
    // The error grows with the anisotropy, and stays within 1.3 % at k_y/k_z = 1.4.
    assert!(isotropic < at_0 && at_0 < at_0_4, "{at_0} {at_0_4}");
    assert!(at_0_4 <= 0.013, "μ_s = 0.4: {at_0_4}");
    cuesight_figures::record!(
        "physics-kimgrip-grip-threshold-error-mu-s-0",
        "{:.2}",
        at_0 * 100.0
    );
    cuesight_figures::record!(
        "physics-kimgrip-grip-threshold-error-mu-s-0-4",
        "{:.2}",
        at_0_4 * 100.0
    );
}

/// The speed-dependent fast path (`speed_path`, f32) against the general path's Newton
/// solution of the same equations in f64, on 20,000 scenes with laws `μ(v) = a + b e^{−cv}`
/// inside `KimGrip`'s validity domain.
#[cfg(feature = "speed-path")]
#[test]
fn speed_path_agrees_with_the_general_path() {
    extern crate std;
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut uniform = |lo: f32, hi: f32| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
    };
    let (mut checked, mut regime_differs, mut sliding) = (0, 0, 0);
    let (mut worst, mut worst_general32) = (0.0f32, 0.0f32);
    for _ in 0..20_000 {
        let a = uniform(1e-3, 0.05);
        let b = uniform(1e-3, crate::validity::KIM_GRIP_MAX_MU - a);
        let c = uniform(0.05, 5.0);
        let law = FrictionLaw::speed_dependent(a, b, c).unwrap();
        let mu_s = uniform(
            0.0,
            (crate::validity::KIM_GRIP_MAX_MU_MU_S / (a + b)).min(1.0),
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
