//! SVG drawing of a played shot (`cuesight shot --svg FILE`): the table (rails with
//! their diamonds, cloth, pockets to scale with their target segments; `table`), every
//! ball with its number, the ghost ball, the cue ball's path before and after the
//! contact, the object ball's path, the chosen pocket, the whole table's paths and
//! events (`whole`), a key with a scale bar and the tip offset (`legend`), and the
//! guidance as a caption.
//!
//! Written as text (no drawing crate: a few dozen elements do not need one). The table
//! is drawn with `x` to the right and `y` up, 1000 px along its length. Post-impact
//! paths are sampled from [`Motion::position_at`], so the sliding parabola shows its
//! curve; a hop (the ball in the air) is a dashed segment. Elements carry ids and
//! classes (`cloth`, `pocket-N`, `ball-N`, `ghost-ball`, `cue-path-before`,
//! `cue-path-after`, `cue-hop`, `object-path`, `object-hop`, `chosen`) for tests and
//! styling.

use std::fmt::Write;

use cuesight::travel::Motion;
use cuesight::Vec3;

use crate::shot_cli::{End, PathEnd, Played};

mod legend;
mod table;
mod whole;

use table::RAIL;

/// Drawn length of the table (px).
const TABLE_PX: f32 = 1000.0;
/// Caption line height (px).
const LINE: f32 = 18.0;
/// Points per sampled path.
const SAMPLES: usize = 120;

/// Metres on the table to pixels.
struct Frame {
    scale: f32,
    margin: f32,
    width: f32,
    radius: f32,
}

impl Frame {
    fn x(&self, x: f32) -> f32 {
        self.margin + x * self.scale
    }
    fn y(&self, y: f32) -> f32 {
        self.margin + (self.width - y) * self.scale
    }
    fn len(&self, l: f32) -> f32 {
        l * self.scale
    }
    fn points(&self, points: &[Vec3]) -> String {
        let mut out = String::new();
        for (i, p) in points.iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            let _ = write!(out, "{:.1},{:.1}", self.x(p.x), self.y(p.y));
        }
        out
    }
}

/// Escape text for element content and attribute values.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// Split a caption line at `; ` or `, ` so that each piece fits the drawing
/// (continuations indented).
fn wrap(line: &str) -> Vec<String> {
    const WIDTH: usize = 140;
    let mut out = Vec::new();
    let mut text = line.to_owned();
    loop {
        if text.chars().count() <= WIDTH {
            out.push(text);
            return out;
        }
        let limit = text
            .char_indices()
            .nth(WIDTH)
            .map_or(text.len(), |(i, _)| i);
        let cut = text[..limit]
            .rfind("; ")
            .or_else(|| text[..limit].rfind(", "))
            .filter(|&i| i > 4)
            .map_or(limit, |i| i + 1);
        out.push(text[..cut].to_owned());
        text = format!("    {}", text[cut..].trim_start());
    }
}

/// `motion`'s centre at `n + 1` times evenly spread over `[from, to]`, plus the phase
/// changes inside that span (so the joins between flight, sliding and rolling are drawn
/// exactly).
fn sample(motion: &Motion, from: f32, to: f32, n: usize) -> Vec<Vec3> {
    let mut times: Vec<f32> = (0..=n)
        .map(|i| from + (to - from) * i as f32 / n as f32)
        .collect();
    for t in [motion.air_time, motion.air_time + motion.sliding_time] {
        if t > from && t < to {
            times.push(t);
        }
    }
    times.sort_by(f32::total_cmp);
    times.into_iter().map(|t| motion.position_at(t)).collect()
}

/// Draw a ball's motion up to `end`: the hop dashed (`{name}-hop`), then the cloth path
/// (`{path_id}`), then its end marker.
fn motion_path(
    svg: &mut String,
    f: &Frame,
    motion: &Motion,
    end: &PathEnd,
    (name, path_id, colour): (&str, &str, &str),
) {
    let air = motion.air_time.min(end.time);
    if air > 0.0 {
        let _ = writeln!(
            svg,
            r#"<polyline id="{name}-hop" class="path hop" points="{}" fill="none" stroke="{colour}" stroke-width="2.5" stroke-dasharray="6 4"/>"#,
            f.points(&[motion.position_at(0.0), motion.position_at(air)])
        );
    }
    if end.time > air {
        let _ = writeln!(
            svg,
            r#"<polyline id="{path_id}" class="path" points="{}" fill="none" stroke="{colour}" stroke-width="2.5" stroke-linejoin="round"/>"#,
            f.points(&sample(motion, air, end.time, SAMPLES))
        );
    }
    let at = motion.position_at(end.time);
    match end.end {
        End::Rest => {
            let _ = writeln!(
                svg,
                r#"<circle id="{name}-rest" class="rest" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="none" stroke="{colour}" stroke-width="1.5" stroke-dasharray="3 3"/>"#,
                f.x(at.x),
                f.y(at.y),
                f.len(f.radius)
            );
        }
        End::Cushion => {
            let (x, y, d) = (f.x(at.x), f.y(at.y), 0.5 * f.len(f.radius));
            let _ = writeln!(
                svg,
                r#"<path id="{name}-cushion" class="cushion-stop" d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="{colour}" stroke-width="2.5"/>"#,
                x - d,
                y - d,
                x + d,
                y + d,
                x - d,
                y + d,
                x + d,
                y - d
            );
        }
        End::Pocket => {}
    }
}

/// The SVG document for a played shot.
pub fn render(played: &Played) -> String {
    let scene = &played.request.scene;
    let table = scene.table();
    let radius = scene.radius();
    let report = &played.report;
    let scale = TABLE_PX / table.length();
    let margin = RAIL * scale + 10.0;
    let f = Frame {
        scale,
        margin,
        width: table.width(),
        radius,
    };
    let caption: Vec<String> = report.to_string().lines().flat_map(wrap).collect();
    let width_px = 2.0 * margin + TABLE_PX;
    let table_px = 2.0 * margin + table.width() * scale;
    let caption_top = table_px + legend::HEIGHT;
    let height_px = caption_top + LINE * caption.len() as f32 + 10.0;

    let mut svg = String::new();
    let _ = writeln!(svg, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width_px:.0}" height="{height_px:.0}" viewBox="0 0 {width_px:.0} {height_px:.0}" font-family="sans-serif">"#
    );
    let _ = writeln!(
        svg,
        "<title>cuesight shot: {}</title>",
        escape(caption.get(2).map_or("", String::as_str))
    );
    let _ = writeln!(
        svg,
        r##"<rect id="background" x="0" y="0" width="{width_px:.0}" height="{height_px:.0}" fill="#ffffff"/>"##
    );
    table::surface(&mut svg, &f, table);
    let chosen = report.target.as_ref().map(|t| t.pocket);
    table::pockets(&mut svg, &f, table, chosen);

    // The whole table, under the guidance's paths.
    let shot = &played.shot;
    let object = shot
        .contact
        .as_ref()
        .map(|c| c.object_ball)
        .or(report.target.as_ref().map(|t| t.object));
    whole::draw(&mut svg, &f, &played.table, object);

    // Paths.
    match &shot.contact {
        Some(contact) => {
            let before = PathEnd {
                time: contact.time,
                end: End::Pocket, // no end marker: the contact is drawn as the ghost ball
                pocket: None,
            };
            motion_path(
                &mut svg,
                &f,
                &shot.cue_before,
                &before,
                ("cue-before", "cue-path-before", "#ffffff"),
            );
            motion_path(
                &mut svg,
                &f,
                &contact.cue_after,
                &played.cue_end,
                ("cue", "cue-path-after", "#e8e8ff"),
            );
            if let Some(end) = &played.object_end {
                motion_path(
                    &mut svg,
                    &f,
                    &contact.object_after,
                    end,
                    ("object", "object-path", "#ffd400"),
                );
            }
        }
        None => motion_path(
            &mut svg,
            &f,
            &shot.cue_before,
            &played.cue_end,
            ("cue", "cue-path-before", "#ffffff"),
        ),
    }

    // Ghost balls and the line of centres.
    if let Some(solution) = &played.solution {
        let g = solution.naive_ghost_ball;
        let _ = writeln!(
            svg,
            r##"<circle id="naive-ghost-ball" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="none" stroke="#bbbbbb" stroke-width="1" stroke-dasharray="2 3"/>"##,
            f.x(g.x),
            f.y(g.y),
            f.len(radius)
        );
    }
    if let Some(contact) = &shot.contact {
        let g = contact.cue_position;
        let o = scene.balls()[contact.object_ball];
        let _ = writeln!(
            svg,
            r##"<line id="line-of-centres" x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#ffffff" stroke-width="1" stroke-opacity="0.6"/>"##,
            f.x(g.x),
            f.y(g.y),
            f.x(o.x),
            f.y(o.y)
        );
        let _ = writeln!(
            svg,
            r##"<circle id="ghost-ball" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="#ffffff" fill-opacity="0.15" stroke="#ffffff" stroke-width="1.5" stroke-dasharray="4 3"/>"##,
            f.x(g.x),
            f.y(g.y),
            f.len(radius)
        );
    }

    // Balls.
    for (i, b) in scene.balls().iter().enumerate() {
        let (class, fill) = match i {
            0 => ("ball cue", "#fbfbf4"),
            i if Some(i) == object => ("ball object", "#ffd400"),
            _ => ("ball", "#c0392b"),
        };
        let _ = writeln!(
            svg,
            r##"<circle id="ball-{i}" class="{class}" cx="{:.1}" cy="{:.1}" r="{:.1}" fill="{fill}" stroke="#222" stroke-width="1"/>"##,
            f.x(b.x),
            f.y(b.y),
            f.len(radius)
        );
        if i > 0 {
            let label = f.len(radius).max(8.0);
            let _ = writeln!(
                svg,
                r##"<text class="ball-label" x="{:.1}" y="{:.1}" font-size="{:.0}" text-anchor="middle" fill="#111">{i}</text>"##,
                f.x(b.x),
                f.y(b.y) + 0.35 * label,
                label
            );
        }
    }

    legend::key(&mut svg, &f, table_px, width_px, played.request.tip_radii);

    // Caption: the guidance text.
    let _ = writeln!(svg, r##"<g id="caption" font-size="13" fill="#222">"##);
    for (i, line) in caption.iter().enumerate() {
        // Leading spaces mark a continuation: indent it (SVG collapses the spaces).
        let text = line.trim_start();
        let x = if text.len() < line.len() { 34 } else { 10 };
        let _ = writeln!(
            svg,
            r#"<text x="{x}" y="{:.1}">{}</text>"#,
            caption_top + LINE * (i as f32 + 0.8),
            escape(text)
        );
    }
    let _ = writeln!(svg, "</g>");
    let _ = writeln!(svg, "</svg>");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup() {
        assert_eq!(escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
    }
}
