//! facebem: one neutral face mesh in, a physically based muscle rig out.

mod basis;

pub use basis::{MuscleBasis, PoseError};
