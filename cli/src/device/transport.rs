//! How the console reaches a device: bytes out, frames in.
//!
//! * [`Stream`]: a byte stream with read timeouts: a serial port ([`Stream::serial`], the
//!   `serialport` crate) or a TCP socket ([`Stream::tcp`], e.g. QEMU's
//!   `-serial tcp::PORT,server`). Frames are cut by a [`FrameReader`], which never keeps
//!   more than `MAX_RAW` bytes of one.
//! * [`Qemu`]: the firmware booted under QEMU ([`cuesight_host::firmware::Firmware`]).
//! * [`Loopback`]: a device in this process ([`cuesight_device::Session`]), for trying the
//!   console and for tests.

use std::collections::VecDeque;
use std::fmt;
use std::io::{self, Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

use cuesight_device::{Control, Identity, Session};
use cuesight_link::frame::{FrameReader, MAX_FRAME};

use cuesight_host::firmware::{Firmware, FirmwareError, Incoming};

/// Why a transport could not move a frame.
#[derive(Debug)]
pub enum TransportError {
    /// The port or socket failed (or could not be opened).
    Io(io::Error),
    /// Nothing ended a frame within this time.
    Timeout(Duration),
    /// The device's side closed (end of stream, QEMU exited).
    Closed,
}

impl fmt::Display for TransportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TransportError::Io(e) => write!(f, "{e}"),
            TransportError::Timeout(t) => {
                write!(f, "no answer within {:.1} s", t.as_secs_f64())
            }
            TransportError::Closed => f.write_str("the device closed the link"),
        }
    }
}

impl std::error::Error for TransportError {}

impl From<io::Error> for TransportError {
    fn from(e: io::Error) -> Self {
        TransportError::Io(e)
    }
}

impl From<FirmwareError> for TransportError {
    fn from(e: FirmwareError) -> Self {
        match e {
            FirmwareError::Io(e) => TransportError::Io(e),
            FirmwareError::Timeout(t) => TransportError::Timeout(t),
            FirmwareError::Closed => TransportError::Closed,
            other => TransportError::Io(io::Error::other(other.to_string())),
        }
    }
}

/// A link to a device.
pub trait Transport {
    /// Writes `bytes` (one or more encoded frames) to the device.
    fn send(&mut self, bytes: &[u8]) -> Result<(), TransportError>;
    /// The next frame from the device, waiting at most `timeout`.
    fn next_frame(&mut self, timeout: Duration) -> Result<Incoming, TransportError>;
}

impl<T: Transport + ?Sized> Transport for &mut T {
    fn send(&mut self, bytes: &[u8]) -> Result<(), TransportError> {
        (**self).send(bytes)
    }

    fn next_frame(&mut self, timeout: Duration) -> Result<Incoming, TransportError> {
        (**self).next_frame(timeout)
    }
}

/// A byte stream whose reads can time out.
pub trait Port: Read + Write {
    /// Bounds the next reads to `timeout`.
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()>;
}

impl Port for TcpStream {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        TcpStream::set_read_timeout(self, Some(timeout.max(Duration::from_millis(1))))
    }
}

impl Port for Box<dyn serialport::SerialPort> {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        self.set_timeout(timeout).map_err(io::Error::from)
    }
}

/// Longest single wait on a port: reads wake up at least this often to check the
/// deadline.
const POLL: Duration = Duration::from_millis(200);

/// Frames over a byte stream.
pub struct Stream<P> {
    port: P,
    reader: FrameReader,
    buf: Box<[u8; 4096]>,
    pos: usize,
    filled: usize,
}

impl Stream<Box<dyn serialport::SerialPort>> {
    /// Opens serial port `path` at `baud` (8N1, no flow control).
    pub fn serial(path: &str, baud: u32) -> Result<Self, TransportError> {
        let port = serialport::new(path, baud)
            .timeout(POLL)
            .open()
            .map_err(|e| TransportError::Io(io::Error::other(format!("{path}: {e}"))))?;
        Ok(Self::new(port))
    }
}

impl Stream<TcpStream> {
    /// Connects to `address` (`HOST:PORT`).
    pub fn tcp(address: &str) -> Result<Self, TransportError> {
        let socket = TcpStream::connect(address)
            .map_err(|e| TransportError::Io(io::Error::new(e.kind(), format!("{address}: {e}"))))?;
        socket.set_nodelay(true)?;
        Ok(Self::new(socket))
    }
}

impl<P: Port> Stream<P> {
    /// Frames over `port`.
    pub fn new(port: P) -> Self {
        Self {
            port,
            reader: FrameReader::new(),
            buf: Box::new([0; 4096]),
            pos: 0,
            filled: 0,
        }
    }
}

impl<P: Port> Transport for Stream<P> {
    fn send(&mut self, bytes: &[u8]) -> Result<(), TransportError> {
        self.port.write_all(bytes)?;
        self.port.flush()?;
        Ok(())
    }

    fn next_frame(&mut self, timeout: Duration) -> Result<Incoming, TransportError> {
        let deadline = Instant::now() + timeout;
        loop {
            while let Some(&byte) = self.buf.get(self.pos).filter(|_| self.pos < self.filled) {
                self.pos += 1;
                if let Some(received) = self.reader.push(byte) {
                    return Ok(Incoming::from_received(received));
                }
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Err(TransportError::Timeout(timeout));
            }
            self.port.set_read_timeout(left.min(POLL))?;
            match self.port.read(&mut self.buf[..]) {
                Ok(0) => return Err(TransportError::Closed),
                Ok(n) => {
                    self.pos = 0;
                    self.filled = n;
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::WouldBlock
                            | io::ErrorKind::TimedOut
                            | io::ErrorKind::Interrupted
                    ) => {}
                Err(e) => return Err(TransportError::Io(e)),
            }
        }
    }
}

/// The firmware under QEMU.
pub struct Qemu {
    firmware: Firmware,
}

impl Qemu {
    /// Talks to `firmware`.
    pub fn new(firmware: Firmware) -> Self {
        Self { firmware }
    }

    /// The firmware back (to wait for its end and collect its log).
    pub fn into_firmware(self) -> Firmware {
        self.firmware
    }
}

impl Transport for Qemu {
    fn send(&mut self, bytes: &[u8]) -> Result<(), TransportError> {
        Ok(self.firmware.send_bytes(bytes)?)
    }

    fn next_frame(&mut self, timeout: Duration) -> Result<Incoming, TransportError> {
        Ok(self.firmware.next_frame(timeout)?)
    }
}

/// A device in this process: the device's [`Session`] (`cuesight-device`) behind a
/// [`FrameReader`], as the firmware runs it. It sends the unprompted `version` frame
/// first, like a booted device, and closes after answering `shutdown`.
pub struct Loopback {
    device: Session,
    reader: FrameReader,
    answers: VecDeque<Incoming>,
    host: FrameReader,
    shut_down: bool,
}

impl Default for Loopback {
    fn default() -> Self {
        Self::new()
    }
}

impl Loopback {
    /// A fresh device, its hello waiting.
    pub fn new() -> Self {
        let device = Session::new(Identity {
            firmware: concat!("cuesight loopback ", env!("CARGO_PKG_VERSION")),
            board: "host",
        });
        let mut link = Self {
            device,
            reader: FrameReader::new(),
            answers: VecDeque::new(),
            host: FrameReader::new(),
            shut_down: false,
        };
        let mut out = [0u8; MAX_FRAME];
        let len = link.device.hello(&mut out);
        link.deliver(&out[..len]);
        link
    }

    /// Frames answered so far and how many with an error (the device's count).
    pub fn counts(&self) -> (u32, u32) {
        (self.device.requests(), self.device.errors())
    }

    /// Cuts the device's output into frames for the host side.
    fn deliver(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            if let Some(received) = self.host.push(byte) {
                self.answers.push_back(Incoming::from_received(received));
            }
        }
    }
}

impl Transport for Loopback {
    fn send(&mut self, bytes: &[u8]) -> Result<(), TransportError> {
        if self.shut_down {
            return Err(TransportError::Io(io::ErrorKind::BrokenPipe.into()));
        }
        let mut out = [0u8; MAX_FRAME];
        for &byte in bytes {
            if let Some(received) = self.reader.push(byte) {
                let served = self.device.serve(received, &mut out);
                let len = served.len.min(out.len());
                let answer = out[..len].to_vec();
                self.deliver(&answer);
                if served.control == Control::Shutdown {
                    self.shut_down = true;
                    break;
                }
            }
        }
        Ok(())
    }

    fn next_frame(&mut self, timeout: Duration) -> Result<Incoming, TransportError> {
        match self.answers.pop_front() {
            Some(answer) => Ok(answer),
            None if self.shut_down => Err(TransportError::Closed),
            None => Err(TransportError::Timeout(timeout)),
        }
    }
}
