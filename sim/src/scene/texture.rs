//! texture (in progress).
