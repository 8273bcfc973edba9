//! raster (in progress).
