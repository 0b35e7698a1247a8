//! The frame stage: the mesh's boundary loops ([`topology`]), the canonical frame found from the
//! eyes and the mouth ([`orient`]) and the feature boxes ([`features`]); a closed mouth or
//! closed eyes are cut open along their contact lines first ([`contact`]).

pub mod contact;
pub mod features;
pub mod orient;
pub mod topology;
