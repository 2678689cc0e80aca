//! Error metrics between a core (f32) outcome and a reference (f64) outcome, as the
//! foundation issue states them: `|Δv|/U`, `R|Δω|/U` (worst of the two balls, full
//! 3-vectors) and the throw-angle difference in degrees.

use crate::grid::Scene;
use crate::reference::{solve, ReferenceConfig, ReferenceError, ReferenceOutcome, ReferenceParams};
use glam::DVec3;

/// Widen a core vector.
pub fn widen(v: cuesight::Vec3) -> DVec3 {
    DVec3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// Reference solve of a grid scene with the default configuration.
pub fn reference(scene: &Scene) -> Result<ReferenceOutcome, ReferenceError> {
    reference_with(scene, &ReferenceConfig::default())
}

/// Reference solve of a grid scene.
pub fn reference_with(
    scene: &Scene,
    config: &ReferenceConfig,
) -> Result<ReferenceOutcome, ReferenceError> {
    solve(
        &ReferenceParams::from_core(&scene.params()),
        DVec3::new(scene.velocity[0] as f64, scene.velocity[1] as f64, 0.0),
        widen(cuesight::Vec3::from_array(scene.spin)),
        config,
    )
}

/// The three error measures of one scene.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SceneError {
    /// `max(|ΔU|, |ΔV|) / U_i`.
    pub velocity: f64,
    /// `R max(|Δω|, |ΔΩ|) / U_i`.
    pub spin: f64,
    /// `|Δψ|` in degrees.
    pub throw_deg: f64,
}

/// Errors of `model` against `reference` for `scene`.
pub fn scene_error(
    scene: &Scene,
    model: &cuesight::Outcome,
    reference: &ReferenceOutcome,
) -> SceneError {
    let speed = scene.speed();
    let radius = scene.radius as f64;
    let dv = widen(model.cue_ball.velocity)
        .distance(reference.cue_ball.velocity)
        .max(widen(model.object_ball.velocity).distance(reference.object_ball.velocity));
    let dw = widen(model.cue_ball.spin)
        .distance(reference.cue_ball.spin)
        .max(widen(model.object_ball.spin).distance(reference.object_ball.spin));
    SceneError {
        velocity: dv / speed,
        spin: radius * dw / speed,
        throw_deg: (model.throw_angle_deg() as f64 - reference.throw_angle_deg()).abs(),
    }
}

/// Max and RMS of each measure over a set of scenes, with the index of each maximum.
#[derive(Clone, Copy, Debug, Default)]
pub struct Summary {
    /// Scenes counted.
    pub count: usize,
    /// Largest error of each measure.
    pub max: SceneError,
    /// Index (into the scenes given) of each maximum: velocity, spin, throw.
    pub argmax: [usize; 3],
    /// Root-mean-square of each measure.
    pub rms: SceneError,
}

impl Summary {
    /// Summarise `(index, error)` pairs.
    pub fn of(errors: impl IntoIterator<Item = (usize, SceneError)>) -> Self {
        let mut s = Summary::default();
        let mut sum = [0.0f64; 3];
        for (i, e) in errors {
            s.count += 1;
            for (k, (value, max)) in [
                (e.velocity, &mut s.max.velocity),
                (e.spin, &mut s.max.spin),
                (e.throw_deg, &mut s.max.throw_deg),
            ]
            .into_iter()
            .enumerate()
            {
                sum[k] += value * value;
                if value > *max {
                    *max = value;
                    s.argmax[k] = i;
                }
            }
        }
        let n = s.count.max(1) as f64;
        s.rms = SceneError {
            velocity: (sum[0] / n).sqrt(),
            spin: (sum[1] / n).sqrt(),
            throw_deg: (sum[2] / n).sqrt(),
        };
        s
    }
}

impl Summary {
    /// The figures the docs quote of this summary, `(key, value)`: its maxima
    /// (`KEY-velocity` and `KEY-spin` in % of U, `KEY-throw` in degrees, with `max`
    /// decimals) and its RMS (`KEY-rms`, `v %, Rω %, throw°`, with `rms` decimals). A test
    /// records them (`cuesight_figures::record!`).
    pub fn figures(&self, key: &str, max: [usize; 3], rms: [usize; 3]) -> Vec<(String, String)> {
        let [v, w, t] = max;
        let [rv, rw, rt] = rms;
        vec![
            (
                format!("{key}-velocity"),
                format!("{:.v$}", 100.0 * self.max.velocity),
            ),
            (
                format!("{key}-spin"),
                format!("{:.w$}", 100.0 * self.max.spin),
            ),
            (
                format!("{key}-throw"),
                format!("{:.t$}", self.max.throw_deg),
            ),
            (
                format!("{key}-rms"),
                format!(
                    "{:.rv$} %, {:.rw$} %, {:.rt$}°",
                    100.0 * self.rms.velocity,
                    100.0 * self.rms.spin,
                    self.rms.throw_deg
                ),
            ),
        ]
    }
}

/// A count as the docs print it: `10,000`.
pub fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

impl core::fmt::Display for Summary {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} scenes: max |dv|/U {:.4} %, max R|dw|/U {:.4} %, max throw error {:.4} deg; \
             RMS {:.4} %, {:.4} %, {:.4} deg",
            self.count,
            100.0 * self.max.velocity,
            100.0 * self.max.spin,
            self.max.throw_deg,
            100.0 * self.rms.velocity,
            100.0 * self.rms.spin,
            self.rms.throw_deg
        )
    }
}
