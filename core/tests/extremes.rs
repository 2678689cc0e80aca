//! Extremes suite for the core's collision and strike entry points (issue 6, item 1):
//! named tests at the edges of the physics — cut angles 1e-6 rad from 0 and ±90°, zero
//! spin, exact natural roll, exact gearing (zero initial slip), μ ∈ {0, 1e-7, 0.3},
//! e* ∈ {0, 1}, μ_s ∈ {0, 1}, speeds 1 mm/s–20 m/s (and the 100 m/s limit), every ball
//! set, subnormal-scale inputs — and continuity across every regime switch, bisected to
//! adjacent f32 values. Every output finite, mirror symmetry exact.
//!
//! `host-tests/tests/extremes.rs` already covers a 450-input grid against the reference
//! and `KimGrip`'s grip boundary in μ on 300 pool scenes; this file extends both.

mod common;

use common::*;
use cuesight::strike::{strike, Cue, TipOffset};
use cuesight::{collide, collide_f64, FrictionLaw, Impact, Model, Outcome, Params, Regime, Vec3};
use cuesight_figures::thousands;

/// Every model, `Auto` at a loose and a tight tolerance.
const ALL: [Model; 7] = [
    Model::Ideal,
    Model::Kim,
    Model::KimGrip,
    Model::SeedExact,
    Model::Exact,
    Model::Auto { tolerance: 1e-2 },
    Model::Auto { tolerance: 1e-6 },
];

/// Every model in f32 and f64: no error but a declared refusal ([`answer`]), finite
/// outputs and angles; the exact mirror image (built independently by `mirror`) gives
/// the mirrored outcome bit for bit, or the same refusal.
fn check_all(params: &Params, impact: &Impact, mirror: &Impact, what: &str) {
    check_models(&ALL, params, impact, mirror, what)
}

fn check_models(models: &[Model], params: &Params, impact: &Impact, mirror: &Impact, what: &str) {
    for &model in models {
        let Some(out) = answer(params, impact, model) else {
            assert_eq!(
                collide(params, mirror, model).err(),
                collide(params, impact, model).err(),
                "{what}: {model:?} mirror"
            );
            continue;
        };
        assert!(out.is_finite(), "{what}: {model:?} {out:?}");
        assert!(
            out.throw_angle().is_finite()
                && out.cue_deflection().is_finite()
                && out.separation_angle_deg().is_finite(),
            "{what}: {model:?} angles"
        );
        assert!(out.impulses.normal >= 0.0, "{what}: {model:?} {out:?}");
        match collide_f64(params, impact, model) {
            Ok(wide) => assert!(wide.is_finite(), "{what}: {model:?} f64"),
            // f32 answered at the edge of the domain; f64 may fall just outside.
            Err(cuesight::Error::OutsideValidity { .. }) if may_refuse(params, impact, model) => {}
            Err(e) => panic!("{what}: {model:?} f64 -> {e}"),
        }
        let image = collide(params, mirror, model).unwrap();
        if let Some(field) = mirror_mismatch(&out, &image) {
            panic!("{what}: {model:?} mirror differs in {field}: {out:?} vs {image:?}");
        }
    }
}

fn mirrored(impact: &Impact) -> Impact {
    mirror_impact(impact)
}

fn spins(speed: f32, cut: f32, radius: f32) -> [(&'static str, [f32; 3]); 7] {
    let (vx, vy) = (speed * cut.cos(), speed * cut.sin());
    [
        ("zero spin", [0.0; 3]),
        ("natural roll", [-vy / radius, vx / radius, 0.0]),
        ("draw 2x", [2.0 * vy / radius, -2.0 * vx / radius, 0.0]),
        ("gearing", [0.0, 0.0, -vy / radius]),
        (
            "gearing with topspin",
            [0.0, 0.5 * speed / radius, -vy / radius],
        ),
        ("side 4 U/R", [0.0, 0.0, (4.0 * speed / radius).min(1e4)]),
        ("spin limit", [1e4, -1e4, 1e4]),
    ]
}

fn params_set(radius: f32, mass: f32) -> Vec<(String, Params)> {
    let mut out = Vec::new();
    for mu in [0.0f32, 1e-7, 0.3] {
        for e in [0.0f32, 1.0] {
            for mu_s in [0.0f32, 1.0] {
                let p = Params::new(mu, e, mu_s, radius, mass).unwrap();
                out.push((format!("μ {mu} e {e} μs {mu_s}"), p));
            }
        }
    }
    out.push((
        "Marlow μ(v), μ_ct 0.3".into(),
        Params::new(0.0, 0.95, 0.3, radius, mass)
            .unwrap()
            .with_friction_law(FrictionLaw::MARLOW)
            .with_cue_table_friction(0.3)
            .unwrap(),
    ));
    out
}

/// Cut angles 0, ±1e-6 rad and ±(π/2 − 1e-6) rad through `Impact::from_cut`, speeds
/// 1 mm/s–20 m/s, every ball set, μ ∈ {0, 1e-7, 0.3} × e* ∈ {0, 1} × μ_s ∈ {0, 1} (and
/// Marlow's law with μ_ct 0.3), seven spins: 4,914 inputs × 6 models × f32/f64/mirror.
#[test]
fn cut_angle_limits_speeds_and_ball_sets() {
    let half_pi = core::f32::consts::FRAC_PI_2;
    let mut count = 0;
    for (_, radius, mass) in BALLS {
        for (pname, params) in params_set(radius, mass) {
            for cut in [0.0f32, 1e-6, half_pi - 1e-6] {
                for speed in [1e-3f32, 0.01, 0.2, 2.0, 8.0, 20.0] {
                    for (sname, spin) in spins(speed, cut, radius) {
                        let spin = spin.map(|w| w.clamp(-1e4, 1e4));
                        let impact = Impact::from_cut(speed, cut, spin).unwrap();
                        let image =
                            Impact::from_cut(speed, -cut, [-spin[0], spin[1], -spin[2]]).unwrap();
                        // `from_cut` builds the mirror image exactly (sin is odd).
                        assert_eq!(image, mirrored(&impact));
                        let what = format!("{pname}, φ {cut} rad, U {speed}, {sname}, R {radius}");
                        check_all(&params, &impact, &image, &what);
                        count += 1;
                    }
                }
            }
        }
    }
    assert_eq!(count, 3 * 13 * 3 * 6 * 7);
    cuesight_figures::record!("reliability-extremes-cut-inputs", "{}", thousands(count));
}

/// Head-on shots: exactly no sideways output for any model (nothing breaks the
/// symmetry), and φ = ±1e-6 rad stays within 1e-5 U of head-on.
#[test]
fn head_on_is_symmetric_and_near_head_on_is_continuous() {
    for (_, radius, mass) in BALLS {
        for (pname, params) in params_set(radius, mass) {
            for top in [-2.0f32, 0.0, 1.0, 3.0] {
                let speed = 2.0;
                let head_on =
                    Impact::from_cut(speed, 0.0, [0.0, top * speed / radius, 0.0]).unwrap();
                for model in ALL {
                    // Kim refuses every stun shot here (zero slip: it grips).
                    let Some(a) = answer(&params, &head_on, model) else {
                        continue;
                    };
                    for v in [a.cue_ball.velocity, a.object_ball.velocity] {
                        assert_eq!(v.y, 0.0, "{pname} {model:?}");
                    }
                    for w in [a.cue_ball.spin, a.object_ball.spin] {
                        assert_eq!((w.x, w.z), (0.0, 0.0), "{pname} {model:?}");
                    }
                    for cut in [1e-6f32, -1e-6] {
                        let near =
                            Impact::from_cut(speed, cut, [0.0, top * speed / radius, 0.0]).unwrap();
                        let Some(b) = answer(&params, &near, model) else {
                            continue;
                        };
                        let jump = max_difference(&a, &b, radius) / speed;
                        // Kim's friction direction turns by 90° when a 1e-6 U side slip
                        // appears on a stun shot (its zero-slip discontinuity).
                        let kim_stun =
                            top == 0.0 && matches!(tier_of(&params, &near, model), Model::Kim);
                        if !kim_stun {
                            assert!(
                                jump < 1e-5,
                                "{pname} top {top} {model:?} φ {cut}: {jump:e} U"
                            );
                        }
                    }
                }
            }
        }
    }
}

fn tier_of(params: &Params, impact: &Impact, model: Model) -> Model {
    match model {
        Model::Auto { tolerance } => cuesight::select_model(params, impact, tolerance).0,
        m => m,
    }
}

/// Exact natural roll from `Impact::rolling` (table-contact slip zero) at every cut,
/// speed and ball set: every model finite; for a rolling cue ball the ball–ball slip has
/// no `y` part at φ = 0 and topspin `U/R`.
#[test]
fn exact_natural_roll() {
    for (_, radius, mass) in BALLS {
        let params = Params::POOL.with_ball(radius, mass).unwrap();
        for deg in [0.0f32, 1e-4, 30.0, 60.0, 89.0, 89.99] {
            for speed in [1e-3f32, 0.5, 5.0, 20.0] {
                let (s, c) = (deg.to_radians().sin(), deg.to_radians().cos());
                let impact = Impact::rolling([speed * c, speed * s], radius).unwrap();
                let w = impact.spin();
                assert_eq!(w.z, 0.0);
                let contact = impact.velocity() + w.cross(Vec3::new(0.0, 0.0, -radius));
                assert!(contact.length() <= 4e-7 * speed, "{contact:?}");
                let image = Impact::rolling([speed * c, -speed * s], radius).unwrap();
                check_all(&params, &impact, &image, &format!("roll {deg}° U {speed}"));
            }
        }
        let head_on = Impact::rolling([2.0, 0.0], radius).unwrap();
        let (sy, sz) = head_on.initial_slip(radius);
        assert_eq!(sy, 0.0);
        assert!((sz - 2.0).abs() < 1e-6);
    }
}

/// Exact gearing: `R ω_z = −v_y` and `ω_y = 0` exactly in f32 (`v_y = 8R`, `ω_z = −8`):
/// zero initial slip, so no ball–ball friction at all; every model but `Ideal` reports
/// `Gripping` with zero friction impulse, and the normal impulse is the frictionless one.
#[test]
fn exact_gearing_has_no_friction() {
    for (_, radius, mass) in BALLS {
        for (pname, params) in params_set(radius, mass) {
            let vy = 8.0 * radius;
            for (vx, wx) in [(1.0f32, 0.0f32), (0.2, 50.0), (1e-3, -3.0)] {
                let impact = Impact::from_velocity([vx, vy], [wx, 0.0, -8.0]).unwrap();
                assert_eq!(impact.initial_slip(radius), (0.0, 0.0));
                let image = mirrored(&impact);
                check_all(&params, &impact, &image, &format!("gearing {pname}"));
                for model in [Model::Kim, Model::KimGrip, Model::SeedExact, Model::Exact] {
                    let Some(out) = answer(&params, &impact, model) else {
                        continue;
                    };
                    let expected = if params.friction_law().is_frictionless() {
                        Regime::Frictionless
                    } else {
                        Regime::Gripping
                    };
                    assert_eq!(out.regime, expected, "{pname} {model:?}");
                    assert_eq!(out.impulses.friction, Vec3::ZERO, "{pname} {model:?}");
                    assert_eq!(out.impulses.table_friction, 0.0);
                    let p0 = 0.5 * (1.0 + params.restitution()) * vx * mass;
                    assert!(
                        (out.impulses.normal - p0).abs() <= 1e-6 * p0,
                        "{pname} {model:?} {} vs {p0}",
                        out.impulses.normal
                    );
                    // The cue ball keeps its spin.
                    assert_eq!(out.cue_ball.spin, impact.spin(), "{pname} {model:?}");
                }
            }
        }
    }
}

/// Subnormal-scale inputs: spins of 1e-40 rad/s, speeds of 1e-30 m/s, v_y of 1e-40,
/// μ, μ_s, e* and μ_ct at the smallest subnormal, and the largest accepted values.
/// Every model finite, no error, no energy created beyond rounding, mirror exact.
#[test]
fn subnormal_and_limit_inputs() {
    let tiny = f32::from_bits(1);
    let params_list = [
        Params::POOL,
        Params::new(tiny, tiny, tiny, 0.001, 0.001)
            .unwrap()
            .with_cue_table_friction(tiny)
            .unwrap(),
        Params::new(1.0, 1.0, 1.0, 1.0, 100.0)
            .unwrap()
            .with_cue_table_friction(1.0)
            .unwrap(),
        Params::POOL.with_friction_law(FrictionLaw::speed_dependent(1e-6, 0.5, 100.0).unwrap()),
    ];
    let impacts = [
        ([1.0f32, 0.0], [1e-40f32, 1e-40, 1e-40]),
        ([1.0, 1e-40], [0.0, -1e-40, 0.0]),
        ([1e-30, 0.0], [0.0; 3]),
        ([1e-30, 1e-30], [1e-40, 1e-40, -1e-40]),
        ([1e-30, 0.0], [0.0, 1e4, 0.0]),
        ([1e-40, 0.0], [0.0, 0.0, 1e-40]),
        ([2.0 * tiny, 100.0], [1e4, 1e4, 1e4]),
        ([100.0, -100.0], [-1e4, -1e4, 1e4]),
        ([100.0, 0.0], [0.0, 1e-40, 0.0]),
    ];
    for params in params_list {
        for (v, w) in impacts {
            let impact = Impact::from_velocity(v, w).unwrap();
            let image = mirrored(&impact);
            let what = format!("{params:?} v {v:?} ω {w:?}");
            let case = Case {
                params,
                impact,
                tolerance: 1e-3,
            };
            let models: &[Model] = &ALL;
            check_models(models, &params, &impact, &image, &what);
            for &model in models {
                let Some(out) = answer(&params, &impact, model) else {
                    continue;
                };
                let (before, after) = energies(&case, &out);
                let allowance = energy_allowance(&case, model, &out);
                assert!(
                    after <= before * (1.0 + energy_rounding(&case, model)) + allowance,
                    "{what} {model:?}: {before:e} -> {after:e}"
                );
            }
        }
    }
}

/// Largest difference between two outcomes, `max(|Δv|, R|Δω|)` over both balls (m/s).
fn max_difference(a: &Outcome, b: &Outcome, radius: f32) -> f32 {
    let d = |x: Vec3, y: Vec3| (x - y).length();
    [
        d(a.cue_ball.velocity, b.cue_ball.velocity),
        d(a.object_ball.velocity, b.object_ball.velocity),
        radius * d(a.cue_ball.spin, b.cue_ball.spin),
        radius * d(a.object_ball.spin, b.object_ball.spin),
    ]
    .into_iter()
    .fold(0.0, f32::max)
}

/// Bisect `x ∈ [lo, hi]` (same sign) to adjacent f32 values where `key` changes;
/// `None` if it does not change between the ends.
fn bisect<K: PartialEq>(lo: f32, hi: f32, key: impl Fn(f32) -> K) -> Option<(f32, f32)> {
    let (mut lo, mut hi) = (lo, hi);
    let k_lo = key(lo);
    if k_lo == key(hi) {
        return None;
    }
    while hi.to_bits().abs_diff(lo.to_bits()) > 1 {
        let mid = f32::from_bits((lo.to_bits() + hi.to_bits()) / 2);
        if key(mid) == k_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((lo, hi))
}

/// Deterministic scenes from the property-test domain, away from the reported
/// speed-dependent bug region.
fn scenes(count: usize, seed: u64) -> Vec<Case> {
    let mut state = seed;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 32) as u32
    };
    (0..count)
        .map(|_| {
            let mut raw = [0u32; 16];
            raw.iter_mut().for_each(|r| *r = next());
            Case::decode(raw)
        })
        .collect()
}

/// One regime switch: the parameter bisected and how to rebuild the input.
type Rebuild = fn(&Case, f32) -> Option<(Params, Impact)>;

fn switches() -> [(&'static str, f32, f32, Rebuild); 5] {
    [
        ("μ", 1e-6, 0.3, |c, x| {
            Some((c.params.with_mu(x).ok()?, c.impact))
        }),
        ("e*", 1e-6, 1.0, |c, x| {
            Some((c.params.with_restitution(x).ok()?, c.impact))
        }),
        ("μ_s", 1e-6, 1.0, |c, x| {
            Some((c.params.with_mu_s(x).ok()?, c.impact))
        }),
        ("μ_ct", 1e-6, 0.3, |c, x| {
            Some((c.params.with_cue_table_friction(x).ok()?, c.impact))
        }),
        // Speed at fixed spin: the slip-to-impulse ratio sweeps through the boundary.
        ("U", 1e-3, 20.0, |c, x| {
            let v = c.impact.velocity();
            let s = x / c.impact.speed();
            let w = c.impact.spin();
            Some((
                c.params,
                Impact::from_velocity([v.x * s, v.y * s], [w.x, w.y, w.z]).ok()?,
            ))
        }),
    ]
}

/// Continuity across the slide/grip boundary of `KimGrip`, `SeedExact` and `Exact`,
/// bisected in μ, e*, μ_s, μ_ct and U to adjacent f32 values on 400 scenes of the whole
/// domain (every ball set, constant and speed-dependent friction): the outputs on either
/// side differ by less than 2e-5 U for `KimGrip` and `SeedExact` (its stick branch is the
/// limit of its sliding solution; the root solves stop within 2 ε of `q`), and 2e-3 U for
/// `Exact` (1.4e-3 U before the fix of docs/reliability.md's bug 2; see
/// `exact_is_continuous_at_stick_onset`). The measured jumps are the figures
/// `reliability-extremes-grip-kimgrip-jump` and `-exact-jump` (docs/reliability.md).
#[test]
fn grip_boundary_is_continuous_in_every_parameter() {
    const MODELS: [(Model, f32); 3] = [
        (Model::KimGrip, 2e-5),
        (Model::SeedExact, 2e-5),
        (Model::Exact, 2e-3),
    ];
    let mut worst = [[0.0f32; 5]; MODELS.len()];
    let mut crossings = [[0usize; 5]; MODELS.len()];
    for case in scenes(400, 6) {
        for (k, (_, lo, hi, rebuild)) in switches().into_iter().enumerate() {
            for (m, (model, bound)) in MODELS.into_iter().enumerate() {
                let eval = |x: f32| {
                    rebuild(&case, x).and_then(|(p, i)| {
                        let c = Case {
                            params: p,
                            impact: i,
                            tolerance: 1.0,
                        };
                        if in_tiny_slip_bug_region(&c) {
                            None
                        } else {
                            answer(&p, &i, model)
                        }
                    })
                };
                let key = |x: f32| eval(x).map(|o| o.regime);
                let Some((a, b)) = bisect(lo, hi, key) else {
                    continue;
                };
                let (Some(oa), Some(ob)) = (eval(a), eval(b)) else {
                    continue;
                };
                crossings[m][k] += 1;
                let speed = rebuild(&case, a).unwrap().1.speed();
                let jump = max_difference(&oa, &ob, case.params.radius()) / speed;
                worst[m][k] = worst[m][k].max(jump);
                assert!(
                    jump < bound,
                    "{model:?}: jump {jump:e} U between {a} and {b} ({:?} -> {:?}) in {case:?}",
                    oa.regime,
                    ob.regime
                );
            }
        }
    }
    for (m, (model, _)) in MODELS.into_iter().enumerate() {
        for (k, (var, ..)) in switches().into_iter().enumerate() {
            println!(
                "{:10} in {var:4}: {:3} crossings, largest jump {:.2e} U",
                model.name(),
                crossings[m][k],
                worst[m][k]
            );
        }
    }
    // docs/physics.md §7: SeedExact's largest jump over every bisected parameter.
    let seed_exact = MODELS
        .iter()
        .position(|(model, _)| *model == Model::SeedExact)
        .expect("SeedExact is bisected");
    cuesight_figures::record!(
        "physics-seed-exact-boundary-jump-domain",
        "{:.1e}",
        worst[seed_exact].iter().fold(0.0f32, |a, &b| a.max(b))
    );
    assert!(crossings.iter().all(|c| c[0] > 50), "{crossings:?}");
    // The figures docs/reliability.md quotes: over the five parameters bisected.
    let total = |m: usize| crossings[m].iter().sum::<usize>();
    let largest = |m: usize| worst[m].iter().copied().fold(0.0f32, f32::max);
    cuesight_figures::record!(
        "reliability-extremes-grip-kimgrip-crossings",
        "{}",
        total(0)
    );
    cuesight_figures::record!(
        "reliability-extremes-grip-kimgrip-jump",
        "{:.1e}",
        largest(0)
    );
    cuesight_figures::record!("reliability-extremes-grip-exact-jump", "{:.1e}", largest(2));
}

/// `μ → 0`: the frictionless result (μ = 0) and the smallest subnormal μ agree to 1e-6 U
/// for every model and every grid scene; so do μ_s, μ_ct → 0, except `KimGrip` at
/// μ_ct → 0: any μ_ct > 0 takes its general path (the slide in pieces, `docs/physics.md`
/// §4 item 8) where μ_ct = 0 may take its fast path (the single mid-point direction),
/// a change of method held to twice its declared bound (each side is within the bound
/// of the reference) and recorded.
#[test]
fn friction_to_zero_is_continuous() {
    let tiny = f32::from_bits(1);
    let mut kim_grip_cue_table = 0.0f32;
    for case in scenes(300, 7) {
        let p = case.params;
        for (name, zero, small) in [
            ("μ", p.with_mu(0.0).unwrap(), p.with_mu(tiny).unwrap()),
            ("μ_s", p.with_mu_s(0.0).unwrap(), p.with_mu_s(tiny).unwrap()),
            (
                "μ_ct",
                p.with_cue_table_friction(0.0).unwrap(),
                p.with_cue_table_friction(tiny).unwrap(),
            ),
        ] {
            for model in ALL {
                // Both refused (μ·μ_s past KimGrip's limit), or only the tiny μ_ct at
                // e* < 0.01 (the domain's own edge): nothing to compare.
                let (Some(a), Some(b)) = (
                    answer(&zero, &case.impact, model),
                    answer(&small, &case.impact, model),
                ) else {
                    continue;
                };
                let jump = max_difference(&a, &b, p.radius()) / case.impact.speed();
                // (`Auto` takes `KimGrip` at a tolerance of 5e-3 or more.)
                if name == "μ_ct" && matches!(model, Model::KimGrip | Model::Auto { .. }) {
                    if model == Model::KimGrip {
                        kim_grip_cue_table = kim_grip_cue_table.max(jump);
                    }
                    assert!(
                        jump < 2.0 * cuesight::KIM_GRIP_DECLARED_BOUND,
                        "{name} {model:?}: {jump:e} U in {case:?}"
                    );
                    continue;
                }
                assert!(jump <= 1e-6, "{name} {model:?}: {jump:e} U in {case:?}");
            }
        }
    }
    cuesight_figures::record!(
        "reliability-extremes-kimgrip-cue-table-to-zero",
        "{:.1e}",
        kim_grip_cue_table
    );
}

/// `KimGrip` is continuous through zero slip (exact gearing ± a few ulps of side spin)
/// and through the switch of the pressed ball (ω_y through 0): the stick impulse is
/// linear in the slip. `Kim` is not — its friction impulse keeps the size μ p₀ whatever
/// the slip, a jump of up to 2.5 μ p₀ until its validity domain — so near zero slip with
/// μ > 0 it now refuses (the contact grips: `Reason::Grips`).
#[test]
fn zero_slip_continuity() {
    let mut kim_refusals = 0usize;
    for (_, radius, mass) in BALLS {
        for (pname, params) in params_set(radius, mass) {
            let vy = 8.0 * radius;
            let geared = Impact::from_velocity([1.0, vy], [0.0, 0.0, -8.0]).unwrap();
            let Some(at) = answer(&params, &geared, Model::KimGrip) else {
                continue;
            };
            for ulps in [1u32, 2, 16, 256] {
                for sign in [1i32, -1] {
                    let wz = f32::from_bits((8.0f32.to_bits() as i32 + sign * ulps as i32) as u32);
                    let wy = sign as f32 * ulps as f32 * 1e-6;
                    for spin in [[0.0, 0.0, -wz], [0.0, wy, -8.0], [0.0, wy, -wz]] {
                        let near = Impact::from_velocity([1.0, vy], spin).unwrap();
                        let out = answer(&params, &near, Model::KimGrip).unwrap();
                        let (sy, sz) = near.initial_slip(radius);
                        let slip = sy.hypot(sz);
                        let jump = max_difference(&at, &out, radius);
                        // The inputs themselves differ by R|Δω|.
                        let input = radius * (near.spin() - geared.spin()).length();
                        // Outputs move by at most the slip they cancel (× 1/ν for R ω).
                        assert!(
                            jump <= input + 2.5 * slip + 1e-6,
                            "{pname}: jump {jump:e} for slip {slip:e}"
                        );
                        // Refused iff μ p₀ exceeds the stick impulse (`answer` checks it).
                        if answer(&params, &near, Model::Kim).is_none() {
                            kim_refusals += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(kim_refusals > 0, "no scene with friction near zero slip");
    cuesight_figures::record!(
        "reliability-extremes-kim-zero-slip-refusals",
        "{kim_refusals}"
    );
}

/// `Auto` switches tier where an estimate crosses the tolerance; the jump across that
/// switch (bisected in μ) is the difference of two tiers that both meet the tolerance
/// when the estimates bound the errors, so it would stay within 2 × tolerance × U; the
/// stated bound is 4 × (the largest measured: docs/reliability.md, §4). Checked
/// on the domain the estimates were calibrated and validated on (the foundation
/// domain: μ 0.02–0.1, e* 0.9–1, μ_s 0–0.4, μ_ct = 0; here with every ball set, U 1 mm/s
/// –20 m/s and spins to 4 U/R). Outside it (μ to 0.3, μ_s to 1, e* to 0, μ_ct > 0) the
/// estimates are not calibrated and the jump reaches ~10× the tolerance:
/// `bug_auto_estimates_outside_their_calibration_domain`.
#[test]
fn auto_tier_switch_jumps_are_within_twice_the_tolerance() {
    let (crossings, worst, at) = auto_switch_jumps(true);
    println!(
        "Auto, calibration domain: {crossings} tier switches, largest jump {worst:.3} × tolerance"
    );
    assert!(crossings > 100);
    // Once measured 3.13 (the figure now: docs/reliability.md §4): spins to 4 U/R, speeds to 20 m/s and grazing cuts go beyond the
    // grid the estimates were checked on, and there they can under-estimate by ~1.6×.
    assert!(worst <= 4.0, "{worst} at {at}");
    cuesight_figures::record!("reliability-extremes-auto-switches", "{crossings}");
    cuesight_figures::record!("reliability-extremes-auto-jump", "{worst:.2}");
}

/// (crossings, largest jump / tolerance, where) over 300 scenes × 3 tolerances, μ
/// bisected in the calibration range (`calibrated`) or 1e-6–0.3.
fn auto_switch_jumps(calibrated: bool) -> (usize, f32, String) {
    let mut worst = 0.0f32;
    let mut at = String::new();
    let mut crossings = 0;
    for mut case in scenes(300, 8) {
        let (lo, hi) = if calibrated {
            let p = case.params;
            case.params = p
                .with_restitution(0.9 + 0.1 * p.restitution())
                .and_then(|p| p.with_mu_s(0.4 * p.mu_s()))
                .and_then(|p| p.with_cue_table_friction(0.0))
                .unwrap();
            (0.02, 0.1)
        } else {
            (1e-6, 0.3)
        };
        for tolerance in [1e-2f32, 1e-3, 1e-4] {
            let key = |mu: f32| {
                let p = case.params.with_mu(mu).unwrap();
                cuesight::select_model(&p, &case.impact, tolerance).0
            };
            let Some((a, b)) = bisect(lo, hi, key) else {
                continue;
            };
            crossings += 1;
            let model = Model::Auto { tolerance };
            let oa = collide(&case.params.with_mu(a).unwrap(), &case.impact, model).unwrap();
            let ob = collide(&case.params.with_mu(b).unwrap(), &case.impact, model).unwrap();
            let jump = max_difference(&oa, &ob, case.params.radius()) / case.impact.speed();
            if jump / tolerance > worst {
                worst = jump / tolerance;
                at = format!(
                    "Auto {tolerance}: {:?} -> {:?} at μ {a}..{b}: {case:?}",
                    key(a),
                    key(b)
                );
            }
        }
    }
    (crossings, worst, at)
}

#[test]
fn auto_is_continuous_outside_the_calibration_domain() {
    let (crossings, worst, at) = auto_switch_jumps(false);
    println!("Auto, whole domain: {crossings} tier switches, largest jump {worst:.3} × tolerance");
    assert!(worst <= 2.0, "jump {worst} × tolerance at {at}");
    cuesight_figures::record!("reliability-extremes-auto-outside-jump", "{worst:.1}");
}

/// `Exact` at its slide → grip switch, in the same bisection as
/// `grip_boundary_is_continuous_in_every_parameter`, held to its own accuracy target
/// (0.02 % = 2e-4 U). Before the fix of docs/reliability.md's bug 2 it failed: the largest jump
/// was 1.4e-3 U, and 1.1e-2 U with a speed-dependent law at a tiny slip (U 4.4265 m/s,
/// stun, μ(v) = 0.031 + 0.174 e^{−6.3 v}).
#[test]
fn exact_is_continuous_at_stick_onset() {
    let mut worst = (0.0f32, String::new());
    for case in scenes(400, 6) {
        for (var, lo, hi, rebuild) in switches() {
            let eval =
                |x: f32| rebuild(&case, x).map(|(p, i)| collide(&p, &i, Model::Exact).unwrap());
            let Some((a, b)) = bisect(lo, hi, |x| eval(x).map(|o| o.regime)) else {
                continue;
            };
            let (Some(oa), Some(ob)) = (eval(a), eval(b)) else {
                continue;
            };
            let speed = rebuild(&case, a).unwrap().1.speed();
            let jump = max_difference(&oa, &ob, case.params.radius()) / speed;
            if jump > worst.0 {
                worst = (jump, format!("{var} {a}..{b}: {case:?}"));
            }
        }
    }
    assert!(worst.0 < 2e-4, "jump {:e} U at {}", worst.0, worst.1);
}

/// Subnormal inputs that once gave `KimGrip` a `NumericalFailure`: (1) the smallest
/// subnormal approach speed with e* = 0 — the frictionless normal impulse underflows to
/// 0 (now: no impulse, no friction); (2) a speed-dependent law with a subnormal
/// high-speed limit `a` — now refused at construction (`a ≥ 1e-6`), while `a = 1e-6`
/// at a subnormal-scale slip works (found with b = 0.5; b is now 0.1 − 1e-6, inside
/// KimGrip's validity domain).
#[test]
fn kim_grip_subnormal_inputs() {
    let params = Params::POOL.with_restitution(0.0).unwrap();
    let impact = Impact::from_velocity([f32::from_bits(1), 0.0], [0.0, 0.0, 1.0]).unwrap();
    let first = collide(&params, &impact, Model::KimGrip);
    assert!(first.is_ok(), "{first:?}");
    let refused = FrictionLaw::speed_dependent(f32::from_bits(1), 0.5, 100.0);
    assert_eq!(
        refused.unwrap_err().field(),
        Some(cuesight::Field::Friction)
    );
    // μ(0) = a + b = 0.1: inside KimGrip's validity domain (μ(0)·μ_s = 0.02).
    let law = FrictionLaw::speed_dependent(1e-6, 0.1 - 1e-6, 100.0).unwrap();
    let params = Params::POOL.with_friction_law(law);
    let impact = Impact::from_velocity([1.0, 0.0], [1e-40; 3]).unwrap();
    for model in Model::ALL {
        // Kim refuses: a slip of 1e-40-scale grips at once.
        assert!(answer(&params, &impact, model).is_some() || model == Model::Kim);
    }
}

/// Strike entry points at their limits, chained into every model: cue speed from the
/// smallest subnormal to 20 m/s, tip offsets on the 0.5 R circle, every ball set, cue
/// mass 0.1–2 kg, e_t 0 and 1; `to_impact` at ±(π/2 − 1e-6) rad. Left and right english
/// mirror exactly.
#[test]
fn strike_limits_chain_into_every_model() {
    let tiny = f32::from_bits(1);
    for (_, radius, mass) in BALLS {
        let params = Params::POOL.with_ball(radius, mass).unwrap();
        for cue in [
            Cue::new(0.1, 0.0).unwrap(),
            Cue::TYPICAL,
            Cue::new(2.0, 1.0).unwrap(),
        ] {
            for speed in [tiny, 1e-3, 1.0, 20.0] {
                for k in 0..8 {
                    let angle = k as f32 * core::f32::consts::FRAC_PI_4;
                    let (s, h) = (0.5 * angle.cos(), 0.5 * angle.sin());
                    let tip = TipOffset::from_radius_fraction(s, h, radius).unwrap();
                    let hit = match strike(&params, &cue, tip, speed) {
                        Ok(hit) => hit,
                        // Rounding can put |b| a hair above 0.5 R.
                        Err(e) => {
                            assert_eq!(e.field(), Some(cuesight::Field::TipOffset));
                            continue;
                        }
                    };
                    assert!(hit.speed.is_finite() && hit.spin.is_finite() && hit.speed >= 0.0);
                    let other = TipOffset::from_radius_fraction(-s, h, radius).unwrap();
                    let mirror_hit = strike(&params, &cue, other, speed).unwrap();
                    assert_eq!(mirror_hit.speed, hit.speed);
                    assert_eq!(
                        mirror_hit.spin,
                        Vec3::new(-hit.spin.x, hit.spin.y, -hit.spin.z)
                    );
                    if hit.speed == 0.0 {
                        continue; // a subnormal cue speed can give a zero ball speed
                    }
                    for cut in [0.0f32, 0.5, core::f32::consts::FRAC_PI_2 - 1e-6] {
                        let Ok(impact) = hit.to_impact(cut) else {
                            // U cos φ underflows for a subnormal ball speed.
                            assert!(hit.speed < 1e-30);
                            continue;
                        };
                        let image = mirror_hit.to_impact(-cut).unwrap();
                        assert_eq!(image, mirrored(&impact));
                        check_all(
                            &params,
                            &impact,
                            &image,
                            &format!("strike {speed} {k} {cut}"),
                        );
                    }
                }
            }
        }
    }
}
