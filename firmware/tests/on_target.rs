//! On-target unit tests (defmt-test), built for the Cortex-M4F with the firmware's own
//! release profile (opt-level "z", LLVM's inline threshold 50, fat LTO) and run in QEMU
//! (`cargo test --release` in `firmware/`; `cargo xtask test` step "firmware: on-target
//! tests"). They check what host tests cannot: the FPU's square root, the target's
//! code generation of the models and the link codec, the boot self-test, and the
//! device session on its own stack.
//!
//! Golden values come from outside the code under test: IEEE 754 correctly rounded
//! constants, and the f64 reference solver of `host-tests` (`cuesight collide ...
//! --model reference --json`, quoted at each use).
#![no_std]
#![no_main]

use cuesight_firmware as _; // panic and fault handlers, defmt logger, timestamps

/// Distance in ulps between two finite f32 of the same sign.
fn ulps(a: f32, b: f32) -> u32 {
    (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs() as u32
}

#[defmt_test::tests]
mod tests {
    use super::ulps;

    /// The board as the firmware sets it up (its clock gives the log's timestamps).
    #[init]
    fn init() {
        let _board = cuesight_firmware::board::init();
    }
    use cuesight::{collide, math, Error, Impact, Model, Params};
    use cuesight_device::{Identity, Session, Upload};
    use cuesight_link::error::FrameFault;
    use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME};
    use cuesight_link::{Collide, SCHEMA_HASH};
    use cuesight_link::{Empty, LinkError, Request, Response};
    use static_cell::ConstStaticCell;

    /// The image's own memory routines (`cuesight_firmware::mem`, in place of
    /// `compiler_builtins`'): every source and destination alignment, lengths 0–40,
    /// the bytes copied or cleared equal to the source pattern or zero, and not one byte
    /// outside the range touched (golden values: the pattern `7 i + 3`, written here).
    #[test]
    fn memory_routines_copy_and_clear_every_alignment_and_length() {
        use cuesight_firmware::mem;
        #[repr(align(8))]
        struct Buffer([u8; 48]);
        const UNTOUCHED: u8 = 0xa5;
        let pattern = |i: usize| (7 * i + 3) as u8;
        let mut src = Buffer([0; 48]);
        for (i, byte) in src.0.iter_mut().enumerate() {
            *byte = pattern(i);
        }
        for from in 0..4 {
            for to in 0..4 {
                for len in 0..=40 {
                    // The generic forms at every offset, the `4` and `8` forms at offset 0
                    // of the 8-aligned buffers (their contract).
                    for form in [1, 4, 8] {
                        if form > 1 && (from != 0 || to != 0) {
                            continue;
                        }
                        let mut copied = Buffer([UNTOUCHED; 48]);
                        let mut cleared = Buffer([UNTOUCHED; 48]);
                        // SAFETY: both ranges lie inside their 48-byte buffers
                        // (3 + 40 <= 48), distinct buffers; the `4` and `8` forms only at
                        // offset 0 of 8-aligned ones.
                        unsafe {
                            let d = copied.0.as_mut_ptr().add(to);
                            let s = src.0.as_ptr().add(from);
                            let c = cleared.0.as_mut_ptr().add(to);
                            match form {
                                8 => {
                                    mem::__aeabi_memcpy8(d, s, len);
                                    mem::__aeabi_memclr8(c, len);
                                }
                                4 => {
                                    mem::__aeabi_memcpy4(d, s, len);
                                    mem::__aeabi_memclr4(c, len);
                                }
                                _ => {
                                    mem::__aeabi_memcpy(d, s, len);
                                    mem::__aeabi_memclr(c, len);
                                }
                            }
                        }
                        for i in 0..48 {
                            let inside = i >= to && i < to + len;
                            let copy = if inside {
                                pattern(i - to + from)
                            } else {
                                UNTOUCHED
                            };
                            let clear = if inside { 0 } else { UNTOUCHED };
                            defmt::assert_eq!(
                                copied.0[i],
                                copy,
                                "copy {} {} {} at {}",
                                from,
                                to,
                                len,
                                i
                            );
                            defmt::assert_eq!(cleared.0[i], clear, "clear {} {} at {}", to, len, i);
                        }
                    }
                }
            }
        }
    }

    /// The FPU's `vsqrt.f32` through the math shim: IEEE 754 correctly rounded.
    #[test]
    fn square_root_is_correctly_rounded() {
        // √2 = 1.41421356237…: nearest f32 0x3fb504f3; √3 = 1.7320508075…: 0x3fddb3d7.
        defmt::assert_eq!(math::sqrt(2.0).to_bits(), 0x3fb5_04f3);
        defmt::assert_eq!(math::sqrt(3.0).to_bits(), 0x3fdd_b3d7);
        defmt::assert_eq!(math::sqrt(0.0), 0.0);
        defmt::assert!(math::sqrt(-1.0).is_nan());
    }

    /// The shim's elementary functions on the target, against correctly rounded
    /// constants: within the ulps `math::accurate` documents (exp 1, ln 3, atan2 2).
    #[test]
    fn elementary_functions_within_their_ulps() {
        // e = 2.718281828…: 0x402df854; ln 10 = 2.302585093…: 0x40135d8e.
        defmt::assert!(ulps(math::exp(1.0), f32::from_bits(0x402d_f854)) <= 1);
        defmt::assert!(ulps(math::ln(10.0), f32::from_bits(0x4013_5d8e)) <= 3);
        // π: 0x40490fdb; π/4: 0x3f490fdb; −3π/4 = −2.35619449…: 0xc016cbe4.
        defmt::assert_eq!(math::atan2(0.0, -1.0).to_bits(), 0x4049_0fdb);
        defmt::assert!(ulps(math::atan2(1.0, 1.0), f32::from_bits(0x3f49_0fdb)) <= 2);
        defmt::assert!(ulps(math::atan2(-1.0, -1.0), f32::from_bits(0xc016_cbe4)) <= 2);
        let (sin, cos) = math::sin_cos(core::f32::consts::FRAC_PI_6);
        defmt::assert!(ulps(sin, 0.5) <= 2 && ulps(cos, f32::from_bits(0x3f5d_b3d7)) <= 2);
    }

    /// 2 m/s, 30° cut, 70 rad/s of draw on the pool defaults. The reference solver
    /// (`cuesight collide --speed 2 --cut 30 --spin 0,-70,0 --model reference --json`):
    /// cue ball v (0.04330128, 0.96285945, 0) m/s, object ball v (1.6887496, 0.03714053,
    /// 0.0758294) m/s, throw 1.2598983°. Every model that claims 0.05 % of U on pool
    /// balls and is in the image (KimGrip, Exact, Auto at 1e-3) is within 5e-4 U = 1 mm/s of it
    /// on every velocity component and 0.01° of throw, computed on the target.
    #[test]
    fn models_match_the_reference_on_the_target() {
        const CUE: [f32; 3] = [0.043_301_28, 0.962_859_45, 0.0];
        const OBJECT: [f32; 3] = [1.688_749_6, 0.037_140_53, 0.075_829_4];
        const THROW_DEG: f32 = 1.259_898_3;
        let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0, -70.0, 0.0]);
        let impact = defmt::unwrap!(impact.ok());
        // The firmware leaves `SeedExact` and `Kim` out (firmware/Cargo.toml): typed
        // refusals.
        for model in [Model::SeedExact, Model::Kim] {
            defmt::assert!(collide(&Params::POOL, &impact, model) == Err(Error::ModelLeftOut));
        }
        for model in [
            Model::KimGrip,
            Model::Exact,
            Model::Auto { tolerance: 1e-3 },
        ] {
            let out = defmt::unwrap!(collide(&Params::POOL, &impact, model).ok());
            let cue = out.cue_ball.velocity.to_array();
            let object = out.object_ball.velocity.to_array();
            for i in 0..3 {
                defmt::assert!(
                    math::abs(cue[i] - CUE[i]) <= 1e-3 && math::abs(object[i] - OBJECT[i]) <= 1e-3,
                    "{=str}: component {=usize}: cue {=f32}, object {=f32}",
                    model.name(),
                    i,
                    cue[i],
                    object[i]
                );
            }
            let throw = out.throw_angle_deg();
            defmt::assert!(
                math::abs(throw - THROW_DEG) <= 0.01,
                "{=str}: throw {=f32} deg",
                model.name(),
                throw
            );
        }
    }

    /// The boot self-test (every model on the built-in shots) passes on the target.
    #[test]
    fn boot_self_test_passes() {
        defmt::assert_eq!(cuesight_firmware::shots::run_all(), 0);
    }

    /// The device session, compiled for the target: a `version` request is answered
    /// with this schema; a frame with a flipped bit gets a typed CRC error and the
    /// session goes on; a `collide` answer decodes.
    #[test]
    fn session_answers_and_survives_a_corrupt_frame() {
        static UPLOAD: ConstStaticCell<Upload> = ConstStaticCell::new(Upload::new());
        static FRAMES: ConstStaticCell<FrameReader> = ConstStaticCell::new(FrameReader::new());
        let identity = Identity {
            firmware: "on-target tests",
            board: "qemu",
        };
        let mut session = Session::with_upload(identity, UPLOAD.take());
        let frames = FRAMES.take();
        let mut request = [0u8; MAX_FRAME];
        let mut answer = [0u8; MAX_FRAME];

        let mut exchange = |seq: u16, message: &Request, flip: Option<usize>| -> Response {
            let len = defmt::unwrap!(frame::encode(SCHEMA_HASH, seq, message, &mut request).ok());
            if let Some(byte) = flip {
                request[byte] ^= 0x10; // not a zero: the frame still ends at its 0x00
            }
            let mut served = None;
            for &byte in &request[..len] {
                if let Some(received) = frames.push(byte) {
                    served = Some(session.serve(received, &mut answer));
                }
            }
            let served = defmt::unwrap!(served);
            let mut reader = FrameReader::new();
            let mut decoded = None;
            for &byte in &answer[..served.len] {
                if let Some(Received::Frame(raw)) = reader.push(byte) {
                    let (header, body) = defmt::unwrap!(frame::open(raw).ok());
                    defmt::assert_eq!(header.schema, SCHEMA_HASH);
                    decoded = frame::decode::<Response>(body).ok();
                }
            }
            defmt::unwrap!(decoded)
        };

        match exchange(0, &Request::Version(Empty {}), None) {
            Response::Version(version) => defmt::assert_eq!(version.schema, SCHEMA_HASH),
            _ => defmt::panic!("version: not a version answer"),
        }
        match exchange(1, &Request::Version(Empty {}), Some(3)) {
            Response::Error(LinkError::Frame(FrameFault::Crc { .. })) => {}
            _ => defmt::panic!("flipped bit: not a CRC error"),
        }
        match exchange(1, &Request::Collide(Collide::new(2.0, 30.0)), None) {
            Response::Collide(answer) => defmt::assert!(answer.object.v[0] > 0.0),
            _ => defmt::panic!("collide: not a collide answer"),
        }
    }
}
