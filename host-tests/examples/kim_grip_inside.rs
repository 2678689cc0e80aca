//! `KimGrip` inside its validity domain, measure by measure: on the domain map's scenes
//! (`cuesight_host::domain`, any seed and count) it answers, the worst |Δv|/U, R|Δω|/U
//! and throw error (object ball leaving with ≥ 5 % of U, as the domain map) against the
//! reference, each with its scene, and the worst |Δv|/U and R|Δω|/U per band of μ —
//! the three figures issue 16 item 3 bounds (0.25 %, 0.5 %, 0.1°), which the domain
//! map's test asserts on seed 16's 100,000 scenes only.
//!
//! `cargo run --release -p cuesight-host --example kim_grip_inside -- [SEED] [COUNT]`
//! (default: seed 16, 100,000 scenes; about 10 s per 100,000 on two cores, the reference
//! solving only the scenes `KimGrip` answers).
use cuesight::{collide, Model};
use cuesight_host::compare::scene_error;
use cuesight_host::domain::{scene, MIN_OBJECT_SPEED};

/// Upper edges of the μ bands (the law's largest μ).
const MU_BANDS: [f64; 5] = [0.05, 0.1, 0.15, 0.5, 1.0];

/// What one thread found: scenes answered, the worst of each measure with its scene
/// index, and the worst |Δv|/U and R|Δω|/U per μ band.
#[derive(Default)]
struct Worst {
    answered: usize,
    measure: [(f64, u64); 3],
    bands: [[f64; 2]; MU_BANDS.len()],
}

impl Worst {
    fn merge(mut self, other: Worst) -> Worst {
        self.answered += other.answered;
        for (mine, theirs) in self.measure.iter_mut().zip(other.measure) {
            if theirs.0 > mine.0 {
                *mine = theirs;
            }
        }
        for (mine, theirs) in self.bands.iter_mut().zip(other.bands) {
            for (m, t) in mine.iter_mut().zip(theirs) {
                *m = m.max(t);
            }
        }
        self
    }
}

fn scan(seed: u64, indices: impl Iterator<Item = u64>) -> Worst {
    let mut worst = Worst::default();
    for index in indices {
        let d = scene(seed, index);
        let Ok(out) = collide(&d.params(), &d.impact(), Model::KimGrip) else {
            continue;
        };
        worst.answered += 1;
        let reference = d.reference();
        let e = scene_error(&d.scene, &out, &reference);
        let moving = reference.object_ball.velocity.length() / d.scene.speed() >= MIN_OBJECT_SPEED;
        let values = [e.velocity, e.spin, if moving { e.throw_deg } else { 0.0 }];
        for (w, v) in worst.measure.iter_mut().zip(values) {
            if v > w.0 {
                *w = (v, index);
            }
        }
        let band = MU_BANDS
            .iter()
            .position(|&edge| d.mu() <= edge)
            .unwrap_or(MU_BANDS.len() - 1);
        worst.bands[band][0] = worst.bands[band][0].max(e.velocity);
        worst.bands[band][1] = worst.bands[band][1].max(e.spin);
    }
    worst
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seed: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(16);
    let count: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let worst = std::thread::scope(|s| {
        let halves: Vec<_> = (0..2u64)
            .map(|half| s.spawn(move || scan(seed, (half..count).step_by(2))))
            .collect();
        halves
            .into_iter()
            .map(|h| h.join().expect("scanning thread"))
            .fold(Worst::default(), Worst::merge)
    });
    println!(
        "seed {seed}, {count} domain scenes: KimGrip answers {} (the rest outside its validity domain)",
        worst.answered
    );
    for (name, (value, index)) in ["|dv|/U", "R|dw|/U"].iter().zip(&worst.measure) {
        println!("worst {name} {:.3} % (scene {index})", 100.0 * value);
    }
    let (throw, index) = worst.measure[2];
    println!("worst throw {throw:.3} deg (scene {index})");
    let mut low = 0.0;
    for (edge, [velocity, spin]) in MU_BANDS.iter().zip(worst.bands) {
        println!(
            "mu {low}-{edge}: |dv|/U {:.3} %, R|dw|/U {:.3} %",
            100.0 * velocity,
            100.0 * spin
        );
        low = *edge;
    }
}
