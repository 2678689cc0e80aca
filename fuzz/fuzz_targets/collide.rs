//! Fuzz target `collide`: see `cuesight_fuzz::collide` for what it decodes and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    cuesight_fuzz::collide::run(data);
});
