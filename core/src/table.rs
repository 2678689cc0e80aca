//! Tables, pockets, ball sets and the scene of balls on a table (fixed capacity).
//!
//! Table coordinates: origin at a corner of the playing surface, `x` along its length,
//! `y` along its width, metres. A pocket is the target segment its mouth presents to a
//! ball **centre** (the jaws moved in by one ball radius), so "the ball reaches the
//! pocket" means its centre crosses that segment.

use crate::error::{check, Error, Field, Result};
use crate::math;
use crate::vector::Vec3;

/// Most balls a scene holds (cue ball included).
pub const MAX_BALLS: usize = 16;
/// Most pockets a table has.
pub const MAX_POCKETS: usize = 6;

/// Radius and mass of a set of balls.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BallSet {
    /// Radius (m).
    pub radius: f32,
    /// Mass (kg).
    pub mass: f32,
}

impl BallSet {
    /// Pool: 57.15 mm, 170 g (physics-notes §5).
    pub const POOL: Self = Self {
        radius: 0.028575,
        mass: 0.17,
    };
    /// Snooker: 52.5 mm, 142 g.
    pub const SNOOKER: Self = Self {
        radius: 0.02625,
        mass: 0.142,
    };
    /// Carom: 61.5 mm, 210 g.
    pub const CAROM: Self = Self {
        radius: 0.03075,
        mass: 0.21,
    };
}

/// A pocket's target segment for a ball centre, from `a` to `b` (m).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pocket {
    /// One end of the target segment.
    pub a: Vec3,
    /// The other end.
    pub b: Vec3,
}

impl Pocket {
    /// Centre of the target segment.
    pub fn centre(&self) -> Vec3 {
        (self.a + self.b) * 0.5
    }
}

/// A rectangular table with up to six pockets.
#[derive(Clone, PartialEq)]
pub struct Table {
    length: f32,
    width: f32,
    /// The pockets, `pockets[..pocket_count]`; the rest are unused (both ends at the
    /// origin).
    pockets: [Pocket; MAX_POCKETS],
    pocket_count: usize,
}

impl core::fmt::Debug for Table {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Table")
            .field("length", &self.length)
            .field("width", &self.width)
            .field("pockets", &self.pockets())
            .finish()
    }
}

/// The pool preset ([`Table::pool`]), laid out at compile time.
const POOL: Table = Table::layout(2.54, 1.27, 0.116, 0.13, BallSet::POOL.radius);
/// The snooker preset ([`Table::snooker`]).
const SNOOKER: Table = Table::layout(3.569, 1.778, 0.086, 0.095, BallSet::SNOOKER.radius);
/// The carom preset ([`Table::carom`]).
const CAROM: Table = Table::layout(2.84, 1.42, 0.0, 0.0, BallSet::CAROM.radius);

impl Table {
    /// A table of playing surface `length` × `width` (m, each in `(0, 10]`), with the
    /// usual six pockets of mouth widths `corner_mouth` and `side_mouth` (m; zero for a
    /// pocketless carom table), for balls of radius `radius` (m, in `[0.001, 1]`, as
    /// [`Scene::new`] takes it).
    pub fn new(
        length: f32,
        width: f32,
        corner_mouth: f32,
        side_mouth: f32,
        radius: f32,
    ) -> Result<Self> {
        let length = check(Field::Table, length, 0.0, 10.0, true)?;
        let width = check(Field::Table, width, 0.0, length, true)?;
        let corner_mouth = check(Field::Table, corner_mouth, 0.0, 0.5 * width, false)?;
        let side_mouth = check(Field::Table, side_mouth, 0.0, 0.5 * length, false)?;
        // The pockets' target segments are moved in by the radius.
        let radius = check(Field::Radius, radius, 0.001, 1.0, false)?;
        Ok(Self::layout(
            length,
            width,
            corner_mouth,
            side_mouth,
            radius,
        ))
    }

    /// The table of [`Table::new`] for arguments that pass its checks: a `const fn`, so
    /// that the presets are laid out at compile time (the firmware then links no table
    /// arithmetic; f32 arithmetic is IEEE 754 at compile time too, so the pockets are
    /// the same to the bit).
    const fn layout(
        length: f32,
        width: f32,
        corner_mouth: f32,
        side_mouth: f32,
        radius: f32,
    ) -> Self {
        let unused = Pocket {
            a: Vec3::ZERO,
            b: Vec3::ZERO,
        };
        let mut pockets = [unused; MAX_POCKETS];
        let mut count = 0;
        if corner_mouth > 0.0 {
            // Jaws on the two rails at `corner_mouth / √2` from the corner; the segment is
            // moved one radius in along the diagonal.
            let jaw = corner_mouth * core::f32::consts::FRAC_1_SQRT_2;
            let inset = radius * core::f32::consts::SQRT_2;
            // Across the table (y) the near and far ends are exact mirror images,
            // `y_near = W − y_far` in f32, so that a scene mirrored across the long axis
            // meets exactly mirrored pockets.
            let (a_near, a_far) = mirrored(width, inset);
            let (b_near, b_far) = mirrored(width, jaw + inset);
            let corners = [
                (0.0, 1.0, a_near, b_near),
                (length, -1.0, a_near, b_near),
                (0.0, 1.0, a_far, b_far),
                (length, -1.0, a_far, b_far),
            ];
            while count < corners.len() {
                let (x, dx, a_y, b_y) = corners[count];
                pockets[count] = Pocket {
                    a: Vec3::new(x + dx * (jaw + inset), a_y, 0.0),
                    b: Vec3::new(x + dx * inset, b_y, 0.0),
                };
                count += 1;
            }
        }
        if side_mouth > 0.0 {
            let (near, far) = mirrored(width, radius);
            let sides = [near, far];
            let mut i = 0;
            while i < sides.len() {
                pockets[count] = Pocket {
                    a: Vec3::new(0.5 * (length - side_mouth), sides[i], 0.0),
                    b: Vec3::new(0.5 * (length + side_mouth), sides[i], 0.0),
                };
                count += 1;
                i += 1;
            }
        }
        Self {
            length,
            width,
            pockets,
            pocket_count: count,
        }
    }

    /// 9-ft pool table: 2.54 × 1.27 m, corner mouths 116 mm, side mouths 130 mm.
    pub fn pool() -> Self {
        POOL
    }

    /// Full-size snooker table: 3.569 × 1.778 m, corner mouths 86 mm, middle 95 mm.
    pub fn snooker() -> Self {
        SNOOKER
    }

    /// Carom (match) table: 2.84 × 1.42 m, no pockets.
    pub fn carom() -> Self {
        CAROM
    }

    /// Length (m).
    pub const fn length(&self) -> f32 {
        self.length
    }
    /// Width (m).
    pub const fn width(&self) -> f32 {
        self.width
    }
    /// The pockets.
    pub fn pockets(&self) -> &[Pocket] {
        self.pockets.get(..self.pocket_count).unwrap_or(&[])
    }

    /// `true` when a ball of `radius` centred at `p` lies on the playing surface.
    pub fn contains(&self, p: Vec3, radius: f32) -> bool {
        p.x >= radius && p.x <= self.length - radius && p.y >= radius && p.y <= self.width - radius
    }
}

/// `(y, W − y)` for a `0 < y ≤ W/2` near the `y = 0` rail, rounded so that each is
/// exactly `W` minus the other in f32 and neither moves outwards (a side pocket's target
/// stays on the cushion line or inside it): the far one is `W − y` rounded down, the
/// near one `W − far`, exact (Sterbenz) as `far ≥ W/2`.
const fn mirrored(width: f32, y: f32) -> (f32, f32) {
    let mut far = width - y;
    if width - far < y && far > 0.0 {
        far = f32::from_bits(far.to_bits() - 1);
    }
    (width - far, far)
}

/// Balls at rest on a table: index 0 is the cue ball.
///
/// ```
/// use cuesight::table::{BallSet, Scene, Table, MAX_BALLS};
/// use cuesight::{Field, Vec3};
///
/// let r = BallSet::POOL.radius;
/// let mut scene = Scene::new(Table::pool(), r, [0.635, 0.635])?; // cue ball: index 0
/// let one = scene.add_ball([1.905, 0.635])?; // on the foot spot
/// assert_eq!(one, 1);
/// assert_eq!(scene.balls().len(), 2);
/// // Straight down the table the cue ball touches ball 1 after 1.27 m − 2R.
/// let d = scene.contact_distance(Vec3::new(1.0, 0.0, 0.0), one).unwrap();
/// assert!((d - (1.27 - 2.0 * r)).abs() < 1e-5);
///
/// // Every placement is checked: off the cloth, overlapping, or one too many.
/// let off = scene.add_ball([3.0, 0.635]).unwrap_err();
/// assert_eq!(off.field(), Some(Field::Position));
/// let overlap = scene.add_ball([1.905 + r, 0.635]).unwrap_err();
/// assert_eq!(overlap.field(), Some(Field::Spacing));
/// for i in 2..MAX_BALLS {
///     scene.add_ball([0.1 + 0.15 * i as f32, 1.0])?;
/// }
/// let full = scene.add_ball([0.2, 0.2]).unwrap_err();
/// assert_eq!(full.field(), Some(Field::BallCount));
/// # Ok::<(), cuesight::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    table: Table,
    balls: heapless::Vec<Vec3, MAX_BALLS>,
    radius: f32,
}

impl Scene {
    /// A scene on `table` for balls of `radius` (m), with the cue ball at `cue_ball`.
    pub fn new(table: Table, radius: f32, cue_ball: [f32; 2]) -> Result<Self> {
        let radius = check(Field::Radius, radius, 0.001, 1.0, false)?;
        let mut scene = Self {
            table,
            balls: heapless::Vec::new(),
            radius,
        };
        scene.add_ball(cue_ball)?;
        Ok(scene)
    }

    /// Place another ball; returns its index. Errors: a coordinate not finite or off the
    /// playing surface ([`Field::Position`], the coordinate), overlapping a ball
    /// ([`Field::Spacing`], the centre distance; touching is allowed), or more than
    /// [`MAX_BALLS`] ([`Field::BallCount`]).
    pub fn add_ball(&mut self, position: [f32; 2]) -> Result<usize> {
        let x = check(Field::Position, position[0], -1e3, 1e3, false)?;
        let y = check(Field::Position, position[1], -1e3, 1e3, false)?;
        let p = Vec3::new(x, y, 0.0);
        if !self.table.contains(p, self.radius) {
            // Name the coordinate that is off the playing surface.
            let r = self.radius;
            let x_on = x >= r && x <= self.table.length - r;
            return Err(Error::OutOfRange {
                field: Field::Position,
                value: if x_on { y } else { x },
            });
        }
        for other in &self.balls {
            let distance = (*other - p).length();
            if distance < 2.0 * self.radius * (1.0 - 1e-6) {
                return Err(Error::OutOfRange {
                    field: Field::Spacing,
                    value: distance,
                });
            }
        }
        self.balls.push(p).map_err(|_| Error::OutOfRange {
            field: Field::BallCount,
            value: (MAX_BALLS + 1) as f32,
        })?;
        Ok(self.balls.len() - 1)
    }

    /// The table.
    pub fn table(&self) -> &Table {
        &self.table
    }
    /// Ball centres (index 0: cue ball).
    pub fn balls(&self) -> &[Vec3] {
        &self.balls
    }
    /// Ball radius (m).
    pub const fn radius(&self) -> f32 {
        self.radius
    }

    /// Distance the cue ball's centre travels along the unit direction `aim` before it
    /// touches ball `index` (`None` if the line misses it or the ball is behind).
    pub fn contact_distance(&self, aim: Vec3, index: usize) -> Option<f32> {
        let (cue, target) = (*self.balls.first()?, *self.balls.get(index)?);
        let to_target = target - cue;
        let along = to_target.dot(aim);
        let across = to_target.x * aim.y - to_target.y * aim.x;
        let reach = 2.0 * self.radius;
        // `reach² − across²` factored: near a graze `reach − |across|` is exact
        // (Sterbenz), where the difference of the squares cancels (a carom ball one
        // 2⁻²³ m step inside tangency: contact 0.6 µm off, the line of centres turned by
        // 1e-5 rad).
        let across = math::abs(across);
        let gap = (reach - across) * (reach + across);
        // Written so that a NaN aim gives `None` (it gave a contact at distance 0).
        if along > 0.0 && gap >= 0.0 {
            Some(math::max(along - math::sqrt(gap), 0.0))
        } else {
            None
        }
    }
}

impl Scene {
    /// Unit line of centres (cue ball → ball `index`, table frame) where the cue ball
    /// moving along the unit `aim` first touches it, from the same geometry as
    /// [`Scene::contact_distance`]: `(√gap · aim + lateral · ẑ×aim) / 2R`, with
    /// `lateral` the ball's offset from the path. Exact where it should be (a straight
    /// shot: `aim`), and exactly mirrored with the scene; `None` when there is no
    /// contact. Balls touching (or within the placement tolerance of it) already: the
    /// line of centres where they are.
    pub(crate) fn contact_line(&self, aim: Vec3, index: usize) -> Option<Vec3> {
        let (cue, target) = (*self.balls.first()?, *self.balls.get(index)?);
        let to_target = target - cue;
        let along = to_target.dot(aim);
        let side = Vec3::new(-aim.y, aim.x, 0.0);
        let lateral = to_target.dot(side);
        let reach = 2.0 * self.radius;
        let offset = math::abs(lateral);
        let gap = (reach - offset) * (reach + offset);
        if !(along > 0.0 && gap >= 0.0) {
            return None;
        }
        let root = math::sqrt(gap);
        let line = if along - root >= 0.0 {
            aim * root + side * lateral
        } else {
            to_target
        };
        let length = if along - root >= 0.0 {
            reach
        } else {
            to_target.length()
        };
        Some(Vec3::new(line.x / length, line.y / length, 0.0))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;

    /// Found by the `shot_scene` fuzz target: `Table::new` did not check the radius, so
    /// a NaN or infinite one gave a table whose pockets were NaN.
    #[test]
    fn a_table_for_an_invalid_radius_is_refused() {
        for radius in [f32::NAN, f32::INFINITY, -f32::INFINITY] {
            assert_eq!(
                Table::new(2.54, 1.27, 0.116, 0.13, radius),
                Err(Error::NotFinite {
                    field: Field::Radius
                })
            );
        }
        for radius in [0.0, -0.03, 1e-4, 1.5] {
            assert_eq!(
                Table::new(2.54, 1.27, 0.116, 0.13, radius)
                    .unwrap_err()
                    .field(),
                Some(Field::Radius),
                "{radius}"
            );
        }
        for radius in [0.001, BallSet::POOL.radius, 1.0] {
            let table = Table::new(2.54, 1.27, 0.116, 0.13, radius).unwrap();
            assert!(table
                .pockets()
                .iter()
                .all(|p| p.a.is_finite() && p.b.is_finite()));
        }
    }

    /// The presets, laid out at compile time, are the tables `Table::new` lays out at
    /// run time from the same dimensions (which pass its checks), to the bit.
    #[test]
    fn presets_are_the_tables_new_lays_out() {
        use core::hint::black_box;
        let presets = [
            (
                Table::pool(),
                [2.54, 1.27, 0.116, 0.13, BallSet::POOL.radius],
                6,
            ),
            (
                Table::snooker(),
                [3.569, 1.778, 0.086, 0.095, BallSet::SNOOKER.radius],
                6,
            ),
            (
                Table::carom(),
                [2.84, 1.42, 0.0, 0.0, BallSet::CAROM.radius],
                0,
            ),
        ];
        let bits = |t: &Table| {
            let mut bits = std::vec![t.length().to_bits(), t.width().to_bits()];
            for p in t.pockets() {
                for v in [p.a, p.b] {
                    bits.extend(v.to_array().map(f32::to_bits));
                }
            }
            bits
        };
        for (preset, [length, width, corner, side, radius], pockets) in presets {
            let built = Table::new(
                black_box(length),
                black_box(width),
                black_box(corner),
                black_box(side),
                black_box(radius),
            )
            .unwrap();
            assert_eq!(preset.pockets().len(), pockets);
            assert_eq!(bits(&preset), bits(&built));
            assert_eq!(preset, built);
        }
    }

    /// Near a graze the distance to contact is `along − √(4R² − across²)`, evaluated
    /// here in f64 from the same f32 positions: within a few ulp of the table
    /// coordinates, where `reach² − across²` in f32 had cancelled (carom ball one 2⁻²³ m
    /// step inside tangency: 0.6 µm off).
    /// A ball off the table reported its x coordinate even when y was the one off, and
    /// an overlapping ball was reported as a position with its x coordinate: the
    /// message did not say what was wrong. Now the coordinate off the surface, or the
    /// centre distance of the overlap (`Field::Spacing`), is named.
    #[test]
    fn placement_errors_name_what_is_wrong() {
        use std::string::ToString;
        let r = BallSet::POOL.radius;
        let mut scene = Scene::new(Table::pool(), r, [0.5, 0.6]).unwrap();
        let off = |value| {
            Err(Error::OutOfRange {
                field: Field::Position,
                value,
            })
        };
        assert_eq!(scene.add_ball([1.0, 1.26]), off(1.26));
        assert_eq!(scene.add_ball([0.01, 0.6]), off(0.01));
        assert_eq!(scene.add_ball([2.6, -1.0]), off(2.6));
        assert_eq!(
            scene.add_ball([0.5 + r, 0.6]),
            Err(Error::OutOfRange {
                field: Field::Spacing,
                value: (0.5 + r) - 0.5,
            })
        );
        assert_eq!(scene.add_ball([0.5 + 2.0 * r, 0.6]), Ok(1));
        let message = scene.add_ball([0.5, 0.6]).unwrap_err().to_string();
        assert_eq!(
            message,
            "spacing = 0 is outside centre distances of at least 2R (balls may touch)"
        );
    }

    /// `contact_distance` with a NaN aim reported a contact at distance 0 (NaN failed
    /// both rejection tests and `max(NaN, 0)` is 0); an infinite one likewise. Now no
    /// contact.
    #[test]
    fn contact_distance_of_a_nan_aim_is_none() {
        let mut scene = Scene::new(Table::pool(), BallSet::POOL.radius, [0.5, 0.6]).unwrap();
        scene.add_ball([1.5, 0.6]).unwrap();
        for aim in [
            Vec3::new(f32::NAN, 0.0, 0.0),
            Vec3::new(0.0, f32::NAN, 0.0),
            Vec3::new(f32::INFINITY, f32::NEG_INFINITY, 0.0),
        ] {
            assert_eq!(scene.contact_distance(aim, 1), None, "{aim:?}");
        }
        assert_eq!(scene.contact_distance(Vec3::new(1.0, 0.0, 0.0), 0), None);
        assert_eq!(scene.contact_distance(Vec3::new(1.0, 0.0, 0.0), 2), None);
    }

    /// The line of centres at contact, from the geometry, is exactly the aim for a
    /// straight shot (also touching) and within a few ε of the f64 geometry otherwise.
    #[test]
    fn contact_line_matches_the_geometry() {
        let r = BallSet::POOL.radius;
        let x = Vec3::new(1.0, 0.0, 0.0);
        for object in [[1.5f32, 0.6], [0.5 + 2.0 * r, 0.6]] {
            let mut scene = Scene::new(Table::pool(), r, [0.5, 0.6]).unwrap();
            scene.add_ball(object).unwrap();
            assert_eq!(scene.contact_line(x, 1), Some(x));
        }
        let mut scene = Scene::new(Table::pool(), r, [0.5, 0.6]).unwrap();
        scene.add_ball([1.5, 0.63]).unwrap();
        for turn in [-0.02f32, -0.01, 0.0, 0.02, 0.04] {
            let aim = Vec3::new(turn.cos(), turn.sin(), 0.0);
            let line = scene.contact_line(aim, 1).unwrap();
            let (ax, ay) = (f64::from(aim.x), f64::from(aim.y));
            let (tx, ty) = (1.0f64, f64::from(0.63f32) - f64::from(0.6f32));
            let along = tx * ax + ty * ay;
            let lateral = -tx * ay + ty * ax;
            let reach = 2.0 * f64::from(r);
            let root = (reach * reach - lateral * lateral).sqrt();
            let expected = [
                (ax * root - ay * lateral) / reach,
                (ay * root + ax * lateral) / reach,
            ];
            assert!(along > root);
            let error = (f64::from(line.x) - expected[0]).hypot(f64::from(line.y) - expected[1]);
            assert!(error < 1e-5, "{turn}: {line:?} vs {expected:?}");
        }
        assert_eq!(scene.contact_line(Vec3::new(0.0, 1.0, 0.0), 1), None);
    }

    /// Each pocket's mirror image across the long axis (`y → W − y`, in f32) is
    /// exactly another pocket, ends in the same order: corner 0 ↔ 2, 1 ↔ 3, side 4 ↔ 5.
    /// The near pockets were at `inset`, the far ones at `W − inset` rounded, so
    /// mirrored shots into them differed in the last bits.
    #[test]
    fn pockets_mirror_exactly_across_the_long_axis() {
        let custom = Table::new(2.1, 1.07, 0.11, 0.125, 0.0286).unwrap();
        for table in [Table::pool(), Table::snooker(), custom] {
            let w = table.width();
            let p = table.pockets();
            assert_eq!(p.len(), 6);
            for (i, j) in [(0, 2), (1, 3), (4, 5)] {
                for (near, far) in [(p[i].a, p[j].a), (p[i].b, p[j].b)] {
                    assert_eq!(near.x, far.x);
                    assert_eq!(w - near.y, far.y, "{i} {j}");
                    assert_eq!(w - far.y, near.y, "{i} {j}");
                }
            }
            // Side pockets on (or inside) the cushion lines `y = R` and `y = W − R`.
            let r = if w > 1.5 {
                BallSet::SNOOKER.radius
            } else if w > 1.1 {
                BallSet::POOL.radius
            } else {
                0.0286
            };
            assert!(p[4].a.y >= r && p[5].a.y <= w - r, "{:?} {:?}", p[4], p[5]);
        }
    }

    #[test]
    fn contact_distance_near_a_graze_keeps_its_digits() {
        for set in [BallSet::POOL, BallSet::SNOOKER, BallSet::CAROM] {
            let r = set.radius;
            let cue = [0.3f32, 0.5];
            let reach = 2.0 * f64::from(r);
            for steps in [1u32, 2, 16, 256, 65_536] {
                // The object's y offset `steps` grid steps (2⁻²³ m) inside tangency.
                let grid = 1.0 / 8_388_608.0;
                let dy = ((reach / grid).floor() - f64::from(steps - 1)) * grid;
                let object = [1.2f32, (0.5 + dy) as f32];
                let mut scene = Scene::new(Table::carom(), r, cue).unwrap();
                scene.add_ball(object).unwrap();
                let got = scene
                    .contact_distance(Vec3::new(1.0, 0.0, 0.0), 1)
                    .expect("inside tangency: a hit");
                let (along, across) = (
                    f64::from(object[0]) - f64::from(cue[0]),
                    f64::from(object[1]) - f64::from(cue[1]),
                );
                let expected = along - (reach * reach - across * across).sqrt();
                // along − √gap: a few roundings of numbers ≤ 1 m, plus the √ of a gap
                // with relative error 3ε.
                let root = (reach * reach - across * across).sqrt();
                let allowed = 4.0 * 1.2e-7 + 3.0 * 6e-8 * root;
                assert!(
                    (f64::from(got) - expected).abs() <= allowed,
                    "R {r}, {steps} steps: {got} vs {expected}"
                );
            }
        }
    }
}
