//! Shared by the shot entry points' integration tests (`shot_extremes`,
//! `shot_validation`, `shot_properties`): ball sets with their tables, the setup, the
//! finiteness checks of every output of `play` and `Motion`, and the mirror image of a
//! scene across the table's long axis.
#![allow(dead_code)]

use cuesight::shot::{Contact, Shot, ShotSetup, Stroke};
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{BallSet, Scene, Table};
use cuesight::travel::{Cloth, Motion};
use cuesight::{Model, Params, Vec3};

/// f32 unit roundoff, 2⁻²⁴.
pub const EPS32: f64 = 5.960_464_477_539_063e-8;

/// Every ball set with its table: (name, balls, table).
pub fn sets() -> [(&'static str, BallSet, Table); 3] {
    [
        ("pool", BallSet::POOL, Table::pool()),
        ("snooker", BallSet::SNOOKER, Table::snooker()),
        ("carom", BallSet::CAROM, Table::carom()),
    ]
}

/// Typical cue and cloth, the collision parameters for `set`, `model`.
pub fn setup(set: BallSet, model: Model) -> ShotSetup {
    ShotSetup {
        params: Params::POOL.with_ball(set.radius, set.mass).unwrap(),
        cue: Cue::TYPICAL,
        cloth: Cloth::TYPICAL,
        model,
    }
}

/// The next f32 above `x` (towards +∞); `x` finite.
pub fn next_up(x: f32) -> f32 {
    if x == 0.0 {
        return f32::from_bits(1);
    }
    let b = x.to_bits();
    f32::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

/// The next f32 below `x` (towards −∞); `x` finite.
pub fn next_down(x: f32) -> f32 {
    -next_up(-x)
}

/// Unit in the last place of `x` (f32), as f64.
pub fn ulp(x: f32) -> f64 {
    let x = x.abs();
    (next_up(x) as f64) - (x as f64)
}

/// `Err(what)` naming the first non-finite output of a motion: every field, the phase
/// ends, the box, and position / velocity / spin at the phase ends and in between.
pub fn motion_finite(m: &Motion) -> Result<(), String> {
    let vectors = [
        ("start", m.start),
        ("initial_velocity", m.initial_velocity),
        ("sliding_acceleration", m.sliding_acceleration),
        ("rolling_velocity", m.rolling_velocity),
        ("initial_spin", m.initial_spin),
        ("landing", m.landing()),
        ("rolling_start", m.rolling_start()),
        ("rest", m.rest()),
        ("bounds.min", m.bounds().min),
        ("bounds.max", m.bounds().max),
    ];
    for (what, v) in vectors {
        if !v.is_finite() {
            return Err(format!("{what} {v:?} in {m:?}"));
        }
    }
    let scalars = [
        ("air_time", m.air_time),
        ("hop_height", m.hop_height),
        ("sliding_time", m.sliding_time),
        ("rolling_time", m.rolling_time),
        ("stop_time", m.stop_time()),
    ];
    for (what, x) in scalars {
        if !x.is_finite() || x < 0.0 {
            return Err(format!("{what} = {x} in {m:?}"));
        }
    }
    let ends = [
        0.0,
        0.5 * m.air_time,
        m.air_time,
        m.air_time + 0.5 * m.sliding_time,
        m.air_time + m.sliding_time,
        m.air_time + m.sliding_time + 0.5 * m.rolling_time,
        m.stop_time(),
        2.0 * m.stop_time() + 1.0,
    ];
    for t in ends {
        for (what, v) in [
            ("position_at", m.position_at(t)),
            ("velocity_at", m.velocity_at(t)),
            ("spin_at", m.spin_at(t)),
        ] {
            if !v.is_finite() {
                return Err(format!("{what}({t}) = {v:?} in {m:?}"));
            }
        }
    }
    Ok(())
}

/// `Err(what)` naming the first non-finite output of a played shot.
pub fn shot_finite(s: &Shot) -> Result<(), String> {
    if !s.launch.speed.is_finite() || s.launch.speed < 0.0 || !s.launch.spin.is_finite() {
        return Err(format!("launch {:?}", s.launch));
    }
    motion_finite(&s.cue_before).map_err(|e| format!("cue_before: {e}"))?;
    if let Some(c) = &s.contact {
        contact_finite(c)?;
    }
    Ok(())
}

fn contact_finite(c: &Contact) -> Result<(), String> {
    let fine = c.time.is_finite()
        && c.time >= 0.0
        && c.cue_position.is_finite()
        && c.line_of_centres.is_finite()
        && c.cut_angle.is_finite()
        && c.cut_angle.abs() < core::f32::consts::FRAC_PI_2;
    if !fine {
        return Err(format!("contact {c:?}"));
    }
    if !c.outcome.is_finite()
        || !c.outcome.throw_angle().is_finite()
        || !c.outcome.cue_deflection().is_finite()
        || !c.outcome.separation_angle_deg().is_finite()
    {
        return Err(format!("outcome {:?}", c.outcome));
    }
    motion_finite(&c.cue_after).map_err(|e| format!("cue_after: {e}"))?;
    motion_finite(&c.object_after).map_err(|e| format!("object_after: {e}"))?;
    if let Some((_, t)) = c.pocket {
        if !(t.is_finite() && t >= 0.0) {
            return Err(format!("pocket time {t}"));
        }
    }
    Ok(())
}

/// Round `y` to the grid of multiples of 2⁻²³ (0.12 µm). On that grid `W − y` is exact
/// in f32 for every table width `W ∈ [1, 2)` m (the presets), so a scene and its mirror
/// image have exactly opposite centre-to-centre vectors.
pub fn snap(y: f32) -> f32 {
    let scale = 8_388_608.0f64; // 2²³
    ((y as f64 * scale).round() / scale) as f32
}

/// The mirror image of `scene` across the table's long axis `y = W/2`: `y → W − y`
/// (exact when the scene is on the [`snap`] grid), same ball order.
pub fn mirror_scene(scene: &Scene) -> Scene {
    let w = scene.table().width();
    let balls = scene.balls();
    let mut image = Scene::new(
        scene.table().clone(),
        scene.radius(),
        [balls[0].x, w - balls[0].y],
    )
    .unwrap();
    for b in &balls[1..] {
        image.add_ball([b.x, w - b.y]).unwrap();
    }
    image
}

/// A stroke and its mirror image: built from `direction` and `(x, −y)`, tip side
/// `side` and `−side` (`Stroke::new` normalises both the same way).
pub fn stroke_pair(cue_speed: f32, tip: TipOffset, direction: [f32; 2]) -> (Stroke, Stroke) {
    let image = TipOffset::new(-tip.side(), tip.height()).unwrap();
    (
        Stroke::new(cue_speed, tip, direction).unwrap(),
        Stroke::new(cue_speed, image, [direction[0], -direction[1]]).unwrap(),
    )
}

/// Midpoint of two f32 of the same sign, on their bit patterns (bisection to adjacent
/// values).
pub fn mid(a: f32, b: f32) -> f32 {
    let sum = u64::from(a.to_bits()) + u64::from(b.to_bits());
    f32::from_bits((sum / 2) as u32)
}

/// Mirror of a polar vector (velocity, acceleration, direction) across `y`.
pub fn mv(v: Vec3) -> Vec3 {
    Vec3::new(v.x, -v.y, v.z)
}

/// Mirror of an axial vector (angular velocity) across `y`: `(−x, y, −z)`.
pub fn mw(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, w.y, -w.z)
}

/// Index of the pocket that is the mirror image of pocket `i` (same segment with
/// `y → W − y`, ends in the same order), found from the table's geometry to within
/// `tol` metres.
pub fn mirror_pocket(table: &Table, i: usize, tol: f64) -> Option<usize> {
    let w = table.width() as f64;
    let p = table.pockets()[i];
    table.pockets().iter().position(|q| {
        let close = |a: Vec3, b: Vec3| {
            (a.x as f64 - b.x as f64).abs() <= tol && (a.y as f64 - (w - b.y as f64)).abs() <= tol
        };
        close(q.a, p.a) && close(q.b, p.b)
    })
}

/// Largest `max(|Δv|, R|Δω|)` between two states (m/s).
pub fn state_difference(v: (Vec3, Vec3), w: (Vec3, Vec3), radius: f32) -> f64 {
    let d = |a: Vec3, b: Vec3| {
        let (x, y, z) = (
            a.x as f64 - b.x as f64,
            a.y as f64 - b.y as f64,
            a.z as f64 - b.z as f64,
        );
        (x * x + y * y + z * z).sqrt()
    };
    d(v.0, w.0).max(radius as f64 * d(v.1, w.1))
}

/// Scene with the cue ball at `cue` and object balls at `others`; panics if refused.
pub fn scene(table: &Table, radius: f32, cue: [f32; 2], others: &[[f32; 2]]) -> Scene {
    let mut s = Scene::new(table.clone(), radius, cue).unwrap();
    for o in others {
        s.add_ball(*o)
            .unwrap_or_else(|e| panic!("ball {o:?} refused: {e}"));
    }
    s
}

/// Fixed proptest configuration (as `tests/common`): XorShift with a fixed seed (CI is
/// deterministic; `PROPTEST_RNG_SEED` / `PROPTEST_CASES` override), failures persisted
/// next to the test source (`<test>.proptest-regressions`).
pub fn config(cases: u32, seed: u64) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, FileFailurePersistence, RngAlgorithm, RngSeed};
    Config {
        cases,
        rng_algorithm: RngAlgorithm::XorShift,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        max_shrink_iters: 4096,
        ..Config::default()
    }
}

/// `Err(what)` naming the first non-finite number of a guidance answer.
pub fn guidance_finite(g: &cuesight::guidance::Guidance) -> Result<(), String> {
    let s = &g.stroke;
    let mut numbers = vec![s.cue_speed, s.aim_deg, s.launch_speed];
    numbers.extend(s.aim);
    numbers.extend(s.launch_spin);
    if let Some(c) = &g.contact {
        numbers.extend([c.time, c.cut_deg, c.speed, c.throw_deg]);
        numbers.extend(c.cue_position);
        numbers.extend(c.line_of_centres);
        numbers.extend(c.spin);
        numbers.extend(c.error_estimate);
    }
    for path in [Some(&g.cue_ball), g.object_ball.as_ref()]
        .into_iter()
        .flatten()
    {
        motion_finite(&path.motion)?;
        numbers.extend([path.rolling_direction_deg, path.end.time]);
        numbers.extend(path.velocity);
        numbers.extend(path.end_position);
    }
    if let Some(t) = &g.target {
        numbers.extend(t.miss);
    }
    if let Some(solve) = &g.solve {
        let a = &solve.solution;
        numbers.extend([
            solve.aim_deg,
            solve.naive_aim_deg,
            a.correction_deg,
            a.correction_mm,
        ]);
        numbers.extend([a.cut_angle_deg, a.residual]);
    }
    match numbers.iter().find(|x| !x.is_finite()) {
        Some(x) => Err(format!("{x} in {g:?}")),
        None => Ok(()),
    }
}
