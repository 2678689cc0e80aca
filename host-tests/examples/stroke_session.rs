//! Prints the `stroke` request lines of a seeded synthetic stroke (the demo session's):
//!
//!     cargo run -q -p cuesight-host --example stroke_session -- [SEED RATE_HZ SPEED_M_S]
//!
//! The window is sent in chunks of 1,000 samples; the last chunk also sets a tip offset
//! 2R/5 above centre (natural roll).

use cuesight_host::strokes::{stroke_requests, synthetic_stroke};
use cuesight_protocol::Request;

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("numbers: SEED RATE_HZ SPEED_M_S"))
        .collect();
    let (seed, rate, speed) = match args[..] {
        [seed, rate, speed] => (seed as u64, rate, speed),
        _ => (7, 1000.0, 2.5),
    };
    let stroke = synthetic_stroke(seed, rate, speed);
    let mut requests = stroke_requests(&stroke, 1000);
    if let Some(Request::Stroke(last)) = requests.last_mut() {
        last.tip_offset = Some([0.0, 0.4 * cuesight::Params::POOL.radius()]);
    }
    for request in &requests {
        println!("{}", serde_json::to_string(request).expect("serializes"));
    }
}
