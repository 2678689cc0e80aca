//! # cuesight — spinning billiard-ball collisions on a microcontroller
//!
//! `no_std`, heap-free, single-precision engine that predicts what happens when a
//! spinning cue ball hits a resting object ball: both balls' velocities and spins
//! (vertical components included), the throw of the object ball, the cue ball's
//! deflection from the tangent line, and whether the contact slid or gripped.
//!
//! Physics: H.-C. Kim, *Collision of two spinning billiard balls and the role of
//! table* (arXiv:2402.13258, "the seed"), first order in the ball–ball friction μ,
//! with the errata of `docs/physics.md` applied (E1: sign of the object-ball table
//! friction torque) and a gripping branch the seed lacks (E6).
//!
//! Frame (seed §2): `x` from the cue-ball centre to the object-ball centre, `z` up,
//! `y = z × x`. SI units throughout: m, s, kg, rad/s.
//!
//! ```
//! use cuesight::{collide, Impact, Model, Params};
//! let params = Params::POOL;
//! let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0, 0.0, 0.0]).unwrap();
//! let out = collide(&params, &impact, Model::KimGrip).unwrap();
//! assert!(out.throw_angle_deg() > 0.0); // stun cut: the object ball is thrown forward
//! ```
#![no_std]
#![cfg_attr(
    feature = "unstable-intrinsics",
    feature(core_intrinsics),
    allow(internal_features)
)]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod aim;
mod error;
mod estimate;
mod exact;
mod friction;
pub mod guidance;
mod ideal;
mod impact;
#[cfg(feature = "kim")]
mod kim;
mod kim_grip;
pub mod math;
mod model;
mod outcome;
mod params;
mod real;
#[cfg(feature = "seed-exact")]
mod seed_exact;
pub mod shot;
pub mod sim;
pub mod strike;
pub mod table;
pub mod travel;
pub mod validity;
mod vector;

pub use error::{Error, Field, Result};
pub use estimate::{error_estimate, select as select_model, KIM_GRIP_DECLARED_BOUND};
pub use friction::FrictionLaw;
pub use impact::Impact;
#[cfg(feature = "libm")]
pub use model::collide_f64;
pub use model::{collide, collide_in, Model};
pub use outcome::{BallState, Impulses, Outcome, Regime};
pub use params::Params;
pub use real::Real;
pub use vector::Vec3;

/// The README's code blocks, compiled and run as doctests (`cargo test -p cuesight
/// --doc`): its library example cannot go stale. Only under `cfg(doctest)`, so the
/// packaged crate, which has no README of the workspace, builds without it.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;

/// Moment-of-inertia factor of a uniform solid sphere, `I = ν M R²` (seed eq. (10)).
pub const NU: f32 = 0.4;
