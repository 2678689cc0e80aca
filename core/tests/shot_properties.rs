//! Property tests (proptest) of the shot entry points over their valid domain (issue 6,
//! item 3, extended to `travel`, `table`, `shot`, `aim` and `guidance`).
//!
//! 1. `shot_chain_holds_on_the_valid_domain`: random scenes (every ball set and its
//!    table, 1–15 object balls), cues, cloths, collision parameters and models, strokes
//!    aimed at a ball (with offsets up to ±2R, so grazes happen) or anywhere: `play` and
//!    `guide` never fail and every output is finite; each of the three motions (cue ball
//!    before, cue ball and object ball after) obeys the travel properties below.
//! 2. `travel_matches_f64_closed_forms`: random motion states (lifted or not, near
//!    natural roll or not); the f32 `Motion` against the TP A.4 closed forms written here
//!    in f64 from docs/shot.md's equations, every quantity within `1e-5 |x₆₄|` plus an
//!    absolute floor of 1e-6 of its natural scale (speed `S = |v₀| + R|ω₀|`, times
//!    `S/(μ g)`, lengths `S t_stop`), plus for quantities that change in time the
//!    rounding of the f32 phase times, `4ε (t_stop + S/(μ_c g))` × their rate (the second
//!    term: the slip `|v − Rω|` near natural roll has an O(1) relative error).
//! 3. `solved_aims_pocket_the_ball`: random pool and snooker shots; `solve_aim` either
//!    names why there is no aim, or its aim, played forward, sends the object ball's
//!    centre across the pocket's mouth line within `TOLERANCE` of the pocket centre
//!    (the crossing found here by sampling and bisection of `position_at`, not by the
//!    core's crossing code), plus that evaluation's rounding: 8 ulp of the table length
//!    across the line, times `1 + cot θ` along it for a path meeting the mouth line at
//!    an angle θ.
//!
//! Travel properties of a motion: finite; it lands (air time finite, ≥ 0, the landing
//! is `position_at(air_time)`); kinetic energy `½v² + ½νR²ω²` never increases (to 8ε of
//! its start); while sliding the table slip `|v + ω × (−Rẑ)|` never increases, while
//! rolling and in flight the speed never increases (a sliding ball's speed may: topspin
//! turns into speed, as in a follow shot, which is why the slip is the sliding
//! invariant); it stops at `stop_time` (velocity zero there and after) and `rest()` is
//! `position_at(stop_time)`, bit for bit.
//!
//! Seeds are fixed; `PROPTEST_CASES` / `PROPTEST_RNG_SEED` override; failures persist to
//! `tests/shot_properties.proptest-regressions`. `-- --nocapture` prints the figures.

mod shot_common;

use cuesight::aim::{solve_aim, AimError, TOLERANCE};
use cuesight::guidance::{guide, Aim};
use cuesight::shot::{play, ShotSetup, Stroke};
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{BallSet, Scene};
use cuesight::travel::{Cloth, Motion};
use cuesight::validity::{kim_grip, Reason};
use cuesight::{FrictionLaw, Model, Params, Vec3};
use cuesight_figures::thousands;
use proptest::prelude::*;
use proptest::test_runner::{contextualize_config, TestCaseError, TestRunner};
use shot_common::*;
use std::cell::RefCell;

const SHOT_CASES: u32 = 600_000;
const MOTION_CASES: u32 = 2_000_000;
const AIM_CASES: u32 = 200_000;

type Raw = [u32; 16];

fn unit(x: u32) -> f64 {
    x as f64 / 4_294_967_296.0
}

/// Pick by weights: the index and the position within the chosen slice, in `[0, 1)`.
fn pick(x: u32, weights: &[u32]) -> (usize, f64) {
    let total: u32 = weights.iter().sum();
    let u = unit(x) * total as f64;
    let mut start = 0.0;
    for (i, &w) in weights.iter().enumerate() {
        let end = start + w as f64;
        if u < end || i + 1 == weights.len() {
            return (i, ((u - start) / w as f64).clamp(0.0, 1.0 - f64::EPSILON));
        }
        start = end;
    }
    unreachable!()
}

fn log_uniform(x: u32, lo: f64, hi: f64) -> f64 {
    (lo.ln() + unit(x) * (hi.ln() - lo.ln())).exp()
}

/// 64-bit LCG for the ball positions of a case, seeded from the draw.
struct Lcg(u64);
impl Lcg {
    fn unit(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / 16_777_216.0
    }
}

/// A shot from the valid domain.
#[derive(Clone, Debug)]
struct ShotCase {
    scene: Scene,
    stroke: Stroke,
    setup: ShotSetup,
}

fn cloth(x: u32, y: u32) -> Cloth {
    match pick(x, &[2, 3, 1]) {
        (0, _) => Cloth::TYPICAL,
        (1, f) => Cloth::new(
            log_uniform((f * 4e9) as u32, 1e-3, 1.0) as f32,
            log_uniform(y, 1e-3, 0.5) as f32,
        )
        .unwrap(),
        _ => {
            let ends = [(1e-3, 1e-3), (1e-3, 0.5), (1.0, 1e-3), (1.0, 0.5)];
            let (s, r) = ends[(y % 4) as usize];
            Cloth::new(s, r).unwrap()
        }
    }
}

impl ShotCase {
    /// Decode a raw draw: ball set and table, cloth (typical, log-uniform over the
    /// accepted ranges, or their ends), cue (typical or m_c 0.1–2 kg, e_t 0–1), μ 0–0.3
    /// or Marlow's law, e* and μ_s 0–1, μ_ct 0–0.3, any model (`Auto` at 1e-6–1); cue
    /// ball anywhere on the surface, 1–15 object balls; cue speed 1 mm/s–20 m/s
    /// log-uniform (the smallest subnormal and 20 m/s weighted in); tip anywhere within
    /// the 0.5 R miscue limit (on it weighted in); aimed at an object ball with a
    /// sideways offset up to ±2R (grazes included), or in any direction.
    fn decode(raw: Raw) -> ShotCase {
        let (_, set, table) = sets()[(raw[0] % 3) as usize].clone();
        let r = set.radius;
        let cue = match pick(raw[2], &[2, 3]) {
            (0, _) => Cue::TYPICAL,
            (_, f) => Cue::new(0.1 + 1.9 * f as f32, unit(raw[3]) as f32).unwrap(),
        };
        let mu = match pick(raw[4], &[1, 6, 1]) {
            (0, _) => FrictionLaw::Constant(0.0),
            (1, f) => FrictionLaw::Constant((0.3 * f) as f32),
            _ => FrictionLaw::MARLOW,
        };
        let params = Params::new(0.0, unit(raw[5]) as f32, unit(raw[6]) as f32, r, set.mass)
            .unwrap()
            .with_friction_law(mu)
            .with_cue_table_friction((0.3 * unit(raw[3] ^ raw[5])) as f32)
            .unwrap();
        let model = match raw[6] % 5 {
            0 => Model::Ideal,
            1 => Model::Kim,
            2 => Model::KimGrip,
            3 => Model::Exact,
            _ => Model::Auto {
                tolerance: log_uniform(raw[7], 1e-6, 1.0) as f32,
            },
        };
        let setup = ShotSetup {
            params,
            cue,
            cloth: cloth(raw[1], raw[8]),
            model,
        };
        let (l, w) = (table.length(), table.width());
        let mut rng = Lcg(u64::from(raw[9]) << 32 | u64::from(raw[10]));
        let mut place = || {
            [
                r + (l - 2.0 * r) * rng.unit(),
                r + (w - 2.0 * r) * rng.unit(),
            ]
        };
        let mut scene = Scene::new(table, r, place()).unwrap();
        let wanted = match pick(raw[11], &[4, 3, 1]) {
            (0, _) => 1,
            (1, f) => 2 + (f * 4.0) as usize,
            (_, f) => 6 + (f * 10.0) as usize,
        };
        for _ in 0..60 {
            if scene.balls().len() > wanted {
                break;
            }
            let _ = scene.add_ball(place());
        }
        let speed = match pick(raw[12], &[1, 1, 12]) {
            (0, _) => f32::from_bits(1),
            (1, _) => 20.0,
            (_, f) => log_uniform((f * 4e9) as u32, 1e-3, 20.0) as f32,
        };
        let angle = std::f64::consts::TAU * unit(raw[13]);
        let radius = match pick(raw[14], &[1, 5]) {
            (0, _) => 0.5,
            (_, f) => 0.5 * f.sqrt(),
        };
        let tip = TipOffset::from_radius_fraction(
            (radius * angle.cos()) as f32 * 0.999_999,
            (radius * angle.sin()) as f32 * 0.999_999,
            r,
        )
        .unwrap();
        let direction = match pick(raw[15], &[7, 3]) {
            (0, f) => {
                let balls = scene.balls();
                let target = balls[1 + ((f * (balls.len() - 1) as f64) as usize)];
                let to = target - balls[0];
                let offset = (unit(raw[14] ^ raw[13]) as f32 * 2.0 - 1.0) * 2.0 * r / to.length();
                [to.x - offset * to.y, to.y + offset * to.x]
            }
            (_, f) => {
                let a = std::f64::consts::TAU * f;
                [a.cos() as f32, a.sin() as f32]
            }
        };
        ShotCase {
            scene,
            stroke: Stroke::new(speed, tip, direction).unwrap(),
            setup,
        }
    }
}

/// Largest figures seen.
#[derive(Default, Debug)]
struct Figures {
    shots: u64,
    /// Shots refused outside the collision model's validity domain.
    refused: u64,
    contacts: u64,
    pocketed: u64,
    motions: u64,
    lifted: u64,
    /// Energy gain beyond its start, relative to it (largest; ≤ 0 expected).
    energy_gain: f64,
    /// Slip growth while sliding, relative to `|v₀| + R|ω₀|` (largest).
    slip_growth: f64,
    /// Speed growth while rolling, relative to the speed (largest).
    speed_growth: f64,
}

fn energy(m: &Motion, t: f32, radius: f32) -> f64 {
    let (v, w) = (m.velocity_at(t), m.spin_at(t));
    let sq = |a: Vec3| (a.x as f64).powi(2) + (a.y as f64).powi(2) + (a.z as f64).powi(2);
    0.5 * sq(v) + 0.5 * 0.4 * (radius as f64).powi(2) * sq(w)
}

/// The travel properties of one motion (module docs).
fn check_motion(m: &Motion, radius: f32, fig: &mut Figures) -> Result<(), TestCaseError> {
    motion_finite(m).map_err(TestCaseError::fail)?;
    fig.motions += 1;
    prop_assert!(m.air_time >= 0.0 && m.air_time.is_finite(), "{m:?}");
    if m.air_time > 0.0 {
        fig.lifted += 1;
        prop_assert_eq!(m.landing(), m.position_at(m.air_time), "{:?}", m);
    }
    let stop = m.stop_time();
    prop_assert_eq!(
        m.velocity_at(stop),
        Vec3::ZERO,
        "not stopped at stop_time: {:?}",
        m
    );
    prop_assert_eq!(m.velocity_at(2.0 * stop + 1.0), Vec3::ZERO);
    prop_assert_eq!(m.rest(), m.position_at(stop), "{:?}", m);
    prop_assert_eq!(m.rest(), m.position_at(2.0 * stop + 1.0));
    // Times: the phase ends, and 8 points inside each phase.
    let slide_end = m.air_time + m.sliding_time;
    let mut times = vec![0.0f32, m.air_time, slide_end, stop];
    for k in 1..8 {
        let f = k as f32 / 8.0;
        times.push(f * m.air_time);
        times.push(m.air_time + f * m.sliding_time);
        times.push(slide_end + f * m.rolling_time);
    }
    times.sort_by(f32::total_cmp);
    let r = radius as f64;
    let scale = m.initial_velocity.length() as f64 + r * m.initial_spin.length() as f64;
    let e0 = energy(m, 0.0, radius);
    let slip = |t: f32| {
        let (v, w) = (m.velocity_at(t), m.spin_at(t));
        (v.x as f64 - r * w.y as f64).hypot(v.y as f64 + r * w.x as f64)
    };
    for pair in times.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let (ea, eb) = (energy(m, a, radius), energy(m, b, radius));
        fig.energy_gain = fig.energy_gain.max((eb - ea) / e0.max(f64::MIN_POSITIVE));
        prop_assert!(
            eb <= ea + 8.0 * EPS32 * e0,
            "energy grows {ea:e} -> {eb:e} between t = {a} and {b}: {m:?}"
        );
        if a >= m.air_time && b <= slide_end {
            let (sa, sb) = (slip(a), slip(b));
            fig.slip_growth = fig
                .slip_growth
                .max((sb - sa) / scale.max(f64::MIN_POSITIVE));
            prop_assert!(
                sb <= sa + 8.0 * EPS32 * scale,
                "slip grows {sa:e} -> {sb:e} while sliding: {m:?}"
            );
        }
        if a >= slide_end || b <= m.air_time {
            let (va, vb) = (
                m.velocity_at(a).length() as f64,
                m.velocity_at(b).length() as f64,
            );
            fig.speed_growth = fig.speed_growth.max((vb - va) / va.max(f64::MIN_POSITIVE));
            prop_assert!(
                vb <= va * (1.0 + 4.0 * EPS32),
                "speed grows {va:e} -> {vb:e} between t = {a} and {b}: {m:?}"
            );
        }
    }
    Ok(())
}

fn check_shot(case: &ShotCase, fig: &mut Figures) -> Result<(), TestCaseError> {
    let ShotCase {
        scene,
        stroke,
        setup,
    } = case;
    let shot = match play(scene, stroke, setup) {
        Ok(shot) => shot,
        // Refusals of the validity domain reach the caller typed: Kim where its
        // contact grips (gripping index above 1), KimGrip outside its parameters' domain.
        Err(cuesight::Error::OutsideValidity {
            reason: Reason::Grips,
            value,
            ..
        }) if setup.model == Model::Kim && value >= 1.0 => {
            fig.refused += 1;
            return Ok(());
        }
        // KimGrip's refusal is its parameters' (`validity::kim_grip`).
        Err(e) if setup.model == Model::KimGrip && kim_grip(&setup.params) == Err(e) => {
            fig.refused += 1;
            return Ok(());
        }
        Err(e) => {
            return Err(TestCaseError::fail(format!(
                "play refused a valid shot: {e}"
            )))
        }
    };
    shot_finite(&shot).map_err(TestCaseError::fail)?;
    fig.shots += 1;
    let r = scene.radius();
    check_motion(&shot.cue_before, r, fig)?;
    if let Some(c) = &shot.contact {
        fig.contacts += 1;
        fig.pocketed += u64::from(c.pocket.is_some());
        check_motion(&c.cue_after, r, fig)?;
        check_motion(&c.object_after, r, fig)?;
    }
    let aim = stroke.aim();
    let aim_deg = (aim.y as f64).atan2(aim.x as f64).to_degrees() as f32;
    let g = guide(
        scene,
        stroke.cue_speed,
        stroke.tip,
        Aim::Degrees {
            aim_deg,
            target: None,
        },
        setup,
    )
    .map_err(|e| TestCaseError::fail(format!("guide refused a valid shot: {e}")))?;
    guidance_finite(&g).map_err(TestCaseError::fail)?;
    Ok(())
}

fn runner(test: &'static str, cases: u32, seed: u64) -> TestRunner {
    let mut config = contextualize_config(config(cases, seed));
    config.source_file = Some(file!());
    config.test_name = Some(test);
    TestRunner::new(config)
}

#[test]
fn shot_chain_holds_on_the_valid_domain() {
    let name = "shot_chain_holds_on_the_valid_domain";
    let mut runner = runner(name, SHOT_CASES, 0x7368_6f74_0001);
    let figures = RefCell::new(Figures::default());
    let started = std::time::Instant::now();
    let strategy = any::<Raw>().prop_map(ShotCase::decode);
    if let Err(e) = runner.run(&strategy, |case| {
        check_shot(&case, &mut figures.borrow_mut())
    }) {
        panic!("{name}: {e}\n{runner}");
    }
    let f = figures.into_inner();
    println!(
        "{name}: {} cases in {:.1} s ({} refused outside the model's validity domain); {} contacts, {} pocketed; {} motions \
         ({} lifted): energy change ≤ {:.2e} of its start, slip growth while sliding ≤ {:.2e} \
         of |v₀| + R|ω₀|, speed growth while rolling ≤ {:.2e}",
        f.shots,
        started.elapsed().as_secs_f64(),
        f.refused,
        f.contacts,
        f.pocketed,
        f.motions,
        f.lifted,
        f.energy_gain,
        f.slip_growth,
        f.speed_growth
    );
    assert!(
        f.contacts > f.shots / 8 && f.pocketed > 0 && f.lifted > 0,
        "{f:?}"
    );
    // The figures docs/reliability.md quotes.
    cuesight_figures::record!(
        "reliability-shot-chain-contacts",
        "{}",
        thousands(f.contacts)
    );
    cuesight_figures::record!(
        "reliability-shot-chain-pocketed",
        "{}",
        thousands(f.pocketed)
    );
    cuesight_figures::record!("reliability-shot-chain-motions", "{}", thousands(f.motions));
    cuesight_figures::record!("reliability-shot-chain-lifted", "{}", thousands(f.lifted));
    cuesight_figures::record!(
        "reliability-shot-chain-energy-gain",
        "{:.1e}",
        f.energy_gain
    );
    cuesight_figures::record!(
        "reliability-shot-chain-slip-growth",
        "{:.1e}",
        f.slip_growth
    );
    let speed_growth = match f.speed_growth {
        0.0 => "never".to_owned(),
        growth => format!("by at most {growth:.1e}"),
    };
    cuesight_figures::record!("reliability-shot-chain-speed-growth", "{speed_growth}");
}

/// A motion state from the valid domain, and the TP A.4 closed forms in f64.
#[derive(Clone, Copy, Debug)]
struct MotionCase {
    start: Vec3,
    velocity: Vec3,
    spin: Vec3,
    radius: f32,
    cloth: Cloth,
}

impl MotionCase {
    /// Start anywhere on a 4 × 2 m area; horizontal speed 1 mm/s–20 m/s log-uniform in
    /// any direction; lift none (70 %), downward (10 %) or up to 5 m/s; spin free (each
    /// component up to 4 v/R), natural roll, or natural roll plus a slip of 1e-7–10 % of
    /// the speed; every ball radius; any cloth.
    fn decode(raw: Raw) -> MotionCase {
        let radius =
            [BallSet::POOL, BallSet::SNOOKER, BallSet::CAROM][(raw[0] % 3) as usize].radius;
        let r = radius as f64;
        let start = Vec3::new(4.0 * unit(raw[1]) as f32, 2.0 * unit(raw[2]) as f32, 0.0);
        let speed = log_uniform(raw[3], 1e-3, 20.0);
        let heading = std::f64::consts::TAU * unit(raw[4]);
        let (vx, vy) = (speed * heading.cos(), speed * heading.sin());
        let vz = match pick(raw[5], &[7, 1, 2]) {
            (0, _) => 0.0,
            (1, f) => -5.0 * f,
            (_, f) => 5.0 * f,
        };
        let spread = |x: u32| (8.0 * unit(x) - 4.0) * speed / r;
        let spin = match pick(raw[6], &[4, 1, 3]) {
            (0, _) => [spread(raw[7]), spread(raw[8]), spread(raw[9])],
            (1, _) => [-vy / r, vx / r, spread(raw[9])],
            (_, f) => {
                let slip = log_uniform((f * 4e9) as u32, 1e-7, 0.1) * speed;
                let dir = std::f64::consts::TAU * unit(raw[10]);
                [
                    (-vy + slip * dir.sin()) / r,
                    (vx - slip * dir.cos()) / r,
                    spread(raw[9]),
                ]
            }
        };
        MotionCase {
            start,
            velocity: Vec3::new(vx as f32, vy as f32, vz as f32),
            spin: Vec3::new(spin[0] as f32, spin[1] as f32, spin[2] as f32),
            radius,
            cloth: cloth(raw[11], raw[12]),
        }
    }
}

/// TP A.4 in f64, from docs/shot.md: slip `u₀ = v₀ + ω₀ × (−Rẑ)`, friction `μ_c g`
/// against it while sliding for `t_s = 2|u₀|/(7 μ_c g)`, rolling velocity
/// `v_r = v₀ − (2/7) u₀`, then `|v|` falls at `μ_r g` until it stops after
/// `|v_r|/(μ_r g)`; a lifted ball flies `2 v_z/g` first. While sliding the friction's
/// torque `(−Rẑ) × M a` turns the spin (`I = ν M R²`); rolling, `ω = ẑ × v/R` with the
/// spin about `z` kept.
struct Reference {
    start: [f64; 2],
    v0: [f64; 2],
    w0: [f64; 3],
    radius: f64,
    air: f64,
    slide: f64,
    accel: [f64; 2],
    roll: f64,
    vr: [f64; 2],
    decel: f64,
}

impl Reference {
    fn new(c: &MotionCase) -> Self {
        let g = 9.81;
        let f = |x: f32| x as f64;
        let (v0, w0, r) = (
            [f(c.velocity.x), f(c.velocity.y)],
            [f(c.spin.x), f(c.spin.y), f(c.spin.z)],
            f(c.radius),
        );
        let vz = f(c.velocity.z);
        let air = if vz > 0.0 { 2.0 * vz / g } else { 0.0 };
        let u = [v0[0] - r * w0[1], v0[1] + r * w0[0]];
        let slip = u[0].hypot(u[1]);
        let mu_c = f(c.cloth.sliding()) * g;
        let slide = 2.0 * slip / (7.0 * mu_c);
        let accel = if slip > 0.0 {
            [-mu_c * u[0] / slip, -mu_c * u[1] / slip]
        } else {
            [0.0, 0.0]
        };
        let vr = [v0[0] - 2.0 / 7.0 * u[0], v0[1] - 2.0 / 7.0 * u[1]];
        let decel = f(c.cloth.rolling()) * g;
        Reference {
            start: [f(c.start.x), f(c.start.y)],
            v0,
            w0,
            radius: r,
            air,
            slide,
            accel,
            roll: vr[0].hypot(vr[1]) / decel,
            vr,
            decel,
        }
    }

    fn stop(&self) -> f64 {
        self.air + self.slide + self.roll
    }

    /// Position, velocity and spin at `t`.
    fn at(&self, t: f64) -> ([f64; 2], [f64; 2], [f64; 3]) {
        let (p, v, a, w) = (self.start, self.v0, self.accel, self.w0);
        let t = t.max(0.0);
        if t <= self.air {
            return ([p[0] + v[0] * t, p[1] + v[1] * t], v, w);
        }
        let landing = [p[0] + v[0] * self.air, p[1] + v[1] * self.air];
        let s = (t - self.air).min(self.slide);
        let pos = [
            landing[0] + v[0] * s + 0.5 * a[0] * s * s,
            landing[1] + v[1] * s + 0.5 * a[1] * s * s,
        ];
        if t - self.air <= self.slide {
            let k = s / (0.4 * self.radius);
            let spin = [w[0] + a[1] * k, w[1] - a[0] * k, w[2]];
            return (pos, [v[0] + a[0] * s, v[1] + a[1] * s], spin);
        }
        let speed = self.vr[0].hypot(self.vr[1]);
        let tr = (t - self.air - self.slide).min(self.roll);
        let travelled = speed * tr - 0.5 * self.decel * tr * tr;
        let left = speed - self.decel * tr;
        let (dir, vel) = if speed > 0.0 {
            let d = [self.vr[0] / speed, self.vr[1] / speed];
            (d, [d[0] * left, d[1] * left])
        } else {
            ([0.0, 0.0], [0.0, 0.0])
        };
        let r = self.radius;
        (
            [pos[0] + dir[0] * travelled, pos[1] + dir[1] * travelled],
            vel,
            [-vel[1] / r, vel[0] / r, w[2]],
        )
    }
}

#[derive(Default, Debug)]
struct Precision {
    cases: u64,
    /// Largest `(|Δ| − 1e-5|x₆₄|)` as a fraction of the plain floor `1e-6 × scale`.
    plain: f64,
    /// Cases with a quantity beyond `1e-5|x₆₄|` + the plain floor (needing the
    /// time-rounding allowance).
    conditioned: u64,
    /// Largest use of the time-rounding allowance by those, as a fraction of it.
    of_drift: f64,
    at: String,
}

fn check_precision(c: &MotionCase, p: &mut Precision) -> Result<(), TestCaseError> {
    let m = Motion::new(c.start, c.velocity, c.spin, c.radius, &c.cloth)
        .map_err(|e| TestCaseError::fail(format!("valid state refused: {e}")))?;
    let x = Reference::new(c);
    p.cases += 1;
    let f = |v: f32| v as f64;
    // Natural scales: speed `S = |v₀| + R|ω₀|`, times `S/(μ g)`, lengths `S · t_stop`.
    let s = x.v0[0].hypot(x.v0[1]) + x.radius * (x.w0[0].hypot(x.w0[1]).hypot(x.w0[2]));
    let length = s * x.stop() + f(c.velocity.z).abs() * x.air;
    // The f32 phase times carry a rounding of up to 4ε t_stop, plus the sliding time's
    // from the slip `|v − Rω|`, formed with an error of 2ε S (relative error O(1) near
    // natural roll): 4ε S/(μ_c g). That moves anything that changes in time by the
    // time error times its rate (speeds for positions, μ g for velocities, μ_c g/ν for
    // R ω): beyond the floor only where μ_r ≫ μ_c.
    let g = 9.81;
    let (mu_c, mu_r) = (c.cloth.sliding() as f64, c.cloth.rolling() as f64);
    let drift = 4.0 * EPS32 * (x.stop() + s / (mu_c * g));
    let mut conditioned = false;
    let mut compare = |what: &str, got: f64, want: f64, scale: f64, rate: f64| {
        let (plain, allowance) = (1e-6 * scale, drift * rate);
        let floor = plain + allowance;
        let excess = (got - want).abs() - 1e-5 * want.abs();
        p.plain = p.plain.max(excess / plain);
        if excess > plain {
            conditioned = true;
            if (excess - plain) / allowance > p.of_drift {
                p.of_drift = (excess - plain) / allowance;
                p.at = format!("{what} {got:e} vs {want:e} in {c:?}");
            }
        }
        prop_assert!(
            excess <= floor,
            "{what}: f32 {got:e} vs f64 {want:e} (floor {floor:e}) for {c:?}"
        );
        Ok(())
    };
    compare("air_time", f(m.air_time), x.air, x.air, 0.0)?;
    let t_slide = s / (mu_c * g);
    compare("sliding_time", f(m.sliding_time), x.slide, t_slide, 0.0)?;
    let t_roll = s / (mu_r * g);
    compare("rolling_time", f(m.rolling_time), x.roll, t_roll, 0.0)?;
    for k in 0..2 {
        let dv = f(m.sliding_acceleration.to_array()[k]) * f(m.sliding_time);
        compare("Δv sliding", dv, x.accel[k] * x.slide, s, 0.0)?;
        let vr = f(m.rolling_velocity.to_array()[k]);
        compare("rolling_velocity", vr, x.vr[k], s, 0.0)?;
    }
    let (rolling_start, ..) = x.at(x.air + x.slide);
    let (rest, ..) = x.at(x.stop());
    for k in 0..2 {
        let got = f(m.rolling_start().to_array()[k]);
        compare("rolling_start", got, rolling_start[k], length, s)?;
        compare("rest", f(m.rest().to_array()[k]), rest[k], length, s)?;
    }
    let (velocity_rate, spin_rate) = (mu_c.max(mu_r) * g, (mu_c / 0.4).max(mu_r) * g);
    for j in 0..=24 {
        // Times in f32 (what the core is given), the reference at the same instant.
        let t32 = (x.stop() * j as f64 / 20.0) as f32;
        let (pos, vel, spin) = x.at(f(t32));
        let (mp, mv, mw) = (m.position_at(t32), m.velocity_at(t32), m.spin_at(t32));
        for k in 0..2 {
            compare("position_at", f(mp.to_array()[k]), pos[k], length, s)?;
            let v = f(mv.to_array()[k]);
            compare("velocity_at", v, vel[k], s, velocity_rate)?;
        }
        for (got, want) in mw.to_array().into_iter().zip(spin) {
            let r = x.radius;
            compare("R spin_at", r * f(got), r * want, s, spin_rate)?;
        }
    }
    p.conditioned += u64::from(conditioned);
    Ok(())
}

#[test]
fn travel_matches_f64_closed_forms() {
    let name = "travel_matches_f64_closed_forms";
    let mut runner = runner(name, MOTION_CASES, 0x7368_6f74_0002);
    let figures = RefCell::new(Precision::default());
    let started = std::time::Instant::now();
    let strategy = any::<Raw>().prop_map(MotionCase::decode);
    if let Err(e) = runner.run(&strategy, |c| {
        check_precision(&c, &mut figures.borrow_mut())
    }) {
        panic!("{name}: {e}\n{runner}");
    }
    let p = figures.into_inner();
    println!(
        "{name}: {} cases in {:.1} s; beyond 1e-5|x| ≤ {:.3} of the plain floor 1e-6 × scale; \
         {} cases beyond it, using ≤ {:.3} of the time-rounding allowance{}",
        p.cases,
        started.elapsed().as_secs_f64(),
        p.plain,
        p.conditioned,
        p.of_drift,
        if p.conditioned > 0 {
            format!(" (worst: {})", p.at)
        } else {
            String::new()
        }
    );
    // The figures docs/reliability.md quotes.
    cuesight_figures::record!(
        "reliability-shot-travel-conditioned",
        "{}",
        thousands(p.conditioned)
    );
    let conditioned_pct = 100.0 * p.conditioned as f64 / p.cases as f64;
    cuesight_figures::record!(
        "reliability-shot-travel-conditioned-pct",
        "{conditioned_pct:.1}"
    );
    cuesight_figures::record!("reliability-shot-travel-of-drift", "{:.2}", p.of_drift);
}

/// A shot to solve: pool or snooker, cue and object ball anywhere, the pocket needing
/// the smallest cut, cue speed 1–6 m/s, tip within 0.4 R, KimGrip, Exact or Auto.
#[derive(Clone, Debug)]
struct AimCase {
    scene: Scene,
    pocket: usize,
    speed: f32,
    tip: TipOffset,
    setup: ShotSetup,
}

impl AimCase {
    fn decode(raw: Raw) -> AimCase {
        let (_, set, table) = sets()[(raw[0] % 2) as usize].clone();
        let r = set.radius;
        let (l, w) = (table.length(), table.width());
        let at = |x: u32, y: u32| {
            [
                r + (l - 2.0 * r) * unit(x) as f32,
                r + (w - 2.0 * r) * unit(y) as f32,
            ]
        };
        let mut scene = Scene::new(table.clone(), r, at(raw[1], raw[2])).unwrap();
        let mut y = raw[4];
        while scene.add_ball(at(raw[3], y)).is_err() {
            y = y.wrapping_add(0x4000_0000); // a quarter of the width on
        }
        let (c, o) = (scene.balls()[0], scene.balls()[scene.balls().len() - 1]);
        let cut = |i: usize| {
            let (a, b) = (o - c, table.pockets()[i].centre() - o);
            (a.x * b.y - a.y * b.x).atan2(a.dot(b)).abs()
        };
        let pocket = (0..table.pockets().len())
            .min_by(|&a, &b| cut(a).total_cmp(&cut(b)))
            .unwrap();
        let model = match raw[5] % 4 {
            0 | 1 => Model::KimGrip,
            2 => Model::Exact,
            _ => Model::Auto { tolerance: 1e-3 },
        };
        let angle = std::f64::consts::TAU * unit(raw[6]);
        let radius = 0.4 * unit(raw[7]).sqrt();
        AimCase {
            pocket,
            speed: 1.0 + 5.0 * unit(raw[8]) as f32,
            tip: TipOffset::from_radius_fraction(
                (radius * angle.cos()) as f32,
                (radius * angle.sin()) as f32,
                r,
            )
            .unwrap(),
            setup: ShotSetup {
                params: Params::POOL.with_ball(r, set.mass).unwrap(),
                cue: Cue::TYPICAL,
                cloth: Cloth::TYPICAL,
                model,
            },
            scene,
        }
    }
}

#[derive(Default, Debug)]
struct AimFigures {
    cases: u64,
    solved: u64,
    not_hit: u64,
    unreachable: u64,
    not_converged: u64,
    worst_miss: f64,
    worst_cot: f64,
    /// Solutions whose independently measured miss exceeds `TOLERANCE`.
    beyond: u64,
    /// Their largest excess as a fraction of the evaluation's rounding allowance.
    of_rounding: f64,
    evaluations: u32,
}

/// First time the centre crosses the line through `p` along `d` (unit), found by
/// sampling `position_at` at 256 times and bisecting the first sign change: not the
/// core's crossing code.
fn line_crossing(m: &Motion, p: Vec3, d: Vec3) -> Option<f32> {
    let side = |t: f32| {
        let q = m.position_at(t);
        (q.x as f64 - p.x as f64) * d.y as f64 - (q.y as f64 - p.y as f64) * d.x as f64
    };
    let stop = m.stop_time();
    let s0 = side(0.0);
    let mut previous = 0.0f32;
    for k in 1..=256 {
        let t = stop * k as f32 / 256.0;
        if side(t) * s0 <= 0.0 {
            let (mut lo, mut hi) = (previous, t);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if side(mid) * s0 > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(hi);
        }
        previous = t;
    }
    None
}

fn check_aim(case: &AimCase, fig: &mut AimFigures) -> Result<(), TestCaseError> {
    fig.cases += 1;
    let object = case.scene.balls().len() - 1;
    let solution = match solve_aim(
        &case.scene,
        object,
        case.pocket,
        case.speed,
        case.tip,
        &case.setup,
    ) {
        Ok(s) => s,
        Err(AimError::Invalid(e)) => {
            return Err(TestCaseError::fail(format!("valid shot refused: {e}")))
        }
        Err(AimError::ObjectBallNotHit) => {
            fig.not_hit += 1;
            return Ok(());
        }
        Err(AimError::PocketUnreachable) => {
            fig.unreachable += 1;
            return Ok(());
        }
        Err(AimError::NotConverged) => {
            fig.not_converged += 1;
            return Ok(());
        }
    };
    fig.solved += 1;
    fig.evaluations = fig.evaluations.max(solution.evaluations);
    prop_assert!(solution.residual.abs() <= TOLERANCE, "{solution:?}");
    let stroke = Stroke::new(case.speed, case.tip, [solution.aim.x, solution.aim.y]).unwrap();
    let shot = play(&case.scene, &stroke, &case.setup).unwrap();
    let contact = shot.contact.expect("the solved aim hits a ball");
    prop_assert_eq!(contact.object_ball, object);
    let pocket = case.scene.table().pockets()[case.pocket];
    let along = (pocket.b - pocket.a) * (1.0 / (pocket.b - pocket.a).length());
    let t = line_crossing(&contact.object_after, pocket.a, along);
    let t = t.ok_or_else(|| TestCaseError::fail("the object ball never reaches the mouth line"))?;
    let at = contact.object_after.position_at(t);
    let centre = pocket.centre();
    let miss = ((at.x as f64 - centre.x as f64) * along.x as f64
        + (at.y as f64 - centre.y as f64) * along.y as f64)
        .abs();
    // The crossing point of a path that meets the mouth line at a shallow angle θ is
    // ill-conditioned: a rounding δ of the positions across the line moves it by
    // δ cot θ along it. δ: 8 ulp of the table length, for each evaluation.
    let v = contact.object_after.velocity_at(t);
    let (v_along, v_across) = (
        (v.x * along.x + v.y * along.y).abs() as f64,
        (v.x * along.y - v.y * along.x).abs() as f64,
    );
    let cot = v_along / v_across;
    fig.worst_miss = fig.worst_miss.max(miss);
    fig.worst_cot = fig.worst_cot.max(cot);
    let rounding = 8.0 * ulp(case.scene.table().length()) * (1.0 + cot);
    let allowed = TOLERANCE as f64 + rounding;
    if miss > TOLERANCE as f64 {
        fig.beyond += 1;
        fig.of_rounding = fig.of_rounding.max((miss - TOLERANCE as f64) / rounding);
    }
    prop_assert!(
        miss <= allowed,
        "solved aim misses the pocket centre by {miss:e} m (allowed {allowed:e}): {solution:?}"
    );
    Ok(())
}

#[test]
fn solved_aims_pocket_the_ball() {
    let name = "solved_aims_pocket_the_ball";
    let mut runner = runner(name, AIM_CASES, 0x7368_6f74_0003);
    let figures = RefCell::new(AimFigures::default());
    let started = std::time::Instant::now();
    let strategy = any::<Raw>().prop_map(AimCase::decode);
    if let Err(e) = runner.run(&strategy, |c| check_aim(&c, &mut figures.borrow_mut())) {
        panic!("{name}: {e}\n{runner}");
    }
    let f = figures.into_inner();
    println!(
        "{name}: {} cases in {:.1} s; {} solved (≤ {} evaluations, miss at the pocket centre \
         ≤ {:.2e} m, crossing the mouth line at cot θ ≤ {:.0}; {} beyond the tolerance, by \
         ≤ {:.3} of the rounding allowance), {} object ball not hit, {} \
         pocket unreachable, {} not converged",
        f.cases,
        started.elapsed().as_secs_f64(),
        f.solved,
        f.evaluations,
        f.worst_miss,
        f.worst_cot,
        f.beyond,
        f.of_rounding,
        f.not_hit,
        f.unreachable,
        f.not_converged
    );
    assert!(f.solved > f.cases / 2, "{f:?}");
    // The figures docs/reliability.md quotes.
    cuesight_figures::record!("reliability-shot-aim-solved", "{}", thousands(f.solved));
    cuesight_figures::record!("reliability-shot-aim-evaluations", "{}", f.evaluations);
    cuesight_figures::record!("reliability-shot-aim-not-hit", "{}", thousands(f.not_hit));
    cuesight_figures::record!(
        "reliability-shot-aim-unreachable",
        "{}",
        thousands(f.unreachable)
    );
    cuesight_figures::record!(
        "reliability-shot-aim-not-converged",
        "{}",
        thousands(f.not_converged)
    );
    cuesight_figures::record!("reliability-shot-aim-beyond", "{}", thousands(f.beyond));
    cuesight_figures::record!("reliability-shot-aim-miss-um", "{:.1}", f.worst_miss * 1e6);
    cuesight_figures::record!("reliability-shot-aim-cot", "{:.0}", f.worst_cot);
    cuesight_figures::record!("reliability-shot-aim-of-rounding", "{:.3}", f.of_rounding);
}
