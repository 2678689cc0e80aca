//! The primitives of the table's edges: a centre crossing a line outwards, or entering a
//! circle, on one piece of its path (the piece's state `(p, q, s)` at its start: centre
//! `p + q σ + s σ²`), and what such a crossing is.

use super::roots::{first_rise, first_rise_quadratic};
use crate::vector::Vec3;

/// What a crossing of the boundary is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Edge {
    /// A cushion (a rail, a jaw's face or nose) whose horizontal unit normal at the
    /// contact (into the cushion) is given.
    Cushion(Vec3),
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
/// quartic `reach² − |d(σ)|²` ([`first_rise`]).
pub(crate) fn circle_entry(
    (p, q, s): (Vec3, Vec3, Vec3),
    span: f32,
    centre: Vec3,
    reach: f32,
) -> Option<f32> {
    let flat = |v: Vec3| Vec3::new(v.x, v.y, 0.0);
    let (dp, dq, ds) = (flat(p - centre), flat(q), flat(s));
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
