//! Cue-ball/table friction μ_ct while a draw shot presses the cue ball into the cloth
//! (which the seed neglects): `KimGrip` and `Exact` against the reference, which applies
//! it from first principles at the cue ball's table contact.

use cuesight::{collide, Model};
use cuesight_host::compare::{scene_error, widen, Summary};
use cuesight_host::grid::scenes;
use cuesight_host::reference::{solve, ReferenceOutcome, ReferenceParams, ReferenceRegime};
use cuesight_host::validity::answer;

fn reference(params: &cuesight::Params, impact: &cuesight::Impact) -> ReferenceOutcome {
    let v = impact.velocity();
    solve(
        &ReferenceParams::from_core(params),
        glam::DVec3::new(v.x as f64, v.y as f64, 0.0),
        widen(impact.spin()),
        &Default::default(),
    )
    .unwrap()
}

#[test]
fn models_track_the_reference_with_cue_table_friction() {
    for mu_ct in [0.1f32, 0.2] {
        let grid = scenes(41, 3000);
        let solved: Vec<_> = grid
            .iter()
            .map(|s| {
                let params = s.params().with_cue_table_friction(mu_ct).unwrap();
                let r = reference(&params, &s.impact());
                (s, params, r)
            })
            .collect();
        // Over the scenes the model answers: KimGrip refuses μ·μ_ct > 0.05 (its
        // validity domain), the other scenes of the grid.
        let summary = |model: Model, only_sliding: bool| {
            Summary::of(
                solved
                    .iter()
                    .enumerate()
                    .filter(|(_, (_, _, r))| !only_sliding || r.regime == ReferenceRegime::Sliding)
                    .filter_map(|(i, (s, params, r))| {
                        let out = answer(params, &s.impact(), model, "cue-table grid")?;
                        Some((i, scene_error(s, &out, r)))
                    }),
            )
        };
        let kim_grip = summary(Model::KimGrip, false);
        let exact = summary(Model::Exact, true);
        let refused = solved
            .iter()
            .filter(|(_, params, _)| cuesight::validity::kim_grip(params).is_err())
            .count();
        assert!(
            refused < solved.len(),
            "μ_ct {mu_ct}: KimGrip refuses every scene"
        );
        println!("μ_ct {mu_ct}: KimGrip {kim_grip} ({refused} refused)");
        let refused_key = format!("physics-cue-table-{mu_ct}-kim-grip-refused").replace('.', "-");
        cuesight_figures::record!(
            &refused_key,
            "{}",
            cuesight_host::compare::thousands(refused)
        );
        println!("μ_ct {mu_ct}: Exact (sliding) {exact}");
        let key = format!("physics-cue-table-{mu_ct}").replace('.', "-");
        for (key, value) in kim_grip.figures(&format!("{key}-kim-grip"), [3, 3, 3], [3, 3, 3]) {
            cuesight_figures::record!(&key, "{value}");
        }
        for (key, value) in exact.figures(&format!("{key}-exact-sliding"), [4, 4, 4], [4, 4, 4]) {
            cuesight_figures::record!(&key, "{value}");
        }
        assert!(
            kim_grip.max.velocity <= 0.005
                && kim_grip.max.spin <= 0.01
                && kim_grip.max.throw_deg <= 0.25
        );
        assert!(exact.max.velocity <= 2e-4, "{exact}");
    }
}

/// Head-on draw: the pressed cue ball's table friction is the only external horizontal
/// impulse, so it takes exactly μ_ct × (pressing impulse) of x-momentum out of the pair
/// (the cue ball's table contact slides forward throughout); nothing changes for a
/// follow shot (the cue ball lifts off the cloth instead).
#[test]
fn draw_loses_speed_to_the_cloth_and_follow_does_not() {
    // μ·μ_ct = 0.08 × 0.125 = 0.01: inside KimGrip's validity domain (μ·μ_ct ≤ 0.05).
    let mu_ct = 0.125;
    let base = cuesight::Params::POOL.with_mu(0.08).unwrap();
    let with = base.with_cue_table_friction(mu_ct as f32).unwrap();
    let r = 0.028575f32;
    let draw = cuesight::Impact::from_velocity([2.0, 0.0], [0.0, -2.0 / r, 0.0]).unwrap();
    let follow = cuesight::Impact::from_velocity([2.0, 0.0], [0.0, 2.0 / r, 0.0]).unwrap();
    let (a, b) = (reference(&base, &draw), reference(&with, &draw));
    let pressing = b.friction_impulse.z / 0.17; // per unit mass, = cue ball's table normal impulse
    assert!(pressing > 0.0);
    let momentum = |o: &ReferenceOutcome| o.cue_ball.velocity.x + o.object_ball.velocity.x;
    let loss = momentum(&a) - momentum(&b);
    assert!(
        (loss - mu_ct * pressing).abs() < 1e-9,
        "{loss} vs {}",
        mu_ct * pressing
    );
    assert!(
        a.cue_ball.velocity.x > b.cue_ball.velocity.x,
        "cloth friction slows the cue ball"
    );
    for model in [Model::KimGrip, Model::Exact] {
        let out = collide(&with, &draw, model).unwrap();
        assert!(
            (out.cue_ball.velocity.x as f64 - b.cue_ball.velocity.x).abs() < 2e-3,
            "{model:?}"
        );
    }
    let (c, d) = (reference(&base, &follow), reference(&with, &follow));
    assert!(c.cue_ball.velocity.distance(d.cue_ball.velocity) < 1e-12);
}
