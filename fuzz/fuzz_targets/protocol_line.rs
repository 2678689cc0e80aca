//! Fuzz target `protocol_line`: see `cuesight_fuzz::protocol_line` for what it decodes and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    cuesight_fuzz::protocol_line::run(data);
});
