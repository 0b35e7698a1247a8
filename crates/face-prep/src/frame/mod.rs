//! The frame stage: the mesh's boundary loops ([`topology`]), the canonical frame found from the
//! eyes and the mouth ([`orient`]) and the feature boxes ([`features`]); a closed mouth is cut
//! open along its lips' contact line first ([`lip_line`]).

pub mod features;
pub mod lip_line;
pub mod orient;
pub mod topology;
