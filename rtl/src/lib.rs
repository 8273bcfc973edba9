//! wasp-rtl
