//! What went wrong reading a capture: the file, the position and what was
//! expected.

use std::fmt;
use std::path::PathBuf;

/// An error reading a capture: the file, the offset in the decompressed
/// call stream where known (and the call number reached), and the message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CaptureError {
    /// The capture file.
    pub file: PathBuf,
    /// Offset in the decompressed stream, where known.
    pub offset: Option<u64>,
    /// The number of the call being read, where known.
    pub call: Option<u64>,
    /// What was wrong, and what was expected.
    pub message: String,
}

impl fmt::Display for CaptureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(c) = self.call {
            write!(f, ", call {c}")?;
        }
        if let Some(o) = self.offset {
            write!(f, ", offset {o}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for CaptureError {}
