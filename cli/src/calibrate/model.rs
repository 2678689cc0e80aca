//! The throw model of a fit: which parameters are fitted ([`FitKind`]), what computes
//! the throw ([`Solver`]), the physical parameters ([`Physics`]) and the rigid ceiling.

use cuesight::{FrictionLaw, Impact, Model, Params};
use glam::DVec3;

use super::input::{Measurement, Spin};
use cuesight_host::reference::{self, ReferenceConfig, ReferenceParams};

/// Which parameters are fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FitKind {
    /// A constant μ.
    Mu,
    /// `μ(v) = a + b·exp(−c·v)` (TP A.14), `v` the slip speed.
    #[value(name = "mu-v")]
    MuV,
    /// μ(v) and the energetic restitution e*.
    #[value(name = "mu-v-e")]
    MuVE,
    /// μ(v) and the contact's tangential compliance `κ = k_t/k_n` (the reference
    /// solver's compliant contact, `reference/compliant.rs`; always `--model reference`).
    #[value(name = "mu-v-k")]
    MuVK,
}

impl FitKind {
    /// The `--fit` name.
    pub const fn name(self) -> &'static str {
        match self {
            FitKind::Mu => "mu",
            FitKind::MuV => "mu-v",
            FitKind::MuVE => "mu-v-e",
            FitKind::MuVK => "mu-v-k",
        }
    }

    /// Names of the fitted parameters, as `collide` takes them.
    pub const fn parameter_names(self) -> &'static [&'static str] {
        match self {
            FitKind::Mu => &["mu"],
            FitKind::MuV => &["mu", "mu_b", "mu_c"],
            FitKind::MuVE => &["mu", "mu_b", "mu_c", "restitution"],
            FitKind::MuVK => &["mu", "mu_b", "mu_c", "tangential_stiffness"],
        }
    }

    /// Number of fitted parameters.
    pub const fn len(self) -> usize {
        self.parameter_names().len()
    }

    /// Always false (every kind fits at least μ); for clippy's `len_without_is_empty`.
    pub const fn is_empty(self) -> bool {
        false
    }
}

/// What computes the model's throw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Solver {
    /// The core's `KimGrip` tier, evaluated in f64 (`cuesight::collide_f64`); `Exact`
    /// where the parameters leave `KimGrip`'s validity domain (μ(0)·μ_s > 0.2), which a
    /// fit's search and its profile-likelihood scans can reach.
    KimGrip,
    /// The core's `Exact` tier, evaluated in f64.
    Exact,
    /// The f64 first-principles reference solver (`reference::solve`, 1,000 steps).
    Reference,
}

impl Solver {
    /// The `--model` name.
    pub const fn name(self) -> &'static str {
        match self {
            Solver::KimGrip => "kim-grip",
            Solver::Exact => "exact",
            Solver::Reference => "reference",
        }
    }
}

/// Parameters that are not fitted (and the fitted ones' values outside a fit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Physics {
    /// μ(v)'s high-speed limit `a` (the constant μ when `b = 0`).
    pub mu: f64,
    /// Amplitude `b`.
    pub mu_b: f64,
    /// Decay rate `c` (s/m).
    pub mu_c: f64,
    /// Energetic restitution e*.
    pub restitution: f64,
    /// Object-ball/table friction μ_s.
    pub mu_s: f64,
    /// Ball radius (m).
    pub radius: f64,
    /// Ball mass (kg).
    pub mass: f64,
    /// Tangential compliance `κ = k_t/k_n` of the ball–ball contact (reference solver
    /// only); `None`: the rigid contact.
    pub tangential_stiffness: Option<f64>,
}

impl Physics {
    /// The core's pool defaults (μ = 0.05 constant, e* = 0.95, μ_s = 0.3).
    pub fn pool() -> Self {
        let p = Params::POOL;
        Self {
            mu: p.mu() as f64,
            mu_b: 0.0,
            mu_c: 0.0,
            restitution: p.restitution() as f64,
            mu_s: p.mu_s() as f64,
            radius: p.radius() as f64,
            mass: p.mass() as f64,
            tangential_stiffness: None,
        }
    }

    pub(super) fn with(mut self, kind: FitKind, theta: &[f64]) -> Self {
        self.mu = theta[0];
        match kind {
            FitKind::Mu => {
                self.mu_b = 0.0;
                self.mu_c = 0.0;
            }
            FitKind::MuV | FitKind::MuVE | FitKind::MuVK => {
                self.mu_b = theta[1];
                self.mu_c = theta[2];
            }
        }
        match kind {
            FitKind::MuVE => self.restitution = theta[3],
            FitKind::MuVK => self.tangential_stiffness = Some(theta[3]),
            FitKind::Mu | FitKind::MuV => {}
        }
        self
    }

    pub(super) fn core(&self) -> Result<Params, String> {
        let law = if self.mu_b == 0.0 && self.mu_c == 0.0 {
            FrictionLaw::constant(self.mu as f32)
        } else {
            FrictionLaw::speed_dependent(self.mu as f32, self.mu_b as f32, self.mu_c as f32)
        }
        .map_err(|e| e.to_string())?;
        Params::POOL
            .with_friction_law(law)
            .with_restitution(self.restitution as f32)
            .and_then(|p| p.with_mu_s(self.mu_s as f32))
            .and_then(|p| p.with_ball(self.radius as f32, self.mass as f32))
            .map_err(|e| e.to_string())
    }
}

/// The model's throw (degrees) for one measurement (the reference solver at its default
/// steps).
pub fn model_throw(solver: Solver, physics: &Physics, m: &Measurement) -> Result<f64, String> {
    model_throw_with(solver, physics, m, ReferenceConfig::default().steps)
}

/// [`model_throw`] with the compliant reference solver at `compliant_steps` steps
/// (`ReferenceConfig::steps`; the rigid contact always takes its default).
pub fn model_throw_with(
    solver: Solver,
    physics: &Physics,
    m: &Measurement,
    compliant_steps: usize,
) -> Result<f64, String> {
    let w = m.spin.vector(m.speed_mps, m.cut_deg, physics.radius);
    match solver {
        Solver::KimGrip | Solver::Exact if physics.tangential_stiffness.is_some() => Err(
            "the compliant contact (tangential_stiffness) is in the reference solver only: --model reference"
                .to_owned(),
        ),
        Solver::KimGrip | Solver::Exact => {
            let params = physics.core()?;
            let impact =
                Impact::from_cut_degrees(m.speed_mps as f32, m.cut_deg as f32, w.map(|x| x as f32))
                    .map_err(|e| e.to_string())?;
            let model = match solver {
                Solver::KimGrip => Model::KimGrip,
                _ => Model::Exact,
            };
            let out = match cuesight::collide_f64(&params, &impact, model) {
                Err(cuesight::Error::OutsideValidity { .. }) => {
                    cuesight::collide_f64(&params, &impact, Model::Exact)
                }
                answer => answer,
            }
            .map_err(|e| e.to_string())?;
            Ok(out.throw_angle_deg() as f64)
        }
        Solver::Reference => {
            let p = ReferenceParams {
                mu: physics.mu,
                mu_b: physics.mu_b,
                mu_c: physics.mu_c,
                restitution: physics.restitution,
                mu_s: physics.mu_s,
                cue_table_friction: 0.0,
                radius: physics.radius,
                mass: physics.mass,
            };
            let phi = m.cut_deg.to_radians();
            let v = DVec3::new(m.speed_mps * phi.cos(), m.speed_mps * phi.sin(), 0.0);
            let defaults = ReferenceConfig::default();
            let config = ReferenceConfig {
                tangential_stiffness: physics.tangential_stiffness,
                steps: match physics.tangential_stiffness {
                    Some(_) => compliant_steps,
                    None => defaults.steps,
                },
                ..defaults
            };
            reference::solve(&p, v, DVec3::from(w), &config)
                .map(|o| o.throw_angle_deg())
                .map_err(|e| format!("reference solver: {e:?}"))
        }
    }
}

/// The rigid-ball ceiling on throw (degrees): the contact grips and the friction
/// impulse is the one that stops the slip (`ΔV_y = v_y0/7`, TP A.14's 1/7 cap) over the
/// frictionless normal impulse, `atan(2 (U sin φ + R ω_z) / (7 (1 + e*) U cos φ))`; for
/// a stun ball `atan(2 tan φ / (7 (1 + e*)))`. No friction law exceeds it (the
/// object ball's table friction only adds to `V_x`).
pub fn rigid_ceiling_deg(m: &Measurement, restitution: f64, radius: f64) -> f64 {
    let w = m.spin.vector(m.speed_mps, m.cut_deg, radius);
    let phi = m.cut_deg.to_radians();
    let side = m.speed_mps * phi.sin() + radius * w[2];
    (2.0 * side)
        .atan2(7.0 * (1.0 + restitution) * m.speed_mps * phi.cos())
        .to_degrees()
}

/// Measurements with the given spin labelled stun (for tests and examples).
pub fn stun(id: &str, series: &str, cut_deg: f64, speed_mps: f64, throw_deg: f64) -> Measurement {
    Measurement {
        id: id.to_owned(),
        series: series.to_owned(),
        cut_deg,
        speed_mps,
        spin: Spin::Ratio(0.0),
        throw_deg,
        uncertainty_deg: None,
    }
}
