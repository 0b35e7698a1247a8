//! facebem: one neutral face mesh in, a physically based muscle rig out.
//!
//! The face is offset into a closed elastic shell, feature boxes, muscles and skull are found
//! automatically ([`face_prep`]), a constant-element elastostatic BEM ([`bem_core`]) is solved
//! once with one right-hand side per muscle, and each muscle's response is stored per vertex
//! ([`MuscleBasis`]) so sliders pose the face exactly: `v = v0 + Σ_k s_k · D_k`.
//!
//! The stages, in the order [`pipeline`] runs them (`docs/architecture.md`): [`input`] (read a
//! face file), [`frame`] (loops and canonical frame), [`copy`] (the simulated copy), the rig
//! (face-prep: shell and controls), [`solve`], [`transfer`], [`settle`]; then [`expressions`]
//! (presets, ARKit, VRM), [`export`] (glTF, OBJ), [`cache`] (rig files) and [`report`]. The data
//! they share is in [`model`].
//!
//! ```no_run
//! use facebem::{build_face_model, cache, expressions::presets, Control, PipelineParams};
//! let (mesh, obj) = facebem::input::read_face("face.obj".as_ref())?;
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
pub mod cache;
mod control;
pub mod copy;
pub mod export;
pub mod expressions;
pub mod frame;
pub mod input;
pub mod model;
pub mod pipeline;
pub mod report;
pub mod settle;
pub mod solve;
pub mod transfer;

pub use atomic_write::{OutputPathError, WriteError, check_output, write_atomic};
pub use control::{Control, Progress, Stage};
pub use model::{
    FaceModel, MuscleBasis, PipelineError, PipelineParams, PoseError, PrecomputeReport,
    PreparedRig, SUSPICIOUS_AMPLIFICATION, SUSPICIOUS_FORCE_PEAK, SimplifiedFace,
};
pub use pipeline::{build_face_model, prep_rig, prepare};

/// The README's Rust example, run as a doctest (on the bundled default face) so it cannot
/// drift from the API.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
