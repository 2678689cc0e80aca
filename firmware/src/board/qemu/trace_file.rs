//! The IMU trace, streamed in by the host through Arm semihosting (`SYS_OPEN`,
//! `SYS_READ`; Arm IHI 0077 (Semihosting for AArch32 and AArch64) §6.1, §6.9), in
//! chunks, as the emulated IMU needs samples.
//!
//! [`TRACE_FILE`] in QEMU's working directory is a named pipe the host writes the trace
//! into as the firmware reads it (`cuesight_host::live::boot`, which `cargo xtask live`
//! and the tests use; a plain file works too), in the binary form of
//! `crate::live::feed`. A read waits in QEMU for the host's next bytes, with the virtual
//! clock stopped (`-icount`), and only the pipe's end (the host closing it) ends the
//! trace. Why not the board's second UART: a CMSDK UART holds one byte and QEMU hands it
//! one byte per main-loop turn, measured at 14.5 KB/s under `-icount shift=0` (the
//! 531,682-byte binary of `three-strokes-6667.csv` took 36.6 s to arrive), which would
//! take the acceptance run of 100 strokes (41 MB) past half an hour; a semihosting read
//! moves up to a whole chunk in one trap.

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

    /// Fills `buf`; the count read, short only at the end of the stream (or on a failed
    /// read). A pipe's read returns what has arrived, so this reads until `buf` is full.
    #[allow(unsafe_code)]
    pub fn read(&mut self, buf: &mut [u8]) -> usize {
        let mut filled = 0;
        while let Some(rest) = buf.get_mut(filled..).filter(|rest| !rest.is_empty()) {
            // SAFETY: SYS_READ writes at most `rest.len()` bytes into `rest` and returns
            // the number it did *not* read.
            let unread = unsafe { syscall!(READ, self.handle, rest.as_mut_ptr(), rest.len()) };
            let read = rest.len().saturating_sub(unread);
            if read == 0 {
                break;
            }
            filled += read;
        }
        filled
    }
}
