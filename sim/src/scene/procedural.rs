//! procedural (in progress).
