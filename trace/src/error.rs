//! [`TraceError`]: an error reading a trace, a file that cannot be read or
//! a [`Problem`] at a line of the input.

use std::fmt;

use crate::problem::Problem;

/// An error reading a trace.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TraceError {
    /// The file could not be read.
    Io {
        /// The path.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The input breaks the format at a line.
    Malformed {
        /// File name (or the source name given to [`Trace::parse`](crate::Trace::parse)).
        source: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        problem: Problem,
    },
}

impl TraceError {
    /// The broken rule, if the input was read.
    pub fn problem(&self) -> Option<&Problem> {
        match self {
            TraceError::Io { .. } => None,
            TraceError::Malformed { problem, .. } => Some(problem),
        }
    }

    /// The 1-based line of the problem, if the input was read.
    pub fn line(&self) -> Option<usize> {
        match self {
            TraceError::Io { .. } => None,
            TraceError::Malformed { line, .. } => Some(*line),
        }
    }
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TraceError::Io { path, message } => write!(f, "{path}: cannot read: {message}"),
            TraceError::Malformed {
                source,
                line,
                problem,
            } => write!(f, "{source}:{line}: {problem}"),
        }
    }
}

impl std::error::Error for TraceError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TraceError::Io { .. } => None,
            TraceError::Malformed { problem, .. } => Some(problem),
        }
    }
}
