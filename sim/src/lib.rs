//! wasp-sim
