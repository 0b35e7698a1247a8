//! The morph targets of a glTF export: which there are, in file order ([`morph_targets`]), and
//! their accessors ([`target_accessors`]).

use glam::DVec3;
use serde_json::{Map, Value, json};

use super::buffer::Builder;
use super::{GltfExportError, GltfParams, vertex_normals};
use crate::MuscleBasis;
use crate::export::layout::ExportLayout;
use crate::expressions::{self, NameSet};

/// The morph targets of an export, before anything of them is written.
pub(super) struct MorphTargets {
    /// (name, welded position deltas at weight 1), in file order.
    pub(super) targets: Vec<(String, Vec<DVec3>)>,
    /// Animation clips: (clip name, target index).
    pub(super) clip_targets: Vec<(String, usize)>,
    /// `mesh.extras.partialTargets`: names made from only some of their controls.
    pub(super) partial: Map<String, Value>,
    /// `mesh.extras.leftOutTargets`: names left out, with the reason.
    pub(super) left_out: Map<String, Value>,
}

/// Welded position deltas of a pose (sliders in the basis's order) at weight 1.
fn field_of(basis: &MuscleBasis, sliders: &[f64]) -> Vec<DVec3> {
    let mut delta = vec![DVec3::ZERO; basis.neutral.len()];
    for (field, &s) in basis.displacements.iter().zip(sliders) {
        if s != 0.0 {
            for (d, f) in delta.iter_mut().zip(field) {
                *d += s * *f;
            }
        }
    }
    delta
}

/// The named (ARKit, VRM) targets, then facebem's own; fails when two share a name.
pub(super) fn morph_targets(
    basis: &MuscleBasis,
    params: &GltfParams,
) -> Result<MorphTargets, GltfExportError> {
    let mut targets: Vec<(String, Vec<DVec3>)> = Vec::new();
    let mut clip_targets: Vec<(String, usize)> = Vec::new();
    let (named, left_out) = expressions::for_rig(params.names, &basis.muscle_ids);
    let mut partial = Map::new();
    let spelled = |name: &str| params.arkit_naming.name(name);
    for r in &named {
        let e = r.expression;
        if !r.resolved.missing.is_empty() {
            partial.insert(spelled(e.name), json!(r.resolved.missing));
        }
        if e.set == NameSet::Vrm && !params.names.facebem && e.name != "neutral" {
            clip_targets.push((e.name.to_string(), targets.len()));
        }
        targets.push((spelled(e.name), field_of(basis, &r.resolved.sliders)));
    }
    let mut left_out_json = Map::new();
    for (e, controls) in &left_out {
        left_out_json.insert(
            spelled(e.name),
            json!(format!("controls not in this rig: {}", controls.join(", "))),
        );
    }
    for (name, why) in expressions::NOT_MODELLED {
        let set = if expressions::arkit::NAMES.contains(&name) {
            NameSet::Arkit
        } else {
            NameSet::Vrm
        };
        if params.names.contains(set) {
            left_out_json.insert(spelled(name), json!(format!("not modelled: {why}")));
        }
    }
    if params.names.facebem {
        own_targets(basis, params, &mut targets, &mut clip_targets);
    }
    let mut seen = std::collections::HashSet::new();
    if let Some((name, _)) = targets.iter().find(|(name, _)| !seen.insert(name.as_str())) {
        return Err(GltfExportError::DuplicateTarget(name.clone()));
    }
    Ok(MorphTargets {
        targets,
        clip_targets,
        partial,
        left_out: left_out_json,
    })
}

/// Appends facebem's own targets: each muscle's contract and relax, then the presets (with
/// their clips).
fn own_targets(
    basis: &MuscleBasis,
    params: &GltfParams,
    targets: &mut Vec<(String, Vec<DVec3>)>,
    clip_targets: &mut Vec<(String, usize)>,
) {
    for (id, field) in basis.muscle_ids.iter().zip(&basis.displacements) {
        targets.push((
            format!("{id}_contract"),
            field.iter().map(|d| -*d).collect(),
        ));
        targets.push((format!("{id}_relax"), field.clone()));
    }
    for preset in params.presets.iter().filter(|p| p.name != "neutral") {
        let sliders = preset.sliders_for(&basis.muscle_ids);
        clip_targets.push((preset.name.to_string(), targets.len()));
        targets.push((format!("preset_{}", preset.name), field_of(basis, &sliders)));
    }
}

/// Writes each target's POSITION and NORMAL delta accessors; returns the primitive's
/// `targets` entries.
pub(super) fn target_accessors(
    b: &mut Builder,
    basis: &MuscleBasis,
    layout: &ExportLayout,
    targets: &[(String, Vec<DVec3>)],
    neutral_normals: &[DVec3],
    scale: f64,
) -> Result<Vec<Value>, GltfExportError> {
    let mut target_json = Vec::with_capacity(targets.len());
    for (name, delta) in targets {
        let posed: Vec<DVec3> = basis
            .neutral
            .iter()
            .zip(delta)
            .map(|(p, d)| *p + *d)
            .collect();
        let normal_delta: Vec<DVec3> = vertex_normals(&posed, &basis.triangles)
            .iter()
            .zip(neutral_normals)
            .map(|(a, b)| *a - *b)
            .collect();
        let p = b.vec3_accessor(name, &gather(layout, delta, scale), true)?;
        let nd = b.vec3_accessor(name, &gather(layout, &normal_delta, 1.0), false)?;
        target_json.push(json!({ "POSITION": p, "NORMAL": nd }));
    }
    Ok(target_json)
}

/// Per glTF vertex of `layout`: a welded per-vertex field times `factor` (zero for unused
/// input positions).
fn gather(layout: &ExportLayout, field: &[DVec3], factor: f64) -> Vec<DVec3> {
    layout
        .welded
        .iter()
        .map(|w| w.map_or(DVec3::ZERO, |w| field[w as usize] * factor))
        .collect()
}
