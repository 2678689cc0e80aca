//! `KimGrip` against the first-principles reference on the seeded ≥ 10,000-scene grid
//! (foundation issue acceptance): max |Δv|/U ≤ 0.5 %, max R|Δω|/U ≤ 1 %, max throw
//! error ≤ 0.25°; zero panics and zero non-finite outputs for every model; the
//! reference creates no energy and balances y-momentum.
//!
//! The figures are printed and written to `$CARGO_TARGET_TMPDIR/grid-report.txt`.

use cuesight::{collide, Model, Regime};
use cuesight_host::compare::{reference, scene_error, thousands, Summary};
use cuesight_host::grid::{scenes, Scene};
use cuesight_host::reference::{ReferenceOutcome, ReferenceRegime};
use cuesight_host::validity::answer;
use std::fmt::Write as _;

const SEED: u64 = 2024;
const SCENES: usize = 10_000;

struct Solved {
    scene: Scene,
    reference: ReferenceOutcome,
}

fn solved_grid() -> Vec<Solved> {
    scenes(SEED, SCENES)
        .into_iter()
        .map(|scene| Solved {
            reference: reference(&scene).expect("grid scenes are valid reference input"),
            scene,
        })
        .collect()
}

#[test]
fn grid_accuracy_and_invariants() {
    let grid = solved_grid();
    assert!(grid.len() >= 10_000);
    let mut report = String::new();
    let gripping = grid
        .iter()
        .filter(|s| s.reference.regime == ReferenceRegime::Gripping)
        .count();
    writeln!(
        report,
        "grid seed {SEED}: {} scenes, {gripping} grip in the reference",
        grid.len()
    )
    .unwrap();

    // Every model: no error but a declared refusal (Kim where its contact grips),
    // finite outputs (the core turns non-finite into Err).
    let answer = |model: Model, s: &Solved| {
        answer(
            &s.scene.params(),
            &s.scene.impact(),
            model,
            &format!("{:?}", s.scene),
        )
    };
    for model in Model::ALL {
        for s in &grid {
            answer(model, s);
        }
    }

    // Errors over the scenes the model answers.
    let errors = |model: Model, filter: &dyn Fn(&Solved) -> bool| {
        Summary::of(
            grid.iter()
                .enumerate()
                .filter(|(_, s)| filter(s))
                .filter_map(|(i, s)| {
                    let out = answer(model, s)?;
                    Some((i, scene_error(&s.scene, &out, &s.reference)))
                }),
        )
    };
    let all = |_: &Solved| true;
    let sliding = |s: &Solved| s.reference.regime == ReferenceRegime::Sliding;
    let grips = |s: &Solved| s.reference.regime == ReferenceRegime::Gripping;
    let kim_refused = |filter: &dyn Fn(&Solved) -> bool| {
        grid.iter()
            .filter(|s| filter(s) && answer(Model::Kim, s).is_none())
            .count()
    };
    let (kim_refused_sliding, kim_refused_gripping) = (kim_refused(&sliding), kim_refused(&grips));
    writeln!(
        report,
        "Kim refuses {kim_refused_gripping} of the gripping scenes and {kim_refused_sliding} of the sliding ones"
    )
    .unwrap();

    let kim_grip = errors(Model::KimGrip, &all);
    writeln!(report, "KimGrip, all:            {kim_grip}").unwrap();
    let exact_sliding = errors(Model::Exact, &sliding);
    writeln!(report, "Exact, sliding scenes:   {exact_sliding}").unwrap();
    writeln!(
        report,
        "Exact, gripping scenes:  {}",
        errors(Model::Exact, &grips)
    )
    .unwrap();
    writeln!(
        report,
        "KimGrip, sliding scenes: {}",
        errors(Model::KimGrip, &sliding)
    )
    .unwrap();
    writeln!(
        report,
        "KimGrip, gripping scenes: {}",
        errors(Model::KimGrip, &grips)
    )
    .unwrap();
    writeln!(
        report,
        "Kim, sliding scenes:     {}",
        errors(Model::Kim, &sliding)
    )
    .unwrap();
    writeln!(
        report,
        "Kim, gripping scenes:    {}",
        errors(Model::Kim, &grips)
    )
    .unwrap();

    let regime_mismatch = grid
        .iter()
        .filter(|s| {
            let out = collide(&s.scene.params(), &s.scene.impact(), Model::KimGrip).unwrap();
            (out.regime == Regime::Gripping) != (s.reference.regime == ReferenceRegime::Gripping)
        })
        .count();
    writeln!(report, "KimGrip regime differs from the reference in {regime_mismatch} scenes (all at the boundary)")
        .unwrap();

    println!("{report}");

    // The figures of docs/physics.md §2, §4, §6 and §7.
    record_count("physics-grid-scenes", grid.len());
    record_count("physics-grid-gripping", gripping);
    record_count("physics-grid-sliding", grid.len() - gripping);
    record_count("physics-grid-kim-refused-gripping", kim_refused_gripping);
    record_count("physics-grid-kim-refused-sliding", kim_refused_sliding);
    record_count(
        "physics-grid-kimgrip-regime-agrees",
        grid.len() - regime_mismatch,
    );
    record_summary("physics-grid-kimgrip-all", &kim_grip, [3, 3, 3], [3, 3, 3]);
    record_summary(
        "physics-grid-kimgrip-sliding",
        &errors(Model::KimGrip, &sliding),
        [3, 3, 3],
        [3, 3, 3],
    );
    record_summary(
        "physics-grid-kimgrip-gripping",
        &errors(Model::KimGrip, &grips),
        [3, 3, 3],
        [3, 3, 3],
    );
    record_summary(
        "physics-grid-exact-sliding",
        &exact_sliding,
        [4, 4, 4],
        [4, 4, 4],
    );
    record_summary(
        "physics-grid-exact-gripping",
        &errors(Model::Exact, &grips),
        [4, 4, 4],
        [4, 4, 4],
    );
    record_summary(
        "physics-grid-kim-sliding",
        &errors(Model::Kim, &sliding),
        [2, 2, 2],
        [3, 2, 3],
    );
    record_summary(
        "physics-grid-kim-gripping",
        &errors(Model::Kim, &grips),
        [1, 0, 1],
        [1, 0, 1],
    );
    // How far inside the foundation tolerances (0.5 %, 1 %, 0.25°) KimGrip stays, and
    // Exact inside the fidelity ladder's 0.02 %, rounded down.
    let spare = (0.005 / kim_grip.max.velocity)
        .min(0.01 / kim_grip.max.spin)
        .min(0.25 / kim_grip.max.throw_deg);
    cuesight_figures::record!(
        "physics-grid-kimgrip-spare",
        "{:.1}",
        (10.0 * spare).floor() / 10.0
    );
    cuesight_figures::record!(
        "physics-grid-exact-spare",
        "{}",
        (2e-4 / exact_sliding.max.velocity).floor()
    );
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("grid-report.txt");
    std::fs::write(&path, &report).expect("write grid report");

    let worst = |k: usize| &grid[kim_grip.argmax[k]].scene;
    assert!(
        kim_grip.max.velocity <= 0.005,
        "max |dv|/U {} at {:?}",
        kim_grip.max.velocity,
        worst(0)
    );
    assert!(
        kim_grip.max.spin <= 0.01,
        "max R|dw|/U {} at {:?}",
        kim_grip.max.spin,
        worst(1)
    );
    assert!(
        kim_grip.max.throw_deg <= 0.25,
        "max throw error {} at {:?}",
        kim_grip.max.throw_deg,
        worst(2)
    );
    // Fidelity-ladder target for Exact (issue 4): 0.02 % where the reference slides.
    assert!(exact_sliding.max.velocity <= 2e-4, "Exact: {exact_sliding}");
    // Regime flips may only happen where the two models sit on the boundary.
    assert!(
        regime_mismatch * 50 < grid.len(),
        "{regime_mismatch} regime mismatches"
    );
}

fn record_count(key: &str, n: usize) {
    cuesight_figures::record!(key, "{}", thousands(n));
}

fn record_summary(key: &str, s: &Summary, max: [usize; 3], rms: [usize; 3]) {
    for (key, value) in s.figures(key, max, rms) {
        cuesight_figures::record!(&key, "{value}");
    }
}

#[test]
fn reference_creates_no_energy_and_balances_y_momentum() {
    for s in solved_grid() {
        let (m, r) = (s.scene.mass as f64, s.scene.radius as f64);
        let before = cuesight_host::reference::kinetic_energy(
            &cuesight_host::reference::BallState {
                velocity: glam::DVec3::new(
                    s.scene.velocity[0] as f64,
                    s.scene.velocity[1] as f64,
                    0.0,
                ),
                spin: cuesight_host::compare::widen(cuesight::Vec3::from_array(s.scene.spin)),
            },
            m,
            r,
        );
        let after = s.reference.kinetic_energy(m, r);
        assert!(
            after <= before * (1.0 + 1e-12),
            "energy created: {before} -> {after} in {:?}",
            s.scene
        );
        // y-momentum changes only through the object ball's table friction.
        let momentum_y = m * (s.reference.cue_ball.velocity.y + s.reference.object_ball.velocity.y);
        let change = momentum_y - m * s.scene.velocity[1] as f64;
        let table_y = s.reference.table_friction_impulse.y;
        assert!(
            (change - table_y).abs() <= 1e-12 * m * s.scene.speed(),
            "y-momentum {change} vs table {table_y} in {:?}",
            s.scene
        );
        // The table impulse can only be friction: bounded by μ_s times the pressing.
        assert!(
            table_y.abs()
                <= s.scene.mu_s as f64 * s.reference.friction_impulse.z.abs() * (1.0 + 1e-9)
        );
    }
}
