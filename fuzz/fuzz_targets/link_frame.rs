//! Fuzz target `link_frame`: see `cuesight_fuzz::link_frame` for what it decodes and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    cuesight_fuzz::link_frame::run(data);
});
