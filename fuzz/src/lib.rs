//! The cargo-fuzz targets' logic, one module per target, so that a target file is one
//! line and the seed generator (`examples/seeds.rs`) can check that every seed reaches
//! what it was written for. Run them with `cargo xtask fuzz` (docs/reliability.md,
//! "Fuzzing").
//!
//! * [`link_frame`] — byte streams through the device link's frame reader and decoder;
//! * [`link_session`] — frame sequences (valid, damaged, out of order) into a device
//!   session;
//! * [`shot_scene`] — tables, scenes, strokes, shots, inverse aim and ball motion;
//! * [`collide`] — every collision model on arbitrary parameters and impacts.
//!
//! A target fails (panics, which libFuzzer reports as a crash) when a property in its
//! module docs does not hold.

pub mod collide;
pub mod finite;
pub mod input;
pub mod link;
pub mod link_frame;
pub mod link_session;
pub mod shot_scene;
