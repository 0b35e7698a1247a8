//! On-disk cache of a computed face model (placeholder until the pipeline lands).

pub mod container;
