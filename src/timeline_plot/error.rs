//! The drawing errors of the timeline, as the CLI reports them.

/// A drawing error as the CLI reports it.
pub(super) fn drawing<E: std::fmt::Display>(e: E) -> String {
    format!("drawing the timeline: {e}")
}
