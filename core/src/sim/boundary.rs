//! Where a ball's centre may go on a table, and what it meets at the edge.
//!
//! The centre stays in the rectangle one radius inside the cushions' nose lines until it
//! crosses one of the four rail lines outwards. Along a rail line the cushion runs
//! between the pockets' noses: a crossing there is a cushion contact. A crossing in a
//! pocket's gap takes the ball into the pocket's mouth, where it meets the jaws' faces
//! and rounded noses (cushions too), or drops when its centre enters the pocket's circle
//! ([`super::jaws`], pooltool 0.6's geometry). Everything a centre meets in a mouth lies
//! outside the rectangle (the cushions are behind their nose lines, so a centre touching
//! one is within `R` of a line), so a path whose box stays inside the rectangle meets
//! nothing.
//!
//! A mouth also has a back line at the cushion's width behind each of its rails' nose
//! lines: a centre that got past the jaws without entering the circle (geometry other
//! than the presets') drops there, so that no ball leaves the table through a pocket.

pub(crate) use super::crossing::Edge;
use super::crossing::{position, Line};
use super::jaws::Jaws;
use super::mouth::{End, Mouth};
use super::track::Track;
use crate::table::{Table, MAX_POCKETS};
use crate::vector::Vec3;

/// A stretch of a rail line with no cushion (a pocket's mouth between its noses): a
/// crossing of rail `rail` whose coordinate along the rail (`x` for the rails along the
/// length, `y` for the others) lies in `(low, high)` is none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Gap {
    rail: usize,
    low: f32,
    high: f32,
    /// The mouth it opens into (index in [`Boundary`]'s mouths).
    mouth: usize,
}

/// The edges of a table for balls of one radius.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Boundary {
    /// Rails 0–3: `y = R`, `y = W − R`, `x = R`, `x = L − R`.
    rails: [Line; 4],
    gaps: [Gap; 2 * MAX_POCKETS],
    gap_count: usize,
    mouths: [Mouth; MAX_POCKETS],
    mouth_count: usize,
    /// The mouths whose drop circle reaches into the rectangle (bit `k` for mouth `k`;
    /// snooker's corner circles, pooltool's 4" ones 36 mm back, do).
    intruding: u32,
}

impl Boundary {
    /// The boundary of `table` with `jaws` for balls of `radius` (m).
    pub fn new(table: &Table, jaws: &Jaws, radius: f32) -> Self {
        let (length, width) = (table.length(), table.width());
        let rail = |nx: f32, ny: f32, offset: f32| Line {
            normal: Vec3::new(nx, ny, 0.0),
            offset,
        };
        let mut boundary = Self {
            rails: [
                rail(0.0, -1.0, -radius),
                rail(0.0, 1.0, width - radius),
                rail(-1.0, 0.0, -radius),
                rail(1.0, 0.0, length - radius),
            ],
            gaps: [Gap::default(); 2 * MAX_POCKETS],
            gap_count: 0,
            mouths: [Mouth::default(); MAX_POCKETS],
            mouth_count: 0,
            intruding: 0,
        };
        let centre = Vec3::new(0.5 * length, 0.5 * width, 0.0);
        for (index, pocket) in table.pockets().iter().enumerate() {
            let at = pocket.centre();
            // The rail along the length (0 or 1) and, for a corner, the one across it
            // (2 or 3), with their outward normals.
            let (long_rail, out_y) = if at.y < centre.y {
                (0, Vec3::new(0.0, -1.0, 0.0))
            } else {
                (1, Vec3::new(0.0, 1.0, 0.0))
            };
            let nose_line_y = if long_rail == 0 { 0.0 } else { width };
            let mouth_width = (pocket.b - pocket.a).length();
            let (ends, jaw, circle, backs) = if pocket.b.y == pocket.a.y {
                // A side pocket: its mouth's ends on the rail's nose line.
                let half = 0.5 * mouth_width;
                let x = Vec3::new(1.0, 0.0, 0.0);
                let middle = Vec3::new(at.x, nose_line_y, 0.0);
                let ends = [
                    End::new(middle - x * half, -x, out_y, long_rail),
                    End::new(middle + x * half, x, out_y, long_rail),
                ];
                let circle = middle + out_y * jaws.side.depth;
                let jaw = (&jaws.side, jaws.side.angle);
                (ends, jaw, circle, [(out_y, middle), (out_y, middle)])
            } else {
                // A corner: the mouth's ends `mouth / √2` from the corner along each rail.
                let (cross_rail, out_x, corner_x) = if at.x < centre.x {
                    (2, Vec3::new(-1.0, 0.0, 0.0), 0.0)
                } else {
                    (3, Vec3::new(1.0, 0.0, 0.0), length)
                };
                let corner = Vec3::new(corner_x, nose_line_y, 0.0);
                let jaw_distance = mouth_width * core::f32::consts::FRAC_1_SQRT_2;
                let ends = [
                    End::new(corner - out_x * jaw_distance, -out_x, out_y, long_rail),
                    End::new(corner - out_y * jaw_distance, -out_y, out_x, cross_rail),
                ];
                let circle = corner
                    + (out_x + out_y) * (jaws.corner.depth * core::f32::consts::FRAC_1_SQRT_2);
                let jaw = (&jaws.corner, 45.0 + jaws.corner.angle);
                (ends, jaw, circle, [(out_y, corner), (out_x, corner)])
            };
            let (mouth, edges) = Mouth::new(
                index,
                &ends,
                jaw,
                circle,
                &backs,
                jaws.cushion_width,
                radius,
            );
            // The open stretches of the rail lines: a side pocket's between its noses, a
            // corner's from each nose to the corner.
            let open: [Option<(usize, f32, f32)>; 2] = if ends[0].rail == ends[1].rail {
                [Some((ends[0].rail, edges[0], edges[1])), None]
            } else {
                let half_line = |k: usize| {
                    let end = &ends[k];
                    let beyond = if end.rail < 2 {
                        end.toward_rail.x
                    } else {
                        end.toward_rail.y
                    };
                    if beyond > 0.0 {
                        (end.rail, f32::NEG_INFINITY, edges[k])
                    } else {
                        (end.rail, edges[k], f32::INFINITY)
                    }
                };
                [Some(half_line(0)), Some(half_line(1))]
            };
            for (rail, low, high) in open.into_iter().flatten() {
                if boundary.gap_count < boundary.gaps.len() {
                    boundary.gaps[boundary.gap_count] = Gap {
                        rail,
                        low,
                        high,
                        mouth: boundary.mouth_count,
                    };
                    boundary.gap_count += 1;
                }
            }
            if boundary.mouth_count < boundary.mouths.len() {
                // The rectangle's point nearest the circle's centre.
                let nearest = Vec3::new(
                    mouth.centre.x.clamp(radius, length - radius),
                    mouth.centre.y.clamp(radius, width - radius),
                    0.0,
                );
                if (nearest - mouth.centre).length() < mouth.radius {
                    boundary.intruding |= 1 << boundary.mouth_count;
                }
                boundary.mouths[boundary.mouth_count] = mouth;
                boundary.mouth_count += 1;
            }
        }
        boundary
    }

    /// The first time at or after `now` at which `track`'s centre meets a cushion or
    /// drops into a pocket, and which. `None` if it stops first.
    pub fn exit(&self, track: &Track, now: f32) -> Option<(f32, Edge)> {
        // Rails the box around the whole path stays inside of cannot be crossed.
        let (low, high) = (track.bounds.min, track.bounds.max);
        let mut rails = [false; 4];
        let mut any = false;
        for (reach, line) in rails.iter_mut().zip(&self.rails) {
            let n = line.normal;
            let farthest = n.x * if n.x > 0.0 { high.x } else { low.x }
                + n.y * if n.y > 0.0 { high.y } else { low.y };
            *reach = farthest >= line.offset;
            any |= *reach;
        }
        // Drop circles that reach into the rectangle, if the path's box meets theirs.
        let mut intruding = 0u32;
        for (k, mouth) in self.mouths[..self.mouth_count].iter().enumerate() {
            if self.intruding & (1 << k) != 0 && mouth.meets_box(low, high) {
                intruding |= 1 << k;
            }
        }
        if !any && intruding == 0 {
            return None;
        }
        for piece in track.pieces() {
            if piece.to <= now || piece.to == f32::INFINITY {
                continue; // past, or the rest at the end: no crossing
            }
            let from = if piece.from > now { piece.from } else { now };
            let state = piece.at(from);
            let span = piece.to - from;
            let mut best: Option<(f32, Edge)> = None;
            let mut consider = |sigma: f32, edge: Edge| {
                if best.is_none_or(|(b, _)| sigma < b) {
                    best = Some((sigma, edge));
                }
            };
            // A centre meets a mouth's jaws or circle only outside the rectangle (but
            // for a drop circle that reaches into it): in a mouth the piece starts in,
            // or in one whose gap it crosses into (a piece crosses each rail line
            // outwards once at most: its distance is a quadratic). So only those mouths
            // are searched, and those whose circle reaches in if the path's box meets
            // theirs.
            let mut entered = intruding;
            // From when each is searched: the piece's start if it starts in the mouth or
            // the circle reaches onto the cloth, else the gap crossing.
            let mut entered_at = [0.0f32; MAX_POCKETS];
            let start = state.0;
            if self.mouth_count > 0 && self.rails.iter().any(|l| l.normal.dot(start) > l.offset) {
                for (k, mouth) in self.mouths[..self.mouth_count].iter().enumerate() {
                    if mouth.holds(start) {
                        entered |= 1 << k;
                    }
                }
            }
            for (index, line) in self.rails.iter().enumerate() {
                if !rails[index] {
                    continue;
                }
                if let Some(sigma) = line.crossing(state, span) {
                    let gap = if self.gap_count == 0 {
                        None
                    } else {
                        let at = position(state, sigma);
                        let along = if index < 2 { at.x } else { at.y };
                        self.gaps[..self.gap_count]
                            .iter()
                            .find(|g| g.rail == index && along > g.low && along < g.high)
                    };
                    match gap {
                        Some(gap) => {
                            let bit = 1 << gap.mouth;
                            let at = &mut entered_at[gap.mouth];
                            if entered & bit == 0 || sigma < *at {
                                *at = sigma;
                            }
                            entered |= bit;
                        }
                        None => consider(sigma, Edge::Cushion(line.normal, None)),
                    }
                }
            }
            for (k, mouth) in self.mouths[..self.mouth_count].iter().enumerate() {
                if entered == 0 {
                    break;
                }
                if entered & (1 << k) == 0 {
                    continue;
                }
                let (_, q, s) = state;
                let from = entered_at[k];
                let later = (position(state, from), q + s * (2.0 * from), s);
                mouth.meet(later, span - from, &mut |sigma, edge| {
                    consider(from + sigma, edge)
                });
            }
            if let Some((sigma, edge)) = best {
                return Some((from + sigma, edge));
            }
        }
        None
    }
}

#[cfg(test)]
#[path = "boundary/tests.rs"]
mod tests;
