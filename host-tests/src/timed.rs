//! Time-domain (finite-duration) collision solver with gravity, f64, first principles.
//!
//! It exists to measure where the impulsive approximation of [`crate::reference`] (and of
//! every `core` model: gravity neglected, contact instantaneous, seed eqs. (4)–(8)) stops
//! being accurate at low speed. Everything the impulsive reference has is kept, with
//! time as the clock instead of the normal impulse, and two things are added:
//!
//! * **a contact duration.** The ball–ball normal force is Hertzian, `F = k δ^{3/2}`,
//!   `k = (4/3) E* √(R/2)`, `1/E* = 2 (1 − ν²)/E` (two equal balls), while the overlap `δ`
//!   grows. Dissipation is a loading/unloading hysteresis: from the largest overlap
//!   `δ_m` the force follows `F = (k/e*³) (δ − (1 − e*²) δ_m)^{3/2}`, which meets the
//!   loading curve at `δ_m` and returns exactly `e*²` of the compression work. That is
//!   Stronge's energetic coefficient (seed eq. (37)) by construction, whatever friction
//!   and the table do to the normal motion, and for every speed (no calibration).
//!   Reloading follows the same curve; beyond `δ_m` it is virgin loading again.
//! * **gravity.** `M g` acts on both balls throughout; both start at rest on the table
//!   (normal force `M g`). The table's friction on the object ball (`μ_s`) therefore has
//!   a normal force to work with even without any ball–ball friction — the effect that
//!   the impulsive model drops and that dominates at low speed.
//!
//! Contacts, with every force applied at its contact point with its torque `r × F`:
//!
//! * ball–ball: normal `n` from the cue-ball centre to the object-ball centre — fixed
//!   at `x̂` ([`Geometry::Fixed`], the impulsive model's assumption) or the current line
//!   of centres ([`Geometry::Moving`]); lever arms `±R n`. Coulomb friction
//!   `|F_t| ≤ μ F_n` against the tangential slip of the contact points with **explicit
//!   stick**: when the slip would vanish within a step, the tangential impulse that
//!   zeroes it (with the table's response) is solved for and accepted inside the cone;
//!   while stuck, that impulse is solved for every step and sliding resumes if it leaves
//!   the cone. The sliding direction uses the midpoint rule.
//! * table: an explicit unilateral constraint at `−R ẑ` of each ball resting on it
//!   (centre height `R`). Whenever a step would move such a ball's centre down, the
//!   table supplies the normal impulse that cancels it (perfectly inelastic, as in the
//!   reference), with Coulomb friction against the table-contact slip, with stick
//!   (`μ_s` for the object ball; `cue_table_friction`, zero by default as in the seed,
//!   for the cue ball). A ball pushed up leaves the table and flies under gravity.
//!
//! Integration: velocity Verlet with a fixed step `h` (a set fraction of the Hertz
//! duration estimated from the approach speed): half kick — drift — half kick. A kick
//! of length `τ` applies the normal impulse `F_n τ` with friction, the gravity impulse
//! `M g τ` and the table reactions. The impact ends when the unloading force reaches
//! zero (`δ = (1 − e*²) δ_m`); that instant is located inside its step.
use crate::reference::{solve as reference_solve, BallState, ReferenceConfig, ReferenceError};
use crate::reference::{ReferenceOutcome, ReferenceParams};
use glam::{DVec2, DVec3};

/// Moment-of-inertia factor of a solid sphere.
const NU: f64 = 0.4;

/// Gravitational acceleration used by default (m/s²).
pub const GRAVITY: f64 = 9.81;

/// Elastic constants of the ball material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν_p.
    pub poisson_ratio: f64,
}

impl Material {
    /// Phenolic-resin-like constants, E = 11 GPa, ν_p = 0.35, chosen so that a pool-ball
    /// impact (e* = 0.95) lasts 250–300 μs at 1–2 m/s (physics notes §5): 294 μs at
    /// 1 m/s, 256 μs at 2 m/s.
    pub const PHENOLIC: Material = Material {
        youngs_modulus: 11.0e9,
        poisson_ratio: 0.35,
    };

    /// Effective modulus `E*` of two balls of this material: `1/E* = 2 (1 − ν_p²) / E`.
    pub fn effective_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 - self.poisson_ratio * self.poisson_ratio))
    }

    /// Hertz stiffness `k = (4/3) E* √R_eff` (N/m^{3/2}) of two balls of radius `radius`,
    /// `R_eff = R/2`.
    pub fn stiffness(&self, radius: f64) -> f64 {
        4.0 / 3.0 * self.effective_modulus() * (0.5 * radius).sqrt()
    }

    /// Largest overlap `δ_m = (5 m* v² / (4k))^{2/5}` of a head-on Hertz impact at
    /// normal approach speed `speed`, reduced mass `m* = M/2`.
    pub fn max_indentation(&self, radius: f64, mass: f64, speed: f64) -> f64 {
        (5.0 * 0.5 * mass * speed * speed / (4.0 * self.stiffness(radius))).powf(0.4)
    }

    /// Contact duration of a frictionless impact at normal approach speed `speed` with
    /// the hysteresis of energetic restitution `e*`: compression `1.4716 δ_m / v`,
    /// restitution `e*` times that, i.e. `(1 + e*)/2 · 2.9432 δ_m / v` — the classical
    /// `2.87 (m*²/(E*² R_eff v))^{1/5}` for `e* = 1`, so it scales as `v^{-1/5}`.
    pub fn duration(&self, radius: f64, mass: f64, restitution: f64, speed: f64) -> f64 {
        (1.0 + restitution) * 1.471_6 * self.max_indentation(radius, mass, speed) / speed
    }
}

/// Which contact normal the ball–ball force uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Geometry {
    /// `n = x̂` and lever arms `±R x̂` for the whole impact (the impulsive models'
    /// assumption; the only differences from the reference are then gravity and the
    /// contact duration).
    #[default]
    Fixed,
    /// `n` along the current line of centres (the balls move during the impact; for a
    /// cut shot the line of centres turns by about `U sin φ · τ / 2R`).
    Moving,
}

/// Physical parameters of a time-domain solve (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedParams {
    /// Friction, restitution, table friction, radius and mass, as for the reference.
    pub contact: ReferenceParams,
    /// Gravitational acceleration g (m/s²); 0 recovers the impulsive problem.
    pub gravity: f64,
    /// Ball material (sets the Hertz stiffness and so the contact duration).
    pub material: Material,
}

impl TimedParams {
    /// `contact` with default gravity and the phenolic material.
    pub fn new(contact: ReferenceParams) -> Self {
        Self {
            contact,
            gravity: GRAVITY,
            material: Material::PHENOLIC,
        }
    }
}

/// Integration settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedConfig {
    /// Steps per estimated contact duration ([`Material::duration`] at the normal
    /// approach speed): the fixed step is that duration divided by `steps`.
    pub steps: usize,
    /// Contact normal.
    pub geometry: Geometry,
}

impl Default for TimedConfig {
    fn default() -> Self {
        Self {
            steps: 2000,
            geometry: Geometry::Fixed,
        }
    }
}

/// What the time-domain solver found at the instant the balls separate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedOutcome {
    /// Cue ball at separation.
    pub cue_ball: BallState,
    /// Object ball at separation.
    pub object_ball: BallState,
    /// Contact duration (s).
    pub duration: f64,
    /// Time of the largest overlap (end of compression, s).
    pub compression_time: f64,
    /// Largest overlap δ_m (m).
    pub max_indentation: f64,
    /// Largest normal force (N).
    pub peak_force: f64,
    /// Ball–ball normal impulse (N·s).
    pub normal_impulse: f64,
    /// Ball–ball friction impulse on the object ball (N·s).
    pub friction_impulse: DVec3,
    /// Table friction impulse on the object ball (N·s).
    pub table_friction_impulse: DVec3,
    /// The ball–ball contact stuck at some time.
    pub stuck: bool,
    /// Whether each ball (cue, object) is off the table at separation.
    pub airborne: [bool; 2],
    /// Steps taken.
    pub steps: usize,
}

/// Why a time-domain solve was refused or failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimedError {
    /// A parameter is non-finite or out of range (the reference's checks, plus
    /// `e* > 0`, `g ≥ 0`, `E > 0`, `0 ≤ ν_p < 0.5`).
    BadParameter(&'static str),
    /// The cue ball does not approach the object ball (`U_x ≤ 0`).
    NoApproach,
    /// The balls had not separated after 100 estimated contact durations.
    NoSeparation,
    /// The impulsive reference refused the inputs (in [`compare`]).
    Reference(ReferenceError),
}

impl From<ReferenceError> for TimedError {
    fn from(e: ReferenceError) -> Self {
        TimedError::Reference(e)
    }
}

#[derive(Clone, Copy, Debug)]
struct State {
    cue_position: DVec3,
    object_position: DVec3,
    cue: BallState,
    object: BallState,
    friction: DVec3,
    table_friction: DVec3,
}

/// Contact frame: normal and two tangents (`t1` horizontal, `t2 = n × t1`).
#[derive(Clone, Copy)]
struct Frame {
    n: DVec3,
    t1: DVec3,
    t2: DVec3,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Slide,
    Stick,
}

struct Solver {
    p: ReferenceParams,
    gravity: f64,
    geometry: Geometry,
    inertia: f64,
    speed_scale: f64,
}

impl Solver {
    fn frame(&self, s: &State) -> Frame {
        match self.geometry {
            Geometry::Fixed => Frame {
                n: DVec3::X,
                t1: DVec3::Y,
                t2: DVec3::Z,
            },
            Geometry::Moving => {
                let n = (s.object_position - s.cue_position).normalize();
                let t1 = DVec3::Z.cross(n).normalize();
                Frame {
                    n,
                    t1,
                    t2: n.cross(t1),
                }
            }
        }
    }

    fn apply(&self, ball: &mut BallState, r: DVec3, impulse: DVec3) {
        ball.velocity += impulse / self.p.mass;
        ball.spin += r.cross(impulse) / self.inertia;
    }

    /// Tangential slip (components on `t1`, `t2`) of the object-ball contact point
    /// relative to the cue-ball one.
    fn slip(&self, s: &State, f: &Frame) -> DVec2 {
        let r = self.p.radius;
        let v = (s.object.velocity + s.object.spin.cross(-r * f.n))
            - (s.cue.velocity + s.cue.spin.cross(r * f.n));
        DVec2::new(v.dot(f.t1), v.dot(f.t2))
    }

    /// Table reaction on a ball resting on the table after the other impulses of a
    /// kick: unilateral normal impulse, Coulomb friction with stick at `−R ẑ`.
    fn table(&self, ball: &mut BallState, friction_coefficient: f64) -> DVec3 {
        if ball.velocity.z >= 0.0 {
            return DVec3::ZERO;
        }
        let r_table = DVec3::new(0.0, 0.0, -self.p.radius);
        let normal = -ball.velocity.z * self.p.mass;
        self.apply(ball, r_table, DVec3::new(0.0, 0.0, normal));
        ball.velocity.z = 0.0;
        let contact = ball.velocity + ball.spin.cross(r_table);
        let horizontal = DVec3::new(contact.x, contact.y, 0.0);
        let speed = horizontal.length();
        if speed == 0.0 || friction_coefficient == 0.0 {
            return DVec3::ZERO;
        }
        // Contact-point velocity change per unit horizontal impulse: 1/M + R²/I.
        let compliance = 1.0 / self.p.mass + self.p.radius * self.p.radius / self.inertia;
        let magnitude = (speed / compliance).min(friction_coefficient * normal);
        let impulse = -horizontal / speed * magnitude;
        self.apply(ball, r_table, impulse);
        impulse
    }

    /// A kick of duration `tau`: ball–ball impulse `dp n + j.x t1 + j.y t2` on the object
    /// ball (its opposite on the cue ball), gravity, then the table reactions.
    fn kick(&self, s: &State, f: &Frame, dp: f64, j: DVec2, tau: f64) -> State {
        let mut n = *s;
        let r = self.p.radius;
        let tangential = f.t1 * j.x + f.t2 * j.y;
        let impulse = f.n * dp + tangential;
        self.apply(&mut n.object, -r * f.n, impulse);
        self.apply(&mut n.cue, r * f.n, -impulse);
        n.friction += tangential;
        n.object.velocity.z -= self.gravity * tau;
        n.cue.velocity.z -= self.gravity * tau;
        if n.object_position.z <= r {
            n.table_friction += self.table(&mut n.object, self.p.mu_s);
        }
        if n.cue_position.z <= r {
            self.table(&mut n.cue, self.p.cue_table_friction);
        }
        n
    }

    /// Tangential impulse that leaves zero ball–ball slip after the kick (Newton on the
    /// piecewise-affine map, finite-difference Jacobian).
    fn stick_impulse(
        &self,
        s: &State,
        f: &Frame,
        dp: f64,
        tau: f64,
        guess: DVec2,
    ) -> Option<DVec2> {
        let tolerance = 1e-13 * self.speed_scale;
        let mut j = guess;
        for _ in 0..30 {
            let g = self.slip(&self.kick(s, f, dp, j, tau), f);
            if g.length() <= tolerance {
                return Some(j);
            }
            let eps = (j.length() * 1e-6).max(1e-9 * self.p.mass * self.speed_scale);
            let jy = j + DVec2::new(eps, 0.0);
            let jz = j + DVec2::new(0.0, eps);
            let gy = (self.slip(&self.kick(s, f, dp, jy, tau), f) - g) / eps;
            let gz = (self.slip(&self.kick(s, f, dp, jz, tau), f) - g) / eps;
            let det = gy.x * gz.y - gz.x * gy.y;
            if det.abs() < 1e-300 {
                return None;
            }
            j -= DVec2::new(g.x * gz.y - gz.x * g.y, gy.x * g.y - g.x * gy.y) / det;
        }
        None
    }

    /// Sliding kick: friction `μ dp` against the slip, direction from the midpoint.
    fn slide(&self, s: &State, f: &Frame, dp: f64, tau: f64) -> State {
        let t0 = self.slip(s, f);
        if t0.length() == 0.0 || dp == 0.0 || self.p.mu_at(0.0) == 0.0 {
            return self.kick(s, f, dp, DVec2::ZERO, tau);
        }
        let friction = -t0.normalize() * 0.5 * dp * self.p.mu_at(t0.length());
        let half = self.kick(s, f, 0.5 * dp, friction, 0.5 * tau);
        let t_half = self.slip(&half, f);
        let direction = if t_half.length() > 0.0 && t_half.dot(t0) > 0.0 {
            -t_half.normalize()
        } else {
            -t0.normalize()
        };
        self.kick(
            s,
            f,
            dp,
            direction * dp * self.p.mu_at(t_half.length()),
            tau,
        )
    }

    /// One kick (normal impulse `dp` over `tau`) in the given friction mode.
    ///
    /// While stuck (or at zero slip) the impulse `j*` that keeps the slip at zero is
    /// solved for; if it lies outside the cone `μ dp`, sliding starts with the full
    /// friction `μ dp ĵ*` (the implicit Coulomb step: friction against the slip it lets
    /// develop). While sliding, the midpoint rule is used as long as one kick changes
    /// the slip by < 5 % (ball–ball tangential compliance `7/M`); beyond that, stick
    /// onset is solved for, and if the contact cannot stick the kick is split in two
    /// (when it could change the slip by less than its size) or takes the implicit step.
    fn advance(&self, s: &State, dp: f64, tau: f64, mode: Mode, depth: u32) -> (State, Mode) {
        let f = self.frame(s);
        let budget = self.p.mu_at(0.0) * dp;
        let t0 = self.slip(s, &f);
        let tiny = 1e-13 * self.speed_scale;
        if budget <= 0.0 {
            let m = if t0.length() <= tiny {
                Mode::Stick
            } else {
                Mode::Slide
            };
            return (self.kick(s, &f, dp, DVec2::ZERO, tau), m);
        }
        let guess = -t0 * self.p.mass / 7.0;
        if mode == Mode::Stick || t0.length() <= tiny {
            return self.stick_or_start(s, &f, dp, tau, budget, guess);
        }
        let relative_change = 7.0 * budget / (self.p.mass * t0.length());
        let next = self.slide(s, &f, dp, tau);
        let t1 = self.slip(&next, &f);
        let overshoot = t1.dot(t0) <= 0.0 || t1.length() <= tiny;
        if overshoot || relative_change > 0.05 {
            if let Some(j) = self.stick_impulse(s, &f, dp, tau, guess) {
                if j.length() <= budget * (1.0 + 1e-9) {
                    return (self.kick(s, &f, dp, j, tau), Mode::Stick);
                }
                if relative_change <= 1.0 && depth < 20 {
                    let (mid, m) = self.advance(s, 0.5 * dp, 0.5 * tau, Mode::Slide, depth + 1);
                    return self.advance(&mid, 0.5 * dp, 0.5 * tau, m, depth + 1);
                }
                return (
                    self.kick(s, &f, dp, j.normalize() * budget, tau),
                    Mode::Slide,
                );
            }
        }
        (next, Mode::Slide)
    }

    /// Stick if the impulse that zeroes the slip is inside the cone, else slide with
    /// the full friction along it.
    fn stick_or_start(
        &self,
        s: &State,
        f: &Frame,
        dp: f64,
        tau: f64,
        budget: f64,
        guess: DVec2,
    ) -> (State, Mode) {
        match self.stick_impulse(s, f, dp, tau, guess) {
            Some(j) if j.length() <= budget * (1.0 + 1e-9) => {
                (self.kick(s, f, dp, j, tau), Mode::Stick)
            }
            Some(j) => (
                self.kick(s, f, dp, j.normalize() * budget, tau),
                Mode::Slide,
            ),
            None => (self.slide(s, f, dp, tau), Mode::Slide),
        }
    }

    /// Positions move with the velocities; a falling ball lands on the table (the next
    /// kick cancels its downward velocity).
    fn drift(&self, s: &State, h: f64) -> State {
        let mut n = *s;
        n.cue_position += n.cue.velocity * h;
        n.object_position += n.object.velocity * h;
        for z in [&mut n.cue_position.z, &mut n.object_position.z] {
            if *z < self.p.radius {
                *z = self.p.radius;
            }
        }
        n
    }

    /// Overlap of the balls along the current normal.
    fn overlap(&self, s: &State) -> f64 {
        let d = s.object_position - s.cue_position;
        let distance = match self.geometry {
            Geometry::Fixed => d.x,
            Geometry::Moving => d.length(),
        };
        2.0 * self.p.radius - distance
    }
}

/// Hertz loading with the Stronge-calibrated unloading hysteresis.
#[derive(Clone, Copy, Debug)]
struct Hysteresis {
    k: f64,
    e: f64,
    max_overlap: f64,
}

impl Hysteresis {
    /// Overlap at which the unloading force vanishes, `(1 − e*²) δ_m`.
    fn zero_force_overlap(&self) -> f64 {
        (1.0 - self.e * self.e) * self.max_overlap
    }

    /// Normal force at overlap `delta` (does not update the history).
    fn force(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            0.0
        } else if delta >= self.max_overlap {
            self.k * delta.powf(1.5)
        } else {
            let d = delta - self.zero_force_overlap();
            if d <= 0.0 {
                0.0
            } else {
                self.k / (self.e * self.e * self.e) * d.powf(1.5)
            }
        }
    }
}

fn check(name: &'static str, v: f64, lo: f64, hi: f64) -> Result<(), TimedError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(TimedError::BadParameter(name))
    }
}

/// Solve one impact in the time domain: cue ball with `velocity` (z ignored) and `spin`
/// hits the resting object ball (collision frame, both balls on the table, touching at
/// `t = 0`). Returns the state when the ball–ball force has returned to zero.
pub fn solve(
    params: &TimedParams,
    velocity: DVec3,
    spin: DVec3,
    config: &TimedConfig,
) -> Result<TimedOutcome, TimedError> {
    let p = params.contact;
    check("mu", p.mu, 0.0, 10.0)?;
    check("mu_b", p.mu_b, 0.0, 10.0)?;
    check("mu_c", p.mu_c, 0.0, 1e3)?;
    check("restitution", p.restitution, 1e-3, 1.0)?;
    check("mu_s", p.mu_s, 0.0, 10.0)?;
    check("cue_table_friction", p.cue_table_friction, 0.0, 10.0)?;
    check("radius", p.radius, 1e-6, 1e3)?;
    check("mass", p.mass, 1e-6, 1e3)?;
    check("gravity", params.gravity, 0.0, 1e3)?;
    check("youngs_modulus", params.material.youngs_modulus, 1.0, 1e15)?;
    check("poisson_ratio", params.material.poisson_ratio, 0.0, 0.499)?;
    if !(velocity.is_finite() && spin.is_finite()) {
        return Err(TimedError::BadParameter("velocity/spin"));
    }
    if velocity.x <= 0.0 {
        return Err(TimedError::NoApproach);
    }
    let solver = Solver {
        p,
        gravity: params.gravity,
        geometry: config.geometry,
        inertia: NU * p.mass * p.radius * p.radius,
        speed_scale: velocity.length().max(p.radius * spin.length()),
    };
    let mut hertz = Hysteresis {
        k: params.material.stiffness(p.radius),
        e: p.restitution,
        max_overlap: 0.0,
    };
    let estimate = params
        .material
        .duration(p.radius, p.mass, p.restitution, velocity.x);
    let h = estimate / config.steps.max(10) as f64;
    let mut s = State {
        cue_position: DVec3::new(0.0, 0.0, p.radius),
        object_position: DVec3::new(2.0 * p.radius, 0.0, p.radius),
        cue: BallState {
            velocity: DVec3::new(velocity.x, velocity.y, 0.0),
            spin,
        },
        object: BallState::default(),
        friction: DVec3::ZERO,
        table_friction: DVec3::ZERO,
    };
    let mut mode = Mode::Slide;
    let mut stuck = false;
    let mut t = 0.0;
    let mut force = 0.0;
    let mut overlap = 0.0;
    let mut normal_impulse = 0.0;
    let mut peak_force = 0.0f64;
    let mut compression_time = 0.0;
    let mut steps = 0;
    loop {
        steps += 1;
        if steps > 100 * config.steps.max(10) {
            return Err(TimedError::NoSeparation);
        }
        let (half, half_mode) = solver.advance(&s, 0.5 * h * force, 0.5 * h, mode, 0);
        let moved = solver.drift(&half, h);
        let next_overlap = solver.overlap(&moved);
        let unloading = hertz.max_overlap > 0.0 && next_overlap < hertz.max_overlap;
        if unloading && next_overlap <= hertz.zero_force_overlap() {
            // Separation inside this step, at fraction `a` of the drift (the overlap is
            // linear in time over a drift). Redo the step from the synchronised state:
            // over `a h` the force falls from `force` as (δ − δ_p)^{3/2} does for a
            // linear δ, i.e. its mean is 2/5 of the start value.
            let zero = hertz.zero_force_overlap();
            let a = ((overlap - zero) / (overlap - next_overlap)).clamp(0.0, 1.0);
            let dp = 0.4 * force * a * h;
            let (last, last_mode) = solver.advance(&s, dp, a * h, mode, 0);
            stuck |= last_mode == Mode::Stick;
            normal_impulse += dp;
            s = last;
            t += a * h;
            break;
        }
        if next_overlap > hertz.max_overlap {
            hertz.max_overlap = next_overlap;
            compression_time = t + h;
        }
        let next_force = hertz.force(next_overlap);
        let (full, full_mode) = solver.advance(&moved, 0.5 * h * next_force, 0.5 * h, half_mode, 0);
        stuck |= half_mode == Mode::Stick || full_mode == Mode::Stick;
        normal_impulse += 0.5 * h * (force + next_force);
        peak_force = peak_force.max(next_force);
        s = full;
        mode = full_mode;
        force = next_force;
        overlap = next_overlap;
        t += h;
    }
    let r = p.radius;
    let airborne = |z: f64, vz: f64| z > r || vz > 0.0;
    Ok(TimedOutcome {
        cue_ball: s.cue,
        object_ball: s.object,
        duration: t,
        compression_time,
        max_indentation: hertz.max_overlap,
        peak_force,
        normal_impulse,
        friction_impulse: s.friction,
        table_friction_impulse: s.table_friction,
        stuck,
        airborne: [
            airborne(s.cue_position.z, s.cue.velocity.z),
            airborne(s.object_position.z, s.object.velocity.z),
        ],
        steps,
    })
}

/// Difference between two outcomes as the foundation issue measures it: worst of the
/// two balls, full 3-vectors, relative to the incoming speed `U`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Deviation {
    /// `max(|ΔU|, |ΔV|) / U`.
    pub velocity: f64,
    /// `R max(|Δω|, |ΔΩ|) / U`.
    pub spin: f64,
}

impl Deviation {
    /// Between ball states `a` and `b` (cue ball, object ball).
    pub fn between(a: [&BallState; 2], b: [&BallState; 2], speed: f64, radius: f64) -> Self {
        let dv = a[0]
            .velocity
            .distance(b[0].velocity)
            .max(a[1].velocity.distance(b[1].velocity));
        let dw = a[0]
            .spin
            .distance(b[0].spin)
            .max(a[1].spin.distance(b[1].spin));
        Self {
            velocity: dv / speed,
            spin: radius * dw / speed,
        }
    }

    /// `max(|Δv|/U, R|Δω|/U)`.
    pub fn max(&self) -> f64 {
        self.velocity.max(self.spin)
    }
}

/// A time-domain solve next to the impulsive reference (default configuration) for
/// the same inputs.
#[derive(Clone, Copy, Debug)]
pub struct Comparison {
    /// Time-domain outcome.
    pub timed: TimedOutcome,
    /// Impulsive reference outcome.
    pub reference: ReferenceOutcome,
    /// How far apart they are.
    pub deviation: Deviation,
}

/// Solve with both solvers and measure the difference.
pub fn compare(
    params: &TimedParams,
    velocity: DVec3,
    spin: DVec3,
    config: &TimedConfig,
) -> Result<Comparison, TimedError> {
    let timed = solve(params, velocity, spin, config)?;
    let reference = reference_solve(&params.contact, velocity, spin, &ReferenceConfig::default())?;
    let deviation = Deviation::between(
        [&timed.cue_ball, &timed.object_ball],
        [&reference.cue_ball, &reference.object_ball],
        DVec3::new(velocity.x, velocity.y, 0.0).length(),
        params.contact.radius,
    );
    Ok(Comparison {
        timed,
        reference,
        deviation,
    })
}

/// Cue-ball spin of a scenario, in units of `U/R`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpinKind {
    /// No spin.
    Stun,
    /// Natural roll for the incoming velocity: `ω = ẑ × v / R`.
    Roll,
    /// Full draw: minus natural roll.
    Draw,
    /// Right english `ω_z = +U/R`, no roll.
    Side,
}

impl SpinKind {
    /// Short label.
    pub fn label(&self) -> &'static str {
        match self {
            SpinKind::Stun => "stun",
            SpinKind::Roll => "roll",
            SpinKind::Draw => "draw",
            SpinKind::Side => "side",
        }
    }
}

/// The low-speed sweep's scenarios (docs/low-speed-limit.md §4: the sweep example and
/// `tests/low_speed_limit.rs`): every spin, cut (degrees) and ball–ball μ.
pub const SPINS: [SpinKind; 4] = [
    SpinKind::Stun,
    SpinKind::Roll,
    SpinKind::Draw,
    SpinKind::Side,
];
/// The sweep's cut angles (degrees).
pub const CUTS: [f64; 4] = [0.0, 30.0, 60.0, 85.0];
/// The sweep's ball–ball friction coefficients.
pub const MUS: [f64; 3] = [0.05, 0.02, 0.1];

/// One low-speed scenario: spin kind, cut angle and ball–ball friction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scenario {
    /// Cue-ball spin.
    pub spin: SpinKind,
    /// Cut angle φ (degrees).
    pub cut_deg: f64,
    /// Ball–ball friction μ (constant).
    pub mu: f64,
    /// Energetic restitution e*.
    pub restitution: f64,
    /// Object-ball/table friction μ_s.
    pub mu_s: f64,
}

/// Pool ball radius (m).
pub const POOL_RADIUS: f64 = 0.028575;
/// Pool ball mass (kg).
pub const POOL_MASS: f64 = 0.17;

impl Scenario {
    /// Pool balls, e* = 0.95, μ_s = 0.3.
    pub fn pool(spin: SpinKind, cut_deg: f64, mu: f64) -> Self {
        Self {
            spin,
            cut_deg,
            mu,
            restitution: 0.95,
            mu_s: 0.3,
        }
    }

    /// Time-domain parameters (default gravity and material).
    pub fn params(&self) -> TimedParams {
        TimedParams::new(ReferenceParams::constant(
            self.mu,
            self.restitution,
            self.mu_s,
            POOL_RADIUS,
            POOL_MASS,
        ))
    }

    /// Cue-ball velocity and spin at speed `speed` (collision frame).
    pub fn inputs(&self, speed: f64) -> (DVec3, DVec3) {
        let (s, c) = self.cut_deg.to_radians().sin_cos();
        let v = DVec3::new(c, s, 0.0) * speed;
        let w = speed / POOL_RADIUS;
        let spin = match self.spin {
            SpinKind::Stun => DVec3::ZERO,
            SpinKind::Roll => DVec3::new(-s, c, 0.0) * w,
            SpinKind::Draw => DVec3::new(s, -c, 0.0) * w,
            SpinKind::Side => DVec3::new(0.0, 0.0, w),
        };
        (v, spin)
    }

    /// Time-domain solve and reference at `speed` with `params` (which may differ from
    /// [`Scenario::params`], e.g. in gravity).
    pub fn compare_with(
        &self,
        params: &TimedParams,
        speed: f64,
        config: &TimedConfig,
    ) -> Result<Comparison, TimedError> {
        let (v, w) = self.inputs(speed);
        compare(params, v, w, config)
    }

    /// `max(|Δv|/U, R|Δω|/U)` against the reference at `speed`.
    pub fn error(&self, speed: f64, config: &TimedConfig) -> Result<f64, TimedError> {
        Ok(self
            .compare_with(&self.params(), speed, config)?
            .deviation
            .max())
    }

    /// Label such as `roll 30° μ=0.05`.
    pub fn label(&self) -> String {
        format!("{} {:>2.0}° μ={}", self.spin.label(), self.cut_deg, self.mu)
    }
}

/// Speeds `lo … hi` log-spaced with `per_decade` points per decade (both ends kept).
pub fn log_speeds(lo: f64, hi: f64, per_decade: usize) -> Vec<f64> {
    let n = ((hi / lo).log10() * per_decade as f64).round().max(1.0) as usize;
    (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect()
}

/// The speed below which `error(U)` exceeds `threshold`, from a sweep over ascending
/// `speeds`: the highest sampled speed whose error exceeds the threshold, refined by
/// bisection (on log U, to a relative width `1e-3`) against the next sampled speed.
/// `None` if no sampled speed exceeds it; `Some(speeds.last())` if the highest does.
/// Also returns the sampled errors.
pub fn limit_speed(
    speeds: &[f64],
    threshold: f64,
    mut error: impl FnMut(f64) -> f64,
) -> (Option<f64>, Vec<f64>) {
    let errors: Vec<f64> = speeds.iter().map(|&u| error(u)).collect();
    let Some(i) = errors.iter().rposition(|&e| e > threshold) else {
        return (None, errors);
    };
    if i + 1 == speeds.len() {
        return (Some(speeds[i]), errors);
    }
    let (mut lo, mut hi) = (speeds[i], speeds[i + 1]);
    while hi / lo > 1.001 {
        let mid = (lo * hi).sqrt();
        if error(mid) > threshold {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (Some((lo * hi).sqrt()), errors)
}
