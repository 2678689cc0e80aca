//! The `cuesight` command line (`src/bin/cuesight.rs`) and what the Python package
//! calls: `collide` ([`cli`], [`report`]), `shot` and its SVG ([`shot_cli`], [`svg`]),
//! `calibrate` ([`calibrate`]) and the device console ([`device`]). The f64 reference
//! solver and the test suites live in `cuesight-host` (`host-tests/`).
pub mod calibrate;
pub mod cli;
pub mod device;
pub mod report;
pub mod shot_cli;
pub mod svg;
