//! The whole table on the drawing (issue 17): every ball's path from the stroke until
//! it rests or drops, through cushions and collisions ([`crate::shot_cli::TableOutcome`]),
//! drawn thin under the guidance's paths, with a mark at each event: a collision, a
//! cushion hit, a drop into a pocket, and each ball's final position.
//!
//! Elements: `table-path-N` (class `table-path`, one polyline per stretch between two
//! events), `event-K` (classes `event ball`, `event cushion`, `event pocket`), `final-N`.

use std::fmt::Write;

use super::{sample, Frame};
use crate::shot_cli::TableOutcome;

/// A ball's colour on the drawing: the cue ball white, the object ball yellow, the others
/// red.
pub fn colour(ball: usize, object: Option<usize>) -> &'static str {
    match ball {
        0 => "#ffffff",
        b if Some(b) == object => "#ffd400",
        _ => "#ff8a80",
    }
}

/// Collision marks.
pub const COLLISION: &str = "#ff9800";
/// Cushion-hit marks.
pub const CUSHION: &str = "#00e5ff";
/// Drop marks.
pub const DROP: &str = "#111111";

/// Draw every path and event of `whole`; `object` is the object ball's index.
pub fn draw(svg: &mut String, f: &Frame, whole: &TableOutcome, object: Option<usize>) {
    let _ = writeln!(svg, r#"<g id="whole-table">"#);
    for (ball, path) in whole.paths.iter().enumerate() {
        for (k, segment) in path.iter().enumerate() {
            let span = segment.until - segment.since;
            if span <= 0.0 || span.is_nan() {
                continue;
            }
            let points = sample(&segment.motion, 0.0, span, 60);
            let _ = writeln!(
                svg,
                r#"<polyline id="table-path-{ball}-{k}" class="table-path" points="{}" fill="none" stroke="{}" stroke-width="1.5" stroke-opacity="0.85"/>"#,
                f.points(&points),
                colour(ball, object)
            );
        }
    }
    for (k, event) in whole.events.iter().enumerate() {
        let (x, y) = (f.x(event.position[0]), f.y(event.position[1]));
        let mark = match event.kind {
            "ball" => format!(
                r##"<circle id="event-{k}" class="event ball" cx="{x:.1}" cy="{y:.1}" r="4" fill="{COLLISION}" stroke="#222" stroke-width="0.8"/>"##
            ),
            "cushion" => format!(
                r##"<rect id="event-{k}" class="event cushion" x="{:.1}" y="{:.1}" width="7" height="7" fill="{CUSHION}" stroke="#222" stroke-width="0.8"/>"##,
                x - 3.5,
                y - 3.5
            ),
            "pocket" => format!(
                r#"<circle id="event-{k}" class="event pocket" cx="{x:.1}" cy="{y:.1}" r="5" fill="none" stroke="{DROP}" stroke-width="2.5"/>"#
            ),
            _ => continue,
        };
        let _ = writeln!(svg, "{mark}");
    }
    for (ball, end) in whole.final_positions.iter().enumerate() {
        if let Some([x, y]) = end {
            let _ = writeln!(
                svg,
                r#"<circle id="final-{ball}" class="final" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="{}" fill-opacity="0.35" stroke="{}" stroke-width="1.5"/>"#,
                f.x(*x),
                f.y(*y),
                f.len(f.radius),
                colour(ball, object),
                colour(ball, object)
            );
        }
    }
    let _ = writeln!(svg, "</g>");
}
