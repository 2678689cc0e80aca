//! The primitives of the table's edges: a centre crossing a line outwards, or entering a
//! circle, on one piece of its path (the piece's state `(p, q, s)` at its start: centre
//! `p + q σ + s σ²`), and what such a crossing is.

use super::roots::{first_rise, first_rise_quadratic};
use crate::vector::Vec3;

/// What a crossing of the boundary is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Edge {
    /// A cushion whose horizontal unit normal at the contact (into the cushion) is
    /// given: a rail (`None`) or a jaw's face or nose (`Some` of its pocket's index).
    Cushion(Vec3, Option<usize>),
    /// The pocket of that index in [`crate::table::Table::pockets`].
    Pocket(usize),
}

/// A line `normal · r = offset` that the centre meets rising through it, `normal` the
/// horizontal unit vector out of the region the centre is in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Line {
    pub normal: Vec3,
    pub offset: f32,
}

impl Line {
    /// The first time in `[0, span]` (from the piece's state `(p, q, s)`) at which the
    /// centre crosses the line outwards.
    pub fn crossing(&self, (p, q, s): (Vec3, Vec3, Vec3), span: f32) -> Option<f32> {
        let n = self.normal;
        let c = [n.dot(p) - self.offset, n.dot(q), n.dot(s)];
        let value = |x: f32| n.dot(p + q * x + s * (x * x)) - self.offset;
        first_rise_quadratic(c, span, value)
    }
}

/// The centre at `sigma` from the piece's state `(p, q, s)`.
pub(crate) fn position((p, q, s): (Vec3, Vec3, Vec3), sigma: f32) -> Vec3 {
    p + q * sigma + s * (sigma * sigma)
}

/// The first time in `[0, span]` at which the centre (state `(p, q, s)`) comes within
/// `reach` of `centre`, horizontally, while approaching it: the first rise of the
/// quartic `reach² − |d(σ)|²` ([`first_rise`]), after [`within_reach`] rules out the
/// pieces that stay far from it.
pub(crate) fn circle_entry(
    (p, q, s): (Vec3, Vec3, Vec3),
    span: f32,
    centre: Vec3,
    reach: f32,
) -> Option<f32> {
    let flat = |v: Vec3| Vec3::new(v.x, v.y, 0.0);
    let (dp, dq, ds) = (flat(p - centre), flat(q), flat(s));
    if !within_reach(dp, dq, ds, span, reach) {
        return None;
    }
    let reach2 = reach * reach;
    let c = [
        reach2 - dp.dot(dp),
        -2.0 * dp.dot(dq),
        -(dq.dot(dq) + 2.0 * dp.dot(ds)),
        -2.0 * dq.dot(ds),
        -ds.dot(ds),
    ];
    let value = |x: f32| {
        let d = dp + dq * x + ds * (x * x);
        reach2 - d.dot(d)
    };
    first_rise(&c, span, value)
}

/// `false` when the difference `d(σ) = dp + dq σ + ds σ²`, `σ ∈ [0, span]`, surely
/// stays farther than `reach` from the origin. It is the quadratic Bézier curve of the
/// control points `B₀ = dp`, `B₁ = dp + dq span/2`, `B₂ = dp + dq span + ds span²`,
/// so (1) it lies in their box, and (2) it is the chord from `B₀` to `B₂` plus
/// `2t(1 − t) (B₁ − M)` with `M` the chord's midpoint, so within `|B₁ − M|/2` of the
/// chord: farther than `reach` if the chord is farther than `reach + |B₁ − M|/2`. The
/// box is the cheap test, the chord the tight one (a ball rolling past another).
#[inline]
pub(crate) fn within_reach(dp: Vec3, dq: Vec3, ds: Vec3, span: f32, reach: f32) -> bool {
    let middle = dp + dq * (0.5 * span);
    let end = dp + dq * span + ds * (span * span);
    let low_x = min3(dp.x, middle.x, end.x);
    let high_x = -min3(-dp.x, -middle.x, -end.x);
    let low_y = min3(dp.y, middle.y, end.y);
    let high_y = -min3(-dp.y, -middle.y, -end.y);
    // NaN (an unbounded span) fails every comparison: no rejection.
    if low_x > reach || high_x < -reach || low_y > reach || high_y < -reach {
        return false;
    }
    let chord = Vec3::new(end.x - dp.x, end.y - dp.y, 0.0);
    let length_squared = chord.dot(chord);
    let t = if length_squared > 0.0 {
        // NaN stays NaN through `clamp`, and fails the comparison below: no rejection.
        (-Vec3::new(dp.x, dp.y, 0.0).dot(chord) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let closest = Vec3::new(dp.x + chord.x * t, dp.y + chord.y * t, 0.0);
    let bulge = Vec3::new(
        middle.x - 0.5 * (dp.x + end.x),
        middle.y - 0.5 * (dp.y + end.y),
        0.0,
    );
    let margin = reach + 0.5 * bulge.length();
    let far = closest.dot(closest) > margin * margin;
    !far
}

fn min3(a: f32, b: f32, c: f32) -> f32 {
    let m = if a < b { a } else { b };
    if m < c {
        m
    } else {
        c
    }
}
