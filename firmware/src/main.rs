//! cuesight on a Cortex-M4F: evaluates every model on a handful of built-in shots,
//! logs each outcome with defmt and exits through semihosting (0 when every outcome
//! is sane, non-zero otherwise). Boots under QEMU's `mps2-an386`: `cargo xtask run`.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

mod exit;
mod shots;

use defmt_semihosting as _; // global defmt logger: frames go to the host's stdout

#[cortex_m_rt::entry]
fn main() -> ! {
    defmt::info!(
        "cuesight firmware: {=usize} shots x {=usize} models",
        shots::SHOTS.len(),
        cuesight::Model::ALL.len()
    );
    let failures = shots::run_all();
    exit::exit(failures == 0)
}
