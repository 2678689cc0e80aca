//! Host side of cuesight (std): the f64 first-principles reference solver, the QEMU
//! harness and the helpers the test suites share. The `cuesight` CLI that uses them is
//! `cuesight-cli` (`cli/`).
pub mod compare;
pub mod domain;
pub mod firmware;
pub mod grid;
pub mod invariants;
pub mod live;
pub mod live_trace;
pub mod reference;
pub mod shot_scenes;
pub mod strokes;
pub mod timed;
pub mod validity;
