//! The cuesight firmware's serial protocol: newline-delimited JSON requests and answers.
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]
