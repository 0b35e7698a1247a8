//! The mesh's primitives and materials: one primitive with the replaceable skin
//! ([`super::MATERIAL_NAME`]), or, for an OBJ with materials ([`crate::export::material`]), one
//! primitive per material, all sharing the vertices and the morph targets; with a
//! [`super::MeshSplit`] (a head's parts), one mesh per group, each with its materials' primitives.

use serde_json::{Value, json};

use super::GltfParams;
use super::buffer::Builder;
use crate::export::layout::ExportLayout;
use crate::export::material::UserMaterial;

/// The primitives (without their `targets`), and the document's materials, textures, images
/// and samplers; warnings for what could not be used.
pub(super) struct Looks {
    /// (mesh, primitive): the mesh is the triangles' [`super::MeshSplit`] group (0 without).
    pub(super) primitives: Vec<(usize, Value)>,
    pub(super) materials: Vec<Value>,
    pub(super) textures: Vec<Value>,
    pub(super) images: Vec<Value>,
    pub(super) warnings: Vec<String>,
}

/// Writes the index accessors (and embedded images) of the primitives of `layout`, each with
/// `attributes`.
pub(super) fn looks(
    b: &mut Builder,
    layout: &ExportLayout,
    params: &GltfParams,
    attributes: &Value,
) -> Looks {
    let mut looks = Looks {
        primitives: vec![],
        materials: vec![],
        textures: vec![],
        images: vec![],
        warnings: vec![],
    };
    let user = params
        .materials
        .as_ref()
        .filter(|m| !m.materials.is_empty());
    let per_triangle = match user {
        Some(m) if m.triangle_material.len() == layout.triangles.len() => {
            Some(&m.triangle_material)
        }
        Some(m) => {
            looks.warnings.push(format!(
                "the materials name {} triangles for the export's {}: the skin is used",
                m.triangle_material.len(),
                layout.triangles.len()
            ));
            None
        }
        None => None,
    };
    let mesh_of = |t: usize| {
        params
            .mesh_split
            .as_ref()
            .filter(|s| s.triangle_mesh.len() == layout.triangles.len())
            .map_or(0, |s| s.triangle_mesh[t] as usize)
    };
    let meshes = params
        .mesh_split
        .as_ref()
        .filter(|s| s.triangle_mesh.len() == layout.triangles.len())
        .map_or(1, |s| s.names.len().max(1));
    let Some((per_triangle, user)) = per_triangle.zip(user) else {
        looks.materials.push(skin());
        for mesh in 0..meshes {
            let triangles: Vec<[u32; 3]> = (0..layout.triangles.len())
                .filter(|&t| mesh_of(t) == mesh)
                .map(|t| layout.triangles[t])
                .collect();
            if !triangles.is_empty() {
                let indices = b.indices_accessor(&triangles);
                looks
                    .primitives
                    .push((mesh, primitive(attributes, indices, 0)));
            }
        }
        return looks;
    };
    // Material slots in order: the user's, then the skin for triangles without one; within
    // each mesh of the split.
    let skin_slot = user.materials.len();
    let mut groups: Vec<Vec<Vec<[u32; 3]>>> = vec![vec![vec![]; skin_slot + 1]; meshes];
    for (t, (tri, m)) in layout.triangles.iter().zip(per_triangle).enumerate() {
        groups[mesh_of(t).min(meshes - 1)][m.map_or(skin_slot, |m| m as usize)].push(*tri);
    }
    let mut material_of_slot: Vec<Option<usize>> = vec![None; skin_slot + 1];
    for (mesh, slots) in groups.iter().enumerate() {
        for (slot, triangles) in slots.iter().enumerate() {
            if triangles.is_empty() {
                continue;
            }
            let material = match material_of_slot[slot] {
                Some(m) => m,
                None => {
                    let json = match user.materials.get(slot) {
                        Some(m) => user_material(b, m, layout.uvs.is_some(), &mut looks),
                        None => skin(),
                    };
                    looks.materials.push(json);
                    material_of_slot[slot] = Some(looks.materials.len() - 1);
                    looks.materials.len() - 1
                }
            };
            let indices = b.indices_accessor(triangles);
            looks
                .primitives
                .push((mesh, primitive(attributes, indices, material)));
        }
    }
    looks
}

/// A triangle-list primitive.
fn primitive(attributes: &Value, indices: usize, material: usize) -> Value {
    json!({ "attributes": attributes, "indices": indices, "material": material, "mode": 4 })
}

/// [`super::MATERIAL_NAME`]: skin-coloured PBR, metalness 0, double-sided.
fn skin() -> Value {
    json!({
        "name": super::MATERIAL_NAME,
        "pbrMetallicRoughness": {
            "baseColorFactor": SKIN_LINEAR_RGBA,
            "metallicFactor": 0.0,
            "roughnessFactor": 0.6,
        },
        "doubleSided": true,
    })
}

/// The user's material: its texture (embedded) as the base colour, else its `Kd`.
fn user_material(b: &mut Builder, m: &UserMaterial, has_uvs: bool, looks: &mut Looks) -> Value {
    let mut pbr = json!({ "metallicFactor": 0.0, "roughnessFactor": 0.6 });
    match &m.texture {
        Some(t) if has_uvs => {
            let view = b.image_view(&t.bytes);
            looks
                .images
                .push(json!({ "bufferView": view, "mimeType": t.mime }));
            looks
                .textures
                .push(json!({ "source": looks.images.len() - 1 }));
            // The texture is the colour (OBJ writers put a grey Kd beside it, which glTF
            // would multiply in).
            pbr["baseColorTexture"] = json!({ "index": looks.textures.len() - 1 });
        }
        Some(_) => {
            looks.warnings.push(format!(
                "material {:?} has a texture but the OBJ has no texture coordinates: its colour is used",
                m.name
            ));
            pbr["baseColorFactor"] =
                json!([m.base_color[0], m.base_color[1], m.base_color[2], 1.0]);
        }
        None => {
            pbr["baseColorFactor"] =
                json!([m.base_color[0], m.base_color[1], m.base_color[2], 1.0]);
        }
    }
    json!({ "name": m.name, "pbrMetallicRoughness": pbr, "doubleSided": true })
}

/// Base colour of [`super::MATERIAL_NAME`]: a light skin tone, sRGB (224, 172, 150) in linear
/// RGB.
const SKIN_LINEAR_RGBA: [f32; 4] = [0.745, 0.412, 0.305, 1.0];
