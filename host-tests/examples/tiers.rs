//! Error of every model (f32 and f64 evaluation) against the reference on the grid,
//! split by the reference's regime.
use cuesight::{collide, collide_f64, Model};
use cuesight_host::compare::{reference, scene_error, Summary};
use cuesight_host::grid::scenes;
use cuesight_host::reference::ReferenceRegime;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    let grid: Vec<_> = scenes(2024, n)
        .into_iter()
        .map(|s| (s, reference(&s).unwrap()))
        .collect();
    for model in Model::ALL {
        type Collide =
            fn(&cuesight::Params, &cuesight::Impact, Model) -> cuesight::Result<cuesight::Outcome>;
        for (name, f) in [("f32", collide as Collide), ("f64", collide_f64 as Collide)] {
            for regime in [ReferenceRegime::Sliding, ReferenceRegime::Gripping] {
                let s = Summary::of(
                    grid.iter()
                        .enumerate()
                        .filter(|(_, (_, r))| r.regime == regime)
                        .map(|(i, (s, r))| {
                            let out = f(&s.params(), &s.impact(), model).unwrap();
                            (i, scene_error(s, &out, r))
                        }),
                );
                println!("{:9} {name} {:?}: {s}", model.name(), regime);
            }
        }
    }
}
