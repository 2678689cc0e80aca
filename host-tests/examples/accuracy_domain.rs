//! The domain map of docs/accuracy-domain.md: every model against the reference solver
//! on `--scenes N` seeded scenes of the whole accepted domain
//! (`cuesight_host::domain`), printed as Markdown tables with the worst scenes; with
//! `--out DIR`, the heat map is written to `DIR/accuracy-domain.svg`.
//!
//! ```sh
//! cargo run --release -p cuesight-host --example accuracy_domain -- --scenes 100000 --out docs/
//! ```
//!
//! Options: `--scenes N` (default 100,000), `--seed S` (default 16), `--threads T`
//! (default 2), `--out DIR`.
use cuesight_host::domain::{mu_mu_s_band, sample, score_all, worst_scene, worst_throw_scene, Map};
use std::time::Instant;

fn main() {
    let mut scenes = 100_000usize;
    let mut seed = 16u64;
    let mut threads = 2usize;
    let mut out: Option<std::path::PathBuf> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--scenes" => scenes = value().parse().expect("--scenes N"),
            "--seed" => seed = value().parse().expect("--seed S"),
            "--threads" => threads = value().parse().expect("--threads T"),
            "--out" => out = Some(value().into()),
            other => panic!("unknown argument {other}"),
        }
    }
    let start = Instant::now();
    let set = sample(seed, scenes);
    let sampled = start.elapsed();
    let scored = score_all(&set, threads);
    let elapsed = start.elapsed();
    let map = Map::of(&scored);
    let tables = map.markdown();
    println!(
        "{scenes} scenes, seed {seed}, {threads} threads: sampled in {:.2} s, scored \
         (reference + 6 models) in {:.1} s, {:.0} µs per scene per thread",
        sampled.as_secs_f64(),
        elapsed.as_secs_f64(),
        1e6 * elapsed.as_secs_f64() * threads as f64 / scenes.max(1) as f64
    );
    println!("{tables}");
    println!("#### Worst scene per model\n");
    for (m, (name, _)) in cuesight_host::domain::MODELS.iter().enumerate() {
        // Among the scenes the model answers (a refusal outside its validity domain
        // counts as infinitely wrong in the tables, not here); none answered: skip.
        let Some((i, worst)) = worst_scene(&scored, m, |s| s.errors[m].is_some()) else {
            println!("- {name}: no scene answered");
            continue;
        };
        let (t, throw) = worst_throw_scene(&scored, m).expect("scenes");
        for (what, index, s) in [("combined", i, worst), ("throw", t, throw)] {
            let d = &s.scene;
            println!(
                "- {name}, worst {what}: scene {index}: {:?} (|dv|/U, R|dw|/U, throw deg); \
                 U {:.4} m/s, cut {:.4} deg, spin {:?} rad/s, {:?}, e* {}, mu_s {}, mu_ct {}, R {} m",
                s.errors[m].map(|e| (e.velocity, e.spin, e.throw_deg)),
                d.scene.speed(),
                d.cut_deg,
                d.scene.spin,
                d.friction,
                d.scene.restitution,
                d.scene.mu_s,
                d.mu_ct,
                d.scene.radius
            );
        }
    }
    println!("\n#### KimGrip's worst scene per μ·μ_s band\n");
    let bands = cuesight_host::domain::MU_MU_S_BANDS;
    for (b, hi) in bands.iter().enumerate() {
        let worst = worst_scene(&scored, 2, |s| {
            mu_mu_s_band(s) == b && s.errors[2].is_some()
        });
        if let Some((i, s)) = worst {
            let d = &s.scene;
            println!(
                "- mu*mu_s <= {hi}: scene {i}, {:.3e} of U; U {:.4} m/s, cut {:.4} deg, spin {:?} \
                 rad/s ({:?}), {:?}, e* {}, mu_s {}, mu_ct {}",
                s.combined(2),
                d.scene.speed(),
                d.cut_deg,
                d.scene.spin,
                d.spin_draw,
                d.friction,
                d.scene.restitution,
                d.scene.mu_s,
                d.mu_ct
            );
        }
    }
    if let Some(dir) = out {
        std::fs::create_dir_all(&dir).expect("create --out");
        std::fs::write(dir.join("accuracy-domain.svg"), map.svg()).expect("write svg");
    }
}
