//! Map and scenario file formats.
