//! The validated, welded input face mesh and its loaders (OBJ through tobj, glTF/GLB through gltf).

use crate::error::PrepError;
use crate::topology;
use glam::{DMat4, DVec3};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::BufRead;
use std::path::Path;

/// One front-face triangle mesh in the user's INPUT frame: welded (coincident positions merged),
/// triangulated, unused vertices dropped, and validated (one connected, edge-manifold,
/// consistently wound surface with exactly four boundary loops).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaceMesh {
    /// Welded vertex positions, input frame, in order of first appearance in the input.
    pub vertices: Vec<DVec3>,
    /// Triangles indexing [`FaceMesh::vertices`], counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// For every input position (OBJ `v` line order, or glTF POSITION accessor order concatenated
    /// over the mesh's primitives) the welded vertex it became, or `None` if no face used it.
    /// Exports use this to write poses in the user's own vertex order.
    pub input_to_vertex: Vec<Option<u32>>,
}

/// Bit pattern of a position, with −0.0 folded onto +0.0, for exact welding.
fn weld_key(p: DVec3) -> [u64; 3] {
    p.to_array()
        .map(|c| if c == 0.0 { 0u64 } else { c.to_bits() })
}

struct Welded {
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    by_key: HashMap<[u64; 3], u32>,
}

/// Merges bit-identical positions among those used by `triangles` and drops unused ones.
fn weld(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<Welded, PrepError> {
    let mut used = vec![false; positions.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &i in tri {
            match used.get_mut(i as usize) {
                Some(u) => *u = true,
                None => {
                    return Err(PrepError::IndexOutOfRange {
                        triangle: t,
                        index: i,
                        vertex_count: positions.len(),
                    });
                }
            }
        }
    }
    let mut by_key = HashMap::new();
    let mut vertices = Vec::new();
    let mut remap = vec![u32::MAX; positions.len()];
    for (i, &p) in positions.iter().enumerate() {
        if !used[i] {
            continue;
        }
        if !p.is_finite() {
            return Err(PrepError::NonFiniteVertex {
                input_index: i,
                position: p.to_array(),
            });
        }
        let id = *by_key.entry(weld_key(p)).or_insert_with(|| {
            vertices.push(p);
            (vertices.len() - 1) as u32
        });
        remap[i] = id;
    }
    let triangles = triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .collect();
    Ok(Welded {
        vertices,
        triangles,
        by_key,
    })
}

impl FaceMesh {
    /// Builds a face mesh from raw positions and triangles (indices into `positions`), welding
    /// coincident positions, dropping unused ones and validating the result.
    ///
    /// ```
    /// use face_prep::{FaceMesh, PrepError};
    /// use glam::DVec3;
    /// // A single triangle has one boundary loop, not four.
    /// let err = FaceMesh::from_triangles(&[DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]]);
    /// assert!(matches!(err, Err(PrepError::WrongLoopCount { count: 1, .. })));
    /// ```
    pub fn from_triangles(
        positions: &[DVec3],
        triangles: &[[u32; 3]],
    ) -> Result<FaceMesh, PrepError> {
        let w = weld(positions, triangles)?;
        let input_to_vertex = positions
            .iter()
            .map(|&p| w.by_key.get(&weld_key(p)).copied())
            .collect();
        FaceMesh::validated(w.vertices, w.triangles, input_to_vertex)
    }

    fn validated(
        vertices: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        input_to_vertex: Vec<Option<u32>>,
    ) -> Result<FaceMesh, PrepError> {
        let loops = topology::validate(&vertices, &triangles)?;
        topology::check_four_loops(&vertices, &loops)?;
        Ok(FaceMesh {
            vertices,
            triangles,
            input_to_vertex,
        })
    }

    /// Parses OBJ text (tobj, multi-index mode so seams are not split, n-gons fan-triangulated),
    /// welds, validates.
    ///
    /// ```
    /// let obj = std::fs::read_to_string(concat!(
    ///     env!("CARGO_MANIFEST_DIR"),
    ///     "/../../assets/mediapipe_canonical_4loop.obj"
    /// ))
    /// .unwrap();
    /// let face = face_prep::FaceMesh::from_obj_str(&obj).unwrap();
    /// assert_eq!((face.vertices.len(), face.triangles.len()), (468, 852));
    /// ```
    pub fn from_obj_str(text: &str) -> Result<FaceMesh, PrepError> {
        FaceMesh::from_obj_reader(&mut text.as_bytes())
    }

    /// Like [`FaceMesh::from_obj_str`], from a buffered reader.
    pub fn from_obj_reader(reader: &mut impl BufRead) -> Result<FaceMesh, PrepError> {
        let mut bytes = Vec::new();
        reader.read_to_end(&mut bytes).map_err(|e| PrepError::Io {
            path: "<reader>".into(),
            source: e,
        })?;
        let text = String::from_utf8_lossy(&bytes);
        let options = tobj::LoadOptions {
            single_index: false,
            triangulate: true,
            ignore_points: true,
            ignore_lines: true,
        };
        let (models, _materials) =
            tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| Ok(Default::default()))
                .map_err(|e| PrepError::Obj {
                    reason: e.to_string(),
                })?;
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for m in &models {
            let base = (positions.len()) as u32;
            positions.extend(
                m.mesh
                    .positions
                    .chunks_exact(3)
                    .map(|c| DVec3::new(c[0], c[1], c[2])),
            );
            triangles.extend(
                m.mesh
                    .indices
                    .chunks_exact(3)
                    .map(|c| [c[0] + base, c[1] + base, c[2] + base]),
            );
        }
        // NaN check in file order so the message names the `v` line's index.
        let file_positions = scan_obj_positions(&text);
        for (i, p) in file_positions.iter().enumerate() {
            if !p.is_finite() {
                return Err(PrepError::NonFiniteVertex {
                    input_index: i,
                    position: p.to_array(),
                });
            }
        }
        let w = weld(&positions, &triangles)?;
        let input_to_vertex = file_positions
            .iter()
            .map(|&p| w.by_key.get(&weld_key(p)).copied())
            .collect();
        FaceMesh::validated(w.vertices, w.triangles, input_to_vertex)
    }

    /// Loads the first mesh of a glTF/GLB document given as bytes (`.glb` or self-contained
    /// `.gltf` with data URIs), or the mesh named `mesh_name`. The transforms of the first node
    /// that instantiates the mesh (in scene order) are applied.
    pub fn from_gltf_slice(bytes: &[u8], mesh_name: Option<&str>) -> Result<FaceMesh, PrepError> {
        gltf_mesh(bytes, None, mesh_name)
    }
}

/// Positions of the `v` lines of an OBJ text in file order, parsed as tobj does (f64, optional
/// w divides). Lines tobj would reject never reach this function's caller.
fn scan_obj_positions(text: &str) -> Vec<DVec3> {
    let mut out = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        if words.next() != Some("v") {
            continue;
        }
        let nums: Vec<f64> = words.map_while(|w| w.parse::<f64>().ok()).collect();
        if nums.len() < 3 {
            continue;
        }
        let mut p = DVec3::new(nums[0], nums[1], nums[2]);
        if nums.len() == 4 && nums[3] != 0.0 {
            p /= nums[3];
        }
        out.push(p);
    }
    out
}

fn gltf_mesh(
    bytes: &[u8],
    base: Option<&Path>,
    mesh_name: Option<&str>,
) -> Result<FaceMesh, PrepError> {
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice(bytes)?;
    let buffers = gltf::import_buffers(&document, base, blob)?;
    let label = |m: &gltf::Mesh| {
        m.name()
            .map(str::to_owned)
            .unwrap_or_else(|| format!("#{}", m.index()))
    };
    let mesh = match mesh_name {
        None => document.meshes().next().ok_or(PrepError::GltfNoMesh)?,
        Some(name) => document
            .meshes()
            .find(|m| m.name() == Some(name))
            .ok_or_else(|| PrepError::GltfMeshNotFound {
                name: name.to_owned(),
                available: document.meshes().map(|m| label(&m)).collect(),
            })?,
    };
    let world = mesh_world_transform(&document, mesh.index()).unwrap_or(DMat4::IDENTITY);
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (pi, prim) in mesh.primitives().enumerate() {
        let err = |reason: &str| PrepError::GltfPrimitive {
            mesh: label(&mesh),
            primitive: pi,
            reason: reason.to_owned(),
        };
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let base = positions.len() as u32;
        let pos: Vec<DVec3> = reader
            .read_positions()
            .ok_or_else(|| err("no POSITION attribute"))?
            .map(|p| world.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)))
            .collect();
        let n = pos.len() as u32;
        positions.extend(pos);
        let idx: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..n).collect(),
        };
        use gltf::mesh::Mode;
        let tris: Vec<[u32; 3]> = match prim.mode() {
            Mode::Triangles => idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            Mode::TriangleStrip => (2..idx.len())
                .map(|k| {
                    if k % 2 == 0 {
                        [idx[k - 2], idx[k - 1], idx[k]]
                    } else {
                        [idx[k - 1], idx[k - 2], idx[k]]
                    }
                })
                .collect(),
            Mode::TriangleFan => (2..idx.len())
                .map(|k| [idx[0], idx[k - 1], idx[k]])
                .collect(),
            other => return Err(err(&format!("mode {other:?} is not a triangle mode"))),
        };
        for t in tris {
            if t.iter().any(|&i| i >= n) {
                return Err(err("index beyond the POSITION accessor"));
            }
            triangles.push(t.map(|i| i + base));
        }
    }
    if world.determinant() < 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    FaceMesh::from_triangles(&positions, &triangles)
}

/// World transform of the first node (depth-first over the scenes, default scene first) that
/// instantiates mesh `mesh_index`.
fn mesh_world_transform(document: &gltf::Document, mesh_index: usize) -> Option<DMat4> {
    fn visit(node: gltf::Node, parent: DMat4, mesh_index: usize) -> Option<DMat4> {
        let local =
            DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(|x| x as f64)));
        let world = parent * local;
        if node.mesh().map(|m| m.index()) == Some(mesh_index) {
            return Some(world);
        }
        node.children().find_map(|c| visit(c, world, mesh_index))
    }
    let scenes = document
        .default_scene()
        .into_iter()
        .chain(document.scenes());
    for scene in scenes {
        if let Some(m) = scene
            .nodes()
            .find_map(|n| visit(n, DMat4::IDENTITY, mesh_index))
        {
            return Some(m);
        }
    }
    None
}

/// Loads a face mesh, dispatching on the extension: `.obj` (tobj), `.gltf` or `.glb` (gltf,
/// first mesh). See [`load_face_mesh_named`] to pick a glTF mesh by name.
///
/// ```
/// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
///     .join("../../assets/mediapipe_canonical_4loop.obj");
/// let face = face_prep::load_face(&path).unwrap();
/// assert_eq!(face.triangles.len(), 852);
/// ```
pub fn load_face(path: &Path) -> Result<FaceMesh, PrepError> {
    load_face_mesh_named(path, None)
}

/// Like [`load_face`]; for glTF/GLB, `mesh_name` selects the mesh (ignored for OBJ).
pub fn load_face_mesh_named(path: &Path, mesh_name: Option<&str>) -> Result<FaceMesh, PrepError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let read = || {
        std::fs::read(path).map_err(|e| PrepError::Io {
            path: path.to_owned(),
            source: e,
        })
    };
    match ext.as_str() {
        "obj" => FaceMesh::from_obj_reader(&mut &read()?[..]),
        "gltf" | "glb" => gltf_mesh(&read()?, path.parent(), mesh_name),
        _ => Err(PrepError::UnsupportedExtension {
            path: path.to_owned(),
            extension: ext,
        }),
    }
}
