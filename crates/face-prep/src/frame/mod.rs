//! The frame stage: the mesh's boundary loops ([`topology`]), the canonical frame found from the
//! eyes and the mouth ([`orient`]) and the feature boxes ([`features`]).

pub mod features;
pub mod orient;
pub mod topology;
