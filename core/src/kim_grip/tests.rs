use super::*;

/// A friction law built from the enum's variant bypasses `FrictionLaw::constant`'s
/// range check; the fast path's guard assumes μ ≤ 1, so such laws take the general
/// path, whose guard reports the error (found by the `collide` fuzz target: μ = ∞
/// gave a NaN velocity through the fast path).
#[test]
fn unvalidated_friction_never_gives_a_non_finite_outcome() {
    let impacts = [
        // Topspin (object ball pressed), stun with side spin, draw.
        Impact::from_velocity([2.0, -10.0], [340.9, 68.6, 0.0]),
        Impact::from_velocity([2.0, 0.3], [0.0, -20.0, 10.0]),
        Impact::from_velocity([3.0, 0.0], [0.0, -90.0, 0.0]),
    ];
    for mu in [f32::INFINITY, 1e30, 1.5, f32::NAN, -0.5, f32::MIN_POSITIVE] {
        let params = Params::POOL.with_friction_law(FrictionLaw::Constant(mu));
        for impact in &impacts {
            let impact = impact.as_ref().expect("valid impact");
            let results = [
                collide::<f32>(&params, impact),
                collide::<f64>(&params, impact),
            ];
            for outcome in results.iter().flatten() {
                assert!(outcome.is_finite(), "mu = {mu}: {outcome:?}");
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
            [2.0, 0.3],
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
