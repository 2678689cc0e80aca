//! The seeded scene grid the core is judged on (foundation issue): ≥ 10,000 scenes
//! spanning U 0.2–8 m/s, |φ| ≤ 85°, stun / follow / draw / side / near-gearing spins,
//! μ 0.02–0.1, e* 0.9–1, μ_s 0–0.4, pool balls.
//!
//! Inputs are generated in f64, rounded to f32 once, and both the core and the
//! reference see those same rounded values.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Kind of cue-ball spin in a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpinKind {
    /// No spin.
    Stun,
    /// Topspin, 0–150 % of natural roll.
    Follow,
    /// Backspin, 0–200 % of natural roll (reversed).
    Draw,
    /// Side spin with a random follow/draw fraction.
    Side,
    /// Side spin and topspin tuned so the initial slip is within ±5 % of U.
    NearGearing,
}

/// One scene: inputs in the collision frame (f32-representable values).
#[derive(Clone, Copy, Debug)]
pub struct Scene {
    /// Spin category.
    pub kind: SpinKind,
    /// Cue-ball velocity `[v_x, v_y]` (m/s).
    pub velocity: [f32; 2],
    /// Cue-ball spin (rad/s).
    pub spin: [f32; 3],
    /// μ.
    pub mu: f32,
    /// e*.
    pub restitution: f32,
    /// μ_s.
    pub mu_s: f32,
    /// R (m).
    pub radius: f32,
    /// M (kg).
    pub mass: f32,
}

impl Scene {
    /// Speed `|velocity|` (m/s).
    pub fn speed(&self) -> f64 {
        (self.velocity[0] as f64).hypot(self.velocity[1] as f64)
    }

    /// Core parameters.
    pub fn params(&self) -> cuesight::Params {
        cuesight::Params::new(self.mu, self.restitution, self.mu_s, self.radius, self.mass)
            .expect("grid params are valid")
    }

    /// Core impact.
    pub fn impact(&self) -> cuesight::Impact {
        cuesight::Impact::from_velocity(self.velocity, self.spin).expect("grid impact is valid")
    }
}

/// The seeded grid: `count` scenes, cycling through the spin kinds.
pub fn scenes(seed: u64, count: usize) -> Vec<Scene> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let kinds = [
        SpinKind::Stun,
        SpinKind::Follow,
        SpinKind::Draw,
        SpinKind::Side,
        SpinKind::NearGearing,
    ];
    let radius = 0.028575f64;
    (0..count)
        .map(|i| {
            let kind = kinds[i % kinds.len()];
            let speed = rng.random_range(0.2..=8.0f64);
            let cut = rng.random_range(-85.0..=85.0f64).to_radians();
            let (vx, vy) = (speed * cut.cos(), speed * cut.sin());
            let roll = [-vy / radius, vx / radius, 0.0];
            let spin = match kind {
                SpinKind::Stun => [0.0, 0.0, 0.0],
                SpinKind::Follow => {
                    let f = rng.random_range(0.0..=1.5);
                    [roll[0] * f, roll[1] * f, 0.0]
                }
                SpinKind::Draw => {
                    let f = -rng.random_range(0.0..=2.0);
                    [roll[0] * f, roll[1] * f, 0.0]
                }
                SpinKind::Side => {
                    let f = rng.random_range(-1.0..=1.5);
                    let side = rng.random_range(-1.5..=1.5) * speed / radius;
                    [roll[0] * f, roll[1] * f, side]
                }
                SpinKind::NearGearing => {
                    // v_y0 = −v_y − R ω_z = δ_y U,  v_z0 = R ω_y = δ_z U.
                    let dy = rng.random_range(-0.05..=0.05) * speed;
                    let dz = rng.random_range(-0.05..=0.05) * speed;
                    let wx = rng.random_range(-1.0..=1.0) * speed / radius;
                    [wx, dz / radius, (-vy - dy) / radius]
                }
            };
            Scene {
                kind,
                velocity: [vx as f32, vy as f32],
                spin: [spin[0] as f32, spin[1] as f32, spin[2] as f32],
                mu: rng.random_range(0.02..=0.1f64) as f32,
                restitution: rng.random_range(0.9..=1.0f64) as f32,
                mu_s: rng.random_range(0.0..=0.4f64) as f32,
                radius: radius as f32,
                mass: 0.17,
            }
        })
        .collect()
}
