//! Prints the `stroke` request lines of a seeded synthetic stroke (the demo session's),
//! in the link's JSON (`cuesight device`, `firmware/demo/session.jsonl`):
//!
//!     cargo run -q -p cuesight-host --example stroke_session -- [SEED RATE_HZ SPEED_M_S SAMPLES [ID]]
//!
//! Default `7 3333 2.5 5000 1`: 5,000 samples at 3,333 Hz, the whole stroke window
//! (`cuesight_link::STROKE_CAPACITY`, 1.5 s: rest, backswing, forward stroke, impact
//! and follow-through), sent as stroke 1 in 40 chunks of 125 samples. The last chunk
//! also sets a tip offset 2R/5 above centre (natural roll).

use cuesight_host::strokes::{stroke_chunks, synthetic_stroke_of};
use cuesight_link::Request;

/// `json` without its `null` members (absent fields read as `None` all the same).
fn without_nulls(json: &str) -> String {
    let mut out = json.to_owned();
    for key in [
        "setup",
        "scale",
        "tip_offset",
        "cue_mass",
        "tip_restitution",
    ] {
        out = out.replace(&format!(",\"{key}\":null"), "");
    }
    out
}

fn main() {
    let args: Result<Vec<f64>, _> = std::env::args().skip(1).map(|a| a.parse()).collect();
    let (seed, rate, speed, samples, id) = match args.as_deref() {
        Ok([]) => (7, 3333.0, 2.5, 5000, 1),
        Ok([seed, rate, speed, samples]) => (*seed as u64, *rate, *speed, *samples as usize, 1),
        Ok([seed, rate, speed, samples, id]) => {
            (*seed as u64, *rate, *speed, *samples as usize, *id as u16)
        }
        _ => {
            eprintln!("usage: stroke_session [SEED RATE_HZ SPEED_M_S SAMPLES [ID]]");
            std::process::exit(2);
        }
    };
    let stroke = synthetic_stroke_of(seed, rate, speed, Some(samples));
    let mut chunks = stroke_chunks(&stroke, id, 125);
    if let Some(setup) = chunks.last_mut().and_then(|last| last.setup.as_mut()) {
        setup.tip_offset = Some([0.0, 0.4 * cuesight::Params::POOL.radius()]);
    }
    for chunk in chunks {
        let json = serde_json::to_string(&Request::Stroke(chunk)).expect("serializes");
        println!("{}", without_nulls(&json));
    }
}
