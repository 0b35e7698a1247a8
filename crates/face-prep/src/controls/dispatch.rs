//! Placing the rig's standard controls and generating their prescribed displacements: the two
//! dispatch points on [`crate::controls::muscle_kind::Generator`] (see `muscle_kind.rs` on how to add a
//! control).

use crate::controls::anatomy::Landmarks;
use crate::controls::eyelid::eye_lids;
use crate::controls::force_controls::{
    SPHINCTER_RING_MM, cheek_puff_traction, force_band_traction, is_force_control, mouth_xy,
    place_cheek_puff, place_force_band, place_sphincter, sphincter_traction,
};
use crate::controls::jaw::{Jaw, JawMode};
use crate::controls::lip_margin::{MARGINAL_RING_MM, marginal_traction};
use crate::controls::muscle_kind::attachment;
use crate::controls::muscle_kind::{Generator, MuscleKind, Side};
use crate::controls::muscle_model::{AnatomicalParams, MuscleModel, band_pattern, place_band};
use crate::controls::muscles::{Muscle, muscle_pattern};
use crate::controls::rig_parts::RigParts;
use crate::controls::teeth::{on_lower_teeth, sliding_elements};
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, loop_xy};
use crate::shell::Shell;
use glam::DVec3;
use std::collections::{BTreeMap, HashSet};

/// Places one standard control in the anatomical model: its elements (chains) on a rig's
/// `shell`, from its `loops` and feature `boxes`. `skull` holds the rig's skull elements
/// (never part of a band).
pub(crate) fn place_control(
    shell: &Shell,
    loops: &FaceLoops,
    boxes: &FeatureBoxes,
    mm_per_unit: f64,
    anatomical: &AnatomicalParams,
    kind: MuscleKind,
    skull: &HashSet<u32>,
) -> Muscle {
    let (front_chain, back_chain) = match kind.generator() {
        Generator::Band(_) | Generator::Force(_) => match attachment(kind, boxes) {
            Some(att) => {
                let place = if kind.is_force() {
                    place_force_band
                } else {
                    place_band
                };
                place(shell, skull, &att, mm_per_unit, anatomical)
            }
            None => (Vec::new(), Vec::new()),
        },
        // The jaw's elements are skull (rim) elements: [`Jaw::of`].
        Generator::Jaw(_) => (Vec::new(), Vec::new()),
        // The sphincter's ring, or its marginal part's narrower one at the lip margin.
        Generator::Sphincter(lip) | Generator::Marginal(lip) => place_sphincter(
            shell,
            skull,
            &mouth_xy(shell, loops),
            boxes.mouth.center().y,
            lip,
            match kind.generator() {
                Generator::Marginal(_) => MARGINAL_RING_MM,
                _ => SPHINCTER_RING_MM,
            },
            mm_per_unit,
        ),
        // The seal's response is a share of jaw_open's ([`crate::controls::lip_seal`]).
        Generator::Seal => (Vec::new(), Vec::new()),
        Generator::Pressure => (
            Vec::new(),
            place_cheek_puff(shell, skull, &Landmarks::of(boxes)),
        ),
        Generator::Lid(action) => eye_lids(shell, loops, kind.side(), mm_per_unit)
            .map(|lids| lids.band(shell, skull, action))
            .unwrap_or_default(),
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
pub(crate) fn control_pattern(rig: RigParts<'_>, muscle: &Muscle) -> Vec<(u32, DVec3)> {
    let RigParts {
        shell,
        loops,
        boxes,
        anatomical,
        mm_per_unit,
        ..
    } = rig;
    match rig.model {
        MuscleModel::Thesis => muscle_pattern(shell, muscle),
        MuscleModel::Anatomical => match muscle.kind.map(MuscleKind::generator) {
            None | Some(Generator::Band(_)) => {
                band_pattern(shell, loops, boxes, mm_per_unit, anatomical, muscle)
            }
            Some(Generator::Jaw(mode)) => jaw_pattern(rig, mode),
            Some(Generator::Pressure) => cheek_puff_traction(shell, boxes, muscle),
            Some(Generator::Seal) => Vec::new(),
            Some(Generator::Sphincter(_)) => {
                sphincter_traction(shell, loops, boxes, mm_per_unit, muscle)
            }
            Some(Generator::Marginal(_)) => marginal_traction(shell, loops, mm_per_unit, muscle),
            Some(Generator::Force(_)) => {
                force_band_traction(shell, loops, boxes, mm_per_unit, anatomical, muscle)
            }
            Some(Generator::Lid(action)) => eye_lids(
                shell,
                loops,
                muscle.kind.map_or(Side::Left, MuscleKind::side),
                mm_per_unit,
            )
            .map(|lids| {
                lids.pattern(
                    shell,
                    &loop_xy(&shell.vertices, &loops.face),
                    action,
                    muscle.elements(),
                )
            })
            .unwrap_or_default(),
        },
    }
}

/// Per-element displacement of a jaw mode at slider = +1 (the negative of its activation):
/// the jaw segment as the mandible carries it ([`Jaw::carried_activation`]: rigidly above the
/// still neck), every band element of the other controls with that motion times
/// [`Jaw::tissue_weight`] (elements of no band keep 0 there).
fn jaw_pattern(rig: RigParts<'_>, mode: JawMode) -> Vec<(u32, DVec3)> {
    let jaw = Jaw::of(rig.shell, rig.loops, rig.boxes, rig.mm_per_unit);
    let mm = rig.mm_per_unit;
    let mut out: BTreeMap<u32, DVec3> = BTreeMap::new();
    // Only displacement-prescribed elements are carried (a force-driven control's elements
    // are traction-type: a value there would be a traction).
    for (k, m) in rig.muscles.iter().enumerate() {
        if is_force_control(rig.model, rig.muscles, k) {
            continue;
        }
        for e in m.elements() {
            let c = rig.shell.centroid(e as usize);
            let w = jaw.tissue_weight(c.truncate());
            out.insert(e, -w * jaw.carried_activation(mode, c, mm));
        }
    }
    for &e in &jaw.elements {
        let c = rig.shell.centroid(e as usize);
        out.insert(e, -jaw.carried_activation(mode, c, mm));
    }
    // The lower teeth move with the jaw: the deep layer sliding on them follows it along
    // their normal (the solve keeps only that part on a sliding element).
    for e in sliding_elements(rig) {
        if on_lower_teeth(rig.shell, rig.boxes, e) {
            let c = rig.shell.centroid(e as usize);
            out.insert(e, -jaw.activation(mode, c, mm));
        }
    }
    out.into_iter().collect()
}

/// Vertices whose displacement in response `muscle_index` is known exactly rather than
/// averaged from their elements, with that displacement at slider = +1 (canonical frame):
/// for a jaw mode, every vertex of the jaw segment moves as the mandible carries it (so the
/// jaw's part of the outer contour moves with the jaw, and the neck's stays); empty for every
/// other control.
pub(crate) fn prescribed_vertex_motion(
    rig: RigParts<'_>,
    muscle_index: usize,
) -> Vec<(u32, DVec3)> {
    let Some(Generator::Jaw(mode)) = rig
        .muscles
        .get(muscle_index)
        .and_then(|m| m.kind)
        .map(MuscleKind::generator)
    else {
        return Vec::new();
    };
    if rig.model != MuscleModel::Anatomical {
        return Vec::new();
    }
    let jaw = Jaw::of(rig.shell, rig.loops, rig.boxes, rig.mm_per_unit);
    let mm = rig.mm_per_unit;
    let vertices: std::collections::BTreeSet<u32> = jaw
        .elements
        .iter()
        .flat_map(|&e| rig.shell.triangles[e as usize])
        .collect();
    vertices
        .into_iter()
        .map(|v| {
            let p = rig.shell.vertices[v as usize];
            (v, -jaw.carried_activation(mode, p, mm))
        })
        .collect()
}
