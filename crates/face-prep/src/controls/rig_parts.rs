//! The parts of a rig that the controls' rig-wide functions read.
//!
//! The rig (`crate::FaceRig`) is built from the controls stage, so the stage cannot name it:
//! a function that reads the whole rig (the patterns of every control, the sliding elements,
//! the modiolus pins, the force targets) takes these borrowed parts instead, and the rig hands
//! them out (`FaceRig::parts`).

use crate::controls::muscle_model::{AnatomicalParams, MuscleModel};
use crate::controls::muscles::Muscle;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::FaceLoops;
use crate::shell::Shell;

/// A rig's shell, loops, feature boxes, controls, skull, muscle model and scale, borrowed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RigParts<'a> {
    /// The closed shell (canonical frame).
    pub(crate) shell: &'a Shell,
    /// The four boundary loops (face vertex indices, which are the first shell vertices).
    pub(crate) loops: &'a FaceLoops,
    /// The feature boxes.
    pub(crate) boxes: &'a FeatureBoxes,
    /// The controls, in the rig's order.
    pub(crate) muscles: &'a [Muscle],
    /// The skull elements, sorted.
    pub(crate) skull: &'a [u32],
    /// How muscles become prescribed displacements.
    pub(crate) model: MuscleModel,
    /// Parameters of the anatomical muscle model.
    pub(crate) anatomical: &'a AnatomicalParams,
    /// Millimetres per unit of the mesh coordinates.
    pub(crate) mm_per_unit: f64,
}
