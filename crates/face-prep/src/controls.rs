//! Placing the rig's standard controls and generating their prescribed displacements: the two
//! dispatch points on [`crate::muscle_kind::Generator`] (see `muscle_kind.rs` on how to add a
//! control).

use crate::anatomy::attachment;
use crate::muscle_kind::{Generator, MuscleKind};
use crate::muscle_model::{MuscleModel, anatomical_pattern, place_band};
use crate::muscles::{Muscle, muscle_pattern};
use crate::rig::FaceRig;
use glam::DVec3;
use std::collections::HashSet;

impl FaceRig {
    /// Places one standard control in the anatomical model: its elements (chains) on the
    /// shell. `skull` holds the rig's skull elements (never part of a band).
    pub(crate) fn place_control(&self, kind: MuscleKind, skull: &HashSet<u32>) -> Muscle {
        let (front_chain, back_chain) = match kind.generator() {
            Generator::Band(_) => match attachment(kind, &self.boxes) {
                Some(att) => place_band(
                    &self.shell,
                    skull,
                    &att,
                    self.mm_per_unit(),
                    &self.params.anatomical,
                ),
                None => (Vec::new(), Vec::new()),
            },
        };
        Muscle {
            name: kind.display_name().to_owned(),
            kind: Some(kind),
            front_chain,
            back_chain,
        }
    }

    /// Prescribed per-element displacement of `muscle` at slider = +1 (canonical frame): the
    /// thesis rule in the thesis model; in the anatomical model the control's generator (a
    /// custom muscle, `kind == None`, is a band from its chain's ends).
    pub(crate) fn control_pattern(&self, muscle: &Muscle) -> Vec<(u32, DVec3)> {
        match self.params.muscle_model {
            MuscleModel::Thesis => muscle_pattern(&self.shell, muscle),
            MuscleModel::Anatomical => match muscle.kind.map(MuscleKind::generator) {
                None | Some(Generator::Band(_)) => anatomical_pattern(
                    &self.shell,
                    &self.shell_bvh(),
                    &self.boxes,
                    &self.contour_xy(),
                    muscle,
                    self.mm_per_unit(),
                    &self.params.anatomical,
                ),
            },
        }
    }
}
