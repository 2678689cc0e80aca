//! Shared by the core's integration tests: the ball sets, the valid-domain input
//! strategies for proptest, and the physical checks (energy, momentum, mirror image,
//! f32 against f64).
#![allow(dead_code)]

use cuesight::{collide, collide_f64, FrictionLaw, Impact, Model, Outcome, Params, Vec3};
use proptest::prelude::*;
use proptest::test_runner::{FileFailurePersistence, RngAlgorithm, RngSeed};

/// Every ball set the issue names: (name, R in m, M in kg).
pub const BALLS: [(&str, f32, f32); 3] = [
    ("pool", 0.028575, 0.17),
    ("snooker", 0.02625, 0.142),
    ("carom", 0.03075, 0.21),
];

/// f32 unit roundoff, 2⁻²⁴.
pub const EPS32: f64 = 5.960_464_477_539_063e-8;

/// Every model including `Auto` at a middle tolerance.
pub const MODELS: [Model; 6] = [
    Model::Ideal,
    Model::Kim,
    Model::KimGrip,
    Model::SeedExact,
    Model::Exact,
    Model::Auto { tolerance: 1e-3 },
];

/// Fixed proptest configuration: ChaCha with a fixed seed (CI is deterministic; set
/// `PROPTEST_RNG_SEED` to explore others, `PROPTEST_CASES` to change the count), and
/// failures persisted next to the test source (`<test>.proptest-regressions`, committed).
pub fn config(cases: u32, seed: u64) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_algorithm: RngAlgorithm::XorShift,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        max_shrink_iters: 4096,
        ..ProptestConfig::default()
    }
}

/// A collision input from the valid domain, with the `Auto` tolerance to use.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    pub params: Params,
    pub impact: Impact,
    pub tolerance: f32,
}

impl Case {
    pub fn speed(&self) -> f64 {
        let v = self.impact.velocity();
        (v.x as f64).hypot(v.y as f64)
    }
    pub fn models(&self) -> [Model; 6] {
        [
            Model::Ideal,
            Model::Kim,
            Model::KimGrip,
            Model::SeedExact,
            Model::Exact,
            Model::Auto {
                tolerance: self.tolerance,
            },
        ]
    }
}

/// How the cue ball spins (multiples of `U/R`).
#[derive(Clone, Copy, Debug)]
pub enum SpinKind {
    /// No spin.
    Zero,
    /// Arbitrary spin, each component in `[-4, 4] U/R`.
    Free([f64; 3]),
    /// `factor` × natural roll (`< 0`: draw).
    Roll(f64),
    /// Side spin cancelling the cut (`R ω_z = −v_y`) plus topspin: zero `y` slip.
    Gearing(f64),
    /// Initial slip `(δ_y, δ_z) U` with `|δ|` down to 1e-7, plus `ω_x` (in `U/R`).
    NearGearing(f64, f64, f64),
}

/// Raw draw of one case: sixteen uniform `u32`, decoded by [`Case::decode`]. Drawing
/// integers and decoding them in optimised test code is ~10× cheaper than composing
/// proptest's float strategies (proptest itself is built unoptimised in the dev
/// profile), which is what makes 10⁶ cases fit the time budget; shrinking still works
/// (each integer shrinks towards 0, i.e. towards the low end of its range or the first
/// listed variant).
pub type Raw = [u32; 16];

/// `u32` to `[0, 1)`.
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

fn signed_log(sign: u32, x: u32, lo: f64, hi: f64) -> f64 {
    let v = (lo.ln() + unit(x) * (hi.ln() - lo.ln())).exp();
    if sign & 1 == 0 {
        v
    } else {
        -v
    }
}

impl Case {
    /// Decode a raw draw into the valid domain: every ball set; μ constant in [0, 0.3]
    /// (exactly 0 and 1e-7 weighted in), Marlow's fit, or `a + b·exp(−c v)` with
    /// `a ∈ [1e-4, 0.3]`, `a + b ≤ 0.3`, `c ∈ [0, 20]` s/m; e* and μ_s in [0, 1] with both
    /// ends weighted in; μ_ct in [0, 0.3]; U 1 mm/s–20 m/s log-uniform; |φ| < 90° with
    /// grazing cuts to within 1e-5° of 90°; spins up to 4 U/R of every kind; `Auto`
    /// tolerance 1e-6–1 log-uniform. Inputs are built in f64 and rounded once to f32.
    pub fn decode(raw: Raw) -> Case {
        let (_, r, m) = BALLS[(raw[0] % 3) as usize];
        let law = match pick(raw[1], &[1, 1, 7, 1, 3]) {
            (0, _) => FrictionLaw::Constant(0.0),
            (1, _) => FrictionLaw::Constant(1e-7),
            (2, f) => FrictionLaw::Constant((0.3 * f) as f32),
            (3, _) => FrictionLaw::MARLOW,
            (_, f) => {
                let a = 1e-4 + (0.3 - 1e-4) * f;
                let b = unit(raw[2]) * (0.3 - a);
                let c = 20.0 * unit(raw[3]);
                FrictionLaw::speed_dependent(a as f32, b as f32, c as f32).unwrap()
            }
        };
        let with_ends = |x: u32| match pick(x, &[1, 1, 6]) {
            (0, _) => 0.0f32,
            (1, _) => 1.0f32,
            (_, f) => f as f32,
        };
        let mu_ct = match pick(raw[6], &[2, 1, 3]) {
            (0, _) => 0.0f32,
            (1, _) => 0.3f32,
            (_, f) => (0.3 * f) as f32,
        };
        let params = Params::new(0.0, with_ends(raw[4]), with_ends(raw[5]), r, m)
            .unwrap()
            .with_friction_law(law)
            .with_cue_table_friction(mu_ct)
            .unwrap();
        let speed = ((1e-3f64).ln() + unit(raw[7]) * (2e4f64).ln()).exp();
        let cut = match pick(raw[8], &[6, 1, 1]) {
            (0, f) => -89.9 + 179.8 * f,
            (1, f) => {
                let c = 90.0 - 10f64.powf(-5.0 + 4.0 * f);
                if raw[9] & 1 == 0 {
                    c
                } else {
                    -c
                }
            }
            _ => 0.0,
        };
        let spread = |x: u32| -4.0 + 8.0 * unit(x);
        let kind = match pick(raw[10], &[1, 4, 2, 1, 2]) {
            (0, _) => SpinKind::Zero,
            (1, _) => SpinKind::Free([spread(raw[11]), spread(raw[12]), spread(raw[13])]),
            (2, _) => SpinKind::Roll(spread(raw[11])),
            (3, _) => SpinKind::Gearing(spread(raw[11]) / 2.0),
            _ => SpinKind::NearGearing(
                signed_log(raw[9] >> 1, raw[11], 1e-7, 0.05),
                signed_log(raw[9] >> 2, raw[12], 1e-7, 0.05),
                spread(raw[13]) / 2.0,
            ),
        };
        Case {
            impact: impact(speed, cut, kind, r),
            params,
            tolerance: 10f32.powf(-6.0 + 6.0 * unit(raw[15]) as f32),
        }
    }
}

/// Build the impact in f64 and round once to f32.
pub fn impact(speed: f64, cut_deg: f64, kind: SpinKind, radius: f32) -> Impact {
    let r = radius as f64;
    let phi = cut_deg.to_radians();
    let (vx, vy) = (speed * phi.cos(), speed * phi.sin());
    let w = speed / r;
    let spin = match kind {
        SpinKind::Zero => [0.0; 3],
        SpinKind::Free(f) => [f[0] * w, f[1] * w, f[2] * w],
        SpinKind::Roll(f) => [-vy / r * f, vx / r * f, 0.0],
        SpinKind::Gearing(top) => [0.0, top * w, -vy / r],
        SpinKind::NearGearing(dy, dz, wx) => [wx * w, dz * speed / r, (-vy - dy * speed) / r],
    };
    Impact::from_velocity(
        [vx as f32, vy as f32],
        [spin[0] as f32, spin[1] as f32, spin[2] as f32],
    )
    .expect("valid-domain impact")
}

/// The closed-form domain of [`Case::decode`].
pub fn case() -> impl Strategy<Value = Case> {
    any::<Raw>().prop_map(Case::decode)
}

/// The inputs where `KimGrip` is known to go wrong (bug reported; ignored test
/// `properties::bug_kim_grip_speed_dependent_friction_at_tiny_slip_change`): a
/// speed-dependent law `μ(v) = a + b·exp(−c v)` where the slip changes by only a small
/// `Δv` during the impact, `c Δv a/(a+b) < 1e-3` with `Δv = min(|v₀|, 7 μ(0) p₀)` (the
/// whole slip when it grips, or the most the friction can take off it while sliding;
/// `p₀ = (1+e*) U_x/2`). `FrictionLaw::normal_impulse_between` then computes
/// `[Δv + ln(μ(v₀)/μ(v))/c] / (a k̄)` as the difference of two nearly equal terms; in f32
/// it loses its digits (it can come out zero or negative) and `KimGrip` returns a
/// negative normal impulse, creates energy, or breaks the table's friction cone.
pub fn in_tiny_slip_bug_region(case: &Case) -> bool {
    match case.params.friction_law() {
        FrictionLaw::SpeedDependent { a, b, c } => {
            let (sy, sz) = slip(case);
            let (a, b, c) = (a as f64, b as f64, c as f64);
            let p0 =
                0.5 * (1.0 + case.params.restitution() as f64) * case.impact.velocity().x as f64;
            let change = sy.hypot(sz).min(7.0 * (a + b) * p0);
            c > 0.0 && b > 0.0 && c * change * a / (a + b) < 1e-3
        }
        FrictionLaw::Constant(_) => false,
    }
}

/// Cases inside [`in_tiny_slip_bug_region`]: a speed-dependent law with
/// `b ≥ 0.01 (0.3 − a)`, `c ∈ [0.05, 20]`, and either a slip of
/// `10^[−9, 0] × 1e-3 (a+b)/(a c)` (at most U/20) in any direction, or a grazing cut
/// whose `U_x` makes `7 (a+b) p₀` that small.
pub fn tiny_slip_case() -> impl Strategy<Value = Case> {
    any::<Raw>().prop_map(|raw| {
        let base = Case::decode(raw);
        let a = 1e-4 + (0.3 - 1e-4) * unit(raw[1]);
        let b = unit(raw[2]).max(0.01) * (0.3 - a);
        let c = 0.05 + 19.95 * unit(raw[3]);
        let law = FrictionLaw::speed_dependent(a as f32, b as f32, c as f32).unwrap();
        let params = base.params.with_friction_law(law);
        let speed = base.speed();
        let scale = 1e-3 * (a + b) / (a * c) * 10f64.powf(-9.0 * unit(raw[14]));
        let v = base.impact.velocity();
        let cut = (v.y as f64).atan2(v.x as f64).to_degrees();
        let impact = if raw[14] & 1 == 0 {
            let size = scale.min(0.05 * speed);
            let angle = std::f64::consts::TAU * unit(raw[12]);
            let kind = SpinKind::NearGearing(
                size * angle.cos() / speed,
                size * angle.sin() / speed,
                -1.0 + 2.0 * unit(raw[13]),
            );
            impact(speed, cut, kind, params.radius())
        } else {
            // U_x with 7 (a+b) p₀ = scale, keeping the spin of the base case.
            let e = params.restitution() as f64;
            let ux = (2.0 * scale / (7.0 * (a + b) * (1.0 + e))).min(0.5 * speed);
            let uy = (speed * speed - ux * ux).sqrt() * if cut < 0.0 { -1.0 } else { 1.0 };
            let w = base.impact.spin();
            Impact::from_velocity([ux as f32, uy as f32], [w.x, w.y, w.z]).unwrap()
        };
        Case {
            impact,
            params,
            tolerance: base.tolerance,
        }
    })
}

/// Mirror image y → −y of an impact: velocity (x, −y), spin (−x, y, −z).
pub fn mirror_impact(i: &Impact) -> Impact {
    let (v, w) = (i.velocity(), i.spin());
    Impact::from_velocity([v.x, -v.y], [-w.x, w.y, -w.z]).unwrap()
}
pub fn mirror_v(v: Vec3) -> Vec3 {
    Vec3::new(v.x, -v.y, v.z)
}
pub fn mirror_w(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, w.y, -w.z)
}

/// `Some(what)` if `b` is not the exact mirror image of `a` (bit for bit, ±0 equal).
pub fn mirror_mismatch(a: &Outcome, b: &Outcome) -> Option<&'static str> {
    if mirror_v(a.cue_ball.velocity) != b.cue_ball.velocity {
        return Some("cue velocity");
    }
    if mirror_v(a.object_ball.velocity) != b.object_ball.velocity {
        return Some("object velocity");
    }
    if mirror_w(a.cue_ball.spin) != b.cue_ball.spin {
        return Some("cue spin");
    }
    if mirror_w(a.object_ball.spin) != b.object_ball.spin {
        return Some("object spin");
    }
    if a.regime != b.regime {
        return Some("regime");
    }
    let (fa, fb) = (a.impulses.friction, b.impulses.friction);
    if a.impulses.normal != b.impulses.normal
        || fa.x != fb.x
        || fa.y != -fb.y
        || fa.z != fb.z
        || a.impulses.table_friction != b.impulses.table_friction
    {
        return Some("impulses");
    }
    if a.throw_angle() != -b.throw_angle()
        || a.cue_deflection() != b.cue_deflection()
        || a.separation_angle_deg() != b.separation_angle_deg()
    {
        return Some("angles");
    }
    None
}

fn sq(v: Vec3) -> f64 {
    let (x, y, z) = (v.x as f64, v.y as f64, v.z as f64);
    x * x + y * y + z * z
}

/// Kinetic energy per unit mass (J/kg) of a ball, translational + rotational with
/// `I = 2/5 M R²`.
pub fn specific_energy(velocity: Vec3, spin: Vec3, radius: f32) -> f64 {
    let r = radius as f64;
    0.5 * sq(velocity) + 0.5 * 0.4 * r * r * sq(spin)
}

/// Kinetic energy per unit mass before (cue ball only) and after (both balls).
pub fn energies(case: &Case, out: &Outcome) -> (f64, f64) {
    let r = case.params.radius();
    let before = specific_energy(case.impact.velocity(), case.impact.spin(), r);
    let after = specific_energy(out.cue_ball.velocity, out.cue_ball.spin, r)
        + specific_energy(out.object_ball.velocity, out.object_ball.spin, r);
    (before, after)
}

/// Initial tangential slip `(v_y0, v_z0)` (seed eq. (11)) in f64.
pub fn slip(case: &Case) -> (f64, f64) {
    let (v, w, r) = (
        case.impact.velocity(),
        case.impact.spin(),
        case.params.radius() as f64,
    );
    (-(v.y as f64) - r * w.z as f64, r * w.y as f64)
}

/// The derived upper bound on the energy `Kim` can create, per unit mass (J/kg).
///
/// `Kim` applies a friction impulse of fixed size `J = μ(|v₀|) p₀` (per unit mass,
/// `p₀ = (1+e*) U_x / 2`) against the initial slip `v₀`, whatever happens to the slip
/// (it assumes sliding throughout). The kinetic-energy change is the normal part
/// `−(1−e*²) U_x²/4 ≤ 0`, the table part (≤ 0, shown in docs/reliability.md) and the
/// friction part `j·v₀ + ½ jᵀK j` with `K = diag(7, 6)` for `ν = 2/5`. With
/// `j = −J v̂₀` this is at most `J (7 J / 2 − |v₀|)`: positive only when `J` exceeds
/// `2|v₀|/7`, i.e. when the fixed impulse overshoots the one that stops the slip
/// (erratum E6, the gripping case `Kim` does not model) by more than a factor ~2.
pub fn kim_energy_bound(case: &Case) -> f64 {
    let (sy, sz) = slip(case);
    let v0 = sy.hypot(sz);
    let p0 = 0.5 * (1.0 + case.params.restitution() as f64) * case.impact.velocity().x as f64;
    let mu = case.params.friction_law().at(v0 as f32) as f64;
    let j = mu * p0;
    (j * (3.5 * j - v0)).max(0.0)
}

/// Evaluate `model` in f32 and f64.
pub fn both(case: &Case, model: Model) -> (Outcome, Outcome) {
    (
        collide(&case.params, &case.impact, model).expect("f32"),
        collide_f64(&case.params, &case.impact, model).expect("f64"),
    )
}

/// Every output as a specific (per unit mass) velocity in m/s: velocities, `R ω`,
/// impulses / M. 17 numbers.
pub fn output_vector(case: &Case, o: &Outcome) -> [f64; 17] {
    let r = case.params.radius() as f64;
    let m = case.params.mass() as f64;
    let v = |x: f32| x as f64;
    [
        v(o.cue_ball.velocity.x),
        v(o.cue_ball.velocity.y),
        v(o.cue_ball.velocity.z),
        v(o.object_ball.velocity.x),
        v(o.object_ball.velocity.y),
        v(o.object_ball.velocity.z),
        r * v(o.cue_ball.spin.x),
        r * v(o.cue_ball.spin.y),
        r * v(o.cue_ball.spin.z),
        r * v(o.object_ball.spin.x),
        r * v(o.object_ball.spin.y),
        r * v(o.object_ball.spin.z),
        v(o.impulses.normal) / m,
        v(o.impulses.friction.x) / m,
        v(o.impulses.friction.y) / m,
        v(o.impulses.friction.z) / m,
        v(o.impulses.table_friction) / m,
    ]
}

/// Largest component deviation of the f32 outputs from the f64 ones beyond
/// `1e-5 |x₆₄| + 1e-6 U`, in m/s per unit mass (0 when within).
pub fn precision_excess(case: &Case, a: &Outcome, b: &Outcome) -> f64 {
    let (x, y) = (output_vector(case, a), output_vector(case, b));
    let floor = 1e-6 * case.speed();
    x.iter()
        .zip(y.iter())
        .map(|(p, q)| ((p - q).abs() - 1e-5 * q.abs() - floor).max(0.0))
        .fold(0.0, f64::max)
}

/// The tier `Auto` (or any model) actually evaluates for this case.
pub fn tier(case: &Case, model: Model) -> Model {
    match model {
        Model::Auto { tolerance } => {
            cuesight::select_model(&case.params, &case.impact, tolerance).0
        }
        other => other,
    }
}

/// Extra f32-vs-f64 allowance (m/s per unit mass) where a tier's formula is
/// ill-conditioned, on top of `1e-5 |x| + 1e-6 U`:
///
/// * `Kim`: its friction direction is `v̂₀`, discontinuous at zero slip. `v₀` is formed
///   in f32 from inputs of size `S = |U_y| + R|ω_z| + R|ω_y|` with an error of at most
///   `2ε S`, which turns the friction impulse `J = μ p₀` by `2ε S/|v₀|`; outputs move by
///   at most `(1 + 1/ν)(1 + μ_s) ≤ 3.5 (1 + μ_s)` times the impulse change:
///   `A = 10 (1 + μ_s) J ε S / |v₀|` (rounded up from 7).
/// * `KimGrip` with a speed-dependent law: the grip impulse is a difference with an
///   absolute error of about `ε (a+b)/(a c)` m/s (the reported cancellation):
///   `A = 32 ε (a+b)/(a c)`.
/// * `Exact`: the end of restitution is the root of a work balance whose slope, the
///   final normal velocity `e* U_x`, vanishes with e*; a work error `δW ~ N ε U_x²`
///   (N = 24 steps) moves it by `min(√δW, δW/(e* U_x))`: `A = 2 U_x min(√ε, ε/e*)`.
pub fn precision_allowance(case: &Case, model: Model) -> f64 {
    match tier(case, model) {
        Model::Kim => {
            let (sy, sz) = slip(case);
            let v0 = sy.hypot(sz);
            if v0 == 0.0 {
                return f64::INFINITY;
            }
            let (u, w, r) = (
                case.impact.velocity(),
                case.impact.spin(),
                case.params.radius() as f64,
            );
            let size = (u.y as f64).abs() + r * (w.z as f64).abs() + r * (w.y as f64).abs();
            let p0 = 0.5 * (1.0 + case.params.restitution() as f64) * u.x as f64;
            let j = case.params.friction_law().at(v0 as f32) as f64 * p0;
            10.0 * (1.0 + case.params.mu_s() as f64) * j * EPS32 * size / v0
        }
        Model::KimGrip => match case.params.friction_law() {
            FrictionLaw::SpeedDependent { a, b, c } if b > 0.0 && c > 0.0 => {
                32.0 * EPS32 * (a as f64 + b as f64) / (a as f64 * c as f64)
            }
            _ => 0.0,
        },
        Model::Exact => {
            let e = case.params.restitution() as f64;
            let ux = case.impact.velocity().x as f64;
            let shape = if e > 0.0 {
                EPS32.sqrt().min(EPS32 / e)
            } else {
                EPS32.sqrt()
            };
            // Since Exact shares KimGrip's slip integral for a speed-dependent law (its
            // stick test and step budget), it shares that conditioning too.
            let law = match case.params.friction_law() {
                FrictionLaw::SpeedDependent { a, b, c } if b > 0.0 && c > 0.0 => {
                    32.0 * EPS32 * (a as f64 + b as f64) / (a as f64 * c as f64)
                }
                _ => 0.0,
            };
            // 4 (was 2): the impact's end is refined on actual partial steps, each
            // adding its own rounding to the flat work curve's √ε conditioning.
            4.0 * ux * shape + law
        }
        _ => 0.0,
    }
}

/// Energy (J/kg) a tier may create beyond rounding, with the reason (see
/// docs/reliability.md): `Kim` [`kim_energy_bound`]; `KimGrip` the work the
/// table-friction impulses could do if mistimed over the impact, `(X + μ_ct J_z⁺) p`
/// (per unit mass); the others nothing.
pub fn energy_allowance(case: &Case, model: Model, out: &Outcome) -> f64 {
    let m = case.params.mass() as f64;
    match tier(case, model) {
        Model::Kim => kim_energy_bound(case),
        Model::KimGrip => {
            let table = out.impulses.table_friction as f64 / m;
            let cue_table = case.params.cue_table_friction() as f64
                * (out.impulses.friction.z as f64 / m).max(0.0);
            (table + cue_table) * out.impulses.normal as f64 / m
        }
        _ => 0.0,
    }
}

/// Rounding allowance on energy, relative to the initial energy: 8ε for the closed
/// forms (a handful of roundings per output) and `SeedExact` (its impulses are
/// quadrature sums and roots of them, computed relative to the compression end; measured
/// gain ≤ 5.7ε on 200,000 cases), 32ε for `Exact` (sums over 24+ steps).
pub fn energy_rounding(case: &Case, model: Model) -> f64 {
    match tier(case, model) {
        Model::Exact => 32.0 * EPS32,
        _ => 8.0 * EPS32,
    }
}

/// Whether `model` may refuse the scene under its declared validity domain
/// (`cuesight::validity`), recomputed here in f64 from the inputs: `KimGrip` outside
/// `μ ≤ 1`, `μ·μ_s ≤ 0.2` (a speed-dependent law: its `μ(0)`), `μ·μ_ct ≤ 0.05` or, with `μ_ct > 0` and `μ > 0`, below
/// e* = 0.01; `Kim` where its friction
/// impulse `μ p₀` exceeds the stick impulse `s* = |K⁻¹ v₀|` (`K = diag(7, k_z)`,
/// `k_z = 6 − 2.5 μ_s` with the object ball pressed, else 6), with a band of 1e-4
/// around each limit for the core's f32 rounding. Other models never refuse.
pub fn may_refuse(params: &Params, impact: &Impact, model: Model) -> bool {
    outside_domain(params, impact, model, -1e-4)
}

/// The declared domain's complement with the limits moved by the relative `slack`.
fn outside_domain(params: &Params, impact: &Impact, model: Model, slack: f64) -> bool {
    match model {
        Model::KimGrip => {
            let mu = params.mu() as f64;
            // μ ≤ 1 (every accepted law; a speed-dependent one's μ(0)), μ·μ_s ≤ 0.2.
            let (max_mu, max_mu_mu_s) = (1.0, 0.2);
            mu > max_mu * (1.0 + slack)
                || mu * params.mu_s() as f64 > max_mu_mu_s * (1.0 + slack)
                || mu * params.cue_table_friction() as f64 > 0.05 * (1.0 + slack)
                || (params.cue_table_friction() > 0.0
                    && params.mu() > 0.0
                    && params.restitution() < 0.01)
        }
        Model::Kim => {
            let (u, w, r) = (impact.velocity(), impact.spin(), params.radius() as f64);
            let (v_y, v_z) = (-(u.y as f64) - r * w.z as f64, r * w.y as f64);
            let k_z = if v_z > 0.0 {
                6.0 - 2.5 * params.mu_s() as f64
            } else {
                6.0
            };
            let stick = (v_y / 7.0).hypot(v_z / k_z);
            let slip = v_y.hypot(v_z);
            // A slip within the f32 rounding of its inputs may be exact gearing to the
            // core (answered without friction) or a gripping slip (refused): either.
            let size = (u.y as f64).abs() + r * ((w.z as f64).abs() + (w.y as f64).abs());
            if slip <= 4.0 * EPS32 * size {
                return slack < 0.0;
            }
            let mu = params.friction_law().at(slip as f32) as f64;
            let p0 = 0.5 * (1.0 + params.restitution() as f64) * u.x as f64;
            // The f32 slip carries an absolute error of a few roundings of its inputs;
            // relative to the slip it widens the band.
            let band = slack.abs() + 8.0 * EPS32 * size / slip;
            mu * p0 > stick * (1.0 + slack.signum() * band)
        }
        _ => false,
    }
}

/// `collide`, where a refusal ([`cuesight::Error::OutsideValidity`]) is `None` and
/// must be one the domain declares ([`may_refuse`]); an answer well outside the
/// domain (1e-4 past a limit) and any other error panic.
pub fn answer(params: &Params, impact: &Impact, model: Model) -> Option<Outcome> {
    match collide(params, impact, model) {
        Ok(_) if outside_domain(params, impact, model, 1e-4) => {
            panic!("{model:?} answered outside its domain ({params:?} {impact:?})")
        }
        Ok(out) => Some(out),
        Err(cuesight::Error::OutsideValidity { .. }) if may_refuse(params, impact, model) => None,
        Err(e) => panic!("{model:?}: {e} ({params:?} {impact:?})"),
    }
}
