//! First-principles reference solver (f64), independent of the seed's component
//! equations.
//!
//! Two rigid spheres (mass `M`, radius `R`, inertia `I = 2/5 M R²`) and a rigid table
//! are integrated through the impact with the ball–ball **normal impulse `p`** as the
//! independent variable (gravity and contact duration neglected, as in the seed). At
//! every step each contact force is applied as an impulse at its contact point, with
//! its torque `r × J`:
//!
//! * ball–ball contact at `+R x̂` from the cue ball / `−R x̂` from the object ball:
//!   normal impulse `dp x̂` on the object ball, Coulomb friction `|dJ_t| ≤ μ dp`
//!   opposing the tangential slip of the object-ball contact point relative to the
//!   cue-ball one, with **explicit stick**: when the slip would reach zero inside a step
//!   the tangential impulse that zeroes it is solved for (Newton on the piecewise-affine
//!   step map) and accepted if it lies in the friction cone; while stuck, the impulse
//!   that keeps the slip at zero is solved for every step and sliding resumes if it
//!   leaves the cone;
//! * table contact at `−R ẑ` of each ball: a unilateral constraint. Whenever a step
//!   would push a ball's centre down, the table supplies the normal impulse that
//!   cancels it; with it comes Coulomb friction (`μ_s` for the object ball,
//!   `cue_table_friction` — zero by default, as in the seed — for the cue ball)
//!   opposing the table-contact slip, with stick when the needed impulse is small
//!   enough. A ball pushed up simply leaves the table.
//! * restitution is Stronge's energetic one: the impact ends when the work of the
//!   normal force during restitution equals `e*²` times minus its work during
//!   compression (seed eq. (37)).
//!
//! Sliding steps use the midpoint rule for the friction direction (second order);
//! compression end, stick onset and impact end are located inside their steps
//! (`rigid.rs`).
//!
//! Optionally (`ReferenceConfig::tangential_stiffness`, off by default) the ball–ball
//! contact is compliant instead: a normal and a tangential spring, the tangential one
//! in series with the Coulomb slider, so that stored tangential strain can reverse the
//! slip and throw can exceed the rigid ceiling (`compliant.rs`, which gives the model,
//! its sources and its closed-form checks; issue 19).

use glam::DVec3;

mod compliant;
mod rigid;

/// Moment-of-inertia factor of a solid sphere.
const NU: f64 = 0.4;

/// Parameters of a reference solve (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceParams {
    /// Ball–ball friction coefficient μ; with `mu_b > 0` the high-speed limit `a` of
    /// `μ(v) = a + b·exp(−c·v)` (TP A.14), `v` the slip speed.
    pub mu: f64,
    /// Amplitude `b` of the speed-dependent part (0: constant μ).
    pub mu_b: f64,
    /// Decay rate `c` (s/m) of the speed-dependent part.
    pub mu_c: f64,
    /// Energetic coefficient of restitution e*.
    pub restitution: f64,
    /// Object-ball/table friction coefficient μ_s.
    pub mu_s: f64,
    /// Cue-ball/table friction coefficient (the seed neglects it: 0).
    pub cue_table_friction: f64,
    /// Ball radius R (m).
    pub radius: f64,
    /// Ball mass M (kg).
    pub mass: f64,
}

impl ReferenceParams {
    /// The same parameters as a validated core `Params` (cue-ball/table friction 0).
    pub fn from_core(p: &cuesight::Params) -> Self {
        let (mu, mu_b, mu_c) = match p.friction_law() {
            cuesight::FrictionLaw::Constant(mu) => (mu as f64, 0.0, 0.0),
            cuesight::FrictionLaw::SpeedDependent { a, b, c } => (a as f64, b as f64, c as f64),
        };
        Self {
            mu,
            mu_b,
            mu_c,
            restitution: p.restitution() as f64,
            mu_s: p.mu_s() as f64,
            cue_table_friction: p.cue_table_friction() as f64,
            radius: p.radius() as f64,
            mass: p.mass() as f64,
        }
    }
}

/// Integration settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceConfig {
    /// Number of steps across the frictionless impact `(1 + e*) M U_x / 2` (the compliant
    /// contact: at most `π/steps` of the normal spring's phase and `10/steps` rad of the
    /// tangential one per step, `reference/compliant.rs`).
    pub steps: usize,
    /// Apply table friction along `∓x` only, as the seed's eq. (7) approximates,
    /// instead of against the table-contact slip (for measuring that approximation).
    pub table_friction_along_x: bool,
    /// Tangential compliance of the ball–ball contact (`reference/compliant.rs`): the ratio
    /// `κ = k_t/k_n` of the contact's tangential to normal stiffness (dimensionless;
    /// Mindlin's elastic value `2(1 − ν)/(2 − ν)`, 0.67–0.82 for Poisson's ratios
    /// 0–0.4). `None` (the default): the rigid contact, bit for bit the solver without
    /// this option. `κ → ∞` is the rigid limit.
    pub tangential_stiffness: Option<f64>,
}

impl ReferenceParams {
    /// Constant-μ parameters (no cue-ball/table friction).
    pub fn constant(mu: f64, restitution: f64, mu_s: f64, radius: f64, mass: f64) -> Self {
        Self {
            mu,
            mu_b: 0.0,
            mu_c: 0.0,
            restitution,
            mu_s,
            cue_table_friction: 0.0,
            radius,
            mass,
        }
    }

    /// Friction coefficient at slip speed `v` (m/s).
    pub fn mu_at(&self, slip_speed: f64) -> f64 {
        self.mu + self.mu_b * (-self.mu_c * slip_speed).exp()
    }
}

impl Default for ReferenceConfig {
    fn default() -> Self {
        Self {
            steps: 1000,
            table_friction_along_x: false,
            tangential_stiffness: None,
        }
    }
}

/// Contact regime observed by the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceRegime {
    /// μ = 0.
    Frictionless,
    /// Slip never vanished.
    Sliding,
    /// Slip vanished at some point (or was zero from the start) and the contact stuck.
    Gripping,
}

/// Linear and angular velocity of a ball.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BallState {
    /// Centre velocity (m/s).
    pub velocity: DVec3,
    /// Angular velocity (rad/s).
    pub spin: DVec3,
}

/// What the reference solver found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceOutcome {
    /// Cue ball after the impact.
    pub cue_ball: BallState,
    /// Object ball after the impact.
    pub object_ball: BallState,
    /// Contact regime.
    pub regime: ReferenceRegime,
    /// Final normal impulse `p_f` (N·s).
    pub normal_impulse: f64,
    /// Normal impulse at the end of compression `p_c` (N·s).
    pub compression_impulse: f64,
    /// Normal impulse at which the contact first stuck, if it did (N·s).
    pub stick_impulse: Option<f64>,
    /// Total ball–ball friction impulse on the object ball (N·s).
    pub friction_impulse: DVec3,
    /// Total table friction impulse on the object ball (N·s).
    pub table_friction_impulse: DVec3,
    /// Steps taken.
    pub steps: usize,
}

impl ReferenceOutcome {
    /// Throw angle `atan2(V_y, V_x)` in degrees.
    pub fn throw_angle_deg(&self) -> f64 {
        let v = self.object_ball.velocity;
        v.y.atan2(v.x).to_degrees()
    }

    /// Cue-ball deflection from the tangent line, `atan2(U_x, |U_y|)`, in degrees.
    pub fn cue_deflection_deg(&self) -> f64 {
        let u = self.cue_ball.velocity;
        u.x.atan2(u.y.abs()).to_degrees()
    }

    /// Total kinetic energy of both balls (J) for mass `m` and radius `r`.
    pub fn kinetic_energy(&self, m: f64, r: f64) -> f64 {
        kinetic_energy(&self.cue_ball, m, r) + kinetic_energy(&self.object_ball, m, r)
    }
}

/// Kinetic energy of one ball (J).
pub fn kinetic_energy(b: &BallState, m: f64, r: f64) -> f64 {
    0.5 * m * b.velocity.length_squared() + 0.5 * NU * m * r * r * b.spin.length_squared()
}

/// Why a reference solve was refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReferenceError {
    /// A parameter is non-finite or out of its physical range.
    BadParameter(&'static str),
    /// The cue ball does not approach the object ball (`U_x ≤ 0`).
    NoApproach,
}

fn check(name: &'static str, v: f64, lo: f64, hi: f64) -> Result<(), ReferenceError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(ReferenceError::BadParameter(name))
    }
}

/// Solve one impact: cue ball with `velocity` (z ignored) and `spin` hits the resting
/// object ball, collision frame.
pub fn solve(
    params: &ReferenceParams,
    velocity: DVec3,
    spin: DVec3,
    config: &ReferenceConfig,
) -> Result<ReferenceOutcome, ReferenceError> {
    check("mu", params.mu, 0.0, 10.0)?;
    check("mu_b", params.mu_b, 0.0, 10.0)?;
    check("mu_c", params.mu_c, 0.0, 1e3)?;
    check("restitution", params.restitution, 0.0, 1.0)?;
    check("mu_s", params.mu_s, 0.0, 10.0)?;
    check("cue_table_friction", params.cue_table_friction, 0.0, 10.0)?;
    check("radius", params.radius, 1e-6, 1e3)?;
    check("mass", params.mass, 1e-6, 1e3)?;
    if !(velocity.is_finite() && spin.is_finite()) {
        return Err(ReferenceError::BadParameter("velocity/spin"));
    }
    if velocity.x <= 0.0 {
        return Err(ReferenceError::NoApproach);
    }
    match config.tangential_stiffness {
        None => rigid::solve(params, velocity, spin, config),
        Some(kappa) => {
            check("tangential_stiffness", kappa, 1e-6, 1e9)?;
            compliant::solve(params, velocity, spin, config, kappa)
        }
    }
}

fn to_f32(v: DVec3) -> cuesight::Vec3 {
    cuesight::Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}

/// Solve one collision with the reference solver (default configuration) and report
/// it in the core's `Outcome` type (f32), for display next to the closed-form models.
pub fn collide(params: &cuesight::Params, impact: &cuesight::Impact) -> cuesight::Outcome {
    let v = impact.velocity();
    let w = impact.spin();
    let out = solve(
        &ReferenceParams::from_core(params),
        DVec3::new(v.x as f64, v.y as f64, 0.0),
        DVec3::new(w.x as f64, w.y as f64, w.z as f64),
        &ReferenceConfig::default(),
    )
    .expect("validated core inputs are valid reference inputs");
    cuesight::Outcome {
        cue_ball: cuesight::BallState {
            velocity: to_f32(out.cue_ball.velocity),
            spin: to_f32(out.cue_ball.spin),
        },
        object_ball: cuesight::BallState {
            velocity: to_f32(out.object_ball.velocity),
            spin: to_f32(out.object_ball.spin),
        },
        regime: match out.regime {
            ReferenceRegime::Frictionless => cuesight::Regime::Frictionless,
            ReferenceRegime::Sliding => cuesight::Regime::Sliding,
            ReferenceRegime::Gripping => cuesight::Regime::Gripping,
        },
        impulses: cuesight::Impulses {
            normal: out.normal_impulse as f32,
            friction: to_f32(out.friction_impulse),
            table_friction: out.table_friction_impulse.length() as f32,
        },
    }
}
