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

use cuesight_host::domain::{
    sample, scene_figures, score_all, Map, AUTO, GRID, MODELS, MU_MU_S_BANDS,
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

    // KimGrip up to μ·μ_s = 0.2.
    for (i, &hi) in MU_MU_S_BANDS
        .iter()
        .enumerate()
        .take_while(|(_, &hi)| hi <= 0.2)
    {
        let share = map.by_mu_mu_s[i].share(KIM_GRIP, 2);
        assert!(
            share >= 0.995,
            "KimGrip within 5 % of U in band μ·μ_s ≤ {hi}: {share:.4}"
        );
    }
    let share = map.by_mu_mu_s[0].share(KIM_GRIP, 1);
    assert!(
        share >= 0.98,
        "KimGrip within 0.5 % of U at μ·μ_s ≤ 0.02: {share:.4}"
    );
    // Without cue-ball/table friction, up to μ·μ_s = 0.08.
    for (i, &hi) in MU_MU_S_BANDS.iter().enumerate().take(3) {
        let share = map.by_mu_mu_s_no_ct[i].share(KIM_GRIP, 1);
        assert!(
            share >= 0.99,
            "KimGrip within 0.5 % of U in band μ·μ_s ≤ {hi}, μ_ct = 0: {share:.4}"
        );
    }
}
