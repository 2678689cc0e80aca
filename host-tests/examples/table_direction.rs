//! How much the seed's eq. (7) (object-ball table friction along −x only) changes the
//! outcome, measured with the reference on the grid.
use cuesight_host::compare::{reference_with, widen};
use cuesight_host::grid::scenes;
use cuesight_host::reference::{ReferenceConfig, ReferenceRegime};
fn main() {
    let mut worst = [0.0f64; 2];
    for s in scenes(2024, 10_000) {
        let a = reference_with(&s, &ReferenceConfig::default()).unwrap();
        let b = reference_with(
            &s,
            &ReferenceConfig {
                table_friction_along_x: true,
                ..Default::default()
            },
        )
        .unwrap();
        let u = s.speed();
        let dv = a
            .cue_ball
            .velocity
            .distance(b.cue_ball.velocity)
            .max(a.object_ball.velocity.distance(b.object_ball.velocity))
            / u;
        let dw = s.radius as f64
            * a.cue_ball
                .spin
                .distance(b.cue_ball.spin)
                .max(a.object_ball.spin.distance(b.object_ball.spin))
            / u;
        let k = if a.regime == ReferenceRegime::Sliding {
            0
        } else {
            1
        };
        worst[k] = worst[k].max(dv.max(dw));
        let _ = widen;
    }
    println!(
        "max change from table friction along x only: sliding {:.3e} U, gripping {:.3e} U",
        worst[0], worst[1]
    );
}
