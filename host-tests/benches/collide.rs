//! Host time per prediction (criterion), for `cargo xtask bench`: every model and
//! precision on the same 64 grid scenes the bench firmware counts instructions on, and
//! the f64 reference solver on those scenes (how much slower the fast path is not).
//!
//! `cargo bench -p cuesight-host --bench collide`; one iteration evaluates all 64
//! scenes, so the time per prediction is the reported time / 64.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use cuesight::{Impact, Model, Outcome, Params};
use cuesight_host::compare::reference;
use cuesight_host::grid::scenes;

/// Grid seed and scene count shared with `cargo xtask bench` and the bench firmware.
const SEED: u64 = 2024;
const SCENES: usize = 64;

type Predict = fn(&Params, &Impact, Model) -> cuesight::Result<Outcome>;

/// Evaluation precisions and their entry points (as in the bench firmware).
const PRECISIONS: [(&str, Predict); 2] =
    [("f32", cuesight::collide), ("f64", cuesight::collide_f64)];

/// `Model::ALL`, then `Auto` at a few tolerances, with the firmware's labels.
fn models() -> Vec<(String, Model)> {
    let mut all: Vec<(String, Model)> = Model::ALL
        .into_iter()
        .map(|m| (m.name().to_string(), m))
        .collect();
    for tolerance in [1e-2f32, 1e-3, 1e-4] {
        all.push((format!("auto({tolerance:e})"), Model::Auto { tolerance }));
    }
    all
}

fn predictions(c: &mut Criterion) {
    let grid = scenes(SEED, SCENES);
    let inputs: Vec<(Params, Impact)> = grid.iter().map(|s| (s.params(), s.impact())).collect();

    let mut group = c.benchmark_group("collide");
    group.throughput(Throughput::Elements(SCENES as u64));
    for (label, model) in models() {
        for (precision, predict) in PRECISIONS {
            group.bench_with_input(BenchmarkId::new(&label, precision), &inputs, |b, inputs| {
                b.iter(|| {
                    for (params, impact) in inputs {
                        let _ = black_box(predict(black_box(params), black_box(impact), model));
                    }
                })
            });
        }
    }
    group.finish();

    let mut group = c.benchmark_group("reference");
    group.throughput(Throughput::Elements(SCENES as u64));
    group.sample_size(10);
    group.bench_function("solve", |b| {
        b.iter(|| {
            for scene in &grid {
                let _ = black_box(reference(black_box(scene)));
            }
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    // Short runs: `cargo xtask bench` measures ~15 of these and must stay quick.
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(20);
    targets = predictions
}
criterion_main!(benches);
