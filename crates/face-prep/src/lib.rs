//! Face mesh preparation for facebem.

mod muscle_kind;

pub use muscle_kind::{MuscleKind, Side};
