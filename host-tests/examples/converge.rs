use cuesight_host::grid;
use cuesight_host::reference::{solve, ReferenceConfig, ReferenceParams};
use glam::DVec3;
fn main() {
    let scenes = grid::scenes(7, 500);
    for steps in [250usize, 500, 1000, 2000, 4000] {
        let mut worst = (0.0f64, 0);
        for (i, s) in scenes.iter().enumerate() {
            let p = ReferenceParams::from_core(&s.params());
            let v = DVec3::new(s.velocity[0] as f64, s.velocity[1] as f64, 0.0);
            let w = DVec3::new(s.spin[0] as f64, s.spin[1] as f64, s.spin[2] as f64);
            let a = solve(&p, v, w, &ReferenceConfig { steps }).unwrap();
            let b = solve(&p, v, w, &ReferenceConfig { steps: 2 * steps }).unwrap();
            let u = s.speed();
            let r = s.radius as f64;
            let e = [
                a.cue_ball.velocity.distance(b.cue_ball.velocity),
                a.object_ball.velocity.distance(b.object_ball.velocity),
                a.cue_ball.spin.distance(b.cue_ball.spin) * r,
                a.object_ball.spin.distance(b.object_ball.spin) * r,
            ]
            .iter()
            .cloned()
            .fold(0.0, f64::max)
                / u;
            if e > worst.0 {
                worst = (e, i);
            }
            if steps == 1000 && i == 0 {}
        }
        let s = &scenes[worst.1];
        let p = ReferenceParams::from_core(&s.params());
        let v = DVec3::new(s.velocity[0] as f64, s.velocity[1] as f64, 0.0);
        let w = DVec3::new(s.spin[0] as f64, s.spin[1] as f64, s.spin[2] as f64);
        let a = solve(&p, v, w, &ReferenceConfig { steps }).unwrap();
        let b = solve(&p, v, w, &ReferenceConfig { steps: 2 * steps }).unwrap();
        println!("steps {steps} -> {}: max change {:.3e} (relative to U) scene {} {:?}\n  a: {:?} {:?} pf {} \n  b: {:?} {:?} pf {}", 2 * steps, worst.0, worst.1, s,
          a.regime, a.stick_impulse, a.normal_impulse, b.regime, b.stick_impulse, b.normal_impulse);
    }
}
