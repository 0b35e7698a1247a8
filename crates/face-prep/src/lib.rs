//! Face mesh preparation for facebem: from one front-face triangle mesh (four holes: outer
//! contour, two eyes, mouth) to a muscle rig for the BEM.
//!
//! Pipeline: [`load_face`] → [`FaceMesh`] (welded, validated, input frame) →
//! [`FaceRig::build`]: canonical orientation ([`orient`]), loops and [`FeatureBoxes`],
//! closed [`Shell`] (front / back / rim elements), standard muscles by ray projection
//! ([`muscles`]) and skull. Muscle files: [`muscle_file`].
//!
//! ```
//! use face_prep::{FaceRig, MuscleKind, RigParams, load_face};
//! let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
//!     .join("../../assets/mediapipe_canonical_4loop.obj");
//! let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
//! let zyg = rig.muscle_index(MuscleKind::ZygomaticusMajorL).unwrap();
//! assert!(!rig.muscles[zyg].front_chain.is_empty());
//! ```

pub mod anatomy;
pub mod atomic_write;
pub mod bvh;
pub mod closest_point;
mod controls;
pub mod error;
pub mod eyelid;
mod face_mesh;
pub mod features;
pub mod force_controls;
pub mod gltf_read;
pub mod jaw;
pub mod limits;
pub mod modiolus;
pub mod muscle_file;
pub mod muscle_kind;
pub mod muscle_model;
pub mod muscles;
pub mod orient;
mod rig;
pub mod shell;
pub mod teeth;
pub mod topology;
pub mod units;

pub use error::{LoopSummary, MuscleFileError, PrepError};
pub use face_mesh::{
    FaceMesh, GltfFaceData, gltf_face_data, load_face, load_face_mesh_named, load_face_with_limits,
};
pub use features::{Box2, FeatureBoxes};
pub use gltf_read::GltfError;
pub use limits::InputLimits;
pub use muscle_kind::{ControlSpec, Generator, MuscleKind, Placed, Side};
pub use muscles::Muscle;
pub use orient::FaceLoops;
pub use rig::{FaceRig, RigParams};
pub use shell::{ElementTag, FrontRepair, Shell};
