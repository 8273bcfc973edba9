//! def (in progress).
