//! Suites about whole traces: reading, writing and round trips of whole
//! files, malformed input, and property suites. Unit tests sit at the
//! bottom of the module they test; helpers shared by both are in
//! `crate::testkit`.

mod bounds;
mod files;
mod format_md;
mod frames;
mod fuzz;
mod malformed;
mod rejected;
mod texture_format;
mod texture_map;
mod trilinear;
