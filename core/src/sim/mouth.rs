//! One pocket's mouth: its jaws' faces and rounded noses (cushions), its drop circle and
//! back lines ([`super::jaws`] for the geometry and its source), and what a centre meets
//! there on one piece of its path.

use super::crossing::{circle_entry, position, Edge, Line};
use super::jaws::Jaw;
use crate::math;
use crate::vector::Vec3;

/// A jaw's face: where the centre meets it (the face's line moved one radius into the
/// mouth), and the stretch `low ≤ along · r ≤ high` the face covers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Face {
    pub line: Line,
    pub along: Vec3,
    pub low: f32,
    pub high: f32,
}

/// One pocket's mouth: its jaws' faces and noses, its drop circle and back lines, and a
/// box around all of them (for a centre) outside which a path meets none of them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Mouth {
    /// The pocket's index in [`crate::table::Table::pockets`].
    pub pocket: usize,
    /// The box's corners (m).
    pub min: Vec3,
    pub max: Vec3,
    pub faces: [Face; 2],
    /// The noses' centres (m).
    pub noses: [Vec3; 2],
    /// Centre distance at which a ball touches a nose: `R + ρ`.
    pub nose_reach: f32,
    /// The drop circle's centre and radius (m).
    pub centre: Vec3,
    pub radius: f32,
    backs: [Line; 2],
    back_count: usize,
}

/// One end of a mouth: the point `at` on a rail's nose line (m) where the jaw meets
/// it, the unit vector `toward_rail` along the rail away from the pocket, the rail's
/// outward normal `out`, and the rail's index in [`super::boundary::Boundary`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct End {
    pub at: Vec3,
    pub toward_rail: Vec3,
    pub out: Vec3,
    pub rail: usize,
}

impl End {
    pub fn new(at: Vec3, toward_rail: Vec3, out: Vec3, rail: usize) -> Self {
        Self {
            at,
            toward_rail,
            out,
            rail,
        }
    }
}

/// At one end of a mouth, for a jaw whose face is at `angle` (degrees) from the rail's
/// outward normal, `width` deep, and balls of `radius`: the jaw's face, its nose's
/// centre, and how far along the rail from the end the rail's cushion starts (the
/// nose's tangent point).
fn jaw_end(end: &End, jaw: &Jaw, angle: f32, width: f32, radius: f32) -> (Face, Vec3, f32) {
    let (mouth, toward_rail, out) = (end.at, end.toward_rail, end.out);
    let (sin_a, cos_a) = math::sin_cos(angle * (core::f32::consts::PI / 180.0));
    // The face runs into the cushion at α from the rail's normal, towards the pocket.
    let along = out * cos_a - toward_rail * sin_a;
    // The nose is tangent to the rail and the face, `ρ / tan((90° + α)/2)` from the
    // mouth's end along each (`tan(45° + α/2) = (1 + sin α) / cos α`).
    let setback = jaw.nose_radius * cos_a / (1.0 + sin_a);
    let nose = mouth + toward_rail * setback + out * jaw.nose_radius;
    // The face's normal into its cushion, and the line one radius off it.
    let normal = out * sin_a + toward_rail * cos_a;
    let face = Face {
        line: Line {
            normal,
            offset: normal.dot(mouth) - radius,
        },
        along,
        low: along.dot(mouth) + setback,
        high: along.dot(mouth) + width / cos_a,
    };
    (face, nose, setback)
}

impl Mouth {
    /// The mouth of pocket `pocket` between `ends`, with `jaw` and its face's angle
    /// (degrees from the rails' normal), drop circle centred at `circle`, back lines
    /// `cushion_width` beyond each `(normal, point on a nose line)` of `backs`, for balls
    /// of `radius` (m). Also returns, per end, where the rail's cushion starts along it
    /// (the nose's tangent point: `x` on a rail along the length, else `y`).
    pub fn new(
        pocket: usize,
        ends: &[End; 2],
        (jaw, angle): (&Jaw, f32),
        circle: Vec3,
        backs: &[(Vec3, Vec3); 2],
        cushion_width: f32,
        radius: f32,
    ) -> (Self, [f32; 2]) {
        let nose_reach = radius + jaw.nose_radius;
        let drop = jaw.radius;
        let mut mouth = Mouth {
            pocket,
            min: circle - Vec3::new(drop, drop, 0.0),
            max: circle + Vec3::new(drop, drop, 0.0),
            nose_reach,
            centre: circle,
            radius: drop,
            back_count: if backs[0].0 == backs[1].0 { 1 } else { 2 },
            ..Mouth::default()
        };
        let mut edges = [0.0f32; 2];
        for (k, end) in ends.iter().enumerate() {
            let (face, nose, setback) = jaw_end(end, jaw, angle, cushion_width, radius);
            mouth.faces[k] = face;
            mouth.noses[k] = nose;
            // The rail's cushion starts at the nose's tangent point.
            let tangent = end.at + end.toward_rail * setback;
            edges[k] = if end.rail < 2 { tangent.x } else { tangent.y };
            // The box: the nose grown by the reach, the face's ends one radius off.
            let reach = Vec3::new(nose_reach, nose_reach, 0.0);
            mouth.grow(nose - reach);
            mouth.grow(nose + reach);
            for depth in [face.low, face.high] {
                let point = end.at + face.along * (depth - face.along.dot(end.at))
                    - face.line.normal * radius;
                mouth.grow(point);
            }
        }
        for (back, &(out, on_line)) in mouth.backs.iter_mut().zip(backs) {
            *back = Line {
                normal: out,
                offset: out.dot(on_line) + cushion_width,
            };
        }
        (mouth, edges)
    }

    /// Everything of this mouth that the centre meets on a piece (state `(p, q, s)`, for
    /// `span` s), each passed to `consider` with its time from the piece's start.
    /// `true` when `p` is in this mouth's box.
    pub fn holds(&self, p: Vec3) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// `true` when the box from `low` to `high` meets this mouth's box.
    pub fn meets_box(&self, low: Vec3, high: Vec3) -> bool {
        !(low.x > self.max.x || high.x < self.min.x || low.y > self.max.y || high.y < self.min.y)
    }

    #[inline(never)]
    pub fn meet(&self, state: (Vec3, Vec3, Vec3), span: f32, consider: &mut impl FnMut(f32, Edge)) {
        for face in &self.faces {
            if face.low >= face.high {
                continue; // all nose: the face is behind the cushion's width
            }
            if let Some(sigma) = face.line.crossing(state, span) {
                let along = face.along.dot(position(state, sigma));
                if along >= face.low && along <= face.high {
                    consider(sigma, Edge::Cushion(face.line.normal, Some(self.pocket)));
                }
            }
        }
        for nose in &self.noses {
            if let Some(sigma) = circle_entry(state, span, *nose, self.nose_reach) {
                let at = position(state, sigma);
                let towards = Vec3::new(nose.x - at.x, nose.y - at.y, 0.0);
                let distance = towards.length();
                if distance > 0.0 {
                    consider(
                        sigma,
                        Edge::Cushion(towards * (1.0 / distance), Some(self.pocket)),
                    );
                }
            }
        }
        if let Some(sigma) = circle_entry(state, span, self.centre, self.radius) {
            consider(sigma, Edge::Pocket(self.pocket));
        }
        for back in &self.backs[..self.back_count] {
            if let Some(sigma) = back.crossing(state, span) {
                consider(sigma, Edge::Pocket(self.pocket));
            }
        }
    }
}

impl Mouth {
    /// Grow the box to hold `p`.
    fn grow(&mut self, p: Vec3) {
        let (min, max) = (self.min, self.max);
        self.min = Vec3::new(
            if p.x < min.x { p.x } else { min.x },
            if p.y < min.y { p.y } else { min.y },
            0.0,
        );
        self.max = Vec3::new(
            if p.x > max.x { p.x } else { max.x },
            if p.y > max.y { p.y } else { max.y },
            0.0,
        );
    }
}
