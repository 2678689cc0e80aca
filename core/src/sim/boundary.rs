//! Where a ball's centre may go on a table: the rectangle one radius inside the
//! cushions, with each corner cut off by its pocket's mouth line. That region is convex,
//! so the first of its edge lines that the centre crosses outwards is where it leaves:
//! at a cushion, or into a pocket.
//!
//! The pockets are [`Table`]'s target segments (a corner's line across its mouth, a side
//! pocket's segment on the rail line); a corner's line is extended to the rail lines,
//! so that the polygon has no gap, and a side pocket takes the part of its rail line
//! between its ends. The jaws' own shape (their rounded noses, the throat) is not
//! modelled: a ball that reaches a mouth line drops.

use super::roots::first_rise_quadratic;
use super::track::Track;
use crate::table::Table;
use crate::vector::Vec3;

/// What a crossing of the boundary is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Edge {
    /// A cushion whose horizontal unit normal (into the cushion) is given.
    Cushion(Vec3),
    /// The pocket of that index in [`Table::pockets`].
    Pocket(usize),
}

/// One edge line: `normal · r = offset` with the outward unit `normal`, and what it is.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Line {
    normal: Vec3,
    offset: f32,
    /// `Some(pocket)` for a corner pocket's mouth; `None` for a rail (a side pocket on
    /// it is found by where the crossing is).
    pocket: Option<usize>,
}

/// The edge lines of a table for balls of one radius.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Boundary {
    lines: [Line; 8],
    count: usize,
    /// Side pockets: `(pocket, rail line, low x, high x)`.
    sides: [(usize, usize, f32, f32); 2],
    side_count: usize,
}

impl Boundary {
    /// The boundary of `table` for balls of `radius` (m).
    pub fn new(table: &Table, radius: f32) -> Self {
        let (length, width) = (table.length(), table.width());
        let rail = |nx: f32, ny: f32, offset: f32| Line {
            normal: Vec3::new(nx, ny, 0.0),
            offset,
            pocket: None,
        };
        // Rails 0–3: y = R, y = W − R, x = R, x = L − R.
        let mut lines = [
            rail(0.0, -1.0, -radius),
            rail(0.0, 1.0, width - radius),
            rail(-1.0, 0.0, -radius),
            rail(1.0, 0.0, length - radius),
            rail(0.0, 0.0, 0.0),
            rail(0.0, 0.0, 0.0),
            rail(0.0, 0.0, 0.0),
            rail(0.0, 0.0, 0.0),
        ];
        let mut count = 4;
        let mut sides = [(0, 0, 0.0, 0.0); 2];
        let mut side_count = 0;
        let centre = Vec3::new(0.5 * length, 0.5 * width, 0.0);
        for (index, pocket) in table.pockets().iter().enumerate() {
            let along = pocket.b - pocket.a;
            if along.y == 0.0 {
                // A side pocket on the near (y = R) or far rail.
                let rail = if pocket.a.y < centre.y { 0 } else { 1 };
                let (low, high) = if pocket.a.x < pocket.b.x {
                    (pocket.a.x, pocket.b.x)
                } else {
                    (pocket.b.x, pocket.a.x)
                };
                if side_count < sides.len() {
                    sides[side_count] = (index, rail, low, high);
                    side_count += 1;
                }
            } else if count < lines.len() {
                let length = along.length();
                let mut normal = Vec3::new(along.y / length, -along.x / length, 0.0);
                if normal.dot(pocket.a - centre) < 0.0 {
                    normal = -normal;
                }
                lines[count] = Line {
                    normal,
                    offset: normal.dot(pocket.a),
                    pocket: Some(index),
                };
                count += 1;
            }
        }
        Self {
            lines,
            count,
            sides,
            side_count,
        }
    }

    /// The first time at or after `now` at which `track`'s centre crosses an edge line
    /// outwards, and the edge. `None` if it stops inside.
    pub fn exit(&self, track: &Track, now: f32) -> Option<(f32, Edge)> {
        // Lines the box around the whole path stays inside of cannot be crossed.
        let (low, high) = (track.bounds.min, track.bounds.max);
        let mut reachable = [false; 8];
        let mut any = false;
        for (reach, line) in reachable.iter_mut().zip(&self.lines[..self.count]) {
            let n = line.normal;
            let farthest = n.x * if n.x > 0.0 { high.x } else { low.x }
                + n.y * if n.y > 0.0 { high.y } else { low.y };
            *reach = farthest >= line.offset;
            any |= *reach;
        }
        if !any {
            return None;
        }
        for piece in track.pieces() {
            if piece.to <= now || piece.to == f32::INFINITY {
                continue; // past, or the rest at the end: no crossing
            }
            let from = if piece.from > now { piece.from } else { now };
            let (p, q, s) = piece.at(from);
            let span = piece.to - from;
            let mut best: Option<(f32, usize)> = None;
            for (index, line) in self.lines[..self.count].iter().enumerate() {
                if !reachable[index] {
                    continue;
                }
                let n = line.normal;
                let c = [n.dot(p) - line.offset, n.dot(q), n.dot(s)];
                let value = |x: f32| n.dot(p + q * x + s * (x * x)) - line.offset;
                if let Some(sigma) = first_rise_quadratic(c, span, value) {
                    if best.is_none_or(|(b, _)| sigma < b) {
                        best = Some((sigma, index));
                    }
                }
            }
            if let Some((sigma, index)) = best {
                let line = self.lines[index];
                let edge = match line.pocket {
                    Some(pocket) => Edge::Pocket(pocket),
                    None => {
                        let at = p + q * sigma + s * (sigma * sigma);
                        self.sides[..self.side_count]
                            .iter()
                            .find(|(_, rail, low, high)| {
                                *rail == index && at.x >= *low && at.x <= *high
                            })
                            .map_or(Edge::Cushion(line.normal), |(pocket, ..)| {
                                Edge::Pocket(*pocket)
                            })
                    }
                };
                return Some((from + sigma, edge));
            }
        }
        None
    }
}
