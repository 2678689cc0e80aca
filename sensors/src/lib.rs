//! IMU driver, sample ring buffer and stroke estimator for the cuesight smart cue.
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]
