//! Host half of `cargo xtask bench` (a `harness = false` bench target, so it is built
//! optimised): writes the scene set the bench firmware bakes in, and scores the
//! outcomes the firmware printed under QEMU against the f64 reference on the grid.
//!
//! ```text
//! cargo bench -p cuesight-host --bench tradeoff -- scenes --out $PWD/target/bench/scenes.bin
//! cargo bench -p cuesight-host --bench tradeoff -- errors --json $PWD/target/bench/errors.json \
//!     $PWD/target/bench/qemu-libm.txt $PWD/target/bench/qemu-micromath.txt
//! ```
//!
//! (cargo runs bench targets from `host-tests/`, hence the absolute paths.)
//!
//! The errors are those of the outcomes the Cortex-M4F computed (hardware `vsqrt`,
//! the backend's functions), not of a host rebuild. For the `libm` backend every
//! outcome is also recomputed on the host and compared bit for bit.

use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;
use std::time::Instant;

use clap::{Parser, Subcommand};
use cuesight::{BallState, Impulses, Model, Outcome, Regime, Vec3};
use cuesight_host::compare::{reference, scene_error, SceneError, Summary};
use cuesight_host::grid::{scenes, Scene};
use cuesight_host::reference::{ReferenceOutcome, ReferenceRegime};
use serde_json::{json, Value};

#[derive(Parser)]
#[command(
    name = "tradeoff",
    about = "scene set and error scoring for `cargo xtask bench`"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Passed by `cargo bench`; ignored.
    #[arg(long, hide = true, global = true)]
    bench: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Write the grid as the bench firmware's binary scene set.
    Scenes {
        #[arg(long, default_value_t = 2024)]
        seed: u64,
        #[arg(long, default_value_t = 10_000)]
        count: usize,
        /// Leading scenes the firmware counts instructions on.
        #[arg(long, default_value_t = 64)]
        counted: usize,
        #[arg(long)]
        out: PathBuf,
    },
    /// Score firmware outcome listings against the reference on the same grid.
    Errors {
        #[arg(long, default_value_t = 2024)]
        seed: u64,
        #[arg(long, default_value_t = 10_000)]
        count: usize,
        #[arg(long)]
        json: PathBuf,
        /// QEMU output of the bench firmware, one file per backend.
        listings: Vec<PathBuf>,
    },
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        None => {
            println!("tradeoff: nothing to do (`cargo xtask bench` drives this target)");
            Ok(())
        }
        Some(Command::Scenes {
            seed,
            count,
            counted,
            out,
        }) => write_scenes(seed, count, counted, &out),
        Some(Command::Errors {
            seed,
            count,
            json,
            listings,
        }) => score(seed, count, &json, &listings),
    };
    if let Err(message) = result {
        eprintln!("tradeoff: {message}");
        std::process::exit(1);
    }
}

/// Header `b"CSB1"`, seed, count, counted; ten little-endian f32 per scene (layout in
/// `bench-firmware/src/scenes.rs`).
fn write_scenes(seed: u64, count: usize, counted: usize, out: &PathBuf) -> Result<(), String> {
    let grid = scenes(seed, count);
    let mut blob = Vec::with_capacity(20 + 40 * count);
    blob.extend_from_slice(b"CSB1");
    blob.extend_from_slice(&seed.to_le_bytes());
    blob.extend_from_slice(&(count as u32).to_le_bytes());
    blob.extend_from_slice(&(counted.min(count) as u32).to_le_bytes());
    for s in &grid {
        let values = [
            s.velocity[0],
            s.velocity[1],
            s.spin[0],
            s.spin[1],
            s.spin[2],
            s.mu,
            s.restitution,
            s.mu_s,
            s.radius,
            s.mass,
        ];
        for v in values {
            blob.extend_from_slice(&v.to_le_bytes());
        }
    }
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    std::fs::write(out, blob).map_err(|e| format!("{}: {e}", out.display()))?;
    println!(
        "tradeoff: {count} scenes of grid seed {seed} -> {}",
        out.display()
    );
    Ok(())
}

/// A model label of the firmware: a [`Model::name`], or `auto(<tolerance>)`.
fn model_of(label: &str) -> Option<Model> {
    match label
        .strip_prefix("auto(")
        .and_then(|t| t.strip_suffix(')'))
    {
        Some(tolerance) => Some(Model::Auto {
            tolerance: tolerance.parse().ok()?,
        }),
        None => Model::ALL.into_iter().find(|m| m.name() == label),
    }
}

/// The same evaluation on the host, if this build has it.
fn host_outcome(scene: &Scene, model: Model, precision: &str) -> Option<cuesight::Result<Outcome>> {
    let (params, impact) = (scene.params(), scene.impact());
    match precision {
        "f32" => Some(cuesight::collide(&params, &impact, model)),
        "f64" => Some(cuesight::collide_f64(&params, &impact, model)),
        _ => None,
    }
}

/// Scores of one (model, backend, precision).
#[derive(Default)]
struct Tally {
    errors: Vec<(usize, SceneError)>,
    sliding: Vec<(usize, SceneError)>,
    failures: usize,
    host_checked: usize,
    host_mismatches: usize,
    /// Scenes compared with the `libm` image's outcome, and how many differ in a bit.
    libm_checked: usize,
    libm_differences: usize,
}

/// Bit pattern of an outcome, to compare two images' results exactly.
type Bits = (Regime, [[u32; 3]; 4]);

fn bits(o: &Outcome) -> Bits {
    let words = [
        o.cue_ball.velocity,
        o.cue_ball.spin,
        o.object_ball.velocity,
        o.object_ball.spin,
    ]
    .map(|v| v.to_array().map(f32::to_bits));
    (o.regime, words)
}

fn summary_json(s: &Summary) -> Value {
    let e =
        |e: &SceneError| json!({"velocity": e.velocity, "spin": e.spin, "throw_deg": e.throw_deg});
    json!({"scenes": s.count, "max": e(&s.max), "rms": e(&s.rms)})
}

fn score(seed: u64, count: usize, out: &PathBuf, listings: &[PathBuf]) -> Result<(), String> {
    let grid = scenes(seed, count);
    let started = Instant::now();
    let references = solve_all(&grid)?;
    let reference_seconds = started.elapsed().as_secs_f64();
    println!(
        "tradeoff: reference solved on {count} scenes in {reference_seconds:.1} s ({} threads)",
        threads()
    );

    let mut tallies: BTreeMap<(String, String, String), Tally> = BTreeMap::new();
    // Outcomes of the libm image, by (label, precision, scene), for the other backends.
    let mut libm: HashMap<(String, String, usize), Bits> = HashMap::new();
    let mut texts = Vec::new();
    for path in listings {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let backend = text
            .lines()
            .find_map(|l| l.strip_prefix("bench "))
            .and_then(|h| h.split(' ').next())
            .ok_or_else(|| format!("{}: no `bench` header line", path.display()))?
            .to_string();
        texts.push((backend, path, text));
    }
    // The libm listing first, so that the other backends can be compared with it.
    texts.sort_by_key(|(backend, _, _)| backend != "libm");
    for (backend, path, text) in &texts {
        let backend = backend.clone();
        for (n, line) in text.lines().enumerate() {
            let Some(rest) = line.strip_prefix("outcome ") else {
                continue;
            };
            let bad = || format!("{}:{}: malformed outcome line", path.display(), n + 1);
            let fields: Vec<&str> = rest.split(' ').collect();
            if fields.len() < 4 {
                return Err(bad());
            }
            let (label, precision) = (fields[0], fields[1]);
            let index: usize = fields[2].parse().map_err(|_| bad())?;
            let (Some(scene), Some(reference)) = (grid.get(index), references.get(index)) else {
                return Err(format!(
                    "{}: scene {index} is not on the grid",
                    path.display()
                ));
            };
            let tally = tallies
                .entry((label.to_string(), backend.clone(), precision.to_string()))
                .or_default();
            let regime = match fields[3] {
                "frictionless" => Regime::Frictionless,
                "sliding" => Regime::Sliding,
                "gripping" => Regime::Gripping,
                _ => {
                    tally.failures += 1;
                    continue;
                }
            };
            if fields.len() != 16 {
                return Err(bad());
            }
            let mut w = [0f32; 12];
            for (k, word) in fields[4..].iter().enumerate() {
                w[k] = f32::from_bits(u32::from_str_radix(word, 16).map_err(|_| bad())?);
            }
            let ball = |k: usize| BallState {
                velocity: Vec3::new(w[k], w[k + 1], w[k + 2]),
                spin: Vec3::new(w[k + 3], w[k + 4], w[k + 5]),
            };
            let outcome = Outcome {
                cue_ball: ball(0),
                object_ball: ball(6),
                // Not printed by the firmware; the error measures do not use them.
                impulses: Impulses::default(),
                regime,
            };
            let error = scene_error(scene, &outcome, reference);
            tally.errors.push((index, error));
            if reference.regime == ReferenceRegime::Sliding {
                tally.sliding.push((index, error));
            }
            let key = (label.to_string(), precision.to_string(), index);
            if backend == "libm" {
                libm.insert(key, bits(&outcome));
            } else if let Some(theirs) = libm.get(&key) {
                tally.libm_checked += 1;
                if *theirs != bits(&outcome) {
                    tally.libm_differences += 1;
                }
            }
            if backend == "libm" {
                if let Some(host) = model_of(label).and_then(|m| host_outcome(scene, m, precision))
                {
                    tally.host_checked += 1;
                    if !host.is_ok_and(|h| bits(&h) == bits(&outcome)) {
                        tally.host_mismatches += 1;
                    }
                }
            }
        }
    }
    if tallies.is_empty() {
        return Err("no outcome lines in the listings".into());
    }

    let rows: Vec<Value> = tallies
        .into_iter()
        .map(|((model, backend, precision), t)| {
            let all = Summary::of(t.errors.iter().copied());
            let sliding = Summary::of(t.sliding.iter().copied());
            println!("{model:>12} {backend:>9} {precision}: {all}");
            json!({
                "model": model,
                "backend": backend,
                "precision": precision,
                "failures": t.failures,
                "all": summary_json(&all),
                "reference_sliding": summary_json(&sliding),
                "host_checked": t.host_checked,
                "host_mismatches": t.host_mismatches,
                "libm_checked": t.libm_checked,
                "libm_differences": t.libm_differences,
            })
        })
        .collect();
    let report = json!({
        "seed": seed,
        "scenes": count,
        "reference_seconds": reference_seconds,
        "rows": rows,
    });
    let text = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
    std::fs::write(out, text).map_err(|e| format!("{}: {e}", out.display()))?;
    println!("tradeoff: errors -> {}", out.display());
    Ok(())
}

fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The reference on every scene, split over the available cores.
fn solve_all(grid: &[Scene]) -> Result<Vec<ReferenceOutcome>, String> {
    let chunk = grid.len().div_ceil(threads()).max(1);
    std::thread::scope(|s| {
        let workers: Vec<_> = grid
            .chunks(chunk)
            .map(|part| {
                s.spawn(move || {
                    part.iter()
                        .map(|scene| reference(scene).map_err(|e| format!("reference: {e:?}")))
                        .collect::<Result<Vec<_>, String>>()
                })
            })
            .collect();
        let mut all = Vec::with_capacity(grid.len());
        for w in workers {
            all.extend(
                w.join()
                    .map_err(|_| "a reference worker panicked".to_string())??,
            );
        }
        Ok(all)
    })
}
