//! The morph targets of a glTF export: which there are, in file order ([`morph_targets`]), and
//! their accessors ([`target_accessors`]).

use glam::DVec3;
use serde_json::{Map, Value, json};

use super::buffer::{Builder, DELTA_BITS, NORMAL_BITS};
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
    /// `mesh.extras.sameAs`: targets left out because an earlier one is the same, by name.
    pub(super) same_as: Map<String, Value>,
    /// `mesh.extras.negativeOf`: targets left out because they are an earlier one times −1.
    pub(super) negative_of: Map<String, Value>,
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

/// The targets an export of `basis` with `params` writes, in file order, and the names left
/// out because they repeat one of them (for binding those names to it, as VRM expressions).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedTargets {
    /// (name, displacement of every basis vertex at weight 1), in file order.
    pub targets: Vec<(String, Vec<DVec3>)>,
    /// Left-out name → the written target it equals.
    pub same_as: Vec<(String, String)>,
}

/// The targets [`super::export_gltf_layout`] would write for `basis` (no file is built).
///
/// ```
/// use facebem::MuscleBasis;
/// use facebem::export::gltf::{named_targets, GltfParams};
/// use glam::DVec3;
/// let basis = MuscleBasis {
///     muscle_ids: vec!["zygomaticus_major_l".into()],
///     neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     triangles: vec![[0, 1, 2]],
///     displacements: vec![vec![DVec3::ZERO, DVec3::Z * 0.1, DVec3::ZERO]],
/// };
/// let named = named_targets(&basis, &GltfParams::default()).unwrap();
/// assert!(named.targets.iter().any(|(n, _)| n == "mouthSmileLeft"));
/// ```
pub fn named_targets(
    basis: &MuscleBasis,
    params: &GltfParams,
) -> Result<NamedTargets, GltfExportError> {
    super::check_fields(basis, params)?;
    let made = morph_targets(basis, params)?;
    let same_as = made
        .same_as
        .iter()
        .map(|(k, v)| (k.clone(), v.as_str().unwrap_or_default().to_string()))
        .collect();
    Ok(NamedTargets {
        targets: made.targets,
        same_as,
    })
}

/// The named (ARKit, VRM) targets, then facebem's own; fails when two share a name.
pub(super) fn morph_targets(
    basis: &MuscleBasis,
    params: &GltfParams,
) -> Result<MorphTargets, GltfExportError> {
    let mut targets: Vec<(String, Vec<DVec3>)> = Vec::new();
    let mut clip_targets: Vec<(String, usize)> = Vec::new();
    // Whether a target is written even when it repeats another: every ARKit name, which tools
    // look up one by one (jawRight is exactly −jawLeft on every rig).
    let mut always: Vec<bool> = Vec::new();
    let (named, left_out) = expressions::for_rig(params.names, &basis.muscle_ids);
    let mut partial = Map::new();
    let spelled = |name: &str| params.arkit_naming.name(name);
    // The controls' expressions and the named fields, in the standards' order.
    let mut standard: Vec<(NameSet, &str, Vec<DVec3>)> = Vec::new();
    // A named field replaces what the controls would make of its name (a whole head's
    // targets kept off the eyeballs, `crate::transfer::head::HeadBasis::named_fields_for`).
    let replaced: std::collections::HashSet<&str> = params
        .named_fields
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    for r in named
        .iter()
        .filter(|r| !replaced.contains(r.expression.name))
    {
        let e = r.expression;
        if !r.resolved.missing.is_empty() {
            partial.insert(spelled(e.name), json!(r.resolved.missing));
        }
        standard.push((e.set, e.name, field_of(basis, &r.resolved.sliders)));
    }
    let mut fielded = std::collections::HashSet::new();
    for (name, field) in &params.named_fields {
        let set = set_of(name);
        if params.names.contains(set) {
            fielded.insert(name.as_str());
            standard.push((set, name.as_str(), field.clone()));
        }
    }
    standard.sort_by_key(|(set, name, _)| standard_order(*set, name));
    for (set, name, field) in standard {
        if set == NameSet::Vrm && !params.names.facebem && name != "neutral" {
            clip_targets.push((name.to_string(), targets.len()));
        }
        targets.push((spelled(name), field));
        always.push(set == NameSet::Arkit);
    }
    let mut left_out_json = Map::new();
    for (e, controls) in &left_out {
        left_out_json.insert(
            spelled(e.name),
            json!(format!("controls not in this rig: {}", controls.join(", "))),
        );
    }
    for (name, why) in expressions::NOT_MODELLED {
        let set = set_of(name);
        if params.names.contains(set) && !fielded.contains(name) {
            left_out_json.insert(spelled(name), json!(format!("not modelled: {why}")));
        }
    }
    if params.names.facebem {
        own_targets(basis, params, &mut targets, &mut clip_targets);
    }
    always.resize(targets.len(), false);
    let mut seen = std::collections::HashSet::new();
    if let Some((name, _)) = targets.iter().find(|(name, _)| !seen.insert(name.as_str())) {
        return Err(GltfExportError::DuplicateTarget(name.clone()));
    }
    let repeats = leave_out_repeats(targets, &always);
    for name in &repeats.zero {
        left_out_json.insert(
            name.clone(),
            json!("all zero: the base mesh is this expression"),
        );
    }
    let clip_targets = clip_targets
        .into_iter()
        .filter_map(|(clip, t)| repeats.new_index[t].map(|t| (clip, t)))
        .collect();
    Ok(MorphTargets {
        targets: repeats.kept,
        clip_targets,
        partial,
        left_out: left_out_json,
        same_as: repeats.same_as,
        negative_of: repeats.negative_of,
    })
}

/// The standard a name of [`expressions::NOT_MODELLED`] (or any ARKit or VRM name) is of.
fn set_of(name: &str) -> NameSet {
    if expressions::arkit::NAMES.contains(&name) {
        NameSet::Arkit
    } else {
        NameSet::Vrm
    }
}

/// A named target's place in an export: ARKit's names in ARKit's order, then VRM's.
fn standard_order(set: NameSet, name: &str) -> usize {
    let (base, names): (usize, &[&str]) = match set {
        NameSet::Arkit => (0, &expressions::arkit::NAMES),
        _ => (expressions::arkit::NAMES.len(), &expressions::vrm::NAMES),
    };
    base + names.iter().position(|n| *n == name).unwrap_or(names.len())
}

/// The targets that remain once every repeat is left out ([`leave_out_repeats`]).
struct Repeats {
    /// The targets written, in order.
    kept: Vec<(String, Vec<DVec3>)>,
    /// Per input target, its index among `kept` (the target it is the same as, for a left-out
    /// copy); `None` for one left out as all zero or as a negative.
    new_index: Vec<Option<usize>>,
    /// Left-out copy → the earlier target it equals.
    same_as: Map<String, Value>,
    /// Left-out negative → the earlier target it is −1 times.
    negative_of: Map<String, Value>,
    /// Left out because every delta is zero.
    zero: Vec<String>,
}

/// Leaves out each target (unless `always`) that is all zero, exactly equal to an earlier
/// written one, or exactly −1 times one: in the default export `blinkLeft` is `eyeBlinkLeft`,
/// and each muscle's `_relax` is `−_contract` (weight −1 on the kept target gives it). Found by
/// hashing each field's bits (−0 taken as +0), then compared exactly.
fn leave_out_repeats(targets: Vec<(String, Vec<DVec3>)>, always: &[bool]) -> Repeats {
    use std::collections::HashMap;
    use std::hash::{Hash, Hasher};
    let hash_of = |field: &[DVec3], sign: f64| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for d in field {
            for c in d.to_array() {
                // `+ 0.0` turns −0 into +0, so that equal fields hash alike.
                (sign * c + 0.0).to_bits().hash(&mut h);
            }
        }
        h.finish()
    };
    let mut out = Repeats {
        kept: Vec::new(),
        new_index: Vec::with_capacity(targets.len()),
        same_as: Map::new(),
        negative_of: Map::new(),
        zero: Vec::new(),
    };
    let mut by_hash: HashMap<u64, Vec<usize>> = HashMap::new();
    for (i, (name, field)) in targets.into_iter().enumerate() {
        let keep = always.get(i).copied().unwrap_or(false);
        let h = hash_of(&field, 1.0);
        if !keep {
            if field.iter().all(|d| *d == DVec3::ZERO) {
                out.zero.push(name);
                out.new_index.push(None);
                continue;
            }
            let kept = &out.kept;
            let find = |h: u64, sign: f64| {
                by_hash.get(&h).and_then(|c| {
                    c.iter()
                        .copied()
                        .find(|&j| kept[j].1.iter().zip(&field).all(|(a, b)| *a == sign * *b))
                })
            };
            if let Some(j) = find(h, 1.0) {
                out.same_as.insert(name, json!(kept[j].0));
                out.new_index.push(Some(j));
                continue;
            }
            if let Some(j) = find(hash_of(&field, -1.0), -1.0) {
                out.negative_of.insert(name, json!(kept[j].0));
                out.new_index.push(None);
                continue;
            }
        }
        by_hash.entry(h).or_default().push(out.kept.len());
        out.new_index.push(Some(out.kept.len()));
        out.kept.push((name, field));
    }
    out
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

/// Smallest NORMAL delta written: 2⁻¹⁵, one step of a 16-bit normalized normal (the finest
/// normal `KHR_mesh_quantization` stores), a change no renderer shows. A target's far vertices
/// move by a few nanometres and their normals by ~10⁻⁷; written as zero they need no bytes in a
/// sparse accessor (positions are written exactly).
pub const NORMAL_DELTA_RESOLUTION: f64 = 1.0 / 32768.0;

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
            .map(|(a, b)| {
                let d = *a - *b;
                if d.length() < NORMAL_DELTA_RESOLUTION {
                    DVec3::ZERO
                } else {
                    d
                }
            })
            .collect();
        let p = b.delta_accessor(name, &gather(layout, delta, scale), DELTA_BITS)?;
        let nd = b.delta_accessor(name, &gather(layout, &normal_delta, 1.0), NORMAL_BITS)?;
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
