//! The key under the table: what each line and mark means, a scale bar, and the tip
//! offset as the player sees the cue ball.

use std::fmt::Write;

use super::{escape, Frame};

/// Height of the key row (px).
pub const HEIGHT: f32 = 92.0;

/// One entry of the key: the mark's SVG (drawn in a 28 × 14 px box whose top-left
/// corner is `(x, y)`) and its label.
type Entry = (fn(f32, f32) -> String, &'static str);

fn line(colour: &'static str, dash: &'static str) -> impl Fn(f32, f32) -> String {
    move |x, y| {
        format!(
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-width="2.5" stroke-dasharray="{dash}"/>"#,
            x,
            y + 7.0,
            x + 28.0,
            y + 7.0
        )
    }
}

const ENTRIES: [Entry; 11] = [
    (
        |x, y| line("#ffffff", "none")(x, y),
        "cue ball to the contact",
    ),
    (|x, y| line("#e8e8ff", "none")(x, y), "cue ball after it"),
    (|x, y| line("#ffd400", "none")(x, y), "object ball"),
    (|x, y| line("#ffffff", "6 4")(x, y), "in the air (hop)"),
    (
        |x, y| {
            format!(
                r##"<circle cx="{:.1}" cy="{:.1}" r="6" fill="#ffffff" fill-opacity="0.15" stroke="#ffffff" stroke-width="1.5" stroke-dasharray="4 3"/>"##,
                x + 14.0,
                y + 7.0
            )
        },
        "ghost ball (aim, throw included)",
    ),
    (
        |x, y| {
            format!(
                r##"<circle cx="{:.1}" cy="{:.1}" r="6" fill="none" stroke="#bbbbbb" stroke-width="1" stroke-dasharray="2 3"/>"##,
                x + 14.0,
                y + 7.0
            )
        },
        "ghost-ball aim without throw",
    ),
    (
        |x, y| {
            format!(
                r##"<circle cx="{:.1}" cy="{:.1}" r="6" fill="none" stroke="#ffffff" stroke-width="1.5" stroke-dasharray="3 3"/>"##,
                x + 14.0,
                y + 7.0
            )
        },
        "comes to rest",
    ),
    (
        |x, y| {
            format!(
                r##"<path d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="#ffffff" stroke-width="2.5"/>"##,
                x + 9.0,
                y + 2.0,
                x + 19.0,
                y + 12.0,
                x + 9.0,
                y + 12.0,
                x + 19.0,
                y + 2.0
            )
        },
        "guidance path reaches a cushion",
    ),
    (
        |x, y| line("#ff8a80", "none")(x, y).replace("2.5", "1.5"),
        "whole table: every ball's path",
    ),
    (
        |x, y| {
            format!(
                r##"<circle cx="{:.1}" cy="{:.1}" r="4" fill="{}" stroke="#222" stroke-width="0.8"/><rect x="{:.1}" y="{:.1}" width="7" height="7" fill="{}" stroke="#222" stroke-width="0.8"/>"##,
                x + 7.0,
                y + 7.0,
                super::whole::COLLISION,
                x + 17.5,
                y + 3.5,
                super::whole::CUSHION
            )
        },
        "collision, cushion hit",
    ),
    (
        |x, y| {
            format!(
                r##"<circle cx="{:.1}" cy="{:.1}" r="5" fill="none" stroke="{}" stroke-width="2.5"/>"##,
                x + 14.0,
                y + 7.0,
                super::whole::DROP
            )
        },
        "drops into a pocket",
    ),
];

/// Draws the key at `top` (px): the entries on a dark strip (the marks are drawn in the
/// table's colours), a scale bar of `scale_m` metres, and the tip offset `[side,
/// height]` (ball radii) on a cue-ball face.
pub fn key(svg: &mut String, f: &Frame, top: f32, width_px: f32, tip: [f32; 2]) {
    let _ = writeln!(svg, r##"<g id="legend" font-size="12" fill="#222">"##);
    let _ = writeln!(
        svg,
        r##"<rect x="10" y="{:.1}" width="{:.1}" height="{:.1}" rx="4" fill="#2a4a33"/>"##,
        top,
        width_px - 20.0 - HEIGHT,
        HEIGHT - 8.0
    );
    let columns = 4;
    let column_px = (width_px - 40.0 - HEIGHT) / columns as f32;
    for (i, (mark, label)) in ENTRIES.iter().enumerate() {
        let (row, column) = (i / columns, i % columns);
        let (x, y) = (
            20.0 + column_px * column as f32,
            top + 6.0 + 18.0 * row as f32,
        );
        let _ = writeln!(svg, "{}", mark(x, y));
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" fill="#f0f0f0">{}</text>"##,
            x + 36.0,
            y + 11.0,
            escape(label)
        );
    }
    // Scale bar: the cell after the entries.
    let bar_m = 0.5;
    let cell = ENTRIES.len();
    let (x, y) = (
        20.0 + column_px * (cell % columns) as f32,
        top + 6.0 + 18.0 * (cell / columns) as f32,
    );
    let _ = writeln!(
        svg,
        r##"<g id="scale-bar"><path d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="#f0f0f0" stroke-width="2"/><text x="{:.1}" y="{:.1}" fill="#f0f0f0">{} m</text></g>"##,
        x,
        y + 7.0,
        x + f.len(bar_m),
        y + 7.0,
        x,
        y + 2.0,
        x,
        y + 12.0,
        x + f.len(bar_m),
        y + 2.0,
        x + f.len(bar_m),
        y + 12.0,
        x + f.len(bar_m) + 8.0,
        y + 11.0,
        bar_m
    );
    tip_inset(svg, width_px - HEIGHT - 4.0, top, tip);
    let _ = writeln!(svg, "</g>");
}

/// The cue ball's face as the player sees it down the cue (right to the right, up up),
/// with the tip's contact point at `[side, height]` ball radii and the 0.5 R limit of a
/// tip offset dashed.
fn tip_inset(svg: &mut String, left: f32, top: f32, tip: [f32; 2]) {
    let r = 0.5 * (HEIGHT - 8.0) - 8.0;
    let (cx, cy) = (left + 0.5 * HEIGHT, top + 0.5 * (HEIGHT - 8.0) - 4.0);
    let _ = writeln!(
        svg,
        r##"<g id="tip-offset"><circle cx="{cx:.1}" cy="{cy:.1}" r="{r:.1}" fill="#fbfbf4" stroke="#222" stroke-width="1"/><circle cx="{cx:.1}" cy="{cy:.1}" r="{:.1}" fill="none" stroke="#999" stroke-width="0.8" stroke-dasharray="2 2"/><circle class="tip" cx="{:.1}" cy="{:.1}" r="3.5" fill="#1a5fb4"/><text x="{cx:.1}" y="{:.1}" text-anchor="middle" font-size="10">tip</text></g>"##,
        0.5 * r,
        cx + tip[0] * r,
        cy - tip[1] * r,
        cy + r + 11.0,
    );
}
