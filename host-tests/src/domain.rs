//! The domain map (issue 16, item 1): every model against the f64 reference solver over
//! the whole input domain the core's constructors accept, not only the foundation grid
//! of [`crate::grid`].
//!
//! # The sampler ([`sample`])
//!
//! Seeded (`ChaCha8Rng`), one stream per scene index (`seed`, `index`), so any scene can
//! be regenerated alone and the set does not depend on the thread count. Inputs are drawn
//! in f64 and rounded to f32 once; core and reference see the same rounded values.
//!
//! | input | distribution | core's accepted range |
//! |---|---|---|
//! | speed U | 10 % log-uniform 0.01–0.1 m/s, 75 % log-uniform 0.1–10 m/s, 15 % log-uniform 10–100 m/s | (0, 100] m/s |
//! | cut φ | random sign; 85 % uniform 0–89.5°, 15 % uniform 89.5–89.99° | \|φ\| < 90° (v_x > 0 in f32) |
//! | spin ω (rad/s) | 5 % none; 45 % cue-like: follow/draw −2…+2 × natural roll, side ±1.5 U/R, ω_x ±0.5 U/R; 40 % each component uniform ±400 rad/s; 10 % each component log-uniform 1–10,000 rad/s in magnitude, random sign | each component ±10,000 rad/s |
//! | friction law | 85 % constant μ: 3 % exactly 0, else uniform (0, 1]; 15 % μ(v) = a + b·e^(−cv): μ(0) = a + b uniform 0.01–1, a = μ(0)·uniform 0.05–1, c log-uniform 0.01–100 s/m | μ ∈ [0, 1]; a ∈ [1e-6, 1], b ∈ [0, 1], a + b ≤ 1, c ∈ [0, 100] |
//! | μ_s | uniform [0, 1] | [0, 1] |
//! | e* | uniform [0, 1] | [0, 1] |
//! | μ_ct | 70 % 0, 30 % uniform [0, 1] | [0, 1] |
//! | R, M | pool 28.575 mm / 0.17 kg, snooker 26.25 mm / 0.142 kg or carom 30.75 mm / 0.21 kg, equally likely | R ∈ [1 mm, 1 m], M ∈ [1 g, 100 kg] (not covered) |
//!
//! μ in the bins and tables is [`cuesight::Params::mu`]: the constant, or μ(0) = a + b
//! for a speed-dependent law (its stick limit and its largest value).
//!
//! # The measures
//!
//! Per scene and model, [`crate::compare::scene_error`]: `|Δv|/U` and `R|Δω|/U` (worst of
//! the two balls, full 3-vectors) and the throw error in degrees. A scene is *within x of
//! U* when `max(|Δv|, R|Δω|)/U ≤ x`; the map counts x = 0.05 %, 0.5 % and 5 %. A model
//! that returns an error (e.g. `SeedExact`'s `NumericalFailure`) counts as outside every
//! threshold, and is counted apart.

use crate::compare::{scene_error, widen};
use crate::grid::{Scene, SpinKind};
use crate::reference::{solve, ReferenceConfig, ReferenceOutcome, ReferenceParams};
use cuesight::{collide, FrictionLaw, Impact, Model, Params};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;

/// The models mapped, in the order of every table: the five tiers and `Auto` at 1e-3.
pub const MODELS: [(&str, Model); 6] = [
    ("Ideal", Model::Ideal),
    ("Kim", Model::Kim),
    ("KimGrip", Model::KimGrip),
    ("SeedExact", Model::SeedExact),
    ("Exact", Model::Exact),
    ("Auto(1e-3)", Model::Auto { tolerance: 1e-3 }),
];

/// Index of `Auto` in [`MODELS`], and its tolerance.
pub const AUTO: usize = 5;
/// `Auto`'s tolerance in [`MODELS`].
pub const AUTO_TOLERANCE: f64 = 1e-3;

/// The thresholds of the map, in units of U: 0.05 %, 0.5 %, 5 %.
pub const THRESHOLDS: [f64; 3] = [5e-4, 5e-3, 5e-2];

/// How the spin of a scene was drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpinDraw {
    /// No spin.
    None,
    /// Follow/draw and side in the range of a cue stroke, scaled to U.
    CueLike,
    /// Each component uniform in ±400 rad/s.
    Uniform400,
    /// Each component log-uniform in magnitude 1–10,000 rad/s (the core's limit).
    Extreme,
}

/// One sampled scene of the accepted domain.
#[derive(Clone, Copy, Debug)]
pub struct DomainScene {
    /// Velocity, spin, constant μ (or μ(0)), e*, μ_s, R, M as f32 (the `kind` field is
    /// not used by the domain map: [`SpinKind::Side`]).
    pub scene: Scene,
    /// How the spin was drawn.
    pub spin_draw: SpinDraw,
    /// Cut angle φ in degrees (signed), as drawn (the velocity is its f32 rounding).
    pub cut_deg: f64,
    /// The ball–ball friction law.
    pub friction: FrictionLaw,
    /// Cue-ball/table friction μ_ct.
    pub mu_ct: f32,
}

impl DomainScene {
    /// Core parameters (validated: the sampler only draws accepted values).
    pub fn params(&self) -> Params {
        let s = &self.scene;
        Params::new(0.0, s.restitution, s.mu_s, s.radius, s.mass)
            .expect("domain params are valid")
            .with_friction_law(self.friction)
            .with_cue_table_friction(self.mu_ct)
            .expect("domain μ_ct is valid")
    }

    /// Core impact.
    pub fn impact(&self) -> Impact {
        self.scene.impact()
    }

    /// μ, or μ(0) for a speed-dependent law.
    pub fn mu(&self) -> f64 {
        self.params().mu() as f64
    }

    /// Reference solve (default configuration) with the scene's full parameters (friction
    /// law and μ_ct included).
    pub fn reference(&self) -> ReferenceOutcome {
        let s = &self.scene;
        solve(
            &ReferenceParams::from_core(&self.params()),
            glam::DVec3::new(s.velocity[0] as f64, s.velocity[1] as f64, 0.0),
            widen(cuesight::Vec3::from_array(s.spin)),
            &ReferenceConfig::default(),
        )
        .expect("the reference accepts every domain scene")
    }
}

fn log_uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    (rng.random_range(lo.ln()..=hi.ln())).exp()
}

/// Scene `index` of the domain set `seed` (see the module docs for the distribution).
pub fn scene(seed: u64, index: u64) -> DomainScene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    let u: f64 = rng.random();
    let speed = if u < 0.10 {
        log_uniform(&mut rng, 0.01, 0.1)
    } else if u < 0.85 {
        log_uniform(&mut rng, 0.1, 10.0)
    } else {
        log_uniform(&mut rng, 10.0, 100.0)
    };
    let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
    let cut_deg = sign
        * if rng.random::<f64>() < 0.85 {
            rng.random_range(0.0..=89.5)
        } else {
            rng.random_range(89.5..=89.99)
        };
    let cut = f64::to_radians(cut_deg);
    let (vx, vy) = (speed * cut.cos(), speed * cut.sin());
    let (radius, mass) =
        [(0.028575, 0.17), (0.02625, 0.142), (0.03075, 0.21)][rng.random_range(0..3usize)];
    let roll = [-vy / radius, vx / radius];
    let u: f64 = rng.random();
    let (spin_draw, spin) = if u < 0.05 {
        (SpinDraw::None, [0.0; 3])
    } else if u < 0.50 {
        let f = rng.random_range(-2.0..=2.0);
        let side = rng.random_range(-1.5..=1.5) * speed / radius;
        let wx = rng.random_range(-0.5..=0.5) * speed / radius;
        (
            SpinDraw::CueLike,
            [
                roll[0] * f + wx * cut.cos(),
                roll[1] * f + wx * cut.sin(),
                side,
            ],
        )
    } else if u < 0.90 {
        let mut w = [0.0; 3];
        for c in &mut w {
            *c = rng.random_range(-400.0..=400.0);
        }
        (SpinDraw::Uniform400, w)
    } else {
        let mut w = [0.0; 3];
        for c in &mut w {
            let s = if rng.random::<bool>() { 1.0 } else { -1.0 };
            *c = s * log_uniform(&mut rng, 1.0, 10_000.0);
        }
        (SpinDraw::Extreme, w)
    };
    let friction = if rng.random::<f64>() < 0.85 {
        if rng.random::<f64>() < 0.03 {
            FrictionLaw::Constant(0.0)
        } else {
            FrictionLaw::Constant((1.0 - rng.random::<f64>()) as f32)
        }
    } else {
        let mu0 = rng.random_range(0.01..=1.0f64);
        let a = mu0 * rng.random_range(0.05..=1.0);
        let c = log_uniform(&mut rng, 0.01, 100.0);
        let (a, b) = (a as f32, (mu0 - a).max(0.0) as f32);
        // a + b ≤ 1 in f32.
        let b = if a + b > 1.0 { 1.0 - a } else { b };
        FrictionLaw::speed_dependent(a, b, c as f32).expect("drawn inside the accepted range")
    };
    let mu_s = rng.random_range(0.0..=1.0f64) as f32;
    let restitution = rng.random_range(0.0..=1.0f64) as f32;
    let mu_ct = if rng.random::<f64>() < 0.7 {
        0.0
    } else {
        rng.random_range(0.0..=1.0f64) as f32
    };
    let mut vx32 = vx as f32;
    if vx32 <= 0.0 {
        vx32 = f32::MIN_POSITIVE; // cannot happen at |φ| ≤ 89.99° and U ≥ 0.01 m/s
    }
    DomainScene {
        scene: Scene {
            kind: SpinKind::Side,
            velocity: [vx32, vy as f32],
            spin: spin.map(|w: f64| w.clamp(-10_000.0, 10_000.0) as f32),
            mu: match friction {
                FrictionLaw::Constant(mu) => mu,
                FrictionLaw::SpeedDependent { a, b, .. } => a + b,
            },
            restitution,
            mu_s,
            radius: radius as f32,
            mass: mass as f32,
        },
        spin_draw,
        cut_deg,
        friction,
        mu_ct,
    }
}

/// Scenes `0..count` of the domain set `seed`.
pub fn sample(seed: u64, count: usize) -> Vec<DomainScene> {
    (0..count as u64).map(|i| scene(seed, i)).collect()
}

/// The error of one model on one scene; `None` if the model returned an error.
pub type ModelError = Option<crate::compare::SceneError>;

/// Every model's error on one scene, in [`MODELS`] order.
#[derive(Clone, Copy, Debug)]
pub struct Scored {
    /// The scene.
    pub scene: DomainScene,
    /// Per model: its error against the reference, `None` where it returned an error.
    pub errors: [ModelError; 6],
    /// Per model: the error it returned, if any (a refusal outside its validity domain,
    /// [`cuesight::Error::OutsideValidity`], or a failure).
    pub returned: [Option<cuesight::Error>; 6],
    /// The reference's object-ball speed over U (the throw angle is ill-conditioned where
    /// it is small: at |φ| → 90° the object ball barely moves).
    pub object_speed: f64,
    /// The tier `Auto` at [`AUTO_TOLERANCE`] picks, and its a-priori estimate of that
    /// tier's error (`cuesight::select_model`).
    pub auto_pick: (Model, f32),
    /// The f32 floor ([`f32_floor`]): no f32 `Outcome` can be closer to the reference.
    pub f32_floor: f64,
}

/// The error (`max(|Δv|, R|Δω|)/U`, worst of the two balls) of the reference's answer
/// rounded to f32: an `Outcome` holds f32, so no model can be closer than this. It is
/// large where the spin dwarfs the speed: at 0.01 m/s with 10⁴ rad/s, `R|ω|/U` ≈ 3·10⁴
/// and one f32 rounding of ω is ~1e-3 of U.
pub fn f32_floor(scene: &Scene, reference: &ReferenceOutcome) -> f64 {
    let rounding = |v: glam::DVec3| (v - v.as_vec3().as_dvec3()).length();
    let (cue, object) = (&reference.cue_ball, &reference.object_ball);
    let velocity = rounding(cue.velocity).max(rounding(object.velocity));
    let spin = rounding(cue.spin).max(rounding(object.spin));
    velocity.max(scene.radius as f64 * spin) / scene.speed()
}

impl Scored {
    /// `max(|Δv|, R|Δω|)/U` of model `m` (index into [`MODELS`]); +∞ on a model error.
    pub fn combined(&self, m: usize) -> f64 {
        self.errors[m].map_or(f64::INFINITY, |e| e.velocity.max(e.spin))
    }
}

/// Score one scene: reference solve, then every model.
pub fn score(scene: &DomainScene) -> Scored {
    let r = scene.reference();
    let (params, impact) = (scene.params(), scene.impact());
    let results = MODELS.map(|(_, model)| collide(&params, &impact, model));
    Scored {
        scene: *scene,
        errors: results.map(|result| result.ok().map(|out| scene_error(&scene.scene, &out, &r))),
        returned: results.map(Result::err),
        object_speed: r.object_ball.velocity.length() / scene.scene.speed(),
        auto_pick: cuesight::select_model(&params, &impact, AUTO_TOLERANCE as f32),
        f32_floor: f32_floor(&scene.scene, &r),
    }
}

/// Score every scene on `threads` threads (`std::thread::scope`), keeping the order.
pub fn score_all(scenes: &[DomainScene], threads: usize) -> Vec<Scored> {
    let threads = threads.max(1);
    let chunk = scenes.len().div_ceil(threads).max(1);
    std::thread::scope(|s| {
        let handles: Vec<_> = scenes
            .chunks(chunk)
            .map(|c| s.spawn(move || c.iter().map(score).collect::<Vec<_>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("scoring thread"))
            .collect()
    })
}

/// Bands of μ·μ_s the tables are split by (upper edges; the last is 1).
pub const MU_MU_S_BANDS: [f64; 7] = [0.02, 0.05, 0.08, 0.11, 0.2, 0.4, 1.0];

/// Bands of |φ| in degrees (upper edges).
pub const CUT_BANDS: [f64; 4] = [60.0, 85.0, 89.5, 90.0];

/// Bins per axis of the (μ, μ_s) heat map.
pub const GRID: usize = 10;

/// Index of the band `x` falls in (edges are upper edges, inclusive).
pub fn band(x: f64, edges: &[f64]) -> usize {
    edges
        .iter()
        .position(|&e| x <= e)
        .unwrap_or(edges.len() - 1)
}

/// Counts of one region: scenes, and per model and threshold the scenes within it,
/// per model the scenes where the model returned an error, the worst combined error
/// and the worst throw error.
#[derive(Clone, Copy, Debug, Default)]
pub struct Cell {
    /// Scenes in the region.
    pub count: usize,
    /// `within[m][t]`: scenes where model `m` is within [`THRESHOLDS`]`[t]` of U.
    pub within: [[usize; 3]; 6],
    /// Scenes the model refused outside its validity domain (counted outside every
    /// threshold).
    pub refused: [usize; 6],
    /// Scenes where the model returned any other error.
    pub failed: [usize; 6],
    /// Worst `max(|Δv|, R|Δω|)/U` per model (finite outcomes only).
    pub worst: [f64; 6],
    /// Worst throw error (degrees) per model.
    pub worst_throw: [f64; 6],
    /// Worst throw error (degrees) per model where the reference's object ball leaves
    /// with at least [`MIN_OBJECT_SPEED`] of U.
    pub worst_throw_moving: [f64; 6],
    /// Scenes where `Auto(1e-3)` is within its own tolerance, 1e-3 of U.
    pub auto_within_tolerance: usize,
    /// Scenes where `Auto(1e-3)`'s a-priori estimate is at or above its true error.
    pub auto_estimate_bounds: usize,
    /// The smallest ratio of `Auto(1e-3)`'s estimate to its true error (scenes with a
    /// non-zero error; `None` if none).
    pub auto_estimate_min_ratio: Option<f64>,
    /// Scenes where `Auto(1e-3)` picks `Ideal` although the friction law is not zero
    /// (μ(0) > 0) and the reference's object ball moves.
    pub auto_ideal_with_friction: usize,
}

/// The larger of `a` and `b`, NaN if either is (a NaN error must show, not vanish).
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Object-ball speed (fraction of U) above which a throw error counts in
/// [`Cell::worst_throw_moving`].
pub const MIN_OBJECT_SPEED: f64 = 0.05;

impl Cell {
    /// Add one scored scene.
    pub fn add(&mut self, s: &Scored) {
        self.count += 1;
        for m in 0..MODELS.len() {
            match s.errors[m] {
                None => match s.returned[m] {
                    Some(cuesight::Error::OutsideValidity { .. }) => self.refused[m] += 1,
                    _ => self.failed[m] += 1,
                },
                Some(e) => {
                    let c = e.velocity.max(e.spin);
                    for (t, &x) in THRESHOLDS.iter().enumerate() {
                        if c <= x {
                            self.within[m][t] += 1;
                        }
                    }
                    self.worst[m] = nan_max(self.worst[m], c);
                    self.worst_throw[m] = nan_max(self.worst_throw[m], e.throw_deg);
                    if m == AUTO {
                        if c <= AUTO_TOLERANCE {
                            self.auto_within_tolerance += 1;
                        }
                        let estimate = f64::from(s.auto_pick.1);
                        if estimate >= c {
                            self.auto_estimate_bounds += 1;
                        }
                        if c > 0.0 {
                            let ratio = estimate / c;
                            self.auto_estimate_min_ratio =
                                Some(self.auto_estimate_min_ratio.map_or(ratio, |r| r.min(ratio)));
                        }
                        if s.auto_pick.0 == Model::Ideal
                            && s.scene.mu() > 0.0
                            && s.object_speed > 0.0
                        {
                            self.auto_ideal_with_friction += 1;
                        }
                    }
                    if s.object_speed >= MIN_OBJECT_SPEED {
                        self.worst_throw_moving[m] =
                            nan_max(self.worst_throw_moving[m], e.throw_deg);
                    }
                }
            }
        }
    }

    /// Share of the region's scenes where model `m` is within threshold `t`.
    pub fn share(&self, m: usize, t: usize) -> f64 {
        self.within[m][t] as f64 / self.count.max(1) as f64
    }
}

/// The map: totals, bands of μ·μ_s, bands of cut, the (μ, μ_s) grid.
#[derive(Clone, Debug)]
pub struct Map {
    /// Every scene.
    pub all: Cell,
    /// By μ·μ_s band ([`MU_MU_S_BANDS`]).
    pub by_mu_mu_s: [Cell; 7],
    /// By μ·μ_s band, scenes with μ_ct = 0 only.
    pub by_mu_mu_s_no_ct: [Cell; 7],
    /// By |φ| band ([`CUT_BANDS`]).
    pub by_cut: [Cell; 4],
    /// `grid[i][j]`: μ in bin i, μ_s in bin j (width 1/[`GRID`]).
    pub grid: [[Cell; GRID]; GRID],
    /// Scenes with a speed-dependent friction law.
    pub speed_dependent: Cell,
    /// Scenes with μ_ct > 0.
    pub cue_table: Cell,
    /// By how the spin was drawn: none, cue-like, ±400 rad/s, extreme.
    pub by_spin: [Cell; 4],
    /// By speed band ([`SPEED_BANDS`]).
    pub by_speed: [Cell; 3],
}

/// Bands of U in m/s (upper edges).
pub const SPEED_BANDS: [f64; 3] = [0.1, 10.0, 100.0];

impl Map {
    /// Bin the scored scenes.
    pub fn of(scored: &[Scored]) -> Self {
        let mut map = Map {
            all: Cell::default(),
            by_mu_mu_s: [Cell::default(); 7],
            by_mu_mu_s_no_ct: [Cell::default(); 7],
            by_cut: [Cell::default(); 4],
            grid: [[Cell::default(); GRID]; GRID],
            speed_dependent: Cell::default(),
            cue_table: Cell::default(),
            by_spin: [Cell::default(); 4],
            by_speed: [Cell::default(); 3],
        };
        for s in scored {
            let mu = s.scene.mu();
            let mu_s = s.scene.scene.mu_s as f64;
            map.all.add(s);
            map.by_mu_mu_s[band(mu * mu_s, &MU_MU_S_BANDS)].add(s);
            if s.scene.mu_ct == 0.0 {
                map.by_mu_mu_s_no_ct[band(mu * mu_s, &MU_MU_S_BANDS)].add(s);
            }
            map.by_cut[band(s.scene.cut_deg.abs(), &CUT_BANDS)].add(s);
            let bin = |x: f64| ((x * GRID as f64) as usize).min(GRID - 1);
            map.grid[bin(mu)][bin(mu_s)].add(s);
            if matches!(s.scene.friction, FrictionLaw::SpeedDependent { .. }) {
                map.speed_dependent.add(s);
            }
            if s.scene.mu_ct > 0.0 {
                map.cue_table.add(s);
            }
            map.by_spin[s.scene.spin_draw as usize].add(s);
            map.by_speed[band(s.scene.scene.speed(), &SPEED_BANDS)].add(s);
        }
        map
    }

    /// The rows of the three share tables, in order: `(table, key, label, cell)`. The
    /// table is 0 (by μ·μ_s), 1 (by μ·μ_s, μ_ct = 0) or 2 (by cut, speed, spin, friction
    /// law and μ_ct); the key names the row's figure ([`Map::figures`]).
    pub fn share_rows(&self) -> Vec<(usize, String, String, &Cell)> {
        let mut rows = vec![(0, "all".to_string(), "all".to_string(), &self.all)];
        for (table, cells, key) in [
            (0, &self.by_mu_mu_s, "by-mu-mu-s"),
            (1, &self.by_mu_mu_s_no_ct, "by-mu-mu-s-no-ct"),
        ] {
            let mut lo = 0.0;
            for (i, &hi) in MU_MU_S_BANDS.iter().enumerate() {
                let open = if i == 0 { "[" } else { "(" };
                rows.push((
                    table,
                    format!("{key}-{}", key_number(hi)),
                    format!("μ·μ_s {open}{lo}, {hi}]"),
                    &cells[i],
                ));
                lo = hi;
            }
        }
        let mut lo = 0.0;
        for (i, &hi) in CUT_BANDS.iter().enumerate() {
            let open = if i == 0 { "[" } else { "(" };
            rows.push((
                2,
                format!("by-cut-{}", key_number(hi)),
                format!("\\|φ\\| {open}{lo}°, {hi}°)"),
                &self.by_cut[i],
            ));
            lo = hi;
        }
        let mut lo = 0.0;
        for (i, &hi) in SPEED_BANDS.iter().enumerate() {
            rows.push((
                2,
                format!("by-speed-{}", key_number(hi)),
                format!("U ({lo}, {hi}] m/s"),
                &self.by_speed[i],
            ));
            lo = hi;
        }
        for (i, (key, label)) in [
            ("none", "spin: none"),
            ("cue-like", "spin: cue-like"),
            ("uniform-400", "spin: uniform ±400 rad/s"),
            ("extreme", "spin: extreme, to 10⁴ rad/s"),
        ]
        .into_iter()
        .enumerate()
        {
            rows.push((
                2,
                format!("spin-{key}"),
                label.to_string(),
                &self.by_spin[i],
            ));
        }
        rows.push((
            2,
            "speed-dependent".to_string(),
            "μ(v) (speed-dependent)".to_string(),
            &self.speed_dependent,
        ));
        rows.push((
            2,
            "cue-table".to_string(),
            "μ_ct > 0".to_string(),
            &self.cue_table,
        ));
        rows
    }

    /// The figures of the tables, as docs/accuracy-domain.md holds them: `(key, value)`,
    /// the key without its `accuracy-domain-` prefix. Every row of every table is one
    /// figure (its cells after the label, `|`-separated as in [`Map::markdown`]), and so
    /// is each share of a share table (`ROW-MODEL-THRESHOLD`, e.g.
    /// `by-mu-mu-s-0-02-kimgrip-0-5`), each worst case of a model, and `Auto`'s share
    /// within its own tolerance.
    pub fn figures(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        for (_, key, _, cell) in self.share_rows() {
            out.push((key.clone(), share_cells(cell)));
            for (m, (name, _)) in MODELS.iter().enumerate() {
                for (t, threshold) in ["0-05", "0-5", "5"].into_iter().enumerate() {
                    out.push((
                        format!("{key}-{}-{threshold}", model_key(name)),
                        percent(cell.share(m, t)),
                    ));
                }
            }
        }
        for (i, &hi) in MU_MU_S_BANDS.iter().enumerate() {
            out.push((
                format!("worst-by-mu-mu-s-{}", key_number(hi)),
                worst_cells(&self.by_mu_mu_s[i]),
            ));
        }
        for (m, (name, _)) in MODELS.iter().enumerate() {
            let key = format!("worst-{}", model_key(name));
            out.push((key.clone(), self.worst_model_cells(m)));
            out.push((
                format!("{key}-percent"),
                format!("{:.0}", 100.0 * self.all.worst[m]),
            ));
            out.push((
                format!("{key}-throw"),
                format!("{:.1}", self.all.worst_throw[m]),
            ));
            out.push((
                format!("{key}-throw-3"),
                format!("{:.3}", self.all.worst_throw[m]),
            ));
            out.push((
                format!("{key}-throw-moving"),
                format!("{:.1}", self.all.worst_throw_moving[m]),
            ));
            out.push((
                format!("{key}-outside-0-5"),
                (self.all.count - self.all.within[m][1]).to_string(),
            ));
        }
        let all = &self.all;
        // A count of scenes as a share (%, two decimals) and as the count.
        let mut share = |key: &str, n: usize| {
            let percent = 100.0 * n as f64 / all.count.max(1) as f64;
            out.push((key.to_string(), format!("{percent:.2}")));
            out.push((format!("{key}-scenes"), n.to_string()));
        };
        share("auto-within-tolerance", all.auto_within_tolerance);
        share("auto-estimate-bounds", all.auto_estimate_bounds);
        out.push((
            "auto-worst-tolerances".to_string(),
            format!("{:.1}", all.worst[AUTO] / AUTO_TOLERANCE),
        ));
        out.push((
            "auto-estimate-min-ratio".to_string(),
            all.auto_estimate_min_ratio
                .map_or("none".to_string(), |r| format!("{r:.3}")),
        ));
        out.push((
            "auto-ideal-with-friction".to_string(),
            all.auto_ideal_with_friction.to_string(),
        ));
        out.push(("scenes".to_string(), all.count.to_string()));
        out
    }

    /// A row of the worst-case table, after the model name.
    fn worst_model_cells(&self, m: usize) -> String {
        let all = &self.all;
        format!(
            "{:.3e} | {:.3}° | {:.3}° | {} / {} / {} | {} | {}",
            all.worst[m],
            all.worst_throw[m],
            all.worst_throw_moving[m],
            all.count - all.within[m][0],
            all.count - all.within[m][1],
            all.count - all.within[m][2],
            all.refused[m],
            all.failed[m]
        )
    }

    /// Markdown tables: per model, the share within each threshold by region; the worst
    /// errors by μ·μ_s band and per model; `Auto`'s share within its own tolerance.
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        let titles = [
            "By μ·μ_s: % within 0.05 % / 0.5 % / 5 % of U",
            "By μ·μ_s, μ_ct = 0 only: % within 0.05 % / 0.5 % / 5 % of U",
            "By cut, speed, spin, friction law and μ_ct: % within 0.05 % / 0.5 % / 5 % of U",
        ];
        let rows = self.share_rows();
        for (table, title) in titles.into_iter().enumerate() {
            let _ = writeln!(out, "\n#### {title}\n");
            let _ = write!(out, "| region | scenes |");
            for (name, _) in MODELS {
                let _ = write!(out, " {name} |");
            }
            let _ = write!(out, "\n|---|---|");
            for _ in MODELS {
                let _ = write!(out, "---|");
            }
            out.push('\n');
            for (_, _, label, cell) in rows.iter().filter(|row| row.0 == table) {
                let _ = writeln!(out, "| {label} | {} |", share_cells(cell));
            }
        }
        let _ = write!(
            out,
            "\n#### Worst max(\\|Δv\\|, R\\|Δω\\|)/U and worst throw error (object ball ≥ {} % of U) by μ·μ_s\n\n| μ·μ_s up to |",
            100.0 * MIN_OBJECT_SPEED
        );
        for (name, _) in MODELS {
            let _ = write!(out, " {name} |");
        }
        let _ = write!(out, "\n|---|");
        for _ in MODELS {
            let _ = write!(out, "---|");
        }
        out.push('\n');
        for (i, &hi) in MU_MU_S_BANDS.iter().enumerate() {
            let _ = writeln!(out, "| {hi} | {} |", worst_cells(&self.by_mu_mu_s[i]));
        }
        let _ = writeln!(
            out,
            "\n#### Worst case per model (all scenes)\n\n| model | worst max(\\|Δv\\|, R\\|Δω\\|)/U | worst throw error | worst throw error, object ball ≥ {} % of U | scenes outside 0.05 % / 0.5 % / 5 % of U (refusals included) | refused outside the validity domain | other errors |\n|---|---|---|---|---|---|---|",
            100.0 * MIN_OBJECT_SPEED
        );
        for (m, (name, _)) in MODELS.iter().enumerate() {
            let _ = writeln!(out, "| {name} | {} |", self.worst_model_cells(m));
        }
        let _ = writeln!(
            out,
            "\nAuto(1e-3) within its tolerance (1e-3 of U): {:.2} % of the scenes ({} of {}); worst {:.1}× the tolerance.",
            100.0 * self.all.auto_within_tolerance as f64 / self.all.count.max(1) as f64,
            self.all.auto_within_tolerance,
            self.all.count,
            self.all.worst[AUTO] / AUTO_TOLERANCE
        );
        out
    }

    /// An SVG heat map: one row of panels per model, one panel per threshold, each a
    /// [`GRID`]² grid over μ (x, 0 → 1) and μ_s (y, 0 → 1, up), coloured by the share of
    /// the bin's scenes within the threshold (red 0 % → yellow 50 % → green 100 %).
    pub fn svg(&self) -> String {
        const CELL: f64 = 18.0;
        const PANEL: f64 = CELL * GRID as f64;
        const GAP: f64 = 40.0;
        const LEFT: f64 = 100.0;
        const TOP: f64 = 70.0;
        let width = LEFT + 3.0 * (PANEL + GAP);
        let height = TOP + MODELS.len() as f64 * (PANEL + GAP) + 40.0;
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
        );
        let _ = writeln!(
            s,
            r#"<rect width="100%" height="100%" fill="white"/><text x="8" y="20" font-size="14">Share of scenes within 0.05 % / 0.5 % / 5 % of U ({} scenes)</text><text x="8" y="38">bins of μ (x, 0–1) × μ_s (y, 0–1, up): red 0 %, yellow 50 %, green 100 %</text>"#,
            self.all.count
        );
        for (t, label) in ["within 0.05 % of U", "within 0.5 % of U", "within 5 % of U"]
            .iter()
            .enumerate()
        {
            let x = LEFT + t as f64 * (PANEL + GAP);
            let _ = writeln!(s, r#"<text x="{x}" y="{}">{label}</text>"#, TOP - 8.0);
        }
        for (m, (name, _)) in MODELS.iter().enumerate() {
            let y0 = TOP + m as f64 * (PANEL + GAP);
            let _ = writeln!(s, r#"<text x="8" y="{}">{name}</text>"#, y0 + PANEL / 2.0);
            for t in 0..3 {
                let x0 = LEFT + t as f64 * (PANEL + GAP);
                for (i, column) in self.grid.iter().enumerate() {
                    for (j, cell) in column.iter().enumerate() {
                        let share = cell.share(m, t);
                        let (r, g) = if share < 0.5 {
                            (220.0, 440.0 * share)
                        } else {
                            (440.0 * (1.0 - share), 200.0)
                        };
                        let _ = writeln!(
                            s,
                            r#"<rect x="{:.0}" y="{:.0}" width="{CELL}" height="{CELL}" fill="rgb({:.0},{:.0},60)"><title>{name}, μ {:.1}–{:.1}, μ_s {:.1}–{:.1}: {:.1} % of {}</title></rect>"#,
                            x0 + i as f64 * CELL,
                            y0 + PANEL - (j + 1) as f64 * CELL,
                            r,
                            g,
                            i as f64 / GRID as f64,
                            (i + 1) as f64 / GRID as f64,
                            j as f64 / GRID as f64,
                            (j + 1) as f64 / GRID as f64,
                            100.0 * share,
                            cell.count
                        );
                    }
                }
                let _ = writeln!(
                    s,
                    r#"<rect x="{x0}" y="{y0}" width="{PANEL}" height="{PANEL}" fill="none" stroke="black"/><text x="{x0}" y="{}" font-size="10">0</text><text x="{}" y="{}" font-size="10">μ 1</text><text x="{}" y="{}" font-size="10">μ_s 1</text>"#,
                    y0 + PANEL + 12.0,
                    x0 + PANEL - 18.0,
                    y0 + PANEL + 12.0,
                    x0 - 30.0,
                    y0 + 10.0
                );
            }
        }
        s.push_str("</svg>\n");
        s
    }
}

/// A share in percent, as the tables print it.
fn percent(share: f64) -> String {
    format!("{:.1}", 100.0 * share)
}

/// A share-table row after its label: the scenes, then per model the % within
/// 0.05 % / 0.5 % / 5 % of U.
fn share_cells(cell: &Cell) -> String {
    let mut out = cell.count.to_string();
    for m in 0..MODELS.len() {
        let _ = write!(
            out,
            " | {} / {} / {}",
            percent(cell.share(m, 0)),
            percent(cell.share(m, 1)),
            percent(cell.share(m, 2))
        );
    }
    out
}

/// A row of the worst-error table after its band: per model the worst
/// `max(|Δv|, R|Δω|)/U` in % and the worst throw error with the object ball moving.
fn worst_cells(cell: &Cell) -> String {
    (0..MODELS.len())
        .map(|m| {
            format!(
                "{:.2} %, {:.2}°",
                100.0 * cell.worst[m],
                cell.worst_throw_moving[m]
            )
        })
        .collect::<Vec<_>>()
        .join(" | ")
}

/// A band edge in a figure key: `0.02` → `0-02`.
fn key_number(x: f64) -> String {
    x.to_string().replace('.', "-")
}

/// A model's name in a figure key: `Auto(1e-3)` → `auto-1e-3`.
fn model_key(name: &str) -> String {
    name.to_ascii_lowercase().replace('(', "-").replace(')', "")
}

/// The scene where model `m` errs most among those `filter` keeps, by
/// `max(|Δv|, R|Δω|)/U`: its index in `scored` and its scores.
pub fn worst_scene(
    scored: &[Scored],
    m: usize,
    filter: impl Fn(&Scored) -> bool,
) -> Option<(usize, &Scored)> {
    scored
        .iter()
        .enumerate()
        .filter(|(_, s)| filter(s))
        .max_by(|a, b| a.1.combined(m).total_cmp(&b.1.combined(m)))
}

/// The scene where model `m`'s throw errs most: its index in `scored` and its scores.
pub fn worst_throw_scene(scored: &[Scored], m: usize) -> Option<(usize, &Scored)> {
    let throw = |s: &Scored| s.errors[m].map_or(0.0, |e| e.throw_deg);
    scored
        .iter()
        .enumerate()
        .max_by(|a, b| throw(a.1).total_cmp(&throw(b.1)))
}

/// The band of μ·μ_s a scene falls in ([`MU_MU_S_BANDS`]).
pub fn mu_mu_s_band(s: &Scored) -> usize {
    band(s.scene.mu() * s.scene.scene.mu_s as f64, &MU_MU_S_BANDS)
}

/// How docs/accuracy-domain.md names a spin draw.
pub fn spin_label(draw: SpinDraw) -> &'static str {
    match draw {
        SpinDraw::None => "no spin",
        SpinDraw::CueLike => "cue-like spin",
        SpinDraw::Uniform400 => "±400 rad/s spins",
        SpinDraw::Extreme => "extreme spin",
    }
}

/// A number as the docs print it, with a minus sign (−) for a negative one.
fn signed(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}").replace('-', "−")
}

impl DomainScene {
    /// The scene as docs/accuracy-domain.md describes it: `U 0.294 m/s, φ 12.44°, ω
    /// (339.07, 220.11, −66.20) rad/s, μ 0.9837, μ_s 0.9668, e* 0.8638, μ_ct 0, carom
    /// ball`.
    pub fn describe(&self) -> String {
        let s = &self.scene;
        let ball = if s.radius == 0.028575 {
            "pool"
        } else if s.radius == 0.02625 {
            "snooker"
        } else {
            "carom"
        };
        let w = s.spin.map(|w| signed(w as f64, 2));
        let mu = match self.friction {
            FrictionLaw::Constant(mu) => format!("μ {mu:.4}"),
            FrictionLaw::SpeedDependent { a, b, c } => {
                format!("μ(v) = {a:.4} + {b:.4}·e^(−{c:.3}v)")
            }
        };
        let mu_ct = if self.mu_ct == 0.0 {
            "0".to_string()
        } else {
            format!("{:.3}", self.mu_ct)
        };
        format!(
            "U {} m/s, φ {}°, ω ({}, {}, {}) rad/s, {mu}, μ_s {:.4}, e* {:.4}, μ_ct {mu_ct}, {ball} ball",
            significant(s.speed(), 4),
            signed(self.cut_deg, 2),
            w[0],
            w[1],
            w[2],
            s.mu_s,
            s.restitution,
        )
    }
}

/// `x` to `digits` significant digits, fixed-point.
fn significant(x: f64, digits: i32) -> String {
    let decimals = (digits - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// The figures of docs/accuracy-domain.md's prose about single scenes and the spread
/// across bands, `(key, value)` without the `accuracy-domain-` prefix: each model's worst
/// scene (`worst-MODEL-scene`, [`DomainScene::describe`], with its index and errors),
/// `Auto`'s worst throw scene, and `KimGrip`'s worst scenes below μ·μ_s = 0.2 (their
/// error range in % of U, μ_ct range and spin draws).
pub fn scene_figures(scored: &[Scored], map: &Map) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for (m, (name, _)) in MODELS.iter().enumerate() {
        let key = format!("worst-{}-scene", model_key(name));
        if let Some((i, s)) = worst_scene(scored, m, |_| true) {
            let e = s.errors[m].unwrap_or_default();
            out.push((key.clone(), s.scene.describe()));
            out.push((format!("{key}-index"), i.to_string()));
            out.push((
                format!("{key}-velocity"),
                format!("{:.0}", 100.0 * e.velocity),
            ));
            out.push((format!("{key}-spin"), format!("{:.0}", 100.0 * e.spin)));
            out.push((format!("{key}-throw"), format!("{:.1}", e.throw_deg)));
            out.push((
                format!("{key}-percent-2"),
                format!("{:.2}", 100.0 * s.combined(m)),
            ));
        }
        if let Some((i, s)) = worst_throw_scene(scored, m) {
            let key = format!("worst-{}-throw-scene", model_key(name));
            let e = s.errors[m].unwrap_or_default();
            out.push((key.clone(), s.scene.describe()));
            out.push((format!("{key}-index"), i.to_string()));
            out.push((
                format!("{key}-object-speed"),
                format!("{:.0e}", s.object_speed),
            ));
            out.push((
                format!("{key}-error"),
                format!("{:.1e}", e.velocity.max(e.spin)),
            ));
        }
    }
    // KimGrip's worst scene in each band up to μ·μ_s = 0.2.
    const KIM_GRIP: usize = 2;
    let below = MU_MU_S_BANDS.iter().take_while(|&&hi| hi <= 0.2).count();
    let worst: Vec<&Scored> = (0..below)
        .filter_map(|b| worst_scene(scored, KIM_GRIP, |s| mu_mu_s_band(s) == b).map(|(_, s)| s))
        .collect();
    let range = |values: Vec<f64>, decimals: usize| {
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        format!("{lo:.decimals$}–{hi:.decimals$}")
    };
    out.push((
        "kimgrip-worst-to-0-2-percent".to_string(),
        range(
            worst.iter().map(|s| 100.0 * s.combined(KIM_GRIP)).collect(),
            0,
        ),
    ));
    out.push((
        "kimgrip-worst-to-0-2-mu-ct".to_string(),
        range(worst.iter().map(|s| s.scene.mu_ct as f64).collect(), 2),
    ));
    let mut spins: Vec<&str> = worst
        .iter()
        .map(|s| spin_label(s.scene.spin_draw))
        .collect();
    spins.dedup();
    out.push(("kimgrip-worst-to-0-2-spins".to_string(), spins.join(" or ")));
    // Shares across bands: KimGrip within 5 % up to μ·μ_s = 0.2, SeedExact within 5 %
    // with μ_ct = 0 up to 0.11.
    out.push((
        "kimgrip-5-to-0-2".to_string(),
        range(
            (0..below)
                .map(|b| 100.0 * map.by_mu_mu_s[b].share(KIM_GRIP, 2))
                .collect(),
            1,
        ),
    ));
    let to_0_11 = MU_MU_S_BANDS.iter().take_while(|&&hi| hi <= 0.11).count();
    let lowest = (0..to_0_11)
        .map(|b| 100.0 * map.by_mu_mu_s_no_ct[b].share(3, 2))
        .fold(f64::INFINITY, f64::min);
    out.push((
        "seedexact-5-no-ct-to-0-11".to_string(),
        format!("{lowest:.1}"),
    ));
    out
}
