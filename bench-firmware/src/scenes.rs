//! The scene set baked into the image by `build.rs` (written by `cargo xtask bench`
//! from `cuesight_host::grid::scenes`).
//!
//! Layout, little-endian: magic `b"CSB1"`, `u64` grid seed, `u32` scene count, `u32`
//! number of leading scenes used for instruction counts, then per scene ten `f32`:
//! `v_x, v_y` (m/s), `ω_x, ω_y, ω_z` (rad/s), `μ, e*, μ_s, R` (m), `M` (kg).

use cuesight::{Impact, Params};

static BLOB: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/scenes.bin"));

const MAGIC: &[u8; 4] = b"CSB1";
const HEADER: usize = 20;
const FLOATS: usize = 10;
const STRIDE: usize = 4 * FLOATS;

/// The baked set (header checked).
pub struct Scenes {
    /// Seed of the grid the scenes come from.
    pub seed: u64,
    /// Number of scenes.
    pub count: usize,
    /// How many leading scenes the instruction counts use.
    pub counted: usize,
}

/// One scene as validated core inputs.
pub struct Scene {
    /// Ball and contact parameters.
    pub params: Params,
    /// Cue ball at contact.
    pub impact: Impact,
}

impl Scenes {
    /// The baked set, or `None` if the image was built without one (or it is malformed).
    pub fn baked() -> Option<Self> {
        if BLOB.len() < HEADER || &BLOB[..4] != MAGIC {
            return None;
        }
        let seed = u64::from_le_bytes(BLOB[4..12].try_into().ok()?);
        let count = u32::from_le_bytes(BLOB[12..16].try_into().ok()?) as usize;
        let counted = u32::from_le_bytes(BLOB[16..20].try_into().ok()?) as usize;
        if BLOB.len() != HEADER + count * STRIDE || counted > count {
            return None;
        }
        Some(Self {
            seed,
            count,
            counted,
        })
    }

    /// Scene `index` (< `count`), or `None` if the core rejects its inputs.
    pub fn get(&self, index: usize) -> Option<Scene> {
        let at = HEADER + index * STRIDE;
        let f = |k: usize| {
            let bytes = &BLOB[at + 4 * k..at + 4 * k + 4];
            f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])
        };
        let params = Params::new(f(5), f(6), f(7), f(8), f(9)).ok()?;
        let impact = Impact::from_velocity([f(0), f(1)], [f(2), f(3), f(4)]).ok()?;
        Some(Scene { params, impact })
    }
}
