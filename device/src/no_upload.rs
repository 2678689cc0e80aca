//! The stroke upload left out (no `upload` feature): the session answers `stroke` with
//! `unsupported`, and this placeholder takes no memory.

/// No upload: a zero-sized stand-in for the session's type parameter.
pub struct Upload {
    _private: (),
}

impl Upload {
    /// The placeholder.
    pub const fn new() -> Self {
        Self { _private: () }
    }

    /// Nothing to drop.
    pub(crate) fn clear(&mut self) {}
}

impl Default for Upload {
    fn default() -> Self {
        Self::new()
    }
}
