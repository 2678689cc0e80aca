//! Tangential compliance of the ball–ball contact (issue 19, deliverable 3): a
//! lumped-parameter contact with a normal and a tangential spring, the tangential one in
//! series with a Coulomb slider (the spring–slider of Cundall & Strack, Géotechnique 29
//! (1979) 47; its impact form: W. J. Stronge, *Impact Mechanics*, Cambridge 2000, §5
//! "rough compliant bodies"; the elastic-sphere version with Hertz and Mindlin springs
//! is Maw, Barber & Fawcett, Wear 38 (1976) 101).
//!
//! Rigid Coulomb friction stops the slip at most (the contact grips): the friction
//! impulse never exceeds the one that zeroes the tangential relative velocity, which
//! caps throw at the rigid ceiling `atan(2 tan φ / (7 (1 + e*)))` for a stun ball. A
//! compliant contact stores the tangential strain while it sticks and gives it back:
//! the tangential relative velocity can reverse, and the friction impulse can exceed the
//! rigid one by up to a factor 2.
//!
//! **Model** (SI units). Normal force `F` from a linear spring, stiffness `k_n` while
//! compressing and `k_n/e*²` while restoring, so that the work returned is `e*²` times
//! the work of compression — Stronge's energetic restitution, the same end of impact as
//! the rigid solver (module docs of `reference`). With `W(p) = ∫ v_n dp` the work of the
//! normal force (`v_n` the normal relative velocity, negative while approaching; `W_c`
//! its value at the end of compression):
//!
//! ```text
//! F = √(2 k_n (−W))                      while compressing,
//! F = √(2 (k_n/e*²) (W_c (1 − e*²) − W)) while restoring,     dt = dp / F.
//! ```
//!
//! Tangential: the spring's stretch `u` (m, in the contact plane, `y` and `z`) grows
//! with the tangential relative velocity `v_t` of the object-ball contact point
//! relative to the cue-ball one, `du/dt = v_t`, while the slider sticks; the force on
//! the object ball is `−k_t u`; when `k_t |u| > μ(|v_t|) F` the slider slips and `u` is
//! held on the cone `k_t |u| = μ F` (Coulomb). So the tangential impulse per normal
//! impulse never exceeds μ, as in the rigid contact.
//!
//! **Parameter**: `κ = k_t/k_n` (dimensionless). Velocities after the impact depend on
//! `κ` only, not on the stiffness scale (a stiffer contact is shorter in time by the
//! same factor). Both balls' contact points move by `1/M + R²/I = 7/(2M)` per unit
//! tangential impulse and by `1/M` per unit normal impulse, so the tangential and normal
//! frequencies of the stuck contact are `ω_t² = 7 k_t/M`, `ω_n² = 2 k_n/M`, and their
//! ratio `η = ω_t/ω_n = √(7κ/2)`. Mindlin's elastic spheres (J. Appl. Mech. 16 (1949)
//! 259) have `k_t/k_n = 2(1 − ν)/(2 − ν)`: κ 0.67–0.82 for Poisson's ratios 0–0.4.
//!
//! **Closed form** (the golden values of the tests): a stuck contact with `e* = 1` is a
//! half sine in the normal direction, `F ∝ sin(ω_n t)`, over `T = π/ω_n`, and a harmonic
//! oscillator in the tangential one, so `v_t(T) = v_t0 cos(π η)` — a tangential
//! coefficient of restitution `β = −v_t(T)/v_t0 = −cos(π η)` (Stronge 2000 §5; Becker,
//! Schwager & Pöschel, Phys. Rev. E 77 (2008) 011304, for the linear spring). It holds
//! when `k_t |u| ≤ μ F` throughout: for a stun ball `|u|/F` is
//! `(κ/η) tan φ · sin(η x)/sin x` (`x = ω_n t`), constant `κ tan φ` at `η = 1`. The
//! rigid limit is `κ → ∞`.
//!
//! **Integration** in the normal oscillator's phase (time), not in raw normal impulse.
//! While the ball–ball impulse alone acts on `v_n` (each centre moves `dp/M` along `x`, a
//! tangential impulse at `±R x̂` has no normal component at the contact point, so
//! `dv_n/dp = a = 2/M`, 1/kg: m/s per N·s), the normal spring is a harmonic
//! oscillator: `dF/dt = −k v_n` (the spring shortens at `−v_n`; N/s) and
//! `dv_n/dt = a F` (m/s²), so the point `(F/√k, −v_n/√a)` (both √J) turns on a circle of
//! radius `ρ` at the angular rate `ω = √(k a)` (rad/s; `k = k_n` compressing, `k_n/e*²`
//! restoring). With the phase `θ = atan2(F/√k, −v_n/√a)`:
//!
//! ```text
//! v_n = −ρ √a cos θ,   F = ρ √k sin θ,   p(θ₁) − p(θ₀) = ρ (cos θ₀ − cos θ₁)/√a,
//! t(θ₁) − t(θ₀) = (θ₁ − θ₀)/ω.
//! ```
//!
//! Compression ends at `θ = π/2` (`v_n = 0`) and the impact at `θ = π` of the restoring
//! circle (`F = 0`), so both ends are step ends and the step's duration is exact: the
//! √-shaped force near both ends (`F ∝ √p`), where a midpoint `dt = dp/F` is not
//! accurate, needs no small steps. Each step advances `θ` by at most `π/steps` and
//! `ω_t dt ≤ PHASE_STEP·1000/steps`; the circle is rebuilt from the state (`W`, `v_n`)
//! every step, so table reactions that change `v_n` (spin shots) enter at the next step,
//! and the end is bisected as in the rigid solver if `W` reaches `e*²`'s target first.
//! The tangential spring takes a position-Verlet (Störmer) step in time — half a step of
//! `u`, the impulse `−k_t u dt`, half a step of `u` — with the force at the step's middle
//! phase for the cone and `μ` at the predicted middle slip speed (slip change `7/M` per
//! unit tangential impulse, m/s per N·s), second order in `dt`.

use std::f64::consts::{FRAC_PI_2, PI};

use glam::{DVec2, DVec3};

use super::rigid::{Solver, State};
use super::{
    BallState, ReferenceConfig, ReferenceError, ReferenceOutcome, ReferenceParams, ReferenceRegime,
    NU,
};

/// Largest tangential phase advance per step, `ω_t dt`, at `steps = 1000`.
const PHASE_STEP: f64 = 0.01;

/// State of the compliant contact between steps.
#[derive(Clone, Copy, Debug)]
struct Contact {
    balls: State,
    /// Tangential spring stretch (m), `(y, z)`.
    stretch: DVec2,
    /// Normal impulse so far (N·s).
    p: f64,
    /// Work of the normal force so far (J, ≤ 0 until the end of compression).
    work: f64,
}

/// Where a contact is on its normal circle (module docs): radius `ρ` (√J), phase `θ`
/// (rad), and the circle's stiffness `k` (N/m) and rate `ω` (rad/s).
#[derive(Clone, Copy, Debug)]
struct Circle {
    rho: f64,
    theta: f64,
    k: f64,
    omega: f64,
}

struct Compliant {
    solver: Solver,
    /// Normal stiffness while compressing (N/m); any value, only `κ` matters.
    k_n: f64,
    /// Tangential stiffness (N/m).
    k_t: f64,
    /// Tangential frequency of the stuck contact (rad/s).
    omega_t: f64,
    restitution: f64,
    /// Normal relative-velocity change per normal impulse, `a = 2/M` (1/kg).
    a: f64,
    /// Largest phase step of the normal circle (rad) and of the tangential spring.
    max_phase: f64,
    tangential_phase: f64,
}

impl Compliant {
    fn normal_velocity(&self, s: &State) -> f64 {
        self.solver.slip(s).x
    }

    /// Normal force at work `w` (J); `w_c` the work at the end of compression, once it
    /// has ended.
    fn force(&self, w: f64, w_c: Option<f64>) -> f64 {
        match w_c {
            None => (2.0 * self.k_n * (-w).max(0.0)).sqrt(),
            Some(_) if self.restitution == 0.0 => 0.0,
            Some(wc) => {
                let k_r = self.k_n / (self.restitution * self.restitution);
                (2.0 * k_r * (wc * (1.0 - self.restitution * self.restitution) - w).max(0.0)).sqrt()
            }
        }
    }

    /// The normal circle through the contact's `(F, v_n)` (`None` once `e* = 0` ended
    /// compression: the restoring spring is rigid).
    fn circle(&self, c: &Contact, w_c: Option<f64>) -> Option<Circle> {
        let k = match w_c {
            None => self.k_n,
            Some(_) if self.restitution == 0.0 => return None,
            Some(_) => self.k_n / (self.restitution * self.restitution),
        };
        // x = F/√k and y = −v_n/√a, both √J.
        let x = self.force(c.work, w_c) / k.sqrt();
        let y = -self.normal_velocity(&c.balls) / self.a.sqrt();
        Some(Circle {
            rho: x.hypot(y),
            theta: x.atan2(y),
            k,
            omega: (k * self.a).sqrt(),
        })
    }

    /// Phase reached after a normal impulse `dp` on `circle`:
    /// `cos θ₁ = cos θ₀ − dp √a/ρ`.
    fn phase_after(&self, circle: &Circle, dp: f64) -> f64 {
        if circle.rho <= 0.0 {
            return circle.theta;
        }
        (circle.theta.cos() - dp * self.a.sqrt() / circle.rho)
            .clamp(-1.0, 1.0)
            .acos()
    }

    /// One step of normal impulse `dp` from `c`: returns the new contact and whether
    /// the slider stuck (the spring stayed inside the friction cone).
    fn step(&self, c: &Contact, dp: f64, w_c: Option<f64>) -> (Contact, bool) {
        // Duration and middle force from the normal circle (module docs).
        let (dt, force) = match self.circle(c, w_c) {
            Some(circle) if dp > 0.0 => {
                let theta1 = self.phase_after(&circle, dp);
                let dt = (theta1 - circle.theta) / circle.omega;
                let mid = 0.5 * (circle.theta + theta1);
                (dt, circle.rho * circle.k.sqrt() * mid.sin())
            }
            _ => (0.0, 0.0),
        };
        let v0 = self.solver.tangential_slip(&c.balls);
        let mu0 = self.solver.p.mu_at(v0.length());
        let active = force > 0.0 && dt > 0.0 && mu0 > 0.0;
        let (half, j, stuck_half) = if active {
            let drift = c.stretch + 0.5 * dt * v0;
            let (half, _) = cone(drift, mu0 * force / self.k_t);
            // μ at the middle slip speed: the slip moves by 7/M per unit tangential
            // impulse on the object ball (m/s per N·s), half of it by the middle.
            let v_mid = v0 - 3.5 / self.solver.p.mass * self.k_t * half * dt;
            let mu = self.solver.p.mu_at(v_mid.length());
            let (half, stuck) = cone(drift, mu * force / self.k_t);
            (half, -self.k_t * half * dt, stuck)
        } else {
            (DVec2::ZERO, DVec2::ZERO, false)
        };
        let balls = self.solver.step(&c.balls, dp, j);
        let vn0 = self.normal_velocity(&c.balls);
        let vn1 = self.normal_velocity(&balls);
        let work = c.work + 0.5 * (vn0 + vn1) * dp;
        // Second half step of the stretch with the new velocity, on the new cone.
        let (stretch, stuck) = if active {
            let v1 = self.solver.tangential_slip(&balls);
            let end_force = self.force(work, w_c.or((vn1 >= 0.0).then_some(work)));
            let mu = self.solver.p.mu_at(v1.length());
            let (s, stuck_end) = cone(half + 0.5 * dt * v1, mu * end_force / self.k_t);
            (s, stuck_half && stuck_end)
        } else {
            (DVec2::ZERO, false)
        };
        (
            Contact {
                balls,
                stretch,
                p: c.p + dp,
                work,
            },
            stuck,
        )
    }

    /// The step's normal impulse: a phase step of at most `max_phase` on the normal
    /// circle and `tangential_phase/ω_t` in time, up to the circle's end phase `end`
    /// (π/2 compressing, π restoring). Returns `dp` and whether it reaches `end`.
    fn step_size(&self, c: &Contact, w_c: Option<f64>, fallback: f64) -> (f64, bool) {
        let end = if w_c.is_none() { FRAC_PI_2 } else { PI };
        let Some(circle) = self.circle(c, w_c) else {
            return (fallback, false);
        };
        let by_time = self.tangential_phase * circle.omega / self.omega_t;
        let theta1 = circle.theta + self.max_phase.min(by_time);
        let (theta1, at_end) = if theta1 >= end {
            (end, true)
        } else {
            (theta1, false)
        };
        let dp = circle.rho * (circle.theta.cos() - theta1.cos()) / self.a.sqrt();
        if dp > 1e-9 * fallback {
            (dp, at_end)
        } else {
            // Past the circle's end (a table reaction moved v_n): small steps until the
            // end of compression or of the impact is detected from v_n or W.
            (fallback, false)
        }
    }
}

/// `u` held on the disc `|u| ≤ limit`; true when it was inside (the slider sticks).
fn cone(u: DVec2, limit: f64) -> (DVec2, bool) {
    let length = u.length();
    if length <= limit {
        (u, true)
    } else {
        (u * (limit / length), false)
    }
}

/// Integrate one impact with the compliant contact, `kappa = k_t/k_n` (inputs checked).
pub(super) fn solve(
    params: &ReferenceParams,
    velocity: DVec3,
    spin: DVec3,
    config: &ReferenceConfig,
    kappa: f64,
) -> Result<ReferenceOutcome, ReferenceError> {
    let m = params.mass;
    // ω_n = 1 rad/s: k_n = M/2 (any value gives the same velocities).
    let k_n = 0.5 * m;
    let k_t = kappa * k_n;
    let steps = config.steps.max(10);
    let model = Compliant {
        solver: Solver {
            p: *params,
            along_x: config.table_friction_along_x,
            inertia: NU * m * params.radius * params.radius,
            speed_scale: velocity.length().max(params.radius * spin.length()),
        },
        k_n,
        k_t,
        omega_t: (7.0 * k_t / m).sqrt(),
        restitution: params.restitution,
        a: 2.0 / m,
        max_phase: PI / steps as f64,
        tangential_phase: PHASE_STEP * 1000.0 / steps as f64,
    };
    let e = params.restitution;
    // The smallest step, when the circle cannot say (1e-4 of the rigid solver's).
    let fallback = 1e-4 * 0.5 * (1.0 + e).max(1.0) * m * velocity.x / steps as f64;
    let mut contact = Contact {
        balls: State {
            cue: BallState {
                velocity: DVec3::new(velocity.x, velocity.y, 0.0),
                spin,
            },
            object: BallState::default(),
            friction: DVec3::ZERO,
            table_friction: DVec3::ZERO,
        },
        stretch: DVec2::ZERO,
        p: 0.0,
        work: 0.0,
    };
    let mut compression: Option<(f64, f64)> = None; // (p_c, W_c)
    let mut stick_impulse = None;
    let mut taken = 0;
    loop {
        taken += 1;
        let w_c = compression.map(|c| c.1);
        let (dp, at_end) = model.step_size(&contact, w_c, fallback);
        let vn0 = model.normal_velocity(&contact.balls);
        let (next, stuck) = model.step(&contact, dp, w_c);
        let vn1 = model.normal_velocity(&next.balls);
        let mut just_compressed = None;
        if compression.is_none() && vn1 >= 0.0 {
            let fraction = if vn1 > vn0 { -vn0 / (vn1 - vn0) } else { 0.0 };
            compression = Some((
                contact.p + fraction * dp,
                contact.work + 0.5 * vn0 * fraction * dp,
            ));
            just_compressed = Some(fraction);
        }
        if let Some((_, wc)) = compression {
            let target = wc * (1.0 - e * e);
            if w_c.is_some() && at_end && (next.work - target).abs() <= 1e-10 * wc.abs() {
                // The step ended on the restoring circle's end, F = 0: the impact's end.
                if stuck && stick_impulse.is_none() && contact.p > 0.0 {
                    stick_impulse = Some(contact.p);
                }
                contact = next;
                break;
            }
            if next.work >= target {
                // The impact ends inside this step: bisect on the step fraction.
                let (mut lo, mut hi) = (just_compressed.unwrap_or(0.0), 1.0);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if model.step(&contact, mid * dp, w_c).0.work >= target {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                contact = model.step(&contact, hi * dp, w_c).0;
                break;
            }
        }
        if stuck && stick_impulse.is_none() && contact.p > 0.0 {
            stick_impulse = Some(contact.p);
        }
        contact = next;
        if taken > 1_000 * steps {
            break; // cannot happen for valid input: each step is at least `fallback`
        }
    }
    let regime = if params.mu_at(0.0) == 0.0 {
        ReferenceRegime::Frictionless
    } else if stick_impulse.is_some() {
        ReferenceRegime::Gripping
    } else {
        ReferenceRegime::Sliding
    };
    let s = contact.balls;
    Ok(ReferenceOutcome {
        cue_ball: s.cue,
        object_ball: s.object,
        regime,
        normal_impulse: contact.p,
        compression_impulse: compression.map_or(contact.p, |c| c.0),
        stick_impulse,
        friction_impulse: s.friction,
        table_friction_impulse: s.table_friction,
        steps: taken,
    })
}
