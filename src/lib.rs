//! facebem: one neutral face mesh in, a physically based muscle rig out.

mod atomic_write;
mod basis;
pub mod cache;
pub mod export;
pub mod large_face;
pub mod presets;

pub use atomic_write::{WriteError, write_atomic};
pub use basis::{MuscleBasis, PoseError};
