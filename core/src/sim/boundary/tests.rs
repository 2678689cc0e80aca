//! The jaws' geometry against pooltool 0.6's layout formulas, and what a ball meets at a
//! pocket's mouth.

extern crate std;

use super::*;
use crate::table::BallSet;
use crate::travel::{Cloth, Motion};

const R: f32 = BallSet::POOL.radius;

fn pool() -> Boundary {
    Boundary::new(&Table::pool(), &Jaws::POOL, R)
}

/// Where a ball rolling from `from` with `velocity` (m/s, rolling without slip) first
/// meets the boundary.
fn first_edge(
    boundary: &Boundary,
    from: [f32; 2],
    velocity: [f32; 2],
) -> Option<(f32, Edge, Vec3)> {
    let v = Vec3::new(velocity[0], velocity[1], 0.0);
    // Rolling: ω = ẑ × v / R.
    let spin = Vec3::new(-v.y / R, v.x / R, 0.0);
    let motion = Motion::new(
        Vec3::new(from[0], from[1], 0.0),
        v,
        spin,
        R,
        &Cloth::TYPICAL,
    )
    .unwrap();
    let track = Track::new(motion, 0.0, 0.0);
    boundary
        .exit(&track, 0.0)
        .map(|(t, edge)| (t, edge, track.position_at(t)))
}

/// pooltool 0.6's corner nose `1t` (`layout.py`): centre `(pw cos 45° + dc, −rc)` in
/// its frame (across, along; the corner at the origin), `dc = rc / tan((90° + ca)/2)`,
/// `ca = 45° + corner_pocket_angle`; its side nose `4t`: `(−rs, l/2 − sw/2 − ds)`,
/// `ds = rs / tan((90° + sa)/2)`. Computed here in f64 from those formulas; ours
/// (`jaw_end`) by the vector construction, to f32 rounding.
#[test]
fn noses_sit_where_pooltools_layout_puts_them() {
    // Pool, and snooker (pooltool's own snooker jaws; our mouths).
    let tables = [
        (Table::pool(), Jaws::POOL, R, 0.116f64, 0.13f64),
        (
            Table::snooker(),
            Jaws::SNOOKER,
            BallSet::SNOOKER.radius,
            0.086,
            0.095,
        ),
    ];
    for (table, jaws, radius, corner_mouth, side_mouth) in tables {
        let boundary = Boundary::new(&table, &jaws, radius);
        let ca = (45.0 + f64::from(jaws.corner.angle)).to_radians();
        let rc = f64::from(jaws.corner.nose_radius);
        let dc = rc / ((core::f64::consts::FRAC_PI_2 + ca) / 2.0).tan();
        let sa = f64::from(jaws.side.angle).to_radians();
        let rs = f64::from(jaws.side.nose_radius);
        let ds = rs / ((core::f64::consts::FRAC_PI_2 + sa) / 2.0).tan();
        let along_rail = corner_mouth * core::f64::consts::FRAC_1_SQRT_2 + dc;
        let at = |nose: &Vec3, (x, y): (f64, f64)| {
            let off = (f64::from(nose.x) - x)
                .abs()
                .max((f64::from(nose.y) - y).abs());
            assert!(off < 1e-6, "{nose:?} vs ({x}, {y})");
        };
        // Pocket 0 is the corner at the origin: its noses behind the y = 0 rail and
        // the x = 0 rail.
        let corner = &boundary.mouths[0];
        at(&corner.noses[0], (along_rail, -rc));
        at(&corner.noses[1], (-rc, along_rail));
        // Pocket 4 is the side pocket on the y = 0 rail, at x = L/2.
        let side = boundary.mouths.iter().find(|m| m.pocket == 4).unwrap();
        let half_length = 0.5 * f64::from(table.length());
        at(&side.noses[0], (half_length - side_mouth / 2.0 - ds, -rs));
        at(&side.noses[1], (half_length + side_mouth / 2.0 + ds, -rs));
        // Each face's line (one radius off) is tangent to its nose grown by the
        // radius: the nose's centre is `R + ρ` beyond the centre's line.
        for mouth in [corner, side] {
            for (face, nose) in mouth.faces.iter().zip(&mouth.noses) {
                let distance = face.line.offset - face.line.normal.dot(*nose);
                assert!(
                    (distance + mouth.nose_reach).abs() < 1e-6,
                    "{distance} vs {}",
                    mouth.nose_reach
                );
            }
        }
        // Pockets' circles: pooltool's `(−cd/√2, −cd/√2)` and `(−sd, l/2)` (ours:
        // y = −sd).
        let cd = f64::from(jaws.corner.depth) * core::f64::consts::FRAC_1_SQRT_2;
        assert!((f64::from(corner.centre.x) + cd).abs() < 1e-7);
        assert!((f64::from(corner.centre.y) + cd).abs() < 1e-7);
        assert!((f64::from(side.centre.y) + f64::from(jaws.side.depth)).abs() < 1e-7);
    }
}

#[test]
fn a_ball_rolled_into_a_corner_or_a_side_pocket_drops() {
    let boundary = pool();
    // Down the corner's diagonal.
    let (_, edge, _) = first_edge(&boundary, [0.5, 0.5], [-1.0, -1.0]).unwrap();
    assert_eq!(edge, Edge::Pocket(0));
    // Straight into the side pocket on the y = 0 rail.
    let (_, edge, at) = first_edge(&boundary, [1.27, 0.6], [0.0, -1.5]).unwrap();
    assert_eq!(edge, Edge::Pocket(4), "{at:?}");
    // The centre drops where it enters the circle: 64.5 mm around (L/2, −68.5 mm).
    assert!((at.y - (0.0645 - 0.0685)).abs() < 1e-4, "{at:?}");
}

#[test]
fn a_rail_away_from_the_pockets_is_a_cushion_with_its_normal() {
    let boundary = pool();
    let (_, edge, at) = first_edge(&boundary, [0.7, 0.6], [0.0, -2.0]).unwrap();
    assert_eq!(edge, Edge::Cushion(Vec3::new(0.0, -1.0, 0.0), None));
    assert!((at.y - R).abs() < 1e-5);
}

/// A ball sent along the rail into a corner pocket's far jaw (the one on the other
/// rail), or across a side pocket's mouth into its far nose, is turned away by the jaw:
/// a cushion contact whose normal is neither rail's.
#[test]
fn a_ball_into_a_far_jaw_meets_the_jaw_not_the_pocket() {
    let boundary = pool();
    // Along the y = 0 rail's nose line, one radius in plus 1 mm (it grazes no rail):
    // into the corner, where the jaw on the x = 0 rail stands in its way.
    let (_, edge, at) = first_edge(&boundary, [0.8, R + 0.001], [-2.0, 0.0]).unwrap();
    let Edge::Cushion(normal, Some(0)) = edge else {
        panic!("{edge:?} at {at:?}");
    };
    assert!(normal.x < -0.5 && normal.y != 0.0, "{normal:?} at {at:?}");
    // Across the side pocket's mouth at 15° to the rail, into its far (x > L/2) nose.
    let (sin, cos) = (15f32.to_radians().sin(), 15f32.to_radians().cos());
    let (_, edge, at) = first_edge(&boundary, [1.15, 0.06], [2.0 * cos, -2.0 * sin]).unwrap();
    let Edge::Cushion(normal, Some(4)) = edge else {
        panic!("{edge:?} at {at:?}");
    };
    assert!(at.x > 1.27 && at.y < R, "{at:?}");
    assert!(normal.x > 0.3 && normal.y < 0.0, "{normal:?} at {at:?}");
}

/// A table without pockets (carom) keeps its whole rails.
#[test]
fn a_carom_table_is_all_cushion() {
    let boundary = Boundary::new(&Table::carom(), &Jaws::POOL, BallSet::CAROM.radius);
    assert_eq!((boundary.gap_count, boundary.mouth_count), (0, 0));
}

/// Snooker's corner circles (pooltool's 4", 36 mm back) reach into the rectangle: a ball
/// rolled gently into a corner drops there without reaching a rail line.
#[test]
fn a_drop_circle_that_reaches_onto_the_cloth_is_searched_inside_too() {
    let r = BallSet::SNOOKER.radius;
    let boundary = Boundary::new(&Table::snooker(), &Jaws::SNOOKER, r);
    assert_eq!(boundary.intruding & 1, 1, "{:b}", boundary.intruding);
    // The slowest roll down the corner's diagonal that ends within the circle (centre
    // 0.0255 m beyond the corner on both axes, radius 0.1016 m) but inside the rails.
    let entry =
        0.1016 * core::f32::consts::FRAC_1_SQRT_2 - 0.036 * core::f32::consts::FRAC_1_SQRT_2;
    let track = (1..400)
        .map(|step| {
            let speed = 0.005 * step as f32;
            let v = Vec3::new(-speed, -speed, 0.0) * core::f32::consts::FRAC_1_SQRT_2;
            let spin = Vec3::new(-v.y / r, v.x / r, 0.0);
            let start = Vec3::new(0.3, 0.3, 0.0);
            Track::new(
                Motion::new(start, v, spin, r, &Cloth::TYPICAL).unwrap(),
                0.0,
                0.0,
            )
        })
        .find(|track| track.motion.rest().x < entry - 0.002)
        .unwrap();
    let rest = track.motion.rest();
    assert!(
        rest.x > r && rest.y > r,
        "{rest:?} should be inside the rails"
    );
    let (_, edge) = boundary.exit(&track, 0.0).unwrap();
    assert_eq!(edge, Edge::Pocket(0));
    // Pool's circles stay behind the rails.
    assert_eq!(pool().intruding, 0);
}
