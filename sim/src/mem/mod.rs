//! Memory hierarchy (in progress).
