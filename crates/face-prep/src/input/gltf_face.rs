//! A glTF / GLB mesh's vertices and triangles as the file has them (before welding): node
//! transforms applied, strips and fans expanded, a `POSITION` accessor that primitives share
//! read once.

use crate::error::PrepError;
use crate::input::gltf_read::{self, Document};
use crate::input::limits::{InputLimits, check_coordinates};
use glam::{DMat4, DVec3};
use std::path::Path;

/// The vertices of a glTF face mesh as the file has them (before welding): the primitives'
/// POSITION accessors (world frame: the node transforms applied) in order, a shared one once,
/// the triangles indexing them, and TEXCOORD_0 and NORMAL where the file has them.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfFaceData {
    /// Positions, world frame: each primitive's `POSITION` accessor in order, an accessor that
    /// primitives share once (with the first of them's texture coordinates and normals).
    pub positions: Vec<DVec3>,
    /// Triangles indexing [`GltfFaceData::positions`] (strips and fans expanded; wound
    /// counter-clockwise in the world frame).
    pub triangles: Vec<[u32; 3]>,
    /// TEXCOORD_0 per position (glTF convention), if any primitive has it (zeros elsewhere).
    pub uvs: Option<Vec<[f32; 2]>>,
    /// Unit NORMAL per position (world frame), if any primitive has it (`None` elsewhere).
    pub normals: Option<Vec<Option<DVec3>>>,
    /// Per triangle: the glTF material of its primitive ([`crate::gltf_read::material_looks`]).
    pub triangle_material: Vec<Option<u32>>,
}

/// Reads the first mesh of a glTF/GLB document (or the mesh named `mesh_name`) as the file has
/// it, within `limits`; [`crate::FaceMesh::from_gltf_bytes`] welds and validates the same data.
pub fn gltf_face_data(
    bytes: &[u8],
    base: Option<&Path>,
    mesh_name: Option<&str>,
    limits: &InputLimits,
) -> Result<GltfFaceData, PrepError> {
    let mut doc = Document::parse(bytes, base, limits)?;
    let labels = gltf_read::mesh_labels(&doc.root);
    let mesh = select_mesh(&doc, &labels, mesh_name)?;
    gltf_mesh_data(&mut doc, &labels, mesh, limits)
}

/// [`gltf_face_data`] of mesh number `mesh` of a parsed document (`labels`: its meshes' labels).
pub(crate) fn gltf_mesh_data(
    doc: &mut Document,
    labels: &[String],
    mesh: usize,
    limits: &InputLimits,
) -> Result<GltfFaceData, PrepError> {
    let world = doc.mesh_world_transform(mesh)?.unwrap_or(DMat4::IDENTITY);
    let mut vertices = Vertices::default();
    // (POSITION accessor, its first vertex, its count), each accessor read once.
    let mut read: Vec<(usize, u32, u32)> = Vec::new();
    let mut triangles = Vec::new();
    let mut triangle_material = Vec::new();
    for (pi, (pos, indices, mode)) in gltf_read::primitives(&doc.root, mesh)
        .into_iter()
        .enumerate()
    {
        let err = |reason: &str| PrepError::GltfPrimitive {
            mesh: labels.get(mesh).cloned().unwrap_or_default(),
            primitive: pi,
            reason: reason.to_owned(),
        };
        let pos = pos.ok_or_else(|| err("no POSITION attribute"))?;
        // Primitives sharing a POSITION accessor share its vertices: read it once (one file
        // with 14 primitives over one accessor was 14 copies of every vertex).
        let (base, n) = match read.iter().find(|r| r.0 == pos) {
            Some(&(_, base, n)) => (base, n),
            None => {
                let base = vertices.positions.len() as u32;
                let n = read_positions(doc, (mesh, pi, pos), world, limits, &mut vertices)?;
                read.push((pos, base, n));
                (base, n)
            }
        };
        let idx: Vec<u32> = match indices {
            Some(i) => doc.read_indices(i)?,
            None => (0..n).collect(),
        };
        let tris = primitive_triangles(&idx, mode, err)?;
        limits.check_count(
            "triangles",
            (triangles.len() + tris.len()) as u64,
            limits.max_triangles,
        )?;
        for t in tris {
            if let Some(&i) = t.iter().find(|&&i| i >= n) {
                return Err(err(&format!(
                    "index {i} is beyond the POSITION accessor's {n} elements"
                )));
            }
            triangles.push(t.map(|i| i + base));
        }
        let material = (doc.root.meshes.get(mesh))
            .and_then(|m| m.primitives.get(pi)?.material)
            .map(|m| m.value() as u32);
        triangle_material.resize(triangles.len(), material);
    }
    let Vertices {
        positions,
        uvs,
        normals,
    } = vertices;
    if world.determinant() < 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    Ok(GltfFaceData {
        positions,
        triangles,
        uvs: uvs
            .iter()
            .any(Option::is_some)
            .then(|| uvs.iter().map(|t| t.unwrap_or([0.0; 2])).collect()),
        normals: normals.iter().any(Option::is_some).then_some(normals),
        triangle_material,
    })
}

/// The vertex attributes of [`GltfFaceData`] being gathered.
#[derive(Default)]
struct Vertices {
    positions: Vec<DVec3>,
    uvs: Vec<Option<[f32; 2]>>,
    normals: Vec<Option<DVec3>>,
}

/// Appends primitive `pi` of `mesh`'s vertices (its POSITION accessor `pos`, TEXCOORD_0 and
/// NORMAL) in the world frame to `out`; their count.
fn read_positions(
    doc: &mut Document,
    (mesh, pi, pos): (usize, usize, usize),
    world: DMat4,
    limits: &InputLimits,
    out: &mut Vertices,
) -> Result<u32, PrepError> {
    let normal_matrix = glam::DMat3::from_mat4(world).inverse().transpose();
    let (positions, uvs, normals) = (&mut out.positions, &mut out.uvs, &mut out.normals);
    let pos: Vec<DVec3> = doc
        .read_vec3(pos, "POSITION")?
        .into_iter()
        .map(|p| world.transform_point3(p))
        .collect();
    // Every position, used or not (the exports write them all), in the world frame.
    for (i, p) in pos.iter().enumerate() {
        check_coordinates(positions.len() + i, *p)?;
    }
    let n = pos.len() as u32;
    limits.check_count(
        "positions",
        (positions.len() + pos.len()) as u64,
        limits.max_positions,
    )?;
    use gltf::json::mesh::Semantic;
    let end = positions.len() + pos.len();
    if let Some(a) = gltf_read::attribute(&doc.root, mesh, pi, Semantic::TexCoords(0)) {
        uvs.extend(doc.read_texcoords(a)?.into_iter().map(Some));
    }
    uvs.resize(end, None);
    if let Some(a) = gltf_read::attribute(&doc.root, mesh, pi, Semantic::Normals) {
        let read = doc.read_vec3(a, "NORMAL")?;
        normals.extend(
            read.into_iter()
                .map(|n| (normal_matrix * n).try_normalize()),
        );
    }
    normals.resize(end, None);
    positions.extend(pos);
    Ok(n)
}

/// Index of the mesh named `mesh_name` (the first mesh without a name); `labels` are the
/// meshes' labels ([`gltf_read::mesh_labels`]).
fn select_mesh(
    doc: &Document,
    labels: &[String],
    mesh_name: Option<&str>,
) -> Result<usize, PrepError> {
    Ok(match mesh_name {
        None if labels.is_empty() => return Err(PrepError::GltfNoMesh),
        None => 0,
        Some(name) => doc
            .root
            .meshes
            .iter()
            .position(|m| m.name.as_deref() == Some(name))
            .ok_or_else(|| PrepError::GltfMeshNotFound {
                name: name.to_owned(),
                available: labels.to_vec(),
            })?,
    })
}

/// The triangles of a primitive of mode `mode` over the indices `idx` (a list, strip or fan);
/// any other mode is an error (`err`).
fn primitive_triangles(
    idx: &[u32],
    mode: gltf::json::validation::Checked<gltf::json::mesh::Mode>,
    err: impl Fn(&str) -> PrepError,
) -> Result<Vec<[u32; 3]>, PrepError> {
    use gltf::json::mesh::Mode;
    use gltf::json::validation::Checked;
    Ok(match mode {
        Checked::Valid(Mode::Triangles) => {
            idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
        }
        Checked::Valid(Mode::TriangleStrip) => (2..idx.len())
            .map(|k| {
                if k % 2 == 0 {
                    [idx[k - 2], idx[k - 1], idx[k]]
                } else {
                    [idx[k - 1], idx[k - 2], idx[k]]
                }
            })
            .collect(),
        Checked::Valid(Mode::TriangleFan) => (2..idx.len())
            .map(|k| [idx[0], idx[k - 1], idx[k]])
            .collect(),
        Checked::Valid(other) => {
            return Err(err(&format!("mode {other:?} is not a triangle mode")));
        }
        Checked::Invalid => return Err(err("invalid mode")),
    })
}
