//! openarena (in progress).
