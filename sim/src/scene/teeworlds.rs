//! teeworlds (in progress).
