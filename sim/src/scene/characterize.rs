//! characterize (in progress).
