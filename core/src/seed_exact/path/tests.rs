use super::*;

#[test]
fn rule_integrates_degree_15_exactly() {
    for degree in 0..=15 {
        let sum: f64 = RULE.iter().map(|&(t, w)| w * t.powi(degree)).sum();
        let exact = 1.0 / (degree as f64 + 1.0);
        assert!((sum - exact).abs() < 1e-15, "degree {degree}: {sum}");
    }
}

/// `(∫g, ∫c_z ρ^{k_z} g)` over `[1 − q, 1]` by 64 panels of the 8-point rule,
/// graded (`(i/64)²`) towards `ρ = 0` where the non-integer powers live.
fn composite(cy: f64, cz: f64, k_z: f64, q: f64) -> (f64, f64) {
    let lo = 1.0 - q;
    let edge = |i: usize| lo + q * (i as f64 / 64.0).powi(2);
    let (mut n, mut v) = (0.0, 0.0);
    for i in 0..64 {
        let (a, b) = (edge(i), edge(i + 1));
        for &(t, w) in RULE.iter() {
            let rho: f64 = a + (b - a) * t;
            let g = (cy * cy * rho.powi(12) + cz * cz * rho.powf(2.0 * k_z - 2.0)).sqrt();
            n += w * (b - a) * g;
            v += w * (b - a) * cz * rho.powf(k_z) * g;
        }
    }
    (n, v)
}

/// The 8-point rule's error in `∫g` and `∫c_z ρ^k g` against [`composite`], the largest
/// over 181 slip directions, `1 − ρ` from 1e-6 to 1, and μ_s up to `max_mu_s`.
fn worst_quadrature_error(max_mu_s: f64) -> (f64, f64) {
    let mu = 0.05f32;
    let (mut worst_n, mut worst_v) = (0.0f64, 0.0f64);
    for step in 0..=180 {
        let angle = (step as f64 - 90.0).to_radians() * 2.0; // −π..π
        let (cy, cz) = (angle.cos(), angle.sin());
        for mu_s in [0.0, 0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0] {
            if mu_s > max_mu_s {
                continue;
            }
            let path = SlipPath::<f64>::new(cy, cz, mu_s, FrictionLaw::Constant(mu));
            for q in [1e-6, 1e-3, 0.1, 0.5, 0.9, 1.0] {
                let p = path.point(q);
                let scale = mu as f64; // P = (|v₀|/μ) ∫g with |v₀| = 1
                let (n, v) = composite(cy, cz, path.k_z, q);
                worst_n = worst_n.max((p.normal * scale - n).abs());
                worst_v = worst_v.max((p.vertical * scale - v).abs());
            }
        }
    }
    (worst_n, worst_v)
}

/// docs/physics.md §7 item 2: below f32 resolution in the calibrated domain (μ_s ≤
/// 0.4), and within 2e-6 in `∫g` (which is ≥ `(1−ρ⁷)/7`) over all of μ_s ≤ 1, where the
/// worst case is a slide to the stick point (`ρ = 0`) at μ_s = 1 along a slip a few
/// degrees off `y` (the integrand's two terms cross there).
#[test]
fn quadrature_error_is_below_its_stated_bound() {
    let (worst_n, worst_v) = worst_quadrature_error(0.4);
    assert!(worst_n <= 2e-8, "∫g: {worst_n:e}");
    assert!(worst_v <= 1e-9, "∫c_z ρ^k g: {worst_v:e}");
    let (worst_n_all, _) = worst_quadrature_error(1.0);
    assert!(worst_n_all <= 2e-6, "∫g, μ_s ≤ 1: {worst_n_all:e}");
    cuesight_figures::record!("physics-seed-exact-quadrature-error", "{worst_n:.1e}");
    cuesight_figures::record!(
        "physics-seed-exact-quadrature-error-mu-s-1",
        "{worst_n_all:.1e}"
    );
}

#[test]
fn pure_side_slip_is_a_polynomial() {
    // v_z0 = 0: g = ρ⁶, P(ρ) = |v₀| (1 − ρ⁷)/(7μ) exactly.
    let path = SlipPath::<f64>::new(-1.5, 0.0, 0.3, FrictionLaw::Constant(0.05));
    for q in [1e-6, 0.3, 1.0] {
        let p = path.point(q);
        let exact = 1.5 * (1.0 - (1.0 - q).powi(7)) / (7.0 * 0.05f32 as f64);
        // (1 − q)⁷ loses ~1e-10 of 1 − (1 − q)⁷ to cancellation at q = 1e-6.
        assert!((p.normal - exact).abs() < 1e-9 * exact, "{q}: {}", p.normal);
        assert!(p.vertical == 0.0);
    }
}

#[test]
fn head_on_topspin_follows_k_z() {
    // v_y0 = 0: g = ρ^{k_z − 1}, P(ρ) = |v₀| (1 − ρ^{k_z})/(k_z μ),
    // I_z = |v₀|² (1 − ρ^{2k_z})/(2 k_z μ).
    let (mu_s, mu) = (0.3f64, 0.05f32);
    let path = SlipPath::<f64>::new(0.0, 2.0, mu_s, FrictionLaw::Constant(mu));
    let (k_z, mu) = ((2.4 - mu_s) / 0.4, mu as f64);
    for q in [1e-4, 0.5, 1.0] {
        let rho: f64 = 1.0 - q;
        let p = path.point(q);
        let normal = 2.0 * (1.0 - rho.powf(k_z)) / (k_z * mu);
        let vertical = 4.0 * (1.0 - rho.powf(2.0 * k_z)) / (2.0 * k_z * mu);
        // Non-integer power ρ^{4.25} at ρ → 0 (q = 1): the quadrature's measured
        // bound, 2e-8 of ∫g ≥ 1/7.
        assert!(
            (p.normal - normal).abs() < 1.5e-7 * normal,
            "{q}: {}",
            p.normal
        );
        assert!((p.vertical - vertical).abs() < 1.5e-7 * vertical, "{q}");
        assert!((p.z_change - (rho.powf(k_z) - 1.0)).abs() < 1e-14);
    }
}
