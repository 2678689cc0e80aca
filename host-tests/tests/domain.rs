//! The domain map (issue 16, item 1; docs/accuracy-domain.md): 100,000 seeded scenes of
//! the whole input domain the core accepts (`cuesight_host::domain`), every one solved
//! by the f64 reference and by every model (`Ideal`, `Kim`, `KimGrip`, `SeedExact`,
//! `Exact`, `Auto(1e-3)`), on two threads.
//!
//! Asserted, because true on this set and stated in docs/accuracy-domain.md:
//!
//! * coverage: every bin of the map is populated (every (μ, μ_s) cell of the 10 × 10
//!   grid, every μ·μ_s band, every cut band including |φ| > 89.5°, every speed band and
//!   spin draw, μ(v) and μ_ct > 0);
//! * every model answers every scene with finite errors;
//! * `Exact` and `Auto(1e-3)` are within 5 % of U in every scene and within 0.5 % of U
//!   in at least 99.9 % of them;
//! * `Auto(1e-3)`'s estimate is at or above its true error in at least 99.5 % of the
//!   scenes and never below a third of it, and it never picks `Ideal` where a friction
//!   law acts on a moving object ball (issue 16, item 5);
//! * `KimGrip` is within 5 % of U in at least 99.5 % of the scenes of every μ·μ_s band
//!   up to 0.2 (measured 99.9–100 %), and within 0.5 % in at least 98 % of those with
//!   μ·μ_s ≤ 0.02 (measured 98.6 %); without cue-ball/table friction (μ_ct = 0), within
//!   0.5 % in at least 99 % of the scenes of every band up to μ·μ_s = 0.08 (measured
//!   99.9, 99.8 and 99.3 %).
//!
//! The shares are floors under the figures measured at the commit that added this test
//! (the thresholds themselves are the map's); what fails — `KimGrip` above μ·μ_s 0.2,
//! `Kim`, `Ideal`, `SeedExact` off the foundation domain, `Auto(1e-3)` missing its own
//! tolerance — is printed (`-- --nocapture`) and documented, not asserted.
//! The full tables: `cargo run --release -p cuesight-host --example accuracy_domain`.

use cuesight_host::compare::thousands;
use cuesight_host::domain::{
    sample, scene_figures, score_all, Map, AUTO, GRID, MIN_OBJECT_SPEED, MODELS,
};
use std::time::Instant;

const SEED: u64 = 16;
const SCENES: usize = 100_000;
const KIM_GRIP: usize = 2;
const EXACT: usize = 4;

#[test]
fn domain_map() {
    let start = Instant::now();
    let set = sample(SEED, SCENES);
    let scored = score_all(&set, 2);
    let map = Map::of(&scored);
    println!(
        "{SCENES} scenes scored in {:.1} s\n{}",
        start.elapsed().as_secs_f64(),
        map.markdown()
    );
    // The tables of docs/accuracy-domain.md, from the same function as the example's.
    for (key, value) in map
        .figures()
        .into_iter()
        .chain(scene_figures(&scored, &map))
    {
        cuesight_figures::record!(&format!("accuracy-domain-{key}"), "{value}");
    }

    // Coverage: every bin populated (expected ≈ 1,000 per (μ, μ_s) cell).
    // Issue 16, item 5: `Auto(1e-3)`'s estimate at or above its true error in ≥ 99.5 %
    // of the scenes and never below a third of it (measured 99.99 % and 0.51; the
    // estimate's rounding term and `Exact`'s factors were chosen on seed 17's scenes),
    // and no `Ideal` where a friction law acts on a moving object ball.
    let all = &map.all;
    assert!(
        all.auto_estimate_bounds as f64 >= 0.995 * SCENES as f64,
        "Auto's estimate bounds its error in {} of {SCENES} scenes",
        all.auto_estimate_bounds
    );
    let ratio = all.auto_estimate_min_ratio.unwrap_or(f64::INFINITY);
    assert!(
        ratio >= 1.0 / 3.0,
        "Auto's estimate at {ratio} of its error"
    );
    assert_eq!(all.auto_ideal_with_friction, 0);
    assert_eq!(map.all.count, SCENES);
    for (i, column) in map.grid.iter().enumerate() {
        for (j, cell) in column.iter().enumerate() {
            assert!(
                cell.count >= 500,
                "(μ, μ_s) bin ({i}, {j}) of {GRID}²: {} scenes",
                cell.count
            );
        }
    }
    for (i, cell) in map.by_mu_mu_s.iter().enumerate() {
        assert!(cell.count >= 5_000, "μ·μ_s band {i}: {} scenes", cell.count);
    }
    for (i, cell) in map.by_cut.iter().enumerate() {
        assert!(cell.count >= 3_000, "cut band {i}: {} scenes", cell.count);
    }
    for (i, cell) in map.by_speed.iter().enumerate() {
        assert!(cell.count >= 5_000, "speed band {i}: {} scenes", cell.count);
    }
    for (i, cell) in map.by_spin.iter().enumerate() {
        assert!(cell.count >= 3_000, "spin draw {i}: {} scenes", cell.count);
    }
    assert!(map.speed_dependent.count >= 10_000);
    assert!(map.cue_table.count >= 20_000);

    // Every model answers, with finite errors, or refuses as its validity domain
    // declares (only Kim and KimGrip have limits).
    for s in &scored {
        for (m, (name, model)) in MODELS.iter().enumerate() {
            if let Some(error) = s.returned[m] {
                let declared = cuesight_host::validity::declared(&s.scene.params(), *model, &error);
                assert!(declared, "{name}: {error} on {}", s.scene.describe());
            }
        }
    }
    // KimGrip inside its validity domain (issue 16, item 3): within 0.25 % of U in
    // velocity, 0.5 % in R ω and 0.1° of throw where the object ball leaves with at
    // least 5 % of U, on every scene it answers.
    let (mut velocity, mut spin, mut throw, mut answered) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    for s in &scored {
        if let Some(e) = s.errors[KIM_GRIP] {
            answered += 1;
            velocity = velocity.max(e.velocity);
            spin = spin.max(e.spin);
            if s.object_speed >= MIN_OBJECT_SPEED {
                throw = throw.max(e.throw_deg);
            }
        }
    }
    println!(
        "KimGrip inside its domain ({answered} scenes): |dv|/U {:.3} %, R|dw|/U {:.3} %, throw {throw:.3} deg",
        100.0 * velocity,
        100.0 * spin
    );
    for (key, value) in [
        ("kimgrip-inside-scenes", thousands(answered)),
        (
            "kimgrip-inside-velocity",
            format!("{:.3}", 100.0 * velocity),
        ),
        ("kimgrip-inside-spin", format!("{:.3}", 100.0 * spin)),
        ("kimgrip-inside-throw", format!("{throw:.3}")),
    ] {
        cuesight_figures::record!(&format!("accuracy-domain-{key}"), "{value}");
    }
    assert!(
        answered >= SCENES / 10,
        "KimGrip answers only {answered} scenes"
    );
    assert!(
        velocity <= 0.0025,
        "KimGrip |dv|/U {velocity:e} inside its domain"
    );
    assert!(spin <= 0.005, "KimGrip R|dw|/U {spin:e} inside its domain");
    assert!(
        throw <= 0.1,
        "KimGrip throw error {throw} deg inside its domain"
    );
    for (m, (name, _)) in MODELS.iter().enumerate() {
        assert_eq!(map.all.failed[m], 0, "{name} returned errors");
        assert!(map.all.worst[m].is_finite(), "{name}: non-finite error");
        assert!(
            map.all.worst_throw[m].is_finite(),
            "{name}: non-finite throw"
        );
    }

    // Exact and Auto(1e-3).
    for m in [EXACT, AUTO] {
        let name = MODELS[m].0;
        assert_eq!(
            map.all.within[m][2], SCENES,
            "{name}: worst {:.3e} of U",
            map.all.worst[m]
        );
        assert!(
            map.all.share(m, 1) >= 0.999,
            "{name}: {:.4} within 0.5 % of U",
            map.all.share(m, 1)
        );
    }

    // Issue 16, item 4: `Exact` within 1e-4 of U, against each scene's f32 floor (the
    // reference's answer rounded to f32, which no f32 answer can beat). Held: within
    // 1e-4 on ≥ 99.8 % of the scenes whose floor is ≤ 1e-5 of U, and above 1e-3 only
    // where the floor itself is above 1e-3.
    let exact = |s: &&cuesight_host::domain::Scored| s.combined(EXACT);
    let representable: Vec<_> = scored.iter().filter(|s| s.f32_floor <= 1e-5).collect();
    let share = |count: usize, of: usize| 100.0 * count as f64 / of as f64;
    let within_1e_4 = scored.iter().filter(|s| exact(s) <= 1e-4).count();
    let representable_within = representable.iter().filter(|s| exact(s) <= 1e-4).count();
    let floor_above_1e_4 = scored.iter().filter(|s| s.f32_floor > 1e-4).count();
    let above_1e_3: Vec<_> = scored.iter().filter(|s| exact(s) > 1e-3).collect();
    let above_1e_3_off_floor = above_1e_3.iter().filter(|s| s.f32_floor <= 1e-3).count();
    for (key, value) in [
        (
            "exact-within-1e-4",
            format!("{:.2}", share(within_1e_4, SCENES)),
        ),
        (
            "exact-within-1e-4-representable",
            format!("{:.2}", share(representable_within, representable.len())),
        ),
        ("exact-representable", thousands(representable.len())),
        (
            "f32-floor-above-1e-4",
            format!("{:.2}", share(floor_above_1e_4, SCENES)),
        ),
        ("exact-above-1e-3", above_1e_3.len().to_string()),
    ] {
        cuesight_figures::record!(&format!("accuracy-domain-{key}"), "{value}");
    }
    assert!(
        share(representable_within, representable.len()) >= 99.8,
        "Exact within 1e-4 of U on {representable_within} of {} scenes whose f32 floor is <= 1e-5",
        representable.len()
    );
    assert_eq!(
        above_1e_3_off_floor, 0,
        "Exact above 1e-3 of U where f32 could hold the answer"
    );

    // Issue 16, item 5: `Auto(1e-2)` within its tolerance on every scene, and its
    // estimate at or above its true error in ≥ 99.5 % of them and never below a third of
    // it. `Auto` gives exactly the outcome of the tier it picks, so its error is that
    // tier's (scored above); at 1e-2 a scene inside `KimGrip`'s validity domain goes to
    // `KimGrip` on its declared bound alone (`cuesight::estimate::select`).
    let (mut within, mut bounds, mut kim_grip_picks) = (0usize, 0usize, 0usize);
    let (mut worst, mut min_ratio) = (0.0f64, f64::INFINITY);
    for s in &scored {
        let (tier, estimate) = cuesight::select_model(&s.scene.params(), &s.scene.impact(), 1e-2);
        let Some(m) = MODELS.iter().position(|(_, model)| *model == tier) else {
            panic!("Auto(1e-2) picked {tier:?}, not a mapped tier");
        };
        let error = s.combined(m);
        worst = worst.max(error);
        within += usize::from(error <= 1e-2);
        bounds += usize::from(f64::from(estimate) >= error);
        if error > 0.0 {
            min_ratio = min_ratio.min(f64::from(estimate) / error);
        }
        kim_grip_picks += usize::from(tier == cuesight::Model::KimGrip);
    }
    println!(
        "Auto(1e-2): within its tolerance in {within} of {SCENES} scenes (worst {worst:.3e} of U); estimate at or above the error in {bounds}, at least {min_ratio:.3} of it; KimGrip picked in {kim_grip_picks}"
    );
    for (key, value) in [
        (
            "auto-1e-2-within",
            format!("{:.2}", 100.0 * within as f64 / SCENES as f64),
        ),
        ("auto-1e-2-worst", format!("{worst:.3e}")),
        (
            "auto-1e-2-estimate-bounds",
            format!("{:.2}", 100.0 * bounds as f64 / SCENES as f64),
        ),
        ("auto-1e-2-estimate-min-ratio", format!("{min_ratio:.2}")),
        ("auto-1e-2-kimgrip", thousands(kim_grip_picks)),
    ] {
        cuesight_figures::record!(&format!("accuracy-domain-{key}"), "{value}");
    }
    assert_eq!(within, SCENES, "Auto(1e-2): worst {worst:e} of U");
    assert!(
        bounds as f64 >= 0.995 * SCENES as f64,
        "Auto(1e-2)'s estimate bounds {bounds}"
    );
    assert!(
        min_ratio >= 1.0 / 3.0,
        "Auto(1e-2)'s estimate at {min_ratio} of its error"
    );

    // KimGrip's shares by band of μ·μ_s were asserted here (≥ 99.5 % within 5 % of U
    // up to μ·μ_s = 0.2, …) until its validity domain: it now refuses every scene outside
    // the domain and is held above to 0.25 % / 0.5 % / 0.1° on every scene it answers.
}
