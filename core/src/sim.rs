//! The whole table, event by event: every ball from the stroke until all rest or drop.
//!
//! Between events each ball follows its closed-form path ([`crate::travel`], TP A.4:
//! flight, sliding, rolling, rest; its spin about `z` decays at a constant rate,
//! spinning friction). The next event is the earliest of:
//!
//! * **ball–ball**: two centres reach `2R` while approaching (the quartic of
//!   `pair`, solved without closed-form roots so that grazes are robust); the
//!   collision models of the crate ([`crate::collide`], the chosen [`Model`], `Auto`
//!   included) give the outcome, both balls moving and spinning (module `pair`
//!   gives the mapping and what it approximates);
//! * **cushion**: a centre reaches the rail line one radius inside a cushion; Han 2005
//!   gives the rebound ([`Cushion`]);
//! * **pocket**: a centre reaches a pocket's mouth line; the ball drops;
//! * **rest**: a ball stops translating.
//!
//! Only the balls an event changes get new paths, and only the event times that involve
//! them are recomputed: each pair's next contact, each ball's exit from the cloth and
//! its stop are cached (`16 × 15 / 2` pairs; all fixed-size, no heap).
//!
//! ```
//! use cuesight::sim::{play, Setup};
//! use cuesight::shot::Stroke;
//! use cuesight::strike::TipOffset;
//! use cuesight::table::{BallSet, Scene, Table};
//!
//! let r = BallSet::POOL.radius;
//! let mut scene = Scene::new(Table::pool(), r, [0.635, 0.635])?;
//! scene.add_ball([1.905, 0.635])?; // the foot spot
//! let stroke = Stroke::new(2.0, TipOffset::CENTRE, [1.0, 0.0])?;
//! let mut events = 0;
//! let end = play(&scene, &stroke, &Setup::POOL, |_event, _paths| events += 1)?;
//! // A stun shot: the cue ball stops near the object ball's spot, which runs on into
//! // the far cushion and back.
//! assert!(events >= 3);
//! assert!(end.position(1).is_some());
//! # Ok::<(), cuesight::Error>(())
//! ```

mod boundary;
mod collapse;
mod crossing;
mod cushion;
mod jaws;
mod mouth;
mod pair;
mod roots;
mod run;
mod schedule;
pub mod shots;
mod track;

pub use cushion::Cushion;
pub use jaws::{Jaw, Jaws};
pub use run::{play, simulate, Finish, Launch, Paths};

use crate::error::{check, Field, Result};
use crate::model::Model;
use crate::params::Params;
use crate::shot::ShotSetup;
use crate::strike::Cue;
use crate::table::BallSet;
use crate::travel::{Cloth, GRAVITY};
use crate::vector::Vec3;

/// Spin decay of spinning friction on pool cloth: `(10/9) g` ≈ 10.9 rad/s², pooltool
/// 0.6's default (`u_sp = (4/9) R`, so `5 u_sp g / (2R)` whatever the ball size).
pub const SPIN_DECAY: f32 = 10.0 / 9.0 * GRAVITY;

/// Events after which a simulation that has not ended stops with
/// [`Error::Unfinished`](crate::Error::Unfinished), by default: a 9-ball break takes
/// 90–180 (pooltool, issue 17).
pub const MAX_EVENTS: u16 = 1000;

/// Simulated time (s) after which a simulation that has not ended stops with
/// [`Error::Unfinished`](crate::Error::Unfinished): shots on real cloth end in under a
/// minute; the bound also keeps times within f32's digits.
pub const MAX_TIME: f32 = 600.0;

/// Everything a table simulation needs besides the balls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setup {
    /// The stroke and the ball–ball collisions: ball parameters, cue, cloth, model.
    pub shot: ShotSetup,
    /// The cushions.
    pub cushion: Cushion,
    /// The pockets' jaws (unused on a table without pockets).
    pub jaws: Jaws,
    /// Rate (rad/s²) at which spinning friction slows the spin about `z`.
    pub spin_decay: f32,
    /// Event limit ([`MAX_EVENTS`] by default).
    pub max_events: u16,
}

impl Setup {
    /// Pool: [`Params::POOL`], the typical cue and cloth, `KimGrip`, pool cushions.
    pub const POOL: Self = Self {
        shot: ShotSetup {
            params: Params::POOL,
            cue: Cue::TYPICAL,
            cloth: Cloth::TYPICAL,
            model: Model::KimGrip,
        },
        cushion: Cushion::POOL,
        jaws: Jaws::POOL,
        spin_decay: SPIN_DECAY,
        max_events: MAX_EVENTS,
    };

    /// [`Setup::POOL`] for the balls `balls` and the cushions `cushion`.
    pub fn with_balls(self, balls: BallSet, cushion: Cushion) -> Result<Self> {
        Ok(Self {
            shot: ShotSetup {
                params: self.shot.params.with_ball(balls.radius, balls.mass)?,
                ..self.shot
            },
            cushion,
            ..self
        })
    }

    /// Carom: [`Setup::POOL`] with carom balls ([`BallSet::CAROM`]) and cushions
    /// ([`Cushion::CAROM`]).
    pub fn carom() -> Result<Self> {
        Self::POOL.with_balls(BallSet::CAROM, Cushion::CAROM)
    }

    /// Snooker: [`Setup::POOL`] with snooker balls, cushions and jaws
    /// ([`Jaws::SNOOKER`]).
    pub fn snooker() -> Result<Self> {
        Ok(Self {
            jaws: Jaws::SNOOKER,
            ..Self::POOL.with_balls(BallSet::SNOOKER, Cushion::SNOOKER)?
        })
    }

    fn check(&self, radius: f32) -> Result<()> {
        check(Field::SpinDecay, self.spin_decay, 0.0, 1000.0, false)?;
        self.jaws.check()?;
        self.cushion.check_height(radius)
    }
}

/// What happened.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EventKind {
    /// Two balls collided.
    Ball,
    /// A ball hit a cushion.
    Cushion,
    /// A ball dropped into the pocket of this index ([`crate::table::Table::pockets`]).
    Pocket(usize),
    /// A ball stopped translating (it may still spin about `z`).
    Rest,
}

/// One event of a simulation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Event {
    /// Time from the stroke (s).
    pub time: f32,
    /// What happened.
    pub kind: EventKind,
    /// The ball (index in the scene; 0 is the cue ball).
    pub ball: usize,
    /// The other ball of a ball–ball collision.
    pub other: Option<usize>,
    /// Centre of `ball` at the event (m).
    pub position: Vec3,
    /// For a cushion event at a pocket's jaw (its face or rounded nose), the pocket's
    /// index ([`crate::table::Table::pockets`]); `None` for a rail and other events.
    pub jaw: Option<usize>,
}

#[cfg(test)]
mod tests;
