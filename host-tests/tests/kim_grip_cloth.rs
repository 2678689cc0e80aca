//! `KimGrip` on every cloth of its validity domain (issue 16 item 3: within 0.25 % of U
//! in velocity, 0.5 % in `R ω` and 0.1° of throw wherever μ·μ_s ≤ 0.2), against the
//! f64 reference on seeded scenes drawn where its approximations are weakest: 40,000
//! with cloth friction μ_s uniform over 0–1 and μ up to `min(0.15, 0.2/μ_s)`, 20,000
//! with μ 0.15–`min(1, 0.2/μ_s)`; spins up to three times rolling on every axis
//! (topspin presses the object ball into the cloth, which makes the slip's compliance
//! anisotropic), speeds 0.1–10 m/s, cuts to ±89°, e* 0–1, the three ball sizes.
//!
//! The domain map's 10⁵ scenes (`tests/domain.rs`) hold the same bound over the whole
//! domain; this set is denser where it failed: before the curved slide (`kim_grip::curved`,
//! μ_s > 0.4) 67 of 400,000 such scenes were outside it, worst 0.48 % / 0.72 %
//! (`scene_659401_of_the_million` is one the 10⁶-scene map found).

use cuesight::{collide, FrictionLaw, Model};
use cuesight_host::compare::scene_error;
use cuesight_host::domain::{scene, DomainScene, SpinDraw, MIN_OBJECT_SPEED};
use cuesight_host::grid::{Scene, SpinKind};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const SEED: u64 = 99;
const SCENES: u64 = 40_000;
const VELOCITY: f64 = 0.0025;
const SPIN: f64 = 0.005;
const THROW_DEG: f64 = 0.1;

/// The cloth set's μ: from `low`, up to `min(cap, 0.2/μ_s)` (μ_s drawn where that
/// range is not empty); with `speed_dependent`, the `μ(0) = a + b` of a law `a +
/// b e^{−cv}` with `a` 5–100 % of it and `c` log-uniform over 0.01–100 s/m (as the
/// domain map draws them).
/// With `cue_table`, draw (`ω_y < 0`, the cue ball pressed into the cloth) and
/// cue-ball/table friction μ_ct up to `min(1, 0.05/μ)`.
#[derive(Clone, Copy)]
struct MuRange {
    low: f64,
    cap: f64,
    speed_dependent: bool,
    cue_table: bool,
}

/// The cloth set proper: every cloth, μ up to 0.15 (the single direction's range, the
/// fast path's with μ_s ≤ 0.4).
const CLOTHS: MuRange = MuRange {
    low: 0.001,
    cap: 0.15,
    speed_dependent: false,
    cue_table: false,
};

/// Large μ, 0.15–1 (the curved slide's range of μ, `kim_grip::curved`).
const LARGE_MU: MuRange = MuRange {
    low: 0.15,
    cap: cuesight::validity::KIM_GRIP_MAX_MU as f64,
    speed_dependent: false,
    cue_table: false,
};

/// Speed-dependent laws, μ(0) 0.001–1 (the general path's slide in pieces, each piece
/// at its own rate of slip, `kim_grip::budget`).
const SPEED_LAWS: MuRange = MuRange {
    low: 0.001,
    cap: cuesight::validity::KIM_GRIP_MAX_MU as f64,
    speed_dependent: true,
    cue_table: false,
};

/// Draw with cue-ball/table friction, μ 0.001–1, μ·μ_ct ≤ 0.05 (the pieces' sum of the
/// cue ball's table-contact slip, `kim_grip::curved`).
const CUE_TABLE: MuRange = MuRange {
    low: 0.001,
    cap: cuesight::validity::KIM_GRIP_MAX_MU as f64,
    speed_dependent: false,
    cue_table: true,
};

/// Scene `index` of the cloth set with μ in `range`.
fn cloth_scene(index: u64, range: MuRange) -> DomainScene {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    rng.set_stream(index);
    let speed = rng.random_range(0.1f64.ln()..=10f64.ln()).exp();
    let cut_deg: f64 = rng.random_range(-89.0..=89.0);
    let cut = cut_deg.to_radians();
    let (radius, mass) =
        [(0.028575, 0.17), (0.02625, 0.142), (0.03075, 0.21)][rng.random_range(0..3usize)];
    let mut spin = [0.0f64; 3];
    for w in &mut spin {
        *w = rng.random_range(-3.0..=3.0) * speed / radius;
    }
    let mu_mu_s = f64::from(cuesight::validity::KIM_GRIP_MAX_MU_MU_S);
    let mu_s: f64 = rng.random_range(0.0..=(mu_mu_s / range.low).min(1.0));
    let mu_max = (mu_mu_s / mu_s).min(range.cap);
    let mu: f64 = rng.random_range(range.low..=mu_max);
    let restitution: f64 = rng.random_range(0.0..=1.0);
    let friction = if range.speed_dependent {
        let a = mu * rng.random_range(0.05..=1.0);
        let c = rng.random_range(0.01f64.ln()..=100f64.ln()).exp();
        FrictionLaw::speed_dependent(a as f32, (mu - a).max(0.0) as f32, c as f32)
            .expect("drawn inside the accepted range")
    } else {
        FrictionLaw::Constant(mu as f32)
    };
    // (e* ≥ 0.01 where μ_ct acts: `validity::KIM_GRIP_MIN_RESTITUTION`.)
    let restitution = if range.cue_table {
        restitution.max(f64::from(cuesight::validity::KIM_GRIP_MIN_RESTITUTION))
    } else {
        restitution
    };
    let mu_ct = if range.cue_table {
        spin[1] = -spin[1].abs();
        let limit = f64::from(cuesight::validity::KIM_GRIP_MAX_MU_MU_CT);
        rng.random_range(0.0..=(limit / mu).min(1.0))
    } else {
        0.0
    };
    DomainScene {
        scene: Scene {
            kind: SpinKind::Side,
            velocity: [(speed * cut.cos()) as f32, (speed * cut.sin()) as f32],
            spin: spin.map(|w| w as f32),
            mu: mu as f32,
            restitution: restitution as f32,
            mu_s: mu_s as f32,
            radius: radius as f32,
            mass: mass as f32,
        },
        spin_draw: SpinDraw::Uniform400,
        cut_deg,
        friction,
        mu_ct: mu_ct as f32,
    }
}

/// `KimGrip`'s errors against the reference: `(|Δv|/U, R|Δω|/U, throw°)`, the throw
/// counted where the object ball leaves with at least 5 % of U (as the domain map).
fn errors(d: &DomainScene) -> (f64, f64, f64) {
    let out = collide(&d.params(), &d.impact(), Model::KimGrip)
        .unwrap_or_else(|e| panic!("KimGrip refused {d:?}: {e:?}"));
    let reference = d.reference();
    let e = scene_error(&d.scene, &out, &reference);
    let moving = reference.object_ball.velocity.length() / d.scene.speed() >= MIN_OBJECT_SPEED;
    (e.velocity, e.spin, if moving { e.throw_deg } else { 0.0 })
}

/// The worst `(velocity, spin, throw)` per tenth of μ_s over `scenes` scenes with μ in
/// `range`, asserting the bound on each.
fn worst_per_mu_s_band(range: MuRange, scenes: u64) -> Vec<[f64; 3]> {
    std::thread::scope(|s| {
        let halves: Vec<_> = (0..2u64)
            .map(|half| {
                s.spawn(move || {
                    let mut worst = vec![[0.0f64; 3]; 10];
                    for index in (half..scenes).step_by(2) {
                        let d = cloth_scene(index, range);
                        let (velocity, spin, throw) = errors(&d);
                        assert!(
                            velocity <= VELOCITY && spin <= SPIN && throw <= THROW_DEG,
                            "scene {index}: |dv|/U {velocity:e}, R|dw|/U {spin:e}, \
                             throw {throw} deg: {d:?}"
                        );
                        let band = ((d.scene.mu_s * 10.0) as usize).min(9);
                        for (w, e) in worst[band].iter_mut().zip([velocity, spin, throw]) {
                            *w = w.max(e);
                        }
                    }
                    worst
                })
            })
            .collect();
        let parts: Vec<Vec<[f64; 3]>> = halves.into_iter().map(|h| h.join().unwrap()).collect();
        (0..10)
            .map(|b| std::array::from_fn(|k| parts[0][b][k].max(parts[1][b][k])))
            .collect()
    })
}

/// Records `worst` (`(velocity, spin, throw)`) as `physics-kimgrip-{key}-*`.
fn record(key: &str, worst: [f64; 3]) {
    for (name, value) in [
        ("velocity", 100.0 * worst[0]),
        ("spin", 100.0 * worst[1]),
        ("throw", worst[2]),
    ] {
        cuesight_figures::record!(&format!("physics-kimgrip-{key}-{name}"), "{:.3}", value);
    }
}

#[test]
fn kim_grip_within_its_bound_on_every_cloth() {
    let bands = worst_per_mu_s_band(CLOTHS, SCENES);
    let worst_of = |range: std::ops::Range<usize>| -> [f64; 3] {
        std::array::from_fn(|k| {
            bands[range.clone()]
                .iter()
                .map(|w| w[k])
                .fold(0.0, f64::max)
        })
    };
    for (key, worst) in [("fast", worst_of(0..4)), ("curved", worst_of(4..10))] {
        println!(
            "mu_s {}: |dv|/U {:.3} %, R|dw|/U {:.3} %, throw {:.3} deg",
            if key == "fast" { "0-0.4" } else { "0.4-1" },
            100.0 * worst[0],
            100.0 * worst[1],
            worst[2]
        );
        record(&format!("cloth-{key}"), worst);
    }
}

/// μ 0.15–1 with μ·μ_s ≤ 0.2, where the single mid-point direction erred by up to 0.65 %
/// of U and 1.6 % in `R ω` (μ·μ_s ≤ 0.08) and the domain ended until the slide was
/// followed in pieces with the object ball's table friction along its own direction.
#[test]
fn kim_grip_within_its_bound_at_large_mu() {
    let bands = worst_per_mu_s_band(LARGE_MU, SCENES / 2);
    let worst: [f64; 3] = std::array::from_fn(|k| bands.iter().map(|w| w[k]).fold(0.0, f64::max));
    println!(
        "mu 0.15-1: |dv|/U {:.3} %, R|dw|/U {:.3} %, throw {:.3} deg",
        100.0 * worst[0],
        100.0 * worst[1],
        worst[2]
    );
    record("large-mu", worst);
}

/// Scene 659,401 of the domain map's 10⁶-scene set (seed 16; U 4.71 m/s, φ −23°, ω
/// (18.8, 40.5, 135) rad/s, μ 0.0873, μ_s 0.768, e* 0.749, snooker ball): `KimGrip` was
/// 0.337 % of U off in velocity and 0.543 % in `R ω`, breaking its declared bound inside
/// its validity domain.
#[test]
fn scene_659401_of_the_million() {
    let d = scene(16, 659_401);
    assert!((d.scene.mu_s - 0.7677).abs() < 1e-3 && (d.scene.mu - 0.0873).abs() < 1e-3);
    let (velocity, spin, throw) = errors(&d);
    assert!(
        velocity <= VELOCITY && spin <= SPIN && throw <= THROW_DEG,
        "|dv|/U {velocity:e}, R|dw|/U {spin:e}, throw {throw} deg"
    );
}

/// Speed-dependent laws with μ(0) up to 1 and μ(0)·μ_s up to 0.2: with one rate of slip
/// for the whole slide (`k̄ = |v₀|/s*`) the general path was up to 0.18 % / 0.44 % /
/// 0.114° off where μ(0)·μ_s ≤ 0.08 and 0.43 % / 1.06 % / 0.26° up to 0.2, and the domain
/// ended at μ(0) 0.15 and μ(0)·μ_s 0.08; each piece at its own rate holds the bound.
#[test]
fn kim_grip_within_its_bound_under_speed_dependent_laws() {
    let bands = worst_per_mu_s_band(SPEED_LAWS, SCENES / 2);
    let worst: [f64; 3] = std::array::from_fn(|k| bands.iter().map(|w| w[k]).fold(0.0, f64::max));
    println!(
        "speed-dependent laws: |dv|/U {:.3} %, R|dw|/U {:.3} %, throw {:.3} deg",
        100.0 * worst[0],
        100.0 * worst[1],
        worst[2]
    );
    record("speed-laws", worst);
}

/// Draw with cue-ball/table friction up to μ·μ_ct = 0.05: with that friction at the
/// cue ball's initial table-contact slip direction (which turns by up to 27° in the
/// impact) the general path was up to 0.71 % / 2.06 % off there, and the domain ended
/// at μ·μ_ct = 0.01; along the pieces' sum of that slip it holds the bound.
#[test]
fn kim_grip_within_its_bound_with_cue_table_friction() {
    let bands = worst_per_mu_s_band(CUE_TABLE, SCENES / 2);
    let worst: [f64; 3] = std::array::from_fn(|k| bands.iter().map(|w| w[k]).fold(0.0, f64::max));
    println!(
        "cue-ball/table friction: |dv|/U {:.3} %, R|dw|/U {:.3} %, throw {:.3} deg",
        100.0 * worst[0],
        100.0 * worst[1],
        worst[2]
    );
    record("cue-table", worst);
}

/// Scene 241,844 of seed 17's domain set (a speed-dependent law, μ(0) 0.149, c 2.36 s/m,
/// on a cloth of μ_s 0.84: μ(0)·μ_s 0.126): `KimGrip` was 0.32 % of U off in velocity
/// and 0.80 % in `R ω` with one rate of slip for the whole slide, and the domain refused
/// it since; with each piece at its own rate it is inside the bound.
#[test]
fn scene_241844_of_seed_17() {
    let d = scene(17, 241_844);
    assert!(matches!(d.friction, FrictionLaw::SpeedDependent { .. }));
    let (velocity, spin, throw) = errors(&d);
    assert!(
        velocity <= VELOCITY && spin <= SPIN && throw <= THROW_DEG,
        "|dv|/U {velocity:e}, R|dw|/U {spin:e}, throw {throw} deg"
    );
}
