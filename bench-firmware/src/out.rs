//! Buffered plain-text output on the host's stdout (semihosting `SYS_WRITE`), a few
//! kilobytes per host call so that long result listings stay fast.

use core::fmt;

use cortex_m_semihosting::hio::{self, HostStream};

const CAPACITY: usize = 4096;

/// Line-oriented writer; flushes when the buffer fills and on [`Out::flush`].
pub struct Out {
    stream: HostStream,
    buffer: [u8; CAPACITY],
    len: usize,
}

impl Out {
    /// Opens the host's stdout; fails the run without a semihosting host.
    pub fn stdout() -> Self {
        match hio::hstdout() {
            Ok(stream) => Self {
                stream,
                buffer: [0; CAPACITY],
                len: 0,
            },
            Err(()) => crate::exit::fail(format_args!("no semihosting stdout")),
        }
    }

    /// Writes the buffered bytes to the host.
    pub fn flush(&mut self) {
        if self.len > 0 && self.stream.write_all(&self.buffer[..self.len]).is_err() {
            crate::exit::fail(format_args!("semihosting write failed"));
        }
        self.len = 0;
    }

    /// Appends `word` as eight lower-case hex digits (f32 bit patterns travel exactly).
    pub fn hex(&mut self, word: u32) {
        let mut digits = [0u8; 8];
        for (i, d) in digits.iter_mut().enumerate() {
            let nibble = (word >> (28 - 4 * i)) & 0xf;
            *d = b"0123456789abcdef"[nibble as usize];
        }
        self.bytes(&digits);
    }

    fn bytes(&mut self, bytes: &[u8]) {
        if self.len + bytes.len() > CAPACITY {
            self.flush();
        }
        self.buffer[self.len..self.len + bytes.len()].copy_from_slice(bytes);
        self.len += bytes.len();
    }
}

impl fmt::Write for Out {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        for chunk in s.as_bytes().chunks(CAPACITY) {
            self.bytes(chunk);
        }
        Ok(())
    }
}
