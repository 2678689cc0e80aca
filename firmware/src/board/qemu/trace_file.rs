//! The IMU trace, read from a file on the host through Arm semihosting (`SYS_OPEN`,
//! `SYS_READ`; Arm IHI 0077 (Semihosting for AArch32 and AArch64) §6.1, §6.9), in
//! chunks, as the emulated IMU needs samples.
//!
//! The file is [`TRACE_FILE`] in QEMU's working directory, in the binary form of
//! `crate::live::feed` (`cargo xtask live` writes it from a CSV trace). Why not the
//! board's second UART: a CMSDK UART holds one byte and QEMU hands it one byte per
//! main-loop turn, measured at 14.5 KB/s under `-icount shift=0` (the 531,682-byte
//! binary of `three-strokes-6667.csv` took 36.6 s to arrive), which would take the
//! acceptance run of 100 strokes past half an hour; a semihosting read moves a whole
//! chunk in one trap.

use cortex_m_semihosting::{nr, syscall};

/// The trace's file name, relative to QEMU's working directory, NUL-terminated for
/// `SYS_OPEN` (`cargo xtask live` writes the file under this name).
pub const TRACE_FILE: &[u8] = b"cuesight-imu-trace.bin\0";

/// An open trace file.
pub struct TraceFile {
    handle: usize,
}

impl TraceFile {
    /// Opens [`TRACE_FILE`] for reading; `None` when there is none.
    #[allow(unsafe_code)]
    pub fn open() -> Option<Self> {
        // SAFETY: SYS_OPEN takes (name, mode, length without the NUL); the name is a
        // NUL-terminated static.
        let handle = unsafe {
            syscall!(
                OPEN,
                TRACE_FILE.as_ptr(),
                nr::open::R_BINARY,
                TRACE_FILE.len() - 1
            )
        };
        (handle as isize >= 0).then_some(Self { handle })
    }

    /// Reads up to `buf.len()` bytes; the count read (0 at the end of the file or on a
    /// failed read).
    #[allow(unsafe_code)]
    pub fn read(&mut self, buf: &mut [u8]) -> usize {
        // SAFETY: SYS_READ writes at most `buf.len()` bytes into `buf` and returns the
        // number it did *not* read.
        let unread = unsafe { syscall!(READ, self.handle, buf.as_mut_ptr(), buf.len()) };
        buf.len().saturating_sub(unread)
    }
}
