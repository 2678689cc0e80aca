//! Fuzz target `link_session`: see `cuesight_fuzz::link_session` for what it decodes and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    cuesight_fuzz::link_session::run(data);
});
