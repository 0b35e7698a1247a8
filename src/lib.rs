//! facebem: one neutral face mesh in, a physically based muscle rig out.
//!
//! The face is offset into a closed elastic shell, feature boxes, muscles and skull are found
//! automatically ([`face_prep`]), a constant-element elastostatic BEM ([`bem_core`]) is solved
//! once with one right-hand side per muscle, and each muscle's response is stored per vertex
//! ([`MuscleBasis`]) so sliders pose the face exactly: `v = v0 + Σ_k s_k · D_k`.
//!
//! ```no_run
//! use facebem::{build_face_model, cache, presets, Control, PipelineParams};
//! let (mesh, obj) = facebem::open::read_face("face.obj".as_ref())?;
//! let control = Control::new().with_progress(|p| eprintln!("{} {}/{}", p.stage, p.done, p.total));
//! let mut model = build_face_model(&mesh, &PipelineParams::default(), &control)?;
//! model.obj_source = obj;
//! cache::save("face.rig".as_ref(), &model)?;
//! let sliders = presets::find("happy").unwrap().sliders_for(model.muscle_ids());
//! model.write_obj("happy.obj".as_ref(), &sliders)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// The BEM solver facebem is built on (re-exported so callers use the same version).
pub use bem_core;
/// Face import, shell, features, muscles and skull (re-exported so callers use the same
/// version of the types in facebem's API, e.g. [`face_prep::FaceMesh`]).
pub use face_prep;

mod atomic_write;
mod basis;
pub mod cache;
pub mod contact_sheet;
mod control;
pub mod describe;
pub mod export;
pub mod expression_sets;
pub mod face_remesh;
pub mod face_simplify;
pub mod large_face;
mod lid_closure;
pub mod measure;
mod modiolus_pin;
pub mod open;
mod pipeline;
pub mod presets;
mod relaxation;
pub mod remesh;
pub mod rolled_in;
mod solve;
pub mod untangle;

pub use atomic_write::{OutputPathError, WriteError, check_output, write_atomic};
pub use basis::{MuscleBasis, PoseError};
pub use control::{Control, Progress, Stage};
pub use pipeline::{
    FaceModel, PipelineError, PipelineParams, PrecomputeReport, PreparedRig,
    SUSPICIOUS_AMPLIFICATION, SUSPICIOUS_FORCE_PEAK, SimplifiedFace, build_face_model, prep_rig,
    prepare,
};
