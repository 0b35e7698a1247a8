//! A whole file as it is (issue 32, item 1): every position and every polygon of an OBJ (with
//! its `o` / `g` / `usemtl` names), or of every mesh and primitive of a glTF / GLB / VRM (in the
//! world frame of its node), with a map from every vertex to where it came from; and its
//! connected components.

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;

use crate::error::PrepError;
use crate::input::gltf_face::gltf_mesh_data;
use crate::input::gltf_read::{self, Document};
use crate::input::limits::{InputLimits, read_input_file};
use crate::input::obj_text;

/// Where a vertex of a [`Scene`] comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexSource {
    /// The OBJ's `v` line number `index` (0-based, in file order).
    Obj {
        /// 0-based index among the `v` lines.
        index: u32,
    },
    /// Position `vertex` of glTF mesh `mesh` (its primitives' POSITION accessors in order, a
    /// shared one once, as [`crate::gltf_face_data`] reads them).
    Gltf {
        /// The mesh.
        mesh: u32,
        /// The position within the mesh.
        vertex: u32,
    },
}

/// Every vertex and triangle of a file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// Positions (OBJ: as written; glTF: world frame).
    pub positions: Vec<DVec3>,
    /// Where each position comes from.
    pub sources: Vec<VertexSource>,
    /// Triangles (polygons fan-triangulated), indexing [`Scene::positions`].
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle, an index into [`Scene::labels`].
    pub triangle_label: Vec<u32>,
    /// The names the file gives its polygons: OBJ `group/material` (or the one that is given),
    /// glTF `mesh/#material`.
    pub labels: Vec<String>,
    /// glTF only: where each mesh's vertices are ([`GltfMeshPlacement`]), by mesh index.
    pub gltf_meshes: Vec<GltfMeshPlacement>,
    /// glTF only: per position, the file's unit `NORMAL` turned into the world frame (`None`
    /// where its primitive has none, or the normal is zero); empty for an OBJ.
    pub normals: Vec<Option<DVec3>>,
}

/// Where a glTF mesh's vertices are in a [`Scene`], and the transform they were read with.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfMeshPlacement {
    /// The world transform of the first node instantiating the mesh (identity if none).
    pub world_from_mesh: glam::DMat4,
    /// Per primitive, in order: its first scene vertex, its vertex count and its `POSITION`
    /// accessor (primitives sharing an accessor share its scene vertices).
    pub primitives: Vec<PrimitivePlacement>,
    /// Its triangles in [`Scene::triangles`] (meshes sharing an accessor share vertices, not
    /// triangles).
    pub triangles: std::ops::Range<u32>,
}

/// One primitive's vertices in a [`Scene`] ([`GltfMeshPlacement`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrimitivePlacement {
    /// The scene index of its first vertex.
    pub first: u32,
    /// How many vertices it has (its `POSITION` accessor's count).
    pub count: u32,
    /// Its `POSITION` accessor (primitives may share one).
    pub position_accessor: u32,
}

/// A connected component of a [`Scene`]: triangles joined through shared vertices (the same
/// index, or boundary vertices at exactly the same coordinates: UV seams duplicate positions).
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    /// Its triangles (indices into [`Scene::triangles`]).
    pub triangles: Vec<u32>,
    /// Its vertices (indices into [`Scene::positions`]), sorted.
    pub vertices: Vec<u32>,
}

impl Scene {
    /// Reads a face or head file: OBJ, or glTF / GLB / VRM, within `limits`.
    pub fn read(path: &Path, limits: &InputLimits) -> Result<Scene, PrepError> {
        let bytes = read_input_file(path, limits)?;
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Scene::from_obj(&String::from_utf8_lossy(&bytes), limits),
            "gltf" | "glb" | "vrm" => {
                let folder = match path.parent() {
                    Some(f) if !f.as_os_str().is_empty() => f,
                    _ => Path::new("."),
                };
                Scene::from_gltf(&bytes, Some(folder), limits)
            }
            _ => Err(PrepError::UnsupportedExtension {
                path: path.to_path_buf(),
                extension: ext,
            }),
        }
    }

    /// Reads an OBJ text: every `v` line, every `f` line (labelled with the `o` or `g` and
    /// `usemtl` names before it).
    ///
    /// ```
    /// use face_prep::parts::Scene;
    /// let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 6 5 5\nv 5 6 5\n\
    ///            g skin\nusemtl face\nf 1 2 3\ng eye\nf 4 5 6\n";
    /// let s = Scene::from_obj(obj, &Default::default()).unwrap();
    /// assert_eq!(s.labels, ["skin/face", "eye/face"]);
    /// assert_eq!(s.components().len(), 2);
    /// ```
    pub fn from_obj(text: &str, limits: &InputLimits) -> Result<Scene, PrepError> {
        let parsed = obj_text::parse(text).map_err(PrepError::from)?;
        limits.check_count(
            "positions",
            parsed.positions.len() as u64,
            limits.max_positions,
        )?;
        let mut label_of_line: HashMap<usize, String> = HashMap::new();
        let (mut group, mut material) = (String::new(), String::new());
        for (i, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            let rest = || {
                line.split_whitespace()
                    .skip(1)
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            match words.next() {
                Some("o" | "g") => group = rest(),
                Some("usemtl") => material = rest(),
                Some("f") => {
                    let label = match (group.is_empty(), material.is_empty()) {
                        (false, false) => format!("{group}/{material}"),
                        _ => format!("{group}{material}"),
                    };
                    label_of_line.insert(i + 1, label);
                }
                _ => {}
            }
        }
        let mut scene = Scene {
            sources: (0..parsed.positions.len() as u32)
                .map(|index| VertexSource::Obj { index })
                .collect(),
            positions: parsed.positions,
            ..Scene::default()
        };
        let mut label_index: HashMap<String, u32> = HashMap::new();
        for face in &parsed.faces {
            let label = label_of_line.get(&face.line).cloned().unwrap_or_default();
            let c: Vec<u32> = face.corners.iter().map(|c| c.v as u32).collect();
            for k in 2..c.len() {
                scene.push_triangle([c[0], c[k - 1], c[k]], &label, &mut label_index);
            }
            scene.check_triangles(limits)?;
        }
        Ok(scene)
    }

    /// Reads every mesh of a glTF / GLB document (each in the world frame of the first node
    /// that instantiates it), labelled `mesh/material`.
    pub fn from_gltf(
        bytes: &[u8],
        base: Option<&Path>,
        limits: &InputLimits,
    ) -> Result<Scene, PrepError> {
        let mut doc = Document::parse(bytes, base, limits)?;
        let mesh_labels = gltf_read::mesh_labels(&doc.root);
        let mut scene = Scene::default();
        let mut label_index: HashMap<String, u32> = HashMap::new();
        // One scene vertex per POSITION accessor and world transform: primitives and meshes
        // that share an accessor under the same transform share its vertices (a file of 13
        // primitives over one accessor read as 13 copies of every vertex).
        let mut placed: HashMap<(u32, [u64; 16]), u32> = HashMap::new();
        for mesh in 0..mesh_labels.len() {
            let data = gltf_mesh_data(&mut doc, &mesh_labels, mesh, limits)?;
            let world_from_mesh = doc
                .mesh_world_transform(mesh)?
                .unwrap_or(glam::DMat4::IDENTITY);
            let world_bits = world_from_mesh.to_cols_array().map(|c| (c + 0.0).to_bits());
            let mut placement = GltfMeshPlacement {
                world_from_mesh,
                primitives: Vec::new(),
                triangles: 0..0,
            };
            // The mesh's vertices as `gltf_mesh_data` lays them out (each accessor once, in
            // order), and where each goes in the scene.
            let mut to_scene = vec![0u32; data.positions.len()];
            let mut local_first = 0u32;
            for (pos, _, _) in gltf_read::primitives(&doc.root, mesh) {
                let Some(pos) = pos else { continue };
                let position_accessor = pos as u32;
                if let Some(p) = placement
                    .primitives
                    .iter()
                    .find(|p| p.position_accessor == position_accessor)
                    .copied()
                {
                    placement.primitives.push(p);
                    continue;
                }
                let count = doc.root.accessors.get(pos).map_or(0, |a| a.count.0 as u32);
                let local = local_first as usize..(local_first + count) as usize;
                let Some(positions) = data.positions.get(local.clone()) else {
                    return Err(PrepError::GltfPrimitive {
                        mesh: mesh_labels[mesh].clone(),
                        primitive: placement.primitives.len(),
                        reason: "POSITION count differs from the accessor's".into(),
                    });
                };
                let first = *placed
                    .entry((position_accessor, world_bits))
                    .or_insert_with(|| {
                        let first = scene.positions.len() as u32;
                        scene.positions.extend(positions);
                        scene.normals.extend(local.clone().map(|v| {
                            data.normals
                                .as_ref()
                                .and_then(|n| n.get(v).copied().flatten())
                        }));
                        scene
                            .sources
                            .extend(local.clone().map(|v| VertexSource::Gltf {
                                mesh: mesh as u32,
                                vertex: v as u32,
                            }));
                        first
                    });
                limits.check_count(
                    "positions",
                    scene.positions.len() as u64,
                    limits.max_positions,
                )?;
                for (k, v) in local.enumerate() {
                    to_scene[v] = first + k as u32;
                }
                placement.primitives.push(PrimitivePlacement {
                    first,
                    count,
                    position_accessor,
                });
                local_first += count;
            }
            let first_triangle = scene.triangles.len() as u32;
            for (t, m) in data.triangles.iter().zip(&data.triangle_material) {
                let material = m.map_or_else(String::new, |m| format!("#{m}"));
                let label = format!("{}/{material}", mesh_labels[mesh]);
                let t = t.map(|i| to_scene.get(i as usize).copied().unwrap_or(0));
                scene.push_triangle(t, &label, &mut label_index);
            }
            scene.check_triangles(limits)?;
            placement.triangles = first_triangle..scene.triangles.len() as u32;
            scene.gltf_meshes.push(placement);
        }
        Ok(scene)
    }

    /// For every vertex, the first vertex at exactly the same coordinates (itself when it is
    /// the first): the copies a glTF's UV seams or split normals make are one point of the
    /// surface.
    ///
    /// ```
    /// use face_prep::parts::Scene;
    /// let s = Scene::from_obj("v 0 0 0\nv 1 0 0\nv 0 0 0\n", &Default::default()).unwrap();
    /// assert_eq!(s.first_at_same_place(), [0, 1, 0]);
    /// ```
    pub fn first_at_same_place(&self) -> Vec<u32> {
        let mut first_at: HashMap<[u64; 3], u32> = HashMap::new();
        self.positions
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let key = p.to_array().map(|c| (c + 0.0).to_bits());
                *first_at.entry(key).or_insert(i as u32)
            })
            .collect()
    }

    /// Appends a triangle with its label (interned in `index`).
    fn push_triangle(&mut self, t: [u32; 3], label: &str, index: &mut HashMap<String, u32>) {
        let next = index.len() as u32;
        let l = *index.entry(label.to_owned()).or_insert_with(|| {
            self.labels.push(label.to_owned());
            next
        });
        self.triangles.push(t);
        self.triangle_label.push(l);
    }

    fn check_triangles(&self, limits: &InputLimits) -> Result<(), PrepError> {
        let n = self.triangles.len() as u64;
        limits.check_count("triangles", n, limits.max_triangles)
    }

    /// The connected components, largest (most triangles) first; ties in file order.
    pub fn components(&self) -> Vec<Component> {
        let n = self.positions.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn find(parent: &mut [u32], mut a: u32) -> u32 {
            while parent[a as usize] != a {
                let up = parent[parent[a as usize] as usize];
                parent[a as usize] = up;
                a = up;
            }
            a
        }
        let union = |parent: &mut Vec<u32>, a: u32, b: u32| {
            let (ra, rb) = (find(parent, a), find(parent, b));
            if ra != rb {
                parent[ra.max(rb) as usize] = ra.min(rb);
            }
        };
        // A cut surface (a UV seam's duplicated positions) is glued back: boundary vertices at
        // exactly the same coordinates join. A boundary vertex on another surface's interior
        // (a tear film's edge laid on the lid) does not.
        let mut edge_uses: HashMap<(u32, u32), u32> = HashMap::new();
        for t in self
            .triangles
            .iter()
            .filter(|t| t.iter().all(|&v| (v as usize) < n))
        {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edge_uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let mut on_border = vec![false; n];
        for (&(a, b), &uses) in &edge_uses {
            if uses == 1 {
                on_border[a as usize] = true;
                on_border[b as usize] = true;
            }
        }
        let mut first_at: HashMap<[u64; 3], u32> = HashMap::new();
        for (i, p) in self.positions.iter().enumerate() {
            if on_border[i] {
                let key = p.to_array().map(|c| (c + 0.0).to_bits());
                let first = *first_at.entry(key).or_insert(i as u32);
                union(&mut parent, first, i as u32);
            }
        }
        for t in &self.triangles {
            if t.iter().all(|&v| (v as usize) < n) {
                union(&mut parent, t[0], t[1]);
                union(&mut parent, t[0], t[2]);
            }
        }
        let mut by_root: HashMap<u32, usize> = HashMap::new();
        let mut out: Vec<Component> = Vec::new();
        for (ti, t) in self.triangles.iter().enumerate() {
            let Some(&v) = t.first().filter(|&&v| (v as usize) < n) else {
                continue;
            };
            let root = find(&mut parent, v);
            let k = *by_root.entry(root).or_insert_with(|| {
                out.push(Component {
                    triangles: Vec::new(),
                    vertices: Vec::new(),
                });
                out.len() - 1
            });
            out[k].triangles.push(ti as u32);
            out[k]
                .vertices
                .extend(t.iter().filter(|&&v| (v as usize) < n));
        }
        for c in &mut out {
            c.vertices.sort_unstable();
            c.vertices.dedup();
        }
        out.sort_by_key(|c| std::cmp::Reverse(c.triangles.len()));
        out
    }
}
