//! The table in the shot drawing: rails with their diamonds (sights), the cloth, and
//! the pockets drawn to scale with their target segments.

use std::fmt::Write;

use cuesight::table::Table;
use cuesight::Vec3;

use super::Frame;

/// Rail width (m) as drawn.
pub const RAIL: f32 = 0.1;

/// Rails, cloth and diamonds.
pub fn surface(svg: &mut String, f: &Frame, table: &Table) {
    let _ = writeln!(
        svg,
        r##"<rect id="rail" x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" rx="8" fill="#5b3a1e"/>"##,
        f.x(-RAIL),
        f.y(table.width() + RAIL),
        f.len(table.length() + 2.0 * RAIL),
        f.len(table.width() + 2.0 * RAIL)
    );
    let _ = writeln!(
        svg,
        r##"<rect id="cloth" x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="#1f7a3a"/>"##,
        f.x(0.0),
        f.y(table.width()),
        f.len(table.length()),
        f.len(table.width())
    );
    diamonds(svg, f, table);
}

/// The sights on the rails: the usual eighths of the length and quarters of the width
/// (pool, snooker and carom mark them alike), on the middle of the rail, skipping the
/// side pockets' places.
fn diamonds(svg: &mut String, f: &Frame, table: &Table) {
    let (length, width) = (table.length(), table.width());
    let pocketed = !table.pockets().is_empty();
    let rail_middle = 0.5 * RAIL;
    let size = 4.0; // px, half-diagonal
    let mut marks = Vec::new();
    for k in 1..8 {
        if pocketed && k == 4 {
            continue; // the side pocket
        }
        let x = length * k as f32 / 8.0;
        marks.push(Vec3::new(x, -rail_middle, 0.0));
        marks.push(Vec3::new(x, width + rail_middle, 0.0));
    }
    for k in 1..4 {
        let y = width * k as f32 / 4.0;
        marks.push(Vec3::new(-rail_middle, y, 0.0));
        marks.push(Vec3::new(length + rail_middle, y, 0.0));
    }
    let _ = writeln!(svg, r##"<g id="diamonds" fill="#f4ead2">"##);
    for m in marks {
        let (x, y) = (f.x(m.x), f.y(m.y));
        let _ = writeln!(
            svg,
            r#"<path class="diamond" d="M{:.1},{:.1} L{:.1},{:.1} L{:.1},{:.1} L{:.1},{:.1} Z"/>"#,
            x,
            y - size,
            x + size,
            y,
            x,
            y + size,
            x - size,
            y
        );
    }
    let _ = writeln!(svg, "</g>");
}

/// The pockets to scale: each a hole as wide as its mouth (the gap between the jaws,
/// [`Table::new`]'s `corner_mouth` and `side_mouth`) just behind the mouth, and the
/// target segment a ball centre must cross (dashed; the chosen pocket's in yellow, with
/// a ring).
pub fn pockets(svg: &mut String, f: &Frame, table: &Table, chosen: Option<usize>) {
    let (length, width) = (table.length(), table.width());
    for (i, p) in table.pockets().iter().enumerate() {
        let centre = p.centre();
        let is_side = centre.x > length / 3.0 && centre.x < 2.0 * length / 3.0;
        // The target segment is the mouth moved in by one ball radius, as long as the
        // mouth (`Table::new`: corner jaws `mouth/√2` from the corner on each rail).
        let mouth = (p.b - p.a).length();
        let (hole, hole_radius) = if is_side {
            // Mostly behind the rail line: the hole meets the cloth over 80 % of the
            // mouth.
            let behind = if centre.y < 0.5 * width {
                -0.3 * mouth
            } else {
                width + 0.3 * mouth
            };
            (Vec3::new(centre.x, behind, 0.0), 0.5 * mouth)
        } else {
            let corner = Vec3::new(
                if centre.x < 0.5 * length { 0.0 } else { length },
                if centre.y < 0.5 * width { 0.0 } else { width },
                0.0,
            );
            // Centred on the rail corner: the hole reaches the mouth line's middle.
            (corner, 0.5 * mouth)
        };
        let class = if chosen == Some(i) {
            "pocket chosen"
        } else {
            "pocket"
        };
        let _ = writeln!(svg, r#"<g id="pocket-{i}" class="{class}">"#);
        let _ = writeln!(
            svg,
            r##"<circle class="pocket-mouth" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="#111"/>"##,
            f.x(hole.x),
            f.y(hole.y),
            f.len(hole_radius)
        );
        let (stroke, width_px) = if chosen == Some(i) {
            ("#ffd400", 4.0)
        } else {
            ("#9fd3a6", 1.5)
        };
        let _ = writeln!(
            svg,
            r#"<line class="pocket-target" x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{stroke}" stroke-width="{width_px}" stroke-dasharray="4 3"/>"#,
            f.x(p.a.x),
            f.y(p.a.y),
            f.x(p.b.x),
            f.y(p.b.y)
        );
        if chosen == Some(i) {
            let _ = writeln!(
                svg,
                r#"<circle class="pocket-highlight" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="none" stroke="{stroke}" stroke-width="3"/>"#,
                f.x(hole.x),
                f.y(hole.y),
                f.len(hole_radius) + 4.0
            );
        }
        let _ = writeln!(svg, "</g>");
    }
}
