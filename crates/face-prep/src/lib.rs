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

pub mod atomic_write;
pub mod bvh;
pub mod closest_point;
pub mod controls;
pub mod error;
pub mod frame;
pub mod harmonic;
pub mod input;
pub mod parts;
mod rig;
pub mod shell;

// The stages' modules under their short historical paths (`face_prep::orient`, ...).
pub use controls::{
    anatomy, eyelid, force_controls, ids, jaw, lip_margin, lip_seal, modiolus, muscle_file,
    muscle_kind, muscle_model, muscles, teeth,
};
pub use frame::{features, orient, topology};
pub use input::{gltf_read, limits, obj_text, units};

pub use error::{LoopSummary, MuscleFileError, ObjLineError, PrepError};
pub use features::{Box2, FeatureBoxes};
pub use gltf_read::GltfError;
pub use input::face_mesh::{FaceMesh, LoadOptions, WELD_RELATIVE_TOLERANCE, load_face};
pub use input::gltf_face::{GltfFaceData, gltf_face_data};
pub use limits::InputLimits;
pub use muscle_kind::{ControlSpec, Generator, MuscleKind, Placed, Side};
pub use muscles::Muscle;
pub use orient::FaceLoops;
pub use rig::{FaceRig, RigParams, check_not_scrambled};
pub use shell::{ElementTag, FrontRepair, Shell};
