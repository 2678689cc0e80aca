//! Seeded random `shot` scenes, shared by the protocol test (the session answers as
//! `cuesight shot --json`) and the firmware's end-to-end shot test: each is one JSON
//! object that is both a `shot` request body and a `cuesight shot` scene file.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};

struct Preset {
    name: &'static str,
    length: f64,
    width: f64,
    radius: f64,
    pockets: u32,
}

const PRESETS: [Preset; 3] = [
    Preset {
        name: "pool",
        length: 2.54,
        width: 1.27,
        radius: 0.028575,
        pockets: 6,
    },
    Preset {
        name: "snooker",
        length: 3.569,
        width: 1.778,
        radius: 0.02625,
        pockets: 6,
    },
    Preset {
        name: "carom",
        length: 2.84,
        width: 1.42,
        radius: 0.03075,
        pockets: 0,
    },
];

/// The models a body names: those the firmware serves (it leaves `kim` and
/// `seed-exact` out, firmware/Cargo.toml), so that its answers can equal the host's.
const MODELS: [&str; 4] = ["ideal", "kim-grip", "exact", "auto"];

/// A random `shot` body: a preset table, 1–15 object balls placed apart, a stroke,
/// every contact parameter, and either a pocket to solve for or an aim near ball 1
/// (sometimes with a pocket to report on).
pub fn random_body(rng: &mut ChaCha8Rng) -> Value {
    let preset = &PRESETS[rng.random_range(0..3)];
    let r = preset.radius;
    let mut centres: Vec<[f64; 2]> = Vec::new();
    let count = rng.random_range(2..=16);
    while centres.len() < count {
        let p = [
            rng.random_range(2.0 * r..preset.length - 2.0 * r),
            rng.random_range(2.0 * r..preset.width - 2.0 * r),
        ];
        if centres
            .iter()
            .all(|c| (c[0] - p[0]).hypot(c[1] - p[1]) > 2.2 * r)
        {
            centres.push(p);
        }
    }
    let round = |x: f64| (x * 1e4).round() / 1e4;
    let cue = [round(centres[0][0]), round(centres[0][1])];
    let balls: Vec<Value> = centres[1..]
        .iter()
        .map(|c| json!([round(c[0]), round(c[1])]))
        .collect();
    let mut body = json!({
        "table": preset.name,
        "cue": cue,
        "balls": balls,
        "speed": round(rng.random_range(0.5..6.0)),
        "tip": [round(rng.random_range(-0.3..0.3)), round(rng.random_range(-0.35..0.35))],
        "model": MODELS[rng.random_range(0..MODELS.len())],
        "mu": round(rng.random_range(0.02..0.1)),
        "restitution": round(rng.random_range(0.9..1.0)),
        "mu_s": round(rng.random_range(0.0..0.4)),
        "mu_cloth": round(rng.random_range(0.15..0.25)),
        "mu_roll": round(rng.random_range(0.005..0.02)),
    });
    let solve = preset.pockets > 0 && rng.random_bool(0.6);
    if solve {
        body["pocket"] = json!(rng.random_range(0..preset.pockets));
        body["object"] = json!(1);
    } else {
        // Aim near the first object ball, so most shots hit something.
        let (dx, dy) = (centres[1][0] - centres[0][0], centres[1][1] - centres[0][1]);
        let aim = dy.atan2(dx).to_degrees() + rng.random_range(-3.0..3.0);
        body["aim"] = json!(round(aim));
        if preset.pockets > 0 && rng.random_bool(0.5) {
            body["pocket"] = json!(rng.random_range(0..preset.pockets));
        }
    }
    body
}
