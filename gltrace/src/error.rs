//! What went wrong reading a capture: the file, the position and what was
//! expected.

use std::fmt;
use std::path::{Path, PathBuf};

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

/// What the lower layers (container, stream, decoder) report: the
/// decompressed offset and the kind of fault; the call layer adds the call
/// number and the capture adds the file to make a [`CaptureError`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Fault {
    /// Offset in the decompressed stream where the fault was found.
    pub offset: u64,
    pub kind: FaultKind,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum FaultKind {
    /// The decompressed stream ended inside an item.
    Truncated,
    /// The bytes are not what the format allows (the message says what).
    Corrupt(String),
}

impl Fault {
    pub fn corrupt(offset: u64, message: impl Into<String>) -> Fault {
        Fault {
            offset,
            kind: FaultKind::Corrupt(message.into()),
        }
    }

    /// An unknown tag byte: `what` it was to be (an event, a value type...)
    /// and the tags the format has.
    pub fn unknown(offset: u64, what: &str, tag: u8, known: &str) -> Fault {
        Fault::corrupt(
            offset,
            format!(
                "unknown {what} 0x{tag:02x} at decompressed offset {offset} (the format's are \
                 {known})"
            ),
        )
    }

    /// The error for `file`, with the call number where known; `context`
    /// says what was being read when the stream ended (for truncations).
    pub fn into_error(self, file: &Path, call: Option<u64>, context: &str) -> CaptureError {
        let message = match self.kind {
            FaultKind::Truncated => format!(
                "truncated capture: the stream ends at decompressed offset {} inside {context}",
                self.offset
            ),
            FaultKind::Corrupt(m) => m,
        };
        CaptureError {
            file: file.to_path_buf(),
            offset: Some(self.offset),
            call,
            message,
        }
    }
}
