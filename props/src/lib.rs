//! wasp-props
