//! Atomic, input-preserving file writes: the implementation lives in
//! [`face_prep::atomic_write`] (the muscle file writer uses it too) and is re-exported here.

pub use face_prep::atomic_write::{OutputPathError, WriteError, check_output, write_atomic};
