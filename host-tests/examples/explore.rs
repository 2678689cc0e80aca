use cuesight::{collide, Model};
use cuesight_host::grid;
use cuesight_host::reference::{solve, ReferenceConfig, ReferenceParams, ReferenceRegime};
use glam::DVec3;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(2000);
    let scenes = grid::scenes(2024, n);
    for model in [Model::Kim, Model::KimGrip] {
        let mut worst = [(0.0f64, 0usize); 3];
        let mut sum = [0.0f64; 3];
        let mut grips = 0;
        for (i, s) in scenes.iter().enumerate() {
            let out = collide(&s.params(), &s.impact(), model).unwrap();
            let r = solve(
                &ReferenceParams::from_core(&s.params()),
                DVec3::new(s.velocity[0] as f64, s.velocity[1] as f64, 0.0),
                DVec3::new(s.spin[0] as f64, s.spin[1] as f64, s.spin[2] as f64),
                &ReferenceConfig::default(),
            )
            .unwrap();
            if r.regime == ReferenceRegime::Gripping {
                grips += 1;
            }
            let u = s.speed();
            let d = |a: cuesight::Vec3, b: DVec3| {
                DVec3::new(a.x as f64, a.y as f64, a.z as f64).distance(b)
            };
            let ev = d(out.cue_ball.velocity, r.cue_ball.velocity)
                .max(d(out.object_ball.velocity, r.object_ball.velocity))
                / u;
            let ew = (d(out.cue_ball.spin, r.cue_ball.spin)
                .max(d(out.object_ball.spin, r.object_ball.spin)))
                * s.radius as f64
                / u;
            let et = (out.throw_angle_deg() as f64 - r.throw_angle_deg()).abs();
            for (k, e) in [ev, ew, et].into_iter().enumerate() {
                sum[k] += e * e;
                if e > worst[k].0 {
                    worst[k] = (e, i);
                }
            }
        }
        println!("{:?}: grips {grips}/{n}  max dv/U {:.4}% (#{}), max R dw/U {:.4}% (#{}), max throw {:.4} deg (#{}); rms {:.4}% {:.4}% {:.4}",
            model, worst[0].0 * 100.0, worst[0].1, worst[1].0 * 100.0, worst[1].1, worst[2].0, worst[2].1,
            (sum[0] / n as f64).sqrt() * 100.0, (sum[1] / n as f64).sqrt() * 100.0, (sum[2] / n as f64).sqrt());
        for k in 0..3 {
            println!("   worst {k}: {:?}", scenes[worst[k].1]);
        }
    }
}
