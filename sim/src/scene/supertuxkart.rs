//! supertuxkart (in progress).
