//! Three reference shots, for benches, tests and examples: a three-cushion carom point,
//! sixteen balls spread over a pool table, and a 9-ball break. The Cortex-M4F probe
//! measures them (`bench-firmware/src/bin/table_probe.rs`) and the host replays them to
//! check that both give the same result to the bit ([`digest`]).

use super::{play, Setup};
use crate::error::Result;
use crate::shot::Stroke;
use crate::strike::TipOffset;
use crate::table::{BallSet, Scene, Table};

/// A shot: its scene, stroke and setup.
#[derive(Clone, Debug, PartialEq)]
pub struct Shot {
    /// The balls on the table.
    pub scene: Scene,
    /// The stroke.
    pub stroke: Stroke,
    /// Ball, cloth and cushion parameters, and the model.
    pub setup: Setup,
}

/// A three-cushion point (`cli/tests/shot_cli.rs`): from (0.7, 0.4) at 84° and 5 m/s with
/// running side and follow, two cushions, ball 1, a third cushion, ball 2.
pub fn three_cushion() -> Result<Shot> {
    let r = BallSet::CAROM.radius;
    let mut scene = Scene::new(Table::carom(), r, [0.7, 0.4])?;
    scene.add_ball([1.4, 0.9])?;
    scene.add_ball([2.2, 1.1])?;
    Ok(Shot {
        scene,
        stroke: Stroke::at_angle(
            5.0,
            TipOffset::from_radius_fraction(0.3, 0.2, r)?,
            84.0 * core::f32::consts::PI / 180.0,
        )?,
        setup: Setup::carom()?,
    })
}

/// The cue ball at (0.5, 0.4) and fifteen balls in three rows over a pool table, 6 m/s
/// with a little follow.
pub fn sixteen_balls() -> Result<Shot> {
    let r = BallSet::POOL.radius;
    let mut scene = Scene::new(Table::pool(), r, [0.5, 0.4])?;
    for i in 0..15u8 {
        let (row, column) = (f32::from(i / 5), f32::from(i % 5));
        scene.add_ball([0.9 + 0.3 * column, 0.3 + 0.3 * row + 0.05 * column])?;
    }
    Ok(Shot {
        scene,
        stroke: Stroke::at_angle(6.0, TipOffset::from_radius_fraction(0.0, 0.2, r)?, 0.35)?,
        setup: Setup::POOL,
    })
}

/// A 9-ball break: the diamond rack (rows of 1, 2, 3, 2, 1 balls, 0.1 mm apart) with
/// its apex on the foot spot, the cue ball on the head string, 8 m/s into the apex.
pub fn nine_ball_break() -> Result<Shot> {
    let r = BallSet::POOL.radius;
    let (foot, middle) = (1.905, 0.635);
    let mut scene = Scene::new(Table::pool(), r, [0.635, 0.6])?;
    let pitch = 2.0 * r + 1e-4;
    let row_step = pitch * 0.866_025_4; // cos 30°
    for (row, count) in [1u8, 2, 3, 2, 1].into_iter().enumerate() {
        for k in 0..count {
            let y = middle + pitch * (f32::from(k) - f32::from(count - 1) / 2.0);
            scene.add_ball([foot + row_step * row as f32, y])?;
        }
    }
    Ok(Shot {
        scene,
        stroke: Stroke::new(8.0, TipOffset::CENTRE, [foot - 0.635, middle - 0.6])?,
        setup: Setup::POOL,
    })
}

/// A reference shot's builder.
pub type Build = fn() -> Result<Shot>;

/// The reference shots by name.
pub const ALL: [(&str, Build); 3] = [
    ("three-cushion", three_cushion),
    ("sixteen-balls", sixteen_balls),
    ("nine-ball-break", nine_ball_break),
];

/// FNV-1a (32 bits) of a simulation's result, to the bit: every event's time, kind,
/// balls and position, then every ball's final position (`u32::MAX` twice for a
/// pocketed one). Equal digests on the host and the device mean bit-identical results.
pub fn digest(shot: &Shot) -> Result<u32> {
    let mut hash: u32 = 0x811C_9DC5;
    let mut add = |word: u32| {
        for byte in word.to_le_bytes() {
            hash ^= u32::from(byte);
            hash = hash.wrapping_mul(0x0100_0193);
        }
    };
    let finish = play(&shot.scene, &shot.stroke, &shot.setup, |event, _| {
        add(event.time.to_bits());
        add(match event.kind {
            super::EventKind::Ball => 0,
            super::EventKind::Cushion => 1,
            super::EventKind::Pocket(p) => 2 + p as u32,
            super::EventKind::Rest => 100,
        });
        add(event.ball as u32);
        add(event.other.map_or(u32::MAX, |o| o as u32));
        add(event.position.x.to_bits());
        add(event.position.y.to_bits());
    })?;
    for end in finish.positions() {
        match end {
            Some(p) => {
                add(p.x.to_bits());
                add(p.y.to_bits());
            }
            None => {
                add(u32::MAX);
                add(u32::MAX);
            }
        }
    }
    Ok(hash)
}
