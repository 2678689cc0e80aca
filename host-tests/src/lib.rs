//! Host side of cuesight (std): the f64 first-principles reference solver and helpers
//! shared by the CLI and the test suites.
pub mod calibrate;
pub mod cli;
pub mod compare;
pub mod device;
pub mod domain;
pub mod firmware;
pub mod grid;
pub mod invariants;
pub mod live;
pub mod live_trace;
pub mod reference;
pub mod report;
pub mod shot_cli;
pub mod shot_scenes;
pub mod strokes;
pub mod svg;
pub mod timed;
