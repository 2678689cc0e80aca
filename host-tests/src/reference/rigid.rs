//! The rigid contact: the impulse integration described in the module docs of
//! [`super`] (explicit stick, midpoint friction direction, Stronge's energetic end).

use glam::{DVec2, DVec3};

use super::{
    BallState, ReferenceConfig, ReferenceError, ReferenceOutcome, ReferenceParams, ReferenceRegime,
    NU,
};

#[derive(Clone, Copy, Debug)]
pub(super) struct State {
    pub(super) cue: BallState,
    pub(super) object: BallState,
    pub(super) friction: DVec3,
    pub(super) table_friction: DVec3,
}

pub(super) struct Solver {
    pub(super) p: ReferenceParams,
    pub(super) along_x: bool,
    pub(super) inertia: f64,
    pub(super) speed_scale: f64,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Slide,
    Stick,
}

impl Solver {
    pub(super) fn r_cue(&self) -> DVec3 {
        DVec3::new(self.p.radius, 0.0, 0.0)
    }
    pub(super) fn r_object(&self) -> DVec3 {
        DVec3::new(-self.p.radius, 0.0, 0.0)
    }
    pub(super) fn r_table(&self) -> DVec3 {
        DVec3::new(0.0, 0.0, -self.p.radius)
    }

    pub(super) fn apply(&self, ball: &mut BallState, r: DVec3, impulse: DVec3) {
        ball.velocity += impulse / self.p.mass;
        ball.spin += r.cross(impulse) / self.inertia;
    }

    /// Velocity of the object-ball contact point relative to the cue-ball one.
    pub(super) fn slip(&self, s: &State) -> DVec3 {
        (s.object.velocity + s.object.spin.cross(self.r_object()))
            - (s.cue.velocity + s.cue.spin.cross(self.r_cue()))
    }

    pub(super) fn tangential_slip(&self, s: &State) -> DVec2 {
        let v = self.slip(s);
        DVec2::new(v.y, v.z)
    }

    /// Table reaction on one ball after a ball–ball impulse: unilateral normal impulse
    /// and Coulomb friction (with stick) at `−R ẑ`. Returns the friction impulse.
    pub(super) fn table(&self, ball: &mut BallState, friction_coefficient: f64) -> DVec3 {
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
    pub(super) fn step(&self, s: &State, dp: f64, j: DVec2) -> State {
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

/// Integrate one impact with the rigid contact (inputs already checked).
pub(super) fn solve(
    params: &ReferenceParams,
    velocity: DVec3,
    spin: DVec3,
    config: &ReferenceConfig,
) -> Result<ReferenceOutcome, ReferenceError> {
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
