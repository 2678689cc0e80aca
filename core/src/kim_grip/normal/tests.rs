use super::*;

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

/// With one rate for compression and restitution the two-rate impulse is the one-rate
/// `(1+e)a/(2 − ρ)` and its grips, in every regime: sliding to the end, a grip during
/// restitution and one during compression.
#[test]
fn two_rates_with_one_rate_are_the_single_rate_impulse() {
    let (a, e, rho) = (1.5f64, 0.8f64, 0.07f64);
    let compression_end = a / (2.0 - rho);
    let sliding_end = (1.0 + e) * compression_end;
    for grip in [
        2.0 * sliding_end,
        0.5 * (compression_end + sliding_end),
        0.5 * compression_end,
    ] {
        let (one, one_slides) =
            final_normal_impulse::<f64, true>(a, e, 0.5 * (1.0 + e) * a, rho, grip);
        let (two, two_slides, end) = two_rate_normal_impulse::<f64>(a, e, rho, rho, grip);
        assert!((one - two).abs() <= 1e-12, "{one} vs {two} at p* {grip}");
        assert_eq!(one_slides, two_slides);
        assert!((end - compression_end).abs() <= 1e-12);
    }
}

/// Two rates: the sliding end is `p_c + e √(a p_c/(2 − ρ_r))` (the restitution work
/// `(2 − ρ_r) q²/2` equal to `e² a p_c/2`), and the impulse has no jump where the grip
/// passes the compression end or the sliding end.
#[test]
fn two_rate_impulse_is_continuous_across_grip_cases() {
    let (a, e, rho_c, rho_r) = (1.0f64, 0.9f64, 0.02f64, 0.1f64);
    let compression_end = a / (2.0 - rho_c);
    let sliding_end = compression_end + e * (a * compression_end / (2.0 - rho_r)).sqrt();
    let (free, slides, _) = two_rate_normal_impulse::<f64>(a, e, rho_c, rho_r, f64::INFINITY);
    assert!(
        slides && (free - sliding_end).abs() <= 1e-12,
        "{free} vs {sliding_end}"
    );
    for grip in [compression_end, sliding_end] {
        let (below, ..) = two_rate_normal_impulse::<f64>(a, e, rho_c, rho_r, grip * (1.0 - 1e-9));
        let (above, ..) = two_rate_normal_impulse::<f64>(a, e, rho_c, rho_r, grip * (1.0 + 1e-9));
        assert!((below - above).abs() < 1e-7, "{below} vs {above} at {grip}");
    }
}
