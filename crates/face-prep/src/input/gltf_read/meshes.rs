//! What the document's meshes hold: their labels, and the accessors of their primitives.

use std::collections::BTreeMap;

use gltf::json;
use json::validation::Checked;

/// Labels of the meshes (name, or `#index` when unnamed).
pub(crate) fn mesh_labels(root: &json::Root) -> Vec<String> {
    root.meshes
        .iter()
        .enumerate()
        .map(|(i, m)| m.name.clone().unwrap_or_else(|| format!("#{i}")))
        .collect()
}

/// Accessor index of attribute `semantic` of primitive `primitive` of `mesh`, if it has one.
pub(crate) fn attribute(
    root: &json::Root,
    mesh: usize,
    primitive: usize,
    semantic: json::mesh::Semantic,
) -> Option<usize> {
    let p = root.meshes.get(mesh)?.primitives.get(primitive)?;
    p.attributes
        .get(&Checked::Valid(semantic))
        .map(|a| a.value())
}

/// Accessor indices of POSITION and indices, and the mode, of every primitive of `mesh`.
pub(crate) fn primitives(
    root: &json::Root,
    mesh: usize,
) -> Vec<(Option<usize>, Option<usize>, Checked<json::mesh::Mode>)> {
    root.meshes[mesh]
        .primitives
        .iter()
        .map(|p| {
            let attrs: &BTreeMap<_, _> = &p.attributes;
            let pos = attrs
                .get(&Checked::Valid(json::mesh::Semantic::Positions))
                .map(|a| a.value());
            (pos, p.indices.map(|i| i.value()), p.mode)
        })
        .collect()
}
