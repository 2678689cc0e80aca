//! Extremes suite for the shot entry points (issue 6, item 1, extended to `strike`,
//! `travel`, `table`, `shot` and `aim`): named tests at the edges of the shot chain —
//! aims 1e-6 rad either side of grazing an object ball, cut angles → 0 and → ±90°, stun
//! and exact natural roll, tip offsets 0 and at the miscue limit, cue speeds from the
//! smallest subnormal through 1 mm/s to 20 m/s, cloth friction at its limits, balls
//! touching cushions, pockets and each other (centre distance exactly 2R and 2R + 1
//! ulp), travel distances 0 and a table length, every ball set, subnormal-scale inputs,
//! and lifted (hopping) balls. Every output finite; continuity across the travel's
//! regime boundaries (sliding → rolling at the TP 4.1 distance, rolling → rest) and the
//! hit/miss boundary, bisected to adjacent f32 inputs; mirror symmetry across the
//! table's long axis. Expected values come from the TP A.4 / A.30 formulas evaluated
//! here in f64. `-- --nocapture` prints the figures.

mod shot_common;

use cuesight::aim::{solve_aim, AimError};
use cuesight::shot::{play, Shot, ShotSetup, Stroke};
use cuesight::strike::TipOffset;
use cuesight::table::{BallSet, Scene, Table};
use cuesight::travel::{Cloth, Motion, GRAVITY};
use cuesight::{Model, Vec3};
use cuesight_figures::thousands;
use shot_common::*;

/// The models a shot is played with. `Kim` is left out: it refuses every gripping
/// contact (its validity domain), which shots at these extremes reach all the time;
/// `shot_properties` checks that its refusals reach `play`'s caller as typed errors.
const MODELS: [Model; 4] = [
    Model::Ideal,
    Model::KimGrip,
    Model::Exact,
    Model::Auto { tolerance: 1e-3 },
];

fn play_ok(scene: &Scene, stroke: &Stroke, setup: &ShotSetup, what: &str) -> Shot {
    let shot = play(scene, stroke, setup)
        .unwrap_or_else(|e| panic!("{what}: play refused a valid shot: {e} ({stroke:?})"));
    if let Err(e) = shot_finite(&shot) {
        panic!("{what}: non-finite output: {e}");
    }
    shot
}

/// Aim angle (f64, rad) at which the cue ball's path is tangent to a ball at `object`,
/// on the side `sign` (±1) of the line of centres: `θ₀ ± asin(2R/D)`.
fn grazing_angle(cue: Vec3, object: Vec3, radius: f32, sign: f64) -> f64 {
    let (dx, dy) = (
        object.x as f64 - cue.x as f64,
        object.y as f64 - cue.y as f64,
    );
    let d = dx.hypot(dy);
    dy.atan2(dx) + sign * (2.0 * radius as f64 / d).asin()
}

/// Aims 1e-6 rad inside and outside the grazing boundary on both sides of an object
/// ball, at several distances and directions, every ball set and model: inside hits the
/// ball at a cut within a few degrees of ±90° (sign from the side), outside misses it.
#[test]
fn aim_one_microradian_either_side_of_grazing() {
    let mut count = 0;
    for (name, set, table) in sets() {
        let r = set.radius;
        let cue = [snap(0.5), snap(0.5 * table.width())];
        for (dx, dy) in [(0.3f32, 0.0f32), (1.2, 0.31), (0.4, -0.35), (1.9, 0.2)] {
            let object = [snap(cue[0] + dx), snap(cue[1] + dy)];
            let s = scene(&table, r, cue, &[object]);
            let (c, o) = (s.balls()[0], s.balls()[1]);
            for sign in [1.0f64, -1.0] {
                let boundary = grazing_angle(c, o, r, sign);
                for (offset, hits) in [(-1e-6, true), (1e-6, false)] {
                    let angle = (boundary + sign * offset) as f32;
                    let stroke = Stroke::at_angle(3.0, TipOffset::CENTRE, angle).unwrap();
                    for model in MODELS {
                        let what = format!("{name} {dx},{dy} side {sign} {offset} {model:?}");
                        let shot = play_ok(&s, &stroke, &setup(set, model), &what);
                        match (hits, &shot.contact) {
                            (true, Some(contact)) => {
                                assert_eq!(contact.object_ball, 1, "{what}");
                                // The aim is turned by `sign` from the line of centres:
                                // the cut (line of centres → velocity, counter-clockwise
                                // positive) is near sign·90°.
                                let cut = contact.cut_angle.to_degrees();
                                assert!(
                                    cut * sign as f32 > 80.0,
                                    "{what}: cut {cut}° for a near-graze"
                                );
                            }
                            (false, None) => {}
                            _ => panic!("{what}: expected hit = {hits}, got {:?}", shot.contact),
                        }
                        count += 1;
                    }
                }
            }
        }
    }
    println!("grazing aims: {count} shots");
    cuesight_figures::record!("reliability-shot-extremes-grazing-shots", "{count}");
}

/// Bisect the aim angle between a hit and a miss to adjacent f32 angles: `play` never
/// fails in between, and at the last hitting aim the object ball barely moves. Bound:
/// the normal approach speed at contact is `U cos φ = U √(gap)/(2R)` with
/// `gap = 4R² − across²`; one f32 step of the aim (plus the rounding of `across`, 8ε D)
/// changes `across` by at most `D Δθ + 8ε D`, so at the last hit
/// `|v_object| ≤ (1 + e*)/2 · U √(4R (D Δθ + 8ε D))/(2R)` (+ 1 %, the friction models'
/// spin transfer).
#[test]
fn hit_miss_boundary_is_continuous() {
    let mut worst = 0.0f64;
    for (name, set, table) in sets() {
        let r = set.radius;
        let cue = [snap(0.6), snap(0.4 * table.width())];
        for (dx, dy) in [(0.5f32, 0.1f32), (1.5, -0.2), (0.2, 0.25)] {
            let object = [snap(cue[0] + dx), snap(cue[1] + dy)];
            let s = scene(&table, r, cue, &[object]);
            let (c, o) = (s.balls()[0], s.balls()[1]);
            let d = ((o.x - c.x) as f64).hypot((o.y - c.y) as f64);
            for sign in [1.0f64, -1.0] {
                let boundary = grazing_angle(c, o, r, sign);
                for model in [Model::Ideal, Model::KimGrip, Model::Exact] {
                    let setup = setup(set, model);
                    let hit = |angle: f32| {
                        let stroke = Stroke::at_angle(3.0, TipOffset::CENTRE, angle).unwrap();
                        play_ok(&s, &stroke, &setup, name).contact.is_some()
                    };
                    let (inside, outside) = (
                        (boundary - sign * 1e-4) as f32,
                        (boundary + sign * 1e-4) as f32,
                    );
                    assert!(hit(inside) && !hit(outside));
                    let (mut a, mut b) = (inside, outside);
                    while a.to_bits().abs_diff(b.to_bits()) > 1 {
                        let mid = mid(a, b);
                        if hit(mid) {
                            a = mid;
                        } else {
                            b = mid;
                        }
                    }
                    let stroke = Stroke::at_angle(3.0, TipOffset::CENTRE, a).unwrap();
                    let shot = play_ok(&s, &stroke, &setup, name);
                    let contact = shot.contact.unwrap();
                    let u = contact.impact.speed() as f64;
                    let step = (a as f64 - b as f64).abs();
                    let e = if model == Model::Ideal { 1.0 } else { 0.95 };
                    let bound = 1.01
                        * 0.5
                        * (1.0 + e)
                        * u
                        * (4.0 * r as f64 * (d * step + 8.0 * EPS32 * d)).sqrt()
                        / (2.0 * r as f64);
                    let v = contact.outcome.object_ball.velocity.length() as f64;
                    worst = worst.max(v / bound);
                    assert!(
                        v <= bound,
                        "{name} {model:?}: object ball {v} m/s at the last hit (bound {bound})"
                    );
                }
            }
        }
    }
    println!("hit/miss boundary: object-ball speed at the last hit ≤ {worst:.3} of the bound");
    cuesight_figures::record!("reliability-shot-extremes-hit-miss", "{worst:.2}");
}

/// The cue ball at `(x₀, y₀)` aimed along `+x`; the object ball at
/// `(x₀ + run + 2R cos φ, y₀ − 2R sin φ)` (snapped to the mirror grid), or for a target
/// given in grid steps, `y₀ ∓ (2R − k·2⁻²³)` (k steps of the grid inside tangency).
#[derive(Clone, Copy, Debug)]
enum Target {
    Degrees(f64),
    StepsInside(i32),
}

fn cut_scene(table: &Table, radius: f32, run: f64, target: Target) -> Scene {
    let (x0, y0) = (snap(0.3), snap(0.5 * table.width()));
    let r2 = 2.0 * radius as f64;
    let grid = 1.0 / 8_388_608.0;
    let (dx, dy) = match target {
        Target::Degrees(deg) => {
            let cut = deg.to_radians();
            (r2 * cut.cos(), -r2 * cut.sin())
        }
        Target::StepsInside(k) => {
            // |dy| just below 2R on the grid, then k − 1 more steps in; sign of k = side.
            let below = (r2 / grid).floor() * grid;
            let dy = below - (k.unsigned_abs() as f64 - 1.0) * grid;
            let dy = if k > 0 { -dy } else { dy };
            ((r2 * r2 - dy * dy).sqrt(), dy)
        }
    };
    let object = [
        snap((x0 as f64 + run + dx) as f32),
        snap((y0 as f64 + dy) as f32),
    ];
    scene(table, radius, [x0, y0], &[object])
}

/// Where the positions say the contact is, in f64: the cue ball's centre travels
/// `along − √(4R² − across²)` along `+x`; the unit line of centres there. `None` when
/// the path misses (|across| ≥ 2R).
fn exact_contact(s: &Scene) -> Option<(f64, [f64; 2])> {
    let (c, o) = (s.balls()[0], s.balls()[1]);
    let (along, across) = (o.x as f64 - c.x as f64, o.y as f64 - c.y as f64);
    let r2 = 2.0 * s.radius() as f64;
    if across.abs() >= r2 {
        return None;
    }
    let run = along - (r2 * r2 - across * across).sqrt();
    Some((c.x as f64 + run, [(along - run) / r2, across / r2]))
}

/// Cut angles 0 (straight in), ±1°, ±60°, ±89° and 1, 2, 16 and 256 steps of the 2⁻²³
/// grid inside tangency (cuts of 89.88°–88.1°, the closest to 90° that positions on the
/// grid give with an axis-aligned aim), cue ball aimed along the table's axis: every
/// model, every ball set, a centre hit and a side/follow hit. Every target inside
/// tangency is hit. The reported line of centres is the one the positions give (in f64)
/// to within the rounding of the contact point: the cue ball's centre there may be off
/// by 4 ulp(x) along the aim, which turns the unit line of centres by `4 ulp(x)/(2R)`,
/// plus 8ε for its normalisation; the cut angle follows. Straight in with a centre hit:
/// exactly no sideways output.
#[test]
fn cut_angle_zero_and_near_ninety_degrees() {
    let mut worst = 0.0f64;
    let mut targets: Vec<Target> = [0.0, 1.0, -1.0, 60.0, -60.0, 89.0, -89.0]
        .into_iter()
        .map(Target::Degrees)
        .collect();
    for k in [1, 2, 16, 256] {
        targets.push(Target::StepsInside(k));
        targets.push(Target::StepsInside(-k));
    }
    for (name, set, table) in sets() {
        let r = set.radius;
        for target in &targets {
            let s = cut_scene(&table, r, 0.8, *target);
            let (x_contact, centres) = exact_contact(&s).expect("inside tangency");
            let actual = -centres[1].atan2(centres[0]);
            for tip in [
                TipOffset::CENTRE,
                TipOffset::from_radius_fraction(0.3, 0.2, r).unwrap(),
            ] {
                let stroke = Stroke::new(2.0, tip, [1.0, 0.0]).unwrap();
                for model in MODELS {
                    let what = format!("{name} {target:?} {tip:?} {model:?}");
                    let shot = play_ok(&s, &stroke, &setup(set, model), &what);
                    let contact = shot
                        .contact
                        .unwrap_or_else(|| panic!("{what}: missed a ball inside tangency"));
                    let allowed = 4.0 * ulp(x_contact as f32) / (2.0 * r as f64) + 8.0 * EPS32;
                    let l = contact.line_of_centres;
                    let error = (l.x as f64 - centres[0]).hypot(l.y as f64 - centres[1]);
                    let cut_error = (contact.cut_angle as f64 - actual).abs();
                    worst = worst.max(error / allowed).max(cut_error / (1.01 * allowed));
                    assert!(
                        error <= allowed && cut_error <= 1.01 * allowed,
                        "{what}: line of centres {l:?}, cut {} rad; the positions give \
                         {centres:?}, {actual} rad (allowed {allowed:e})",
                        contact.cut_angle
                    );
                    if matches!(target, Target::Degrees(d) if *d == 0.0) {
                        assert_eq!(contact.cut_angle, 0.0, "{what}");
                        assert_eq!(contact.line_of_centres, Vec3::new(1.0, 0.0, 0.0), "{what}");
                        if tip == TipOffset::CENTRE {
                            let o = contact.outcome.object_ball;
                            assert_eq!(o.velocity.y, 0.0, "{what}");
                            assert_eq!(contact.object_after.rolling_velocity.y, 0.0, "{what}");
                            assert_eq!(contact.cue_after.rolling_velocity.y, 0.0, "{what}");
                        }
                    }
                }
            }
        }
    }
    println!("cut angles: error ≤ {worst:.3} of the rounding allowance");
    cuesight_figures::record!("reliability-shot-extremes-cut-angles", "{worst:.3}");
}

/// Stun and zero spin: a centre hit launches with no spin at all; touching the object
/// ball (contact at t = 0) it arrives with exactly the launch state. Farther away the
/// spin at contact is the TP A.4 value `ω_y = μ_c g t/(ν R)` with
/// `t = (v₀ − √(v₀² − 2 μ_c g d))/(μ_c g)` for a contact `d` metres on while sliding,
/// evaluated here in f64 (relative 1e-4: `t` comes from a root the core solves in f32 on
/// its own).
#[test]
fn stun_and_zero_spin() {
    for (name, set, table) in sets() {
        let r = set.radius;
        let setup = setup(set, Model::KimGrip);
        for speed in [0.5f32, 2.0, 3.0] {
            let stroke = Stroke::new(speed, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
            // Touching: centre distance exactly 2R on the x axis.
            let (x0, y0) = touching_x(r);
            let s = scene(&table, r, [x0, y0], &[[x0 + 2.0 * r, y0]]);
            let shot = play_ok(&s, &stroke, &setup, name);
            assert_eq!(shot.launch.spin, Vec3::ZERO, "{name}");
            let c = shot.contact.unwrap();
            assert_eq!(c.time, 0.0, "{name} {speed}");
            assert_eq!(c.impact.spin(), Vec3::ZERO, "{name} {speed}");
            assert_eq!(
                c.impact.velocity(),
                Vec3::new(shot.launch.speed, 0.0, 0.0),
                "{name} {speed}"
            );
            // Half the TP 4.1 sliding distance on.
            let v = shot.launch.speed as f64;
            let d = 0.5 * 12.0 * v * v / (49.0 * 0.2 * GRAVITY as f64);
            let s = scene(
                &table,
                r,
                [x0, y0],
                &[[(x0 as f64 + d + 2.0 * r as f64) as f32, y0]],
            );
            let shot = play_ok(&s, &stroke, &setup, name);
            let c = shot.contact.unwrap();
            let mu_g = 0.2 * GRAVITY as f64;
            let v0 = shot.launch.speed as f64;
            let travelled = s.balls()[1].x as f64 - x0 as f64 - 2.0 * r as f64;
            let t = (v0 - (v0 * v0 - 2.0 * mu_g * travelled).sqrt()) / mu_g;
            assert!(t < 2.0 * v0 / (7.0 * mu_g), "{name}: still sliding");
            let expected = mu_g * t / (0.4 * r as f64);
            let got = c.impact.spin().y as f64;
            assert!(
                (got - expected).abs() <= 1e-4 * expected,
                "{name} {speed}: ω_y {got} vs {expected}"
            );
            assert_eq!(c.impact.spin().x, 0.0);
            assert_eq!(c.impact.spin().z, 0.0);
        }
    }
}

/// A cue-ball position `(x, y)` near the left cushion such that `x + 2R` is exact in
/// f32 (the centre distance to a ball at `x + 2R` is then exactly `2R`), `y` mid-table.
fn touching_x(radius: f32) -> (f32, f32) {
    let mut x = radius;
    loop {
        let o = x + 2.0 * radius;
        if o as f64 - x as f64 == 2.0 * radius as f64 {
            return (x, snap(0.6));
        }
        x = next_up(x);
    }
}

/// Exact natural roll at the strike: a tip `2R/5` above centre gives `ω = v/R` (TP
/// A.30); the cue ball hardly slides (the slip is rounding: sliding time ≤ 1e-6 s), rolls
/// at its launch speed, and stops after `v²/(2 μ_r g)` (TP A.4), to 1e-5 relative; the
/// state at a contact anywhere along the path is natural roll (table slip ≤ 1e-5 v).
#[test]
fn exact_natural_roll_at_strike() {
    for (name, set, table) in sets() {
        let r = set.radius;
        let tip = TipOffset::from_radius_fraction(0.0, 0.4, r).unwrap();
        for speed in [1e-3f32, 0.1, 1.0, 5.0, 20.0] {
            let stroke = Stroke::new(speed, tip, [1.0, 0.0]).unwrap();
            let s = scene(&table, r, [snap(0.3), snap(0.6)], &[[snap(1.5), snap(0.6)]]);
            for model in MODELS {
                let what = format!("{name} {speed} {model:?}");
                let shot = play_ok(&s, &stroke, &setup(set, model), &what);
                let m = &shot.cue_before;
                let v = shot.launch.speed as f64;
                assert!(
                    m.sliding_time <= 1e-6,
                    "{what}: slides {} s",
                    m.sliding_time
                );
                let rolled = m.rest().x as f64 - m.start.x as f64;
                let expected = v * v / (2.0 * 0.01 * GRAVITY as f64);
                assert!(
                    (rolled - expected).abs() <= 1e-5 * expected + 4.0 * ulp(m.rest().x),
                    "{what}: rolls {rolled} m, TP A.4 {expected}"
                );
                if let Some(c) = shot.contact {
                    let (vi, wi) = (c.impact.velocity(), c.impact.spin());
                    let slip = (vi.x as f64 - r as f64 * wi.y as f64)
                        .hypot(vi.y as f64 + r as f64 * wi.x as f64);
                    assert!(slip <= 1e-5 * v, "{what}: slip {slip} at contact");
                }
            }
        }
    }
}

/// Tip offsets: the centre and 16 directions on the miscue limit `|b| = 0.5 R` (a
/// direction whose rounding lands above the limit is refused with `TipOffset`); every
/// ball set and model, a cut shot; outputs finite and the strike's spin follows TP A.30
/// (`ω = 5 v b/(2R²)`, f64, 1e-5 relative).
#[test]
fn tip_offsets_at_the_miscue_limit_and_centre() {
    let mut played = 0;
    for (name, set, table) in sets() {
        let r = set.radius;
        let s = scene(
            &table,
            r,
            [snap(0.5), snap(0.5)],
            &[[snap(1.3), snap(0.72)]],
        );
        let aim = [1.3 - 0.5, 0.72 - 0.5 - 0.8 * r];
        let mut tips = vec![TipOffset::CENTRE];
        for k in 0..16 {
            let a = k as f32 * core::f32::consts::TAU / 16.0;
            tips.push(TipOffset::new(0.5 * r * a.cos(), 0.5 * r * a.sin()).unwrap());
        }
        for tip in tips {
            let stroke = Stroke::new(3.0, tip, aim).unwrap();
            for model in MODELS {
                let what = format!("{name} {tip:?} {model:?}");
                let shot = match play(&s, &stroke, &setup(set, model)) {
                    Err(e) => {
                        assert_eq!(e.field(), Some(cuesight::Field::TipOffset), "{what}");
                        let b = (tip.side() as f64).hypot(tip.height() as f64);
                        assert!(b > 0.5 * r as f64 * (1.0 - 4.0 * EPS32), "{what}");
                        continue;
                    }
                    Ok(shot) => shot,
                };
                shot_finite(&shot).unwrap_or_else(|e| panic!("{what}: {e}"));
                let v = shot.launch.speed as f64;
                let b2 = (tip.side() as f64).powi(2) + (tip.height() as f64).powi(2);
                let expected_v =
                    1.75 * 3.0 / (1.0 + set.mass as f64 / 0.54 + 2.5 * b2 / (r as f64).powi(2));
                assert!((v - expected_v).abs() <= 1e-5 * expected_v, "{what}: v {v}");
                let scale = 2.5 * v / (r as f64).powi(2);
                let w = shot.launch.spin;
                assert!(
                    (w.y as f64 - scale * tip.height() as f64).abs() <= 1e-5 * scale * r as f64
                );
                assert!((w.z as f64 - scale * tip.side() as f64).abs() <= 1e-5 * scale * r as f64);
                assert!(shot.contact.is_some(), "{what}");
                played += 1;
            }
        }
    }
    println!("tip offsets: {played} shots");
    cuesight_figures::record!("reliability-shot-extremes-tip-shots", "{played}");
}

/// Cue speeds from the smallest subnormal through 1 mm/s to the 20 m/s limit, every
/// ball set, a centre and a draw hit: outputs finite; the launch speed follows TP A.30
/// (f64, 1e-5 relative, or exactly 0 when it underflows) and the distance the cue ball
/// would travel never decreases with the cue speed.
#[test]
fn cue_speeds_from_subnormal_to_twenty_metres_per_second() {
    let tiny = f32::from_bits(1);
    let speeds = [
        tiny, 1e-30, 1e-6, 1e-3, 0.01, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 19.99, 20.0,
    ];
    for (name, set, table) in sets() {
        let r = set.radius;
        let s = scene(
            &table,
            r,
            [snap(0.4), snap(0.6)],
            &[[snap(2.0), snap(0.61)]],
        );
        for height in [0.0f32, -0.4] {
            let tip = TipOffset::from_radius_fraction(0.0, height, r).unwrap();
            let mut last_travel = 0.0f64;
            for speed in speeds {
                let stroke = Stroke::new(speed, tip, [1.0, 0.0]).unwrap();
                for model in MODELS {
                    let what = format!("{name} {speed} {height} {model:?}");
                    let shot = play_ok(&s, &stroke, &setup(set, model), &what);
                    let expected = 1.75 * speed as f64
                        / (1.0 + set.mass as f64 / 0.54 + 2.5 * (height as f64).powi(2));
                    let v = shot.launch.speed as f64;
                    if expected > 1e-37 {
                        assert!((v - expected).abs() <= 1e-5 * expected, "{what}: {v}");
                    } else {
                        assert!(v <= 2.0 * expected + 1e-45, "{what}: {v}");
                    }
                    let travel = shot.cue_before.rest().x as f64 - s.balls()[0].x as f64;
                    assert!(
                        travel >= last_travel - 4.0 * ulp(shot.cue_before.rest().x),
                        "{what}: {travel} < {last_travel}"
                    );
                    if model == Model::KimGrip {
                        last_travel = travel;
                    }
                }
            }
        }
    }
}

/// Cloth friction at its limits: the smallest accepted sliding friction and rolling
/// resistance and the largest (1 and 0.5); zero is refused (`ClothFriction`,
/// `RollingResistance`). Every output finite; the stun ball's rolling speed is 5/7 of
/// its launch speed whatever μ_c, its rest position `12v²/(49 μ_c g) + (5v/7)²/(2 μ_r g)`
/// from the start (TP 4.1 + TP A.4, f64, 1e-4 relative).
#[test]
fn cloth_friction_at_its_limits() {
    assert_eq!(
        Cloth::new(0.0, 0.01).unwrap_err().field(),
        Some(cuesight::Field::ClothFriction)
    );
    assert_eq!(
        Cloth::new(0.2, 0.0).unwrap_err().field(),
        Some(cuesight::Field::RollingResistance)
    );
    let smallest_sliding = smallest_accepted(|mu| Cloth::new(mu, 0.01).is_ok());
    let smallest_rolling = smallest_accepted(|mu| Cloth::new(0.2, mu).is_ok());
    println!("smallest accepted μ_c {smallest_sliding:e}, μ_r {smallest_rolling:e}");
    for (name, set, table) in sets() {
        let r = set.radius;
        let s = scene(
            &table,
            r,
            [snap(0.4), snap(0.6)],
            &[[snap(2.0), snap(0.65)]],
        );
        for (mu_c, mu_r) in [
            (smallest_sliding, smallest_rolling),
            (smallest_sliding, 0.5),
            (1.0, smallest_rolling),
            (1.0, 0.5),
            (0.2, 0.01),
        ] {
            let mut setup = setup(set, Model::KimGrip);
            setup.cloth = Cloth::new(mu_c, mu_r).unwrap();
            for speed in [1e-3f32, 1.0, 20.0] {
                let stroke = Stroke::new(speed, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
                let what = format!("{name} μ_c {mu_c} μ_r {mu_r} {speed}");
                let shot = play_ok(&s, &stroke, &setup, &what);
                let m = &shot.cue_before;
                let v = shot.launch.speed as f64;
                let roll = m.rolling_velocity.x as f64;
                assert!((roll - 5.0 / 7.0 * v).abs() <= 1e-5 * v, "{what}: {roll}");
                let g = GRAVITY as f64;
                let expected = 12.0 * v * v / (49.0 * mu_c as f64 * g)
                    + (5.0 * v / 7.0).powi(2) / (2.0 * mu_r as f64 * g);
                let got = m.rest().x as f64 - m.start.x as f64;
                assert!(
                    (got - expected).abs() <= 1e-4 * expected + 4.0 * ulp(m.rest().x),
                    "{what}: rests after {got} m, TP {expected}"
                );
            }
        }
    }
}

/// Smallest positive f32 `accepts` takes (bisection on the bit pattern; the accepted
/// set is an interval up to 1).
fn smallest_accepted(accepts: impl Fn(f32) -> bool) -> f32 {
    let (mut lo, mut hi) = (0u32, 1.0f32.to_bits());
    assert!(accepts(1.0) || accepts(0.5));
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if accepts(f32::from_bits(mid)) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    f32::from_bits(hi)
}

/// The cue ball touching the object ball: centre distance exactly `2R` (contact at
/// t = 0, the launch state arrives unchanged, head-on) and `2R + 1 ulp` (contact after
/// one ulp of travel: the same state to within the travel's change over that ulp,
/// `|Δv| ≤ μ_c g Δt`, `R|Δω| ≤ μ_c g Δt/ν`, plus 4ε of rounding). Every ball set, model,
/// and a centre, follow, draw and side hit; the aim straight at the ball and turned by
/// 10° and 60° (still touching it).
#[test]
fn cue_ball_touching_the_object_ball() {
    let mut worst = 0.0f64;
    for (name, set, table) in sets() {
        let r = set.radius;
        let (x0, y0) = touching_x(r);
        let touching = x0 + 2.0 * r;
        assert_eq!(touching as f64 - x0 as f64, 2.0 * r as f64);
        for tip in [(0.0, 0.0), (0.0, 0.4), (0.0, -0.45), (0.35, 0.1)] {
            let tip = TipOffset::from_radius_fraction(tip.0, tip.1, r).unwrap();
            for turn in [0.0f32, 10.0, -60.0] {
                let aim = turn.to_radians();
                let stroke = Stroke::at_angle(2.0, tip, aim).unwrap();
                for model in MODELS {
                    let what = format!("{name} {tip:?} turn {turn} {model:?}");
                    let setup = setup(set, model);
                    let at = scene(&table, r, [x0, y0], &[[touching, y0]]);
                    let shot = play_ok(&at, &stroke, &setup, &what);
                    let c = shot.contact.unwrap_or_else(|| panic!("{what}: no contact"));
                    let rounding = 4.0 * ulp(touching);
                    if turn == 0.0 {
                        assert_eq!(c.time, 0.0, "{what}");
                        assert_eq!(c.cue_position, at.balls()[0], "{what}");
                        assert_eq!(c.line_of_centres, Vec3::new(1.0, 0.0, 0.0), "{what}");
                    } else {
                        // Turned, the contact distance `along − √gap` is 0 up to rounding.
                        let moved = (c.cue_position - at.balls()[0]).length() as f64;
                        assert!(moved <= rounding, "{what}: moved {moved}");
                        let l = c.line_of_centres;
                        let off = (l.x as f64 - 1.0).hypot(l.y as f64);
                        assert!(
                            off <= rounding / (2.0 * r as f64) + 8.0 * EPS32,
                            "{what}: {l:?}"
                        );
                    }
                    let m = &shot.cue_before;
                    let (arrives, launched) = (c.impact.speed(), m.initial_velocity.length());
                    if turn == 0.0 {
                        assert_eq!(arrives, launched, "{what}");
                    } else {
                        let off = (arrives as f64 - launched as f64).abs();
                        assert!(off <= 4.0 * EPS32 * launched as f64, "{what}: {off}");
                    }
                    let beyond = scene(&table, r, [x0, y0], &[[next_up(touching), y0]]);
                    let next = play_ok(&beyond, &stroke, &setup, &what);
                    let n = next
                        .contact
                        .unwrap_or_else(|| panic!("{what}: no contact at 2R + 1 ulp"));
                    // One ulp farther along x is `ulp/cos(turn)` along the aim.
                    let further = (ulp(touching) + rounding) / (turn.to_radians().cos() as f64);
                    let dt = n.time as f64 - c.time as f64;
                    let speed = shot.launch.speed as f64;
                    assert!(dt.abs() <= 1.01 * further / speed, "{what}: {dt}");
                    let a = (n.cue_position - c.cue_position).length() as f64;
                    assert!(a <= further, "{what}: moved {a}");
                    let mu_g = 0.2 * GRAVITY as f64;
                    let bound = mu_g * dt.abs() / 0.4 + 4.0 * EPS32 * speed;
                    let before = (m.velocity_at(c.time), m.spin_at(c.time));
                    let after = (
                        next.cue_before.velocity_at(n.time),
                        next.cue_before.spin_at(n.time),
                    );
                    let d = state_difference(before, after, r);
                    worst = worst.max(d / bound);
                    assert!(d <= bound, "{what}: state jumps by {d} (bound {bound})");
                }
            }
        }
    }
    println!("touching balls: state change over 1 ulp ≤ {worst:.3} of the bound");
    cuesight_figures::record!("reliability-shot-extremes-touching", "{worst:.2}");
}

/// Stop distance (m) of a centre-hit (stun) cue ball from the cue speed, TP A.30 + TP
/// 4.1 + TP A.4 in f64: `12 v²/(49 μ_c g) + (5v/7)²/(2 μ_r g)`, `v = 1.75 V/(1 + M/m_c)`.
fn stun_stop_distance(cue_speed: f32, mass: f32) -> f64 {
    let v = 1.75 * cue_speed as f64 / (1.0 + mass as f64 / 0.54);
    let g = GRAVITY as f64;
    12.0 * v * v / (49.0 * 0.2 * g) + (5.0 * v / 7.0).powi(2) / (2.0 * 0.01 * g)
}

/// Travel distance from zero (touching, above) to a table length: the object ball on
/// the far cushion, the cue ball on the near one; the cue speed bisected to adjacent
/// f32 values between stopping short and reaching it. `play` never fails in between (a
/// cue ball that stops exactly touching is not a collision), and at the slowest hit the
/// object ball barely moves: the cue ball arrives at most at `√(2 μ_r g Δd)`, `Δd` the
/// change of the stop distance over one f32 step of the cue speed (TP formulas, f64)
/// plus 8 ulp of the table length of rounding, and hands on at most `(1 + e*)/2` of it.
#[test]
fn travel_distance_of_a_table_length() {
    let mut worst = 0.0f64;
    for (name, set, table) in sets() {
        let r = set.radius;
        let y = snap(0.5 * table.width());
        let (x0, x1) = (r, table.length() - r);
        let s = scene(&table, r, [x0, y], &[[x1, y]]);
        let run = x1 as f64 - x0 as f64 - 2.0 * r as f64;
        for model in [Model::Ideal, Model::KimGrip, Model::Exact] {
            let setup = setup(set, model);
            let hit = |v: f32| {
                let stroke = Stroke::new(v, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
                play_ok(&s, &stroke, &setup, name).contact.is_some()
            };
            let (mut lo, mut hi) = (0.1f32, 20.0f32);
            assert!(!hit(lo) && hit(hi), "{name}");
            while hi.to_bits() - lo.to_bits() > 1 {
                let mid = mid(lo, hi);
                if hit(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            // The TP distance for the speeds either side brackets the run.
            let (d_lo, d_hi) = (
                stun_stop_distance(lo, set.mass),
                stun_stop_distance(hi, set.mass),
            );
            assert!(
                d_lo <= run * (1.0 + 1e-5) && d_hi >= run * (1.0 - 1e-5),
                "{name}: {d_lo} {run} {d_hi}"
            );
            let stroke = Stroke::new(hi, TipOffset::CENTRE, [1.0, 0.0]).unwrap();
            let shot = play_ok(&s, &stroke, &setup, name);
            let c = shot.contact.unwrap();
            let arrival = c.impact.speed() as f64;
            let g = GRAVITY as f64;
            let reach = (2.0 * 0.01 * g * ((d_hi - d_lo) + 8.0 * ulp(table.length()))).sqrt();
            worst = worst.max(arrival / reach);
            assert!(
                arrival <= reach,
                "{name} {model:?}: arrives at {arrival} m/s (bound {reach})"
            );
            let e = if model == Model::Ideal { 1.0 } else { 0.95 };
            let object = c.outcome.object_ball.velocity.length() as f64;
            assert!(
                object <= 0.5 * (1.0 + e) * reach * 1.01,
                "{name} {model:?}: {object}"
            );
        }
    }
    println!("table length: arrival speed at the slowest hit ≤ {worst:.3} of the bound");
    cuesight_figures::record!("reliability-shot-extremes-table-length", "{worst:.2}");
}

/// Continuity at the TP 4.1 distance, where the cue ball stops sliding and rolls: the
/// object ball's position bisected to adjacent f32 values across the switch, with stun,
/// follow, draw and side hits, cue speeds 0.5–3 m/s (the switch on the table), every
/// ball set (the rolling → rest switch: `travel_distance_of_a_table_length`). On both
/// sides the cue ball hits the ball (no gap between the phases), and its state at
/// contact moves by at most what one ulp of extra travel explains, `μ_c g Δt/ν` (Δt the
/// change of the contact time), plus 16ε(v₀ + R|ω₀|) for the two formulas meeting at
/// the switch.
#[test]
fn sliding_to_rolling_is_continuous_at_the_tp_4_1_distance() {
    let mut worst = 0.0f64;
    let mut switches = 0;
    for (name, set, table) in sets() {
        let r = set.radius;
        let setup = setup(set, Model::KimGrip);
        let (x0, y) = (snap(0.2), snap(0.5 * table.width()));
        for speed in [0.5f32, 1.5, 3.0] {
            for (side, height) in [(0.0f32, 0.0f32), (0.0, 0.3), (0.0, -0.45), (0.3, -0.2)] {
                let tip = TipOffset::from_radius_fraction(side, height, r).unwrap();
                let stroke = Stroke::new(speed, tip, [1.0, 0.0]).unwrap();
                let free = play_ok(&scene(&table, r, [x0, y], &[]), &stroke, &setup, name);
                let m = free.cue_before;
                let slide_end = m.rolling_start().x;
                let what = format!("{name} {speed} m/s tip ({side}, {height})");
                if m.sliding_time == 0.0 || (slide_end + 2.0 * r) > table.length() - r {
                    continue;
                }
                // The object ball's x where the contact switches from sliding to rolling.
                let contact = |x: f32| {
                    let s = scene(&table, r, [x0, y], &[[x, y]]);
                    play_ok(&s, &stroke, &setup, &what).contact
                };
                let sliding = |x: f32| match contact(x) {
                    Some(c) => c.time <= m.sliding_time,
                    None => panic!(
                        "{what}: no contact with the ball at x = {x} (gap between the phases)"
                    ),
                };
                let centre = slide_end + 2.0 * r;
                let (mut lo, mut hi) = (centre - 0.01, centre + 0.01);
                assert!(sliding(lo) && !sliding(hi), "{what}");
                while hi.to_bits() - lo.to_bits() > 1 {
                    let mid = mid(lo, hi);
                    if sliding(mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let (a, b) = (contact(lo).unwrap(), contact(hi).unwrap());
                let dt = (b.time as f64 - a.time as f64).abs();
                let w0 = m.initial_spin.length() as f64;
                let bound = 0.2 * GRAVITY as f64 * dt / 0.4
                    + 16.0 * EPS32 * (m.initial_velocity.length() as f64 + r as f64 * w0);
                let d = state_difference(
                    (a.impact.velocity(), a.impact.spin()),
                    (b.impact.velocity(), b.impact.spin()),
                    r,
                );
                worst = worst.max(d / bound);
                switches += 1;
                assert!(d <= bound, "{what}: state at contact jumps by {d} m/s (bound {bound}) between x = {lo} and {hi}");
            }
        }
    }
    assert_eq!(switches, 36, "every switch on the table");
    println!("sliding → rolling: {switches} switches, state jump ≤ {worst:.3} of the bound");
    cuesight_figures::record!("reliability-shot-extremes-rolling-switches", "{switches}");
    cuesight_figures::record!("reliability-shot-extremes-rolling-jump", "{worst:.2}");
}

/// `Motion::crossing` and `time_to_reach` across the phase switches (flight → sliding,
/// sliding → rolling) and at the rest position: a target line (or distance) bisected
/// to adjacent f32 values around each switch point, for stun, draw, follow and side
/// spins, a lifted ball, and slanted lines. Both sides of a switch are found (no gap),
/// at times that differ by at most what one ulp of distance explains at the speed
/// there (`2 ulp/v + 4ε t`, plus for a segment the rounding of its ends); just beyond
/// the rest position nothing is found.
#[test]
fn crossing_and_time_to_reach_have_no_gap_between_phases() {
    let r = BallSet::POOL.radius;
    let cloth = Cloth::TYPICAL;
    let mut checked = 0;
    for (vz, spin) in [
        (0.0f32, Vec3::ZERO),
        (0.0, Vec3::new(0.0, -60.0, 0.0)),
        (0.0, Vec3::new(0.0, 90.0, 0.0)),
        (0.0, Vec3::new(10.0, 20.0, 40.0)),
        (0.4, Vec3::new(0.0, -40.0, 0.0)),
    ] {
        let start = Vec3::new(0.3, 0.4, 0.0);
        let v = Vec3::new(1.7, 0.0, vz);
        let m = Motion::new(start, v, spin, r, &cloth).unwrap();
        motion_finite(&m).unwrap();
        let dir = Vec3::new(1.0, 0.0, 0.0);
        let mut points = vec![m.rolling_start()];
        if m.air_time > 0.0 {
            points.push(m.landing());
        }
        for p in points {
            let reach = |d: f32| m.time_to_reach(dir, d);
            let d0 = p.x - start.x;
            let (mut lo, mut hi) = (d0 * 0.99, d0 * 1.01);
            let key = |d: f32| reach(d).map(|t| t <= m.air_time + m.sliding_time);
            // Bisect on "reached, in an earlier phase" vs "reached later".
            assert_eq!(key(lo), Some(p == m.rolling_start() || key(lo).unwrap()));
            let k_lo = key(lo);
            while hi.to_bits() - lo.to_bits() > 1 {
                let mid = mid(lo, hi);
                let k = key(mid);
                assert!(k.is_some(), "{m:?}: distance {mid} not reached");
                if k == k_lo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let (ta, tb) = (reach(lo).unwrap(), reach(hi).unwrap());
            let speed = m.velocity_at(ta).length() as f64;
            let bound = 2.0 * ulp(hi) / speed + 4.0 * EPS32 * tb as f64;
            assert!((tb as f64 - ta as f64).abs() <= bound, "{ta} {tb} {bound}");
            // Same switch, as a crossing of a slanted segment through the point.
            for slant in [0.0f32, 0.3, -1.2] {
                let across = Vec3::new(slant, 1.0, 0.0);
                let at = |x: f32| {
                    let c = Vec3::new(x, p.y, 0.0);
                    m.crossing(c - across * 0.5, c + across * 0.5)
                };
                let (mut lo, mut hi) = (p.x - 0.01, p.x + 0.01);
                let switch = m.air_time
                    + if p == m.landing() {
                        0.0
                    } else {
                        m.sliding_time
                    };
                let before = |x: f32| {
                    at(x).unwrap_or_else(|| panic!("{m:?}: no crossing at x = {x}")) <= switch
                };
                assert!(before(lo) && !before(hi));
                while hi.to_bits() - lo.to_bits() > 1 {
                    let mid = mid(lo, hi);
                    if before(mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let (ta, tb) = (at(lo).unwrap(), at(hi).unwrap());
                // The segment's ends are rounded too: each by half an ulp of its largest
                // coordinate, which moves the line's intercept on the path by up to
                // (1 + |slant|) of that.
                let ends = ulp(hi.abs().max(p.y.abs()) + slant.abs());
                let bound = (2.0 * ulp(hi) + (1.0 + slant.abs() as f64) * ends) / speed
                    + 4.0 * EPS32 * tb as f64;
                assert!(
                    (tb as f64 - ta as f64).abs() <= bound,
                    "slant {slant}: {ta} {tb} {bound}"
                );
                checked += 1;
            }
        }
        // At rest: a line just beyond is never crossed; one 1 µm short is.
        let rest = m.rest();
        let line = |x: f32| m.crossing(Vec3::new(x, -5.0, 0.0), Vec3::new(x, 5.0, 0.0));
        assert!(line(rest.x + 4.0 * ulp(rest.x) as f32).is_none(), "{m:?}");
        assert!(line(rest.x - 1e-6).is_some(), "{m:?}");
        assert!(m
            .time_to_reach(dir, rest.x - start.x + 4.0 * ulp(rest.x) as f32)
            .is_none());
    }
    println!("phase switches: {checked} crossings bisected");
    cuesight_figures::record!("reliability-shot-extremes-phase-crossings", "{checked}");
}

/// Subnormal-scale inputs: aim directions with subnormal components (a unit aim in the
/// right direction, to 1e-6), a subnormal tip offset (no spin to speak of), a motion
/// with subnormal velocity and spin (it stays where it is), a subnormal lift. Every
/// output finite.
#[test]
fn subnormal_scale_inputs() {
    let tiny = f32::from_bits(1);
    for (x, y) in [
        (1e-40f32, 1e-40f32),
        (tiny, 0.0),
        (0.0, -tiny),
        (3e-41, -4e-41),
        (1e-38, 1e-45),
    ] {
        let stroke = Stroke::new(2.0, TipOffset::CENTRE, [x, y]).unwrap();
        let a = stroke.aim();
        let (ex, ey) = {
            let (x, y) = (x as f64, y as f64);
            let l = x.hypot(y);
            (x / l, y / l)
        };
        assert!(
            (a.x as f64 - ex).abs() <= 1e-6 && (a.y as f64 - ey).abs() <= 1e-6,
            "aim [{x:e}, {y:e}] -> {a:?}, expected ({ex}, {ey})"
        );
    }
    for (name, set, table) in sets() {
        let r = set.radius;
        let s = scene(&table, r, [snap(0.4), snap(0.6)], &[[snap(1.0), snap(0.6)]]);
        let tip = TipOffset::new(1e-40, -1e-40).unwrap();
        let stroke = Stroke::new(2.0, tip, [1.0, 1e-40]).unwrap();
        for model in MODELS {
            let shot = play_ok(&s, &stroke, &setup(set, model), name);
            assert!(shot.launch.spin.length() < 1e-30);
            assert!(shot.contact.is_some(), "{name}");
        }
        for (v, w) in [
            (
                Vec3::new(1e-40, -1e-40, 0.0),
                Vec3::new(1e-40, 1e-40, -1e-40),
            ),
            (Vec3::new(tiny, 0.0, tiny), Vec3::ZERO),
            (Vec3::ZERO, Vec3::new(0.0, 1e-40, 0.0)),
            (Vec3::new(1.0, 0.0, 1e-40), Vec3::new(0.0, 1e-40, 0.0)),
        ] {
            let m = Motion::new(s.balls()[0], v, w, r, &Cloth::TYPICAL).unwrap();
            motion_finite(&m).unwrap_or_else(|e| panic!("{name} {v:?} {w:?}: {e}"));
            if v.x.abs() < 1e-30 {
                assert!((m.rest() - m.start).length() < 1e-30, "{m:?}");
            }
        }
    }
}

/// Lifted balls (TP: `v_z > 0` after a collision): the flight lasts `2 v_z/g`, rises
/// `v_z²/(2g)` (f64, 1e-6 relative), keeps its horizontal velocity and spin, lands at
/// `start + v t_air`, and then slides; the path is continuous at the landing. Lifts from
/// 1e-6 m/s to 10 m/s, downward `v_z` ignored. And in played shots: a scan of hard
/// draw/follow shots with grippy ball–ball friction finds collisions that lift a ball;
/// their motions are finite and land.
#[test]
fn hopping_ball_lands() {
    let r = BallSet::POOL.radius;
    for vz in [-1.0f32, 0.0, 1e-6, 0.01, 0.5, 3.0, 10.0] {
        let v = Vec3::new(1.2, -0.4, vz);
        let w = Vec3::new(5.0, -30.0, 12.0);
        let m = Motion::new(Vec3::new(1.0, 0.5, 0.0), v, w, r, &Cloth::TYPICAL).unwrap();
        motion_finite(&m).unwrap();
        let g = GRAVITY as f64;
        let (air, height) = if vz > 0.0 {
            (2.0 * vz as f64 / g, (vz as f64).powi(2) / (2.0 * g))
        } else {
            (0.0, 0.0)
        };
        assert!(
            (m.air_time as f64 - air).abs() <= 1e-6 * air,
            "{vz}: {}",
            m.air_time
        );
        assert!(
            (m.hop_height as f64 - height).abs() <= 1e-6 * height,
            "{vz}"
        );
        assert_eq!(m.initial_velocity, Vec3::new(v.x, v.y, 0.0));
        let landing = m.landing();
        for k in [0.0f32, 0.3, 1.0] {
            let t = k * m.air_time;
            assert_eq!(m.spin_at(t), w, "spin in flight");
            assert_eq!(m.velocity_at(t), m.initial_velocity, "velocity in flight");
        }
        let expected = [1.0 + 1.2 * air, 0.5 - 0.4 * air];
        assert!(
            (landing.x as f64 - expected[0]).abs() <= 1e-6 * (1.0 + air)
                && (landing.y as f64 - expected[1]).abs() <= 1e-6 * (1.0 + air),
            "{vz}: lands at {landing:?}, expected {expected:?}"
        );
        let after = m.position_at(next_up(m.air_time));
        assert!((after - landing).length() < 1e-5, "{vz}");
    }
    // Played shots that lift a ball.
    let mut lifted = 0;
    for (name, set, table) in sets() {
        let r = set.radius;
        for mu in [0.1f32, 0.3, 1.0] {
            let mut setup = setup(set, Model::Exact);
            setup.params = setup.params.with_mu(mu).unwrap();
            for height in [-0.5f32, 0.5] {
                for cut in [0.0f64, 30.0, 70.0] {
                    let s = cut_scene(&table, r, 0.1, Target::Degrees(cut));
                    let tip = TipOffset::from_radius_fraction(0.0, height, r).unwrap();
                    let stroke = Stroke::new(8.0, tip, [1.0, 0.0]).unwrap();
                    for model in [Model::KimGrip, Model::Exact] {
                        setup.model = model;
                        let outside = cuesight::validity::kim_grip(&setup.params).is_err();
                        if model == Model::KimGrip && outside {
                            // Past KimGrip's validity domain: the shot is refused, typed.
                            let refused = play(&s, &stroke, &setup);
                            assert!(
                                matches!(refused, Err(cuesight::Error::OutsideValidity { .. })),
                                "{name} μ {mu}: {refused:?}"
                            );
                            continue;
                        }
                        let shot = play_ok(&s, &stroke, &setup, name);
                        let c = shot.contact.unwrap();
                        for m in [c.cue_after, c.object_after] {
                            if m.air_time > 0.0 {
                                lifted += 1;
                                assert!(m.air_time.is_finite() && m.stop_time() >= m.air_time);
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(lifted > 0, "no played shot lifted a ball");
    println!("hops: {lifted} lifted balls in played shots");
    cuesight_figures::record!("reliability-shot-extremes-hops", "{lifted}");
}

/// Balls touching cushions and pockets: the cue ball in a corner touching both
/// cushions (centre at `(R, R)`), object balls touching a cushion, at a pocket's target
/// centre, and on a pocket's jaw end; shots along a cushion, into a corner and across
/// the table, every ball set and model. Every output finite; a ball that starts on a
/// pocket's target segment and moves is reported in that pocket at time 0 or later.
/// `solve_aim` for a ball at a pocket centre either solves (the forward chain then
/// crosses the mouth within its tolerance) or names why not: never a panic or a
/// non-finite aim.
#[test]
fn balls_touching_cushions_and_pockets() {
    for (name, set, table) in sets() {
        let r = set.radius;
        let (l, w) = (table.length(), table.width());
        let corner = [r, r];
        let mut objects = vec![
            [0.5 * l, r],
            [l - r, w - r],
            [0.5 * l, w - r],
            [l - r, 0.5 * w],
        ];
        for p in table.pockets() {
            objects.push([p.centre().x, p.centre().y]);
            objects.push([p.a.x, p.a.y]);
        }
        for (k, object) in objects.iter().enumerate() {
            let s = match Scene::new(table.clone(), r, corner)
                .and_then(|mut s| s.add_ball(*object).map(|_| s))
            {
                Ok(s) => s,
                Err(e) => panic!("{name}: ball {object:?} on the table refused: {e}"),
            };
            let o = s.balls()[1];
            let straight = [o.x - r, o.y - r];
            for aim in [[1.0f32, 0.0], [0.0, 1.0], [1.0, 1.0], straight] {
                for tip in [
                    TipOffset::CENTRE,
                    TipOffset::from_radius_fraction(0.4, -0.3, r).unwrap(),
                ] {
                    let stroke = Stroke::new(6.0, tip, aim).unwrap();
                    for model in MODELS {
                        let what = format!("{name} object {k} {object:?} aim {aim:?} {model:?}");
                        let shot = play_ok(&s, &stroke, &setup(set, model), &what);
                        if let Some(c) = shot.contact {
                            if let Some((i, t)) = c.pocket {
                                assert!(i < table.pockets().len() && t >= 0.0, "{what}");
                            }
                        }
                    }
                }
            }
            for pocket in 0..table.pockets().len() {
                let what = format!("{name} object {k} {object:?} pocket {pocket}");
                match solve_aim(
                    &s,
                    1,
                    pocket,
                    4.0,
                    TipOffset::CENTRE,
                    &setup(set, Model::KimGrip),
                ) {
                    Ok(solution) => {
                        assert!(
                            solution.aim.is_finite()
                                && solution.residual.abs() <= cuesight::aim::TOLERANCE,
                            "{what}: {solution:?}"
                        );
                    }
                    Err(AimError::Invalid(e)) => {
                        panic!("{what}: valid scene reported invalid: {e}")
                    }
                    Err(_) => {}
                }
            }
        }
    }
}

/// Deterministic generator (64-bit LCG), `[0, 1)`.
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

/// `|y' − (W − y)|` allowed for an absolute position (m): the core adds up to four
/// displacements to a start position (landing, rolling start, rest or a point on the
/// path), each sum rounded to half an ulp of its magnitude, in both the shot and its
/// mirror image: 8 half-ulps of the largest magnitude on the way, `m`.
fn position_bound(m: f32) -> f64 {
    4.0 * ulp(m)
}

/// Compare a motion with the mirror image of another: every velocity, acceleration,
/// spin and time bit for bit; positions (which are absolute, `y → W − y` rounds) within
/// [`position_bound`].
fn mirror_motion(a: &Motion, b: &Motion, w: f32, what: &str) -> f64 {
    assert_eq!(
        mv(a.initial_velocity),
        b.initial_velocity,
        "{what}: initial_velocity"
    );
    assert_eq!(
        mv(a.sliding_acceleration),
        b.sliding_acceleration,
        "{what}: sliding_acceleration"
    );
    assert_eq!(
        mv(a.rolling_velocity),
        b.rolling_velocity,
        "{what}: rolling_velocity"
    );
    assert_eq!(mw(a.initial_spin), b.initial_spin, "{what}: initial_spin");
    assert_eq!(a.air_time, b.air_time, "{what}: air_time");
    assert_eq!(a.hop_height, b.hop_height, "{what}: hop_height");
    assert_eq!(a.sliding_time, b.sliding_time, "{what}: sliding_time");
    assert_eq!(a.rolling_time, b.rolling_time, "{what}: rolling_time");
    let t = 0.5 * (a.air_time + a.sliding_time + a.stop_time());
    assert_eq!(
        mv(a.velocity_at(t)),
        b.velocity_at(t),
        "{what}: velocity_at"
    );
    assert_eq!(mw(a.spin_at(t)), b.spin_at(t), "{what}: spin_at");
    let mut worst = 0.0f64;
    for (p, q) in [
        (a.start, b.start),
        (a.landing(), b.landing()),
        (a.rolling_start(), b.rolling_start()),
        (a.rest(), b.rest()),
        (a.position_at(t), b.position_at(t)),
    ] {
        let magnitude = [a.start, a.landing(), a.rolling_start(), a.rest(), p]
            .iter()
            .fold(w, |m, v| m.max(v.x.abs()).max(v.y.abs()));
        let bound = position_bound(magnitude);
        let dx = (p.x as f64 - q.x as f64).abs();
        let dy = (w as f64 - p.y as f64 - q.y as f64).abs();
        worst = worst.max(dx.max(dy) / bound);
        assert!(
            dx <= bound && dy <= bound,
            "{what}: position {p:?} mirrors to {q:?} (bound {bound:e})"
        );
    }
    worst
}

/// Mirror symmetry across the table's long axis: the scene reflected `y → W − y` (on
/// the 2⁻²³ grid, where that is exact) and the stroke reflected (aim `(x, −y)`, tip side
/// `−side`) give the reflected shot. Exactly, bit for bit: the launch, the contact's
/// ball, time, line of centres, cut (negated), impact and outcome (every component,
/// impulses and angles), every velocity, acceleration, spin and time of the three
/// motions, the pocket (its mirror image) and the time it is reached. Positions are
/// absolute (`W − y` rounds), so they mirror to within [`position_bound`]. 600 random
/// scenes of 1–4 object balls per ball set, strokes aimed at a ball with random offsets,
/// speeds and tips, every model.
#[test]
fn mirror_image_of_scene_and_stroke() {
    let mut rng = Lcg(0x6d69_7272_6f72);
    let mut shots = 0;
    let mut contacts = 0;
    let mut pocketed = 0;
    let mut worst = 0.0f64;
    for (name, set, table) in sets() {
        let r = set.radius;
        let (l, w) = (table.length(), table.width());
        let mut scenes = 0;
        while scenes < 600 {
            let place = |rng: &mut Lcg| {
                [
                    snap(r + (l - 2.0 * r) * rng.unit()),
                    snap(r + (w - 2.0 * r) * rng.unit()),
                ]
            };
            let Ok(mut s) = Scene::new(table.clone(), r, place(&mut rng)) else {
                continue;
            };
            let n = 1 + (rng.unit() * 4.0) as usize;
            for _ in 0..n {
                let _ = s.add_ball(place(&mut rng));
            }
            if s.balls().len() < 2 {
                continue;
            }
            scenes += 1;
            let image = mirror_scene(&s);
            let target = s.balls()[1 + (rng.unit() * (s.balls().len() - 1) as f32) as usize];
            let to = target - s.balls()[0];
            let turn = (rng.unit() - 0.5) * 4.0 * r / to.length();
            let aim = [to.x - turn * to.y, to.y + turn * to.x];
            let tip =
                TipOffset::from_radius_fraction(0.6 * rng.unit() - 0.3, 0.8 * rng.unit() - 0.4, r)
                    .unwrap();
            let speed = 0.2 + 8.0 * rng.unit();
            let (stroke, reflected) = stroke_pair(speed, tip, aim);
            for model in MODELS {
                let setup = setup(set, model);
                let what = format!("{name} {:?} {stroke:?} {model:?}", s.balls());
                let a = play_ok(&s, &stroke, &setup, &what);
                let b = play_ok(&image, &reflected, &setup, &what);
                shots += 1;
                assert_eq!(a.launch.speed, b.launch.speed, "{what}");
                assert_eq!(mw(a.launch.spin), b.launch.spin, "{what}: launch spin");
                worst = worst.max(mirror_motion(
                    &a.cue_before,
                    &b.cue_before,
                    w,
                    &format!("{what} cue_before"),
                ));
                let (ca, cb) = match (a.contact, b.contact) {
                    (None, None) => continue,
                    (Some(ca), Some(cb)) => (ca, cb),
                    (x, y) => panic!("{what}: contact {x:?} vs mirror {y:?}"),
                };
                contacts += 1;
                assert_eq!(ca.object_ball, cb.object_ball, "{what}");
                assert_eq!(ca.time, cb.time, "{what}: contact time");
                assert_eq!(
                    mv(ca.line_of_centres),
                    cb.line_of_centres,
                    "{what}: line of centres"
                );
                assert_eq!(ca.cut_angle, -cb.cut_angle, "{what}: cut");
                let (ia, ib) = (ca.impact, cb.impact);
                assert_eq!(mv(ia.velocity()), ib.velocity(), "{what}: impact velocity");
                assert_eq!(mw(ia.spin()), ib.spin(), "{what}: impact spin");
                let (oa, ob) = (ca.outcome, cb.outcome);
                assert_eq!(mv(oa.cue_ball.velocity), ob.cue_ball.velocity, "{what}");
                assert_eq!(
                    mv(oa.object_ball.velocity),
                    ob.object_ball.velocity,
                    "{what}"
                );
                assert_eq!(mw(oa.cue_ball.spin), ob.cue_ball.spin, "{what}");
                assert_eq!(mw(oa.object_ball.spin), ob.object_ball.spin, "{what}");
                assert_eq!(oa.regime, ob.regime, "{what}");
                assert_eq!(oa.impulses.normal, ob.impulses.normal, "{what}");
                assert_eq!(mv(oa.impulses.friction), ob.impulses.friction, "{what}");
                assert_eq!(
                    oa.impulses.table_friction, ob.impulses.table_friction,
                    "{what}"
                );
                assert_eq!(oa.throw_angle(), -ob.throw_angle(), "{what}");
                assert_eq!(oa.cue_deflection(), ob.cue_deflection(), "{what}");
                let p = ca.cue_position;
                let q = cb.cue_position;
                let bound = position_bound(w.max(p.x.abs()));
                assert!(
                    (p.x as f64 - q.x as f64).abs() <= bound
                        && (w as f64 - p.y as f64 - q.y as f64).abs() <= bound,
                    "{what}: cue position {p:?} vs {q:?}"
                );
                worst = worst.max(mirror_motion(
                    &ca.cue_after,
                    &cb.cue_after,
                    w,
                    &format!("{what} cue_after"),
                ));
                worst = worst.max(mirror_motion(
                    &ca.object_after,
                    &cb.object_after,
                    w,
                    &format!("{what} object_after"),
                ));
                match (ca.pocket, cb.pocket) {
                    (None, None) => {}
                    (Some((i, ti)), Some((j, tj))) => {
                        pocketed += 1;
                        assert_eq!(
                            mirror_pocket(&table, i, 0.0),
                            Some(j),
                            "{what}: pocket {i} vs {j}"
                        );
                        assert_eq!(ti, tj, "{what}: pocket time");
                    }
                    (x, y) => panic!("{what}: pocket {x:?} vs mirror {y:?}"),
                }
            }
        }
    }
    println!("mirror: {shots} shots, {contacts} contacts, {pocketed} pocketed; positions within {worst:.3} of the bound");
    cuesight_figures::record!(
        "reliability-shot-extremes-mirror-shots",
        "{}",
        thousands(shots)
    );
    cuesight_figures::record!(
        "reliability-shot-extremes-mirror-contacts",
        "{}",
        thousands(contacts)
    );
    cuesight_figures::record!("reliability-shot-extremes-mirror-pocketed", "{pocketed}");
    cuesight_figures::record!("reliability-shot-extremes-mirror-positions", "{worst:.1}");
}

/// `solve_aim` at the extremes, every pocketed ball set: straight in to every pocket
/// (cut 0), cuts of 60°, 80° and 88°, the cue ball touching the object ball, cue speeds
/// of 1 mm/s, 0.5 m/s and 20 m/s, centre and side/draw tips. Each answer is a solution
/// whose aim, played forward, crosses the mouth line within the tolerance of the pocket
/// centre, or a reason (`ObjectBallNotHit`, `PocketUnreachable`, `NotConverged`) — never
/// an invalid-input error or a panic — and the scene mirrored across the long axis gives
/// the mirrored answer exactly (aim, correction, cut, residual, evaluations, or the same
/// reason).
#[test]
fn solve_aim_at_the_extremes_and_mirrored() {
    let mut answers = [0usize; 4];
    for (name, set, table) in sets() {
        if table.pockets().is_empty() {
            let s = scene(&table, set.radius, [0.5, 0.6], &[[1.5, 0.6]]);
            let e = solve_aim(
                &s,
                1,
                0,
                2.0,
                TipOffset::CENTRE,
                &setup(set, Model::KimGrip),
            );
            assert_eq!(
                e.unwrap_err(),
                AimError::Invalid(cuesight::Error::OutOfRange {
                    field: cuesight::Field::Pocket,
                    value: 0.0
                })
            );
            continue;
        }
        let r = set.radius;
        let w = table.width();
        let setup = setup(set, Model::KimGrip);
        for (k, pocket) in table.pockets().iter().enumerate() {
            let image_pocket = mirror_pocket(&table, k, 0.0).unwrap();
            let centre = pocket.centre();
            let middle = Vec3::new(0.5 * table.length(), 0.5 * w, 0.0);
            let to = centre - middle;
            let d = to * (1.0 / to.length());
            let object = middle + d * (0.5 * to.length());
            for cut in [0.0f32, 60.0, 80.0, 88.0] {
                for (gap, speed) in [(0.4f32, 0.001f32), (0.4, 0.5), (0.4, 20.0), (0.0, 3.0)] {
                    // Cue ball behind the ghost ball, turned by the cut about it.
                    let ghost = object - d * (2.0 * r);
                    let c = cut.to_radians();
                    let back = Vec3::new(
                        -(d.x * c.cos() - d.y * c.sin()),
                        -(d.x * c.sin() + d.y * c.cos()),
                        0.0,
                    );
                    let cue = ghost + back * gap;
                    let snapped = |p: Vec3| [snap(p.x), snap(p.y)];
                    let (cue, obj) = (snapped(cue), snapped(object));
                    let Ok(mut a) = Scene::new(table.clone(), r, cue) else {
                        continue;
                    };
                    if a.add_ball(obj).is_err() {
                        continue;
                    }
                    let b = mirror_scene(&a);
                    for (side, height) in [(0.0f32, 0.0f32), (0.3, -0.3)] {
                        let what = format!("{name} pocket {k} cut {cut} gap {gap} speed {speed} tip ({side}, {height})");
                        let tip = TipOffset::from_radius_fraction(side, height, r).unwrap();
                        let image_tip = TipOffset::new(-tip.side(), tip.height()).unwrap();
                        let x = solve_aim(&a, 1, k, speed, tip, &setup);
                        let y = solve_aim(&b, 1, image_pocket, speed, image_tip, &setup);
                        match (x, y) {
                            (Ok(x), Ok(y)) => {
                                answers[0] += 1;
                                assert_eq!(x.aim, mv(y.aim), "{what}");
                                assert_eq!(x.correction_deg, -y.correction_deg, "{what}");
                                assert_eq!(x.cut_angle_deg, -y.cut_angle_deg, "{what}");
                                assert_eq!(
                                    (x.residual, x.evaluations),
                                    (y.residual, y.evaluations),
                                    "{what}"
                                );
                                assert!(x.residual.abs() <= cuesight::aim::TOLERANCE, "{what}");
                                let stroke = Stroke::new(speed, tip, [x.aim.x, x.aim.y]).unwrap();
                                let shot = play_ok(&a, &stroke, &setup, &what);
                                let contact = shot.contact.unwrap();
                                assert_eq!(contact.object_ball, 1, "{what}");
                                let along =
                                    (pocket.b - pocket.a) * (1.0 / (pocket.b - pocket.a).length());
                                let t =
                                    contact.object_after.crossing_line(pocket.a, along).unwrap();
                                let miss = along.dot(contact.object_after.position_at(t) - centre);
                                assert!(
                                    miss.abs() as f64
                                        <= cuesight::aim::TOLERANCE as f64
                                            + 8.0 * ulp(table.length()),
                                    "{what}: {miss}"
                                );
                            }
                            (Err(e), Err(f)) => {
                                assert_eq!(e, f, "{what}");
                                assert!(!matches!(e, AimError::Invalid(_)), "{what}: {e}");
                                answers[match e {
                                    AimError::ObjectBallNotHit => 1,
                                    AimError::PocketUnreachable => 2,
                                    _ => 3,
                                }] += 1;
                            }
                            (x, y) => panic!("{what}: {x:?} vs mirror {y:?}"),
                        }
                    }
                }
            }
        }
    }
    println!(
        "solve_aim extremes: {} solved, {} object ball not hit, {} pocket unreachable, {} not converged",
        answers[0], answers[1], answers[2], answers[3]
    );
    assert!(answers[0] > 50, "{answers:?}");
    cuesight_figures::record!("reliability-shot-extremes-aim-solved", "{}", answers[0]);
    cuesight_figures::record!("reliability-shot-extremes-aim-not-hit", "{}", answers[1]);
    cuesight_figures::record!(
        "reliability-shot-extremes-aim-unreachable",
        "{}",
        answers[2]
    );
    cuesight_figures::record!(
        "reliability-shot-extremes-aim-not-converged",
        "{}",
        answers[3]
    );
}
