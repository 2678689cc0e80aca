//! Pocket jaws: the cushions' shape at a pocket's mouth, and the pocket's drop circle.
//!
//! The geometry is pooltool 0.6's (`pooltool/objects/table/layout.py`,
//! `create_pocket_table_cushion_segments` and `create_pocket_table_pockets`; diagram at
//! <https://ekiefl.github.io/2020/12/20/pooltool-alg/#ball-cushion-collision-times>).
//! At each end `M` of a mouth (on the cushion's nose line, where [`crate::table::Table`]
//! puts it: `corner_mouth / √2` from the corner along each rail, `side_mouth / 2` from the
//! side pocket's centre) the rail's nose line meets the jaw's face, a straight cushion
//! running into the pocket at `α` from the rail's outward normal, turned towards the
//! pocket (`α = 45° + angle` at a corner, `α = angle` at a side pocket). The corner
//! between the two is rounded by the nose, a circle of radius `ρ` tangent to both, so the
//! rail's cushion ends `ρ cos α / (1 + sin α)` (`= ρ / tan((90° + α)/2)`) from `M` and
//! the face starts as far from `M` along itself. The face runs back to the cushion's
//! width behind the nose line. A ball drops when its centre enters the pocket's circle:
//! at a corner, centre `depth / √2` beyond the corner along both rails' normals; at a
//! side pocket, `depth` beyond the rail's nose line.
//!
//! A ball meets the faces and noses as it meets any cushion (Han 2005, [`super::Cushion`]),
//! with the horizontal normal at the contact.

use crate::error::{check, Field, Result};

/// One kind of pocket's jaws (corner or side).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Jaw {
    /// The face's angle (degrees) beyond 45° from the rail's normal at a corner pocket,
    /// beyond 0° at a side pocket, turned towards the pocket (pooltool's
    /// `corner_pocket_angle`, `side_pocket_angle`).
    pub angle: f32,
    /// Radius of the rounded nose between the rail and the face (m).
    pub nose_radius: f32,
    /// How far the pocket's circle is set back (m): a corner's centre `depth / √2` beyond
    /// both rails' nose lines, a side pocket's `depth` beyond its rail's.
    pub depth: f32,
    /// Radius of the pocket's circle (m): a ball whose centre enters it drops.
    pub radius: f32,
}

/// The jaws of a table's pockets.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Jaws {
    /// The corner pockets'.
    pub corner: Jaw,
    /// The side pockets'.
    pub side: Jaw,
    /// How far the faces run back from the nose line (m): the cushion's width.
    pub cushion_width: f32,
}

impl Jaws {
    /// Pool: pooltool 0.6's `PocketTableSpecs` defaults (its 7-ft table): corner jaws at
    /// 5.3°, noses 20.95 mm, pocket circle 62 mm set back 41.7 mm; side jaws at 7.14°,
    /// noses 7.95 mm, circle 64.5 mm set back 68.5 mm; cushions 2" wide.
    pub const POOL: Self = Self {
        corner: Jaw {
            angle: 5.3,
            nose_radius: 0.02095,
            depth: 0.0417,
            radius: 0.062,
        },
        side: Jaw {
            angle: 7.14,
            nose_radius: 0.00795,
            depth: 0.0685,
            radius: 0.0645,
        },
        cushion_width: 0.0508,
    };

    /// Snooker: pooltool 0.6's `SnookerTableSpecs` defaults: square jaws (0°), corner
    /// noses and circle 4" (101.6 mm) set back 36 mm; middle noses 2.5" (63.5 mm), circle
    /// 1.68" (42.67 mm) set back 0.95" (24.13 mm); cushions 1.55" wide.
    pub const SNOOKER: Self = Self {
        corner: Jaw {
            angle: 0.0,
            nose_radius: 0.1016,
            depth: 0.036,
            radius: 0.1016,
        },
        side: Jaw {
            angle: 0.0,
            nose_radius: 0.0635,
            depth: 0.02413,
            radius: 0.042672,
        },
        cushion_width: 0.03937,
    };

    /// `Ok` when every figure is in range: angles in `[0°, 40°]`, nose radii and depths
    /// in `[0, 0.2]` m, circle radii in `(0, 0.3]` m, the cushion width in `(0, 0.2]` m;
    /// else [`Field::Cushion`] with the value. (Whether the jaws close the pocket for a
    /// ball is checked with the table, by the simulation.)
    pub fn check(&self) -> Result<()> {
        for jaw in [&self.corner, &self.side] {
            check(Field::Cushion, jaw.angle, 0.0, 40.0, false)?;
            check(Field::Cushion, jaw.nose_radius, 0.0, 0.2, false)?;
            check(Field::Cushion, jaw.depth, 0.0, 0.2, false)?;
            check(Field::Cushion, jaw.radius, 0.0, 0.3, true)?;
        }
        check(Field::Cushion, self.cushion_width, 0.0, 0.2, true)?;
        Ok(())
    }
}
