//! Calibration of the a-priori error estimates (`cuesight::error_estimate`): on a grid
//! with a seed other than the foundation grid's, print the distribution of
//! true error / unscaled estimate for every tier. The calibrated factor of a tier is
//! chosen above the largest ratio printed here.
//!
//! `cargo run --release -p cuesight-host --example estimate_explore`
use cuesight::{collide, error_estimate, Model};
use cuesight_host::compare::{reference, scene_error};
use cuesight_host::grid::scenes;

fn main() {
    let grid = scenes(77, 6000);
    for model in Model::ALL {
        let mut ratios: Vec<f64> = grid
            .iter()
            .map(|s| {
                let r = reference(s).unwrap();
                let out = collide(&s.params(), &s.impact(), model).unwrap();
                let e = scene_error(s, &out, &r);
                let estimate = error_estimate(&s.params(), &s.impact(), model) as f64;
                e.velocity.max(e.spin) / estimate
            })
            .collect();
        ratios.sort_by(|a, b| a.total_cmp(b));
        let q = |p: f64| ratios[((ratios.len() - 1) as f64 * p) as usize];
        println!(
            "{:9} true/estimated error: p50 {:.3} p90 {:.3} p99 {:.3} p99.5 {:.3} max {:.3}",
            model.name(),
            q(0.5),
            q(0.9),
            q(0.99),
            q(0.995),
            q(1.0)
        );
    }
}
