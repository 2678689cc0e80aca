//! Fuzz target `shot_scene`: see `cuesight_fuzz::shot_scene` for what it decodes and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    cuesight_fuzz::shot_scene::run(data);
});
