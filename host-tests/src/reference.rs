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
//! compression end, stick onset and impact end are located inside their steps.

use glam::{DVec2, DVec3};

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
    /// Number of steps across the frictionless impact `(1 + e*) M U_x / 2`.
    pub steps: usize,
    /// Apply table friction along `∓x` only, as the seed's eq. (7) approximates,
    /// instead of against the table-contact slip (for measuring that approximation).
    pub table_friction_along_x: bool,
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

#[derive(Clone, Copy, Debug)]
struct State {
    cue: BallState,
    object: BallState,
    friction: DVec3,
    table_friction: DVec3,
}

struct Solver {
    p: ReferenceParams,
    along_x: bool,
    inertia: f64,
    speed_scale: f64,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Slide,
    Stick,
}

impl Solver {
    fn r_cue(&self) -> DVec3 {
        DVec3::new(self.p.radius, 0.0, 0.0)
    }
    fn r_object(&self) -> DVec3 {
        DVec3::new(-self.p.radius, 0.0, 0.0)
    }
    fn r_table(&self) -> DVec3 {
        DVec3::new(0.0, 0.0, -self.p.radius)
    }

    fn apply(&self, ball: &mut BallState, r: DVec3, impulse: DVec3) {
        ball.velocity += impulse / self.p.mass;
        ball.spin += r.cross(impulse) / self.inertia;
    }

    /// Velocity of the object-ball contact point relative to the cue-ball one.
    fn slip(&self, s: &State) -> DVec3 {
        (s.object.velocity + s.object.spin.cross(self.r_object()))
            - (s.cue.velocity + s.cue.spin.cross(self.r_cue()))
    }

    fn tangential_slip(&self, s: &State) -> DVec2 {
        let v = self.slip(s);
        DVec2::new(v.y, v.z)
    }

    /// Table reaction on one ball after a ball–ball impulse: unilateral normal impulse
    /// and Coulomb friction (with stick) at `−R ẑ`. Returns the friction impulse.
    fn table(&self, ball: &mut BallState, friction_coefficient: f64) -> DVec3 {
        if ball.velocity.z >= 0.0 {
            return DVec3::ZERO;
        }
        let normal = -ball.velocity.z * self.p.mass;
        self.apply(ball, self.r_table(), DVec3::new(0.0, 0.0, normal));
        ball.velocity.z = 0.0;
        let contact = ball.velocity + ball.spin.cross(self.r_table());
        let horizontal = if self.along_x {
            DVec3::new(contact.x, 0.0, 0.0)
        } else {
            DVec3::new(contact.x, contact.y, 0.0)
        };
        let speed = horizontal.length();
        if speed == 0.0 || friction_coefficient == 0.0 {
            return DVec3::ZERO;
        }
        // Contact-point velocity change per horizontal impulse at −R ẑ: (1/M + R²/I).
        let compliance = 1.0 / self.p.mass + self.p.radius * self.p.radius / self.inertia;
        let to_stop = speed / compliance;
        let magnitude = to_stop.min(friction_coefficient * normal);
        let impulse = -horizontal / speed * magnitude;
        self.apply(ball, self.r_table(), impulse);
        impulse
    }

    /// Apply a ball–ball impulse `dp x̂ + (0, j.x, j.y)` on the object ball (and its
    /// opposite on the cue ball), then the table reactions.
    fn step(&self, s: &State, dp: f64, j: DVec2) -> State {
        let mut n = *s;
        let impulse = DVec3::new(dp, j.x, j.y);
        self.apply(&mut n.object, self.r_object(), impulse);
        self.apply(&mut n.cue, self.r_cue(), -impulse);
        n.friction += DVec3::new(0.0, j.x, j.y);
        n.table_friction += self.table(&mut n.object, self.p.mu_s);
        self.table(&mut n.cue, self.p.cue_table_friction);
        n
    }

    /// Tangential impulse that leaves zero slip after a step of `dp` (Newton on the
    /// piecewise-affine map J ↦ slip, finite-difference Jacobian).
    fn stick_impulse(&self, s: &State, dp: f64, guess: DVec2) -> Option<DVec2> {
        let tolerance = 1e-13 * self.speed_scale;
        let mut j = guess;
        for _ in 0..30 {
            let g = self.tangential_slip(&self.step(s, dp, j));
            if g.length() <= tolerance {
                return Some(j);
            }
            let eps = (j.length() * 1e-6).max(1e-9 * self.p.mass * self.speed_scale);
            let gy = (self.tangential_slip(&self.step(s, dp, j + DVec2::new(eps, 0.0))) - g) / eps;
            let gz = (self.tangential_slip(&self.step(s, dp, j + DVec2::new(0.0, eps))) - g) / eps;
            let det = gy.x * gz.y - gz.x * gy.y;
            if det.abs() < 1e-300 {
                return None;
            }
            let delta = DVec2::new(g.x * gz.y - gz.x * g.y, gy.x * g.y - g.x * gy.y) / det;
            j -= delta;
        }
        None
    }

    /// Sliding step: friction `μ dp` against the slip, direction from the midpoint.
    fn slide(&self, s: &State, dp: f64) -> State {
        let t0 = self.tangential_slip(s);
        if t0.length() == 0.0 || dp == 0.0 || self.p.mu_at(0.0) == 0.0 {
            return self.step(s, dp, DVec2::ZERO);
        }
        let half = self.step(
            s,
            0.5 * dp,
            -t0.normalize() * 0.5 * dp * self.p.mu_at(t0.length()),
        );
        let t_half = self.tangential_slip(&half);
        let direction = if t_half.length() > 0.0 && t_half.dot(t0) > 0.0 {
            -t_half.normalize()
        } else {
            -t0.normalize()
        };
        self.step(s, dp, direction * dp * self.p.mu_at(t_half.length()))
    }

    /// Advance by `dp` in the given mode; returns the new state and mode.
    fn advance(&self, s: &State, dp: f64, mode: Mode, depth: u32) -> (State, Mode) {
        // Friction cone for sticking: μ at zero slip (the largest for TP A.14's law).
        let budget = self.p.mu_at(0.0) * dp;
        let t0 = self.tangential_slip(s);
        let k_guess = self.p.mass / 7.0;
        if mode == Mode::Stick || t0.length() <= 1e-13 * self.speed_scale {
            if budget > 0.0 {
                if let Some(j) = self.stick_impulse(s, dp, DVec2::ZERO) {
                    if j.length() <= budget * (1.0 + 1e-9) {
                        return (self.step(s, dp, j), Mode::Stick);
                    }
                }
            } else if t0.length() <= 1e-13 * self.speed_scale {
                return (self.step(s, dp, DVec2::ZERO), Mode::Stick);
            }
        }
        // Close to sticking the slip direction turns quickly; the midpoint rule is only
        // used while one step changes the slip by less than 5 %. Otherwise either the
        // slip can be zeroed within this step (stick onset, solved exactly) or the step
        // is split.
        let relative_change = 7.0 * budget / (self.p.mass * t0.length());
        let next = self.slide(s, dp);
        let t1 = self.tangential_slip(&next);
        let overshoot = t1.dot(t0) <= 0.0 || t1.length() <= 1e-13 * self.speed_scale;
        if (overshoot || relative_change > 0.05) && budget > 0.0 {
            if let Some(j) = self.stick_impulse(s, dp, -t0 * k_guess) {
                if j.length() <= budget * (1.0 + 1e-9) {
                    return (self.step(s, dp, j), Mode::Stick);
                }
            }
            if depth < 40 {
                let (mid, m) = self.advance(s, 0.5 * dp, Mode::Slide, depth + 1);
                return self.advance(&mid, 0.5 * dp, m, depth + 1);
            }
        }
        (next, Mode::Slide)
    }
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
    let solver = Solver {
        p: *params,
        along_x: config.table_friction_along_x,
        inertia: NU * params.mass * params.radius * params.radius,
        speed_scale: velocity.length().max(params.radius * spin.length()),
    };
    let mut state = State {
        cue: BallState {
            velocity: DVec3::new(velocity.x, velocity.y, 0.0),
            spin,
        },
        object: BallState::default(),
        friction: DVec3::ZERO,
        table_friction: DVec3::ZERO,
    };
    let e = params.restitution;
    let steps = config.steps.max(10);
    let dp = 0.5 * (1.0 + e).max(1.0) * params.mass * velocity.x / steps as f64;
    let mut mode = Mode::Slide;
    let mut stick_impulse = None;
    let mut p = 0.0;
    let mut work = 0.0;
    let mut compression: Option<(f64, f64)> = None; // (p_c, W_c)
    let mut taken = 0;
    let normal_velocity = |s: &State| solver.slip(s).x;
    loop {
        taken += 1;
        let vn0 = normal_velocity(&state);
        let (next, next_mode) = solver.advance(&state, dp, mode, 0);
        let vn1 = normal_velocity(&next);
        let work_next = work + 0.5 * (vn0 + vn1) * dp;
        let mut just_compressed = None;
        if compression.is_none() && vn1 >= 0.0 {
            let fraction = if vn1 > vn0 { -vn0 / (vn1 - vn0) } else { 0.0 };
            let pc = p + fraction * dp;
            let wc = work + 0.5 * vn0 * fraction * dp;
            compression = Some((pc, wc));
            just_compressed = Some(fraction);
        }
        if let Some((_, wc)) = compression {
            let target = wc * (1.0 - e * e);
            if work_next >= target {
                // The impact ends inside this step: bisect on the step fraction.
                let mut lo = just_compressed.unwrap_or(0.0);
                let mut hi = 1.0;
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    let (trial, _) = solver.advance(&state, mid * dp, mode, 0);
                    let w = work + 0.5 * (vn0 + normal_velocity(&trial)) * mid * dp;
                    if w >= target {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let (last, last_mode) = solver.advance(&state, hi * dp, mode, 0);
                if last_mode == Mode::Stick && stick_impulse.is_none() {
                    stick_impulse = Some(p);
                }
                state = last;
                p += hi * dp;
                break;
            }
        }
        if next_mode == Mode::Stick && stick_impulse.is_none() {
            stick_impulse = Some(p);
        }
        state = next;
        mode = next_mode;
        work = work_next;
        p += dp;
        if taken > 100 * steps {
            break; // cannot happen for valid input: v_x grows by ≥ dp/M per step
        }
    }
    let regime = if params.mu_at(0.0) == 0.0 {
        ReferenceRegime::Frictionless
    } else if stick_impulse.is_some() {
        ReferenceRegime::Gripping
    } else {
        ReferenceRegime::Sliding
    };
    Ok(ReferenceOutcome {
        cue_ball: state.cue,
        object_ball: state.object,
        regime,
        normal_impulse: p,
        compression_impulse: compression.map_or(p, |c| c.0),
        stick_impulse,
        friction_impulse: state.friction,
        table_friction_impulse: state.table_friction,
        steps: taken,
    })
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
