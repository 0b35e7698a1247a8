//! The user's own GLB / VRM back with the morph targets added (issue 32, item 6).
//!
//! Everything of the input is kept: its JSON is edited in place (only `meshes[*].primitives
//! [*].targets`, `meshes[*].weights`, `meshes[*].extras.targetNames`, `buffers[0].byteLength`,
//! new `bufferViews` and `accessors` at the ends of their arrays, and for a VRM its
//! expressions' morph target binds), and the new data is appended to the binary chunk, so the
//! bytes of every accessor already there stay where they were, identical.
//!
//! - A mesh gets the targets when any of its vertices moves in any of them; every primitive
//!   of that mesh gets them all, after its own targets, in the same order. A target that does
//!   not move a primitive is an accessor without a buffer view (zeros, as glTF defines it);
//!   one that moves fewer than three quarters of its vertices is sparse.
//! - Deltas are written in the mesh's own frame: the world deltas of the rig times the inverse
//!   of the linear part of the transform the mesh was read with
//!   ([`face_prep::parts::GltfMeshPlacement`]). Primitives that share a `POSITION` accessor
//!   share each target's accessor too.
//! - VRM 1.0 (`VRMC_vrm`): each VRM expression's `morphTargetBinds` become the binds of the
//!   target of its name (or of the target it repeats) on every node that shows a moved mesh,
//!   weight 1. VRM 0.x (`VRM`): each `blendShapeMaster` group with the matching `presetName`
//!   (made when missing) binds the same targets, weight 100.

use glam::{DMat3, DQuat, DVec3};
use serde_json::{Map, Value, json};

use face_prep::parts::Scene;

/// Errors writing the user's glTF back.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum UserGltfError {
    /// The input is not a GLB this can extend.
    #[error("{0}")]
    Container(String),
    /// A mesh already has a morph target of a name being added.
    #[error("mesh {mesh} already has a morph target named {name:?}; rename or remove it first")]
    NameTaken {
        /// The mesh's index.
        mesh: usize,
        /// The name.
        name: String,
    },
    /// The scene does not fit the file (read from another file).
    #[error("the head read does not fit the file: {0}")]
    Mismatch(String),
    /// The file would pass glTF's 4 GiB limit.
    #[error("the GLB would be over 4 GiB")]
    TooLarge,
}

/// What was added ([`add_targets`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Added {
    /// The meshes that got the targets.
    pub meshes: Vec<usize>,
    /// The VRM expressions bound.
    pub vrm_expressions: Vec<String>,
}

/// VRM 1.0's expression names and VRM 0.x's preset names for them.
const VRM0_PRESETS: [(&str, &str); 18] = [
    ("happy", "joy"),
    ("angry", "angry"),
    ("sad", "sorrow"),
    ("relaxed", "fun"),
    ("surprised", "surprised"),
    ("aa", "a"),
    ("ih", "i"),
    ("ou", "u"),
    ("ee", "e"),
    ("oh", "o"),
    ("blink", "blink"),
    ("blinkLeft", "blink_l"),
    ("blinkRight", "blink_r"),
    ("lookUp", "lookup"),
    ("lookDown", "lookdown"),
    ("lookLeft", "lookleft"),
    ("lookRight", "lookright"),
    ("neutral", "neutral"),
];

/// `glb` (the bytes `scene` was read from) with `targets` — (name, world displacement of every
/// scene vertex at weight 1) — added to every mesh that moves; `same_as` names targets left out
/// as repeats of another (VRM binds follow them).
pub fn add_targets(
    glb: &[u8],
    scene: &Scene,
    targets: &[(String, Vec<DVec3>)],
    same_as: &[(String, String)],
) -> Result<(Vec<u8>, Added), UserGltfError> {
    let container = |e: face_prep::GltfError| UserGltfError::Container(e.to_string());
    if glb.get(0..4) != Some(b"glTF") {
        return Err(UserGltfError::Container(
            "only a GLB or VRM (binary glTF) is written back; save the .gltf as .glb".into(),
        ));
    }
    let (json_bytes, bin) = face_prep::gltf_read::split_glb(glb).map_err(container)?;
    let mut root: Value = serde_json::from_slice(json_bytes)
        .map_err(|e| UserGltfError::Container(format!("its JSON: {e}")))?;
    if root["buffers"][0].get("uri").is_some() {
        return Err(UserGltfError::Container(
            "its first buffer is an external file, not the GLB's own chunk".into(),
        ));
    }
    let mut bin = bin.map(<[u8]>::to_vec).unwrap_or_default();
    let n = scene.positions.len();
    if let Some((name, _)) = targets.iter().find(|(_, f)| f.len() != n) {
        return Err(UserGltfError::Mismatch(format!(
            "{name} has a wrong length"
        )));
    }
    let mut added = Added::default();
    // Normals on the surface, not the texture layout: UV seams' copies welded.
    let first = scene.first_at_same_place();
    let welded: Vec<[u32; 3]> = scene
        .triangles
        .iter()
        .map(|t| t.map(|v| first.get(v as usize).copied().unwrap_or(v)))
        .collect();
    let neutral_normals = crate::export::gltf::vertex_normals(&scene.positions, &welded);
    // One buffer view of zeros per vertex count, shared by every target that leaves an
    // accessor's vertices still (readers such as the `gltf` crate refuse an accessor without
    // a buffer view, which the specification allows).
    let mut zeros: std::collections::HashMap<u32, usize> = Default::default();
    // (mesh, index of our first target in it)
    let mut first_target: Vec<(usize, usize)> = Vec::new();
    for (mesh, placement) in scene.gltf_meshes.iter().enumerate() {
        let inverse = DMat3::from_mat4(placement.world_from_mesh).inverse();
        if !inverse.is_finite() {
            continue;
        }
        // The mesh's distinct POSITION accessors, each with the primitives that use it.
        let mut by_accessor: Vec<(u32, u32, Vec<std::ops::Range<usize>>)> = Vec::new();
        for p in &placement.primitives {
            let range = p.first as usize..(p.first + p.count) as usize;
            if range.end > n {
                return Err(UserGltfError::Mismatch(format!("mesh {mesh}'s vertices")));
            }
            match by_accessor.iter_mut().find(|a| a.0 == p.position_accessor) {
                Some(a) => a.2.push(range),
                None => by_accessor.push((p.position_accessor, p.count, vec![range])),
            }
        }
        // Only the vertices the mesh's own triangles use get its deltas (meshes may share an
        // accessor's vertices with other meshes).
        let mut used = vec![false; n];
        for t in scene
            .triangles
            .get(placement.triangles.start as usize..placement.triangles.end as usize)
            .unwrap_or_default()
        {
            for &v in t {
                if let Some(u) = used.get_mut(v as usize) {
                    *u = true;
                }
            }
        }
        let moves = targets.iter().any(|(_, field)| {
            by_accessor
                .iter()
                .flat_map(|a| a.2.iter())
                .any(|r| r.clone().any(|v| used[v] && field[v] != DVec3::ZERO))
        });
        if !moves {
            continue;
        }
        // One target and one accessor at a time (memory: one accessor's deltas): the local
        // deltas, the largest of the primitives' copies of each vertex.
        let mut accessors: Vec<(u32, Vec<Value>)> =
            by_accessor.iter().map(|a| (a.0, Vec::new())).collect();
        let mut normal_accessors: Vec<Vec<Value>> = vec![Vec::new(); by_accessor.len()];
        let with_normals = primitives_with_normals(&root, mesh);
        // Normals go from the world to the mesh's frame by the transpose of its linear part.
        let mesh_from_world_normal = DMat3::from_mat4(placement.world_from_mesh).transpose();
        // The file's own normals (as the scene read them), turned with the surface (its seams
        // and hard edges kept); zero where the file has none.
        let file: Vec<Option<Vec<DVec3>>> = by_accessor
            .iter()
            .map(|(_, _, ranges)| {
                let r = ranges.first()?;
                let own = scene.normals.get(r.clone())?;
                let to_mesh = |n: DVec3| (mesh_from_world_normal * n).normalize_or_zero();
                (with_normals && own.iter().any(Option::is_some))
                    .then(|| own.iter().map(|n| n.map_or(DVec3::ZERO, to_mesh)).collect())
            })
            .collect();
        for (_, field) in targets {
            let normals = with_normals.then(|| {
                let moved: Vec<DVec3> = scene
                    .positions
                    .iter()
                    .zip(field)
                    .map(|(p, d)| *p + *d)
                    .collect();
                crate::export::gltf::vertex_normals(&moved, &welded)
            });
            for (slot, (_, count, ranges)) in by_accessor.iter().enumerate() {
                if let Some(normals) = &normals {
                    let local = normal_deltas(
                        (&neutral_normals, normals),
                        file[slot].as_deref(),
                        &first,
                        (ranges, &used),
                        *count,
                        mesh_from_world_normal,
                    );
                    normal_accessors[slot].push(delta_accessor(
                        &mut root, &mut bin, &mut zeros, *count, &local,
                    )?);
                }
                let mut local = vec![DVec3::ZERO; *count as usize];
                for r in ranges {
                    for (out, v) in local.iter_mut().zip(r.clone()) {
                        if !used[v] {
                            continue;
                        }
                        let l = inverse * field[v];
                        if l.length_squared() > out.length_squared() {
                            *out = l;
                        }
                    }
                }
                let id = delta_accessor(&mut root, &mut bin, &mut zeros, *count, &local)?;
                accessors[slot].1.push(id);
            }
        }
        let base = append_to_mesh(&mut root, mesh, targets, &accessors, &normal_accessors)?;
        first_target.push((mesh, base));
        added.meshes.push(mesh);
    }
    if bin.len() > u32::MAX as usize - 64 - json_bytes.len() * 2 {
        return Err(UserGltfError::TooLarge);
    }
    if !bin.is_empty() {
        if root["buffers"].as_array().is_none_or(Vec::is_empty) {
            root["buffers"] = json!([{}]);
        }
        root["buffers"][0]["byteLength"] = json!(bin.len());
    }
    added.vrm_expressions = bind_vrm(&mut root, &first_target, targets, same_as);
    Ok((write_glb(&root, &bin)?, added))
}

/// Appends one target's deltas (`count` of them) as an accessor (on the shared view of
/// zeros, `zeros` by count, when all are zero) and returns its index as JSON.
fn delta_accessor(
    root: &mut Value,
    bin: &mut Vec<u8>,
    zeros: &mut std::collections::HashMap<u32, usize>,
    count: u32,
    deltas: &[DVec3],
) -> Result<Value, UserGltfError> {
    let mut accessor = json!({"componentType": 5126, "count": count, "type": "VEC3"});
    let f32s: Vec<[f32; 3]> = deltas.iter().map(|d| d.as_vec3().to_array()).collect();
    if f32s.iter().flatten().any(|c| !c.is_finite()) {
        return Err(UserGltfError::Mismatch(
            "a displacement is not finite".into(),
        ));
    }
    let moved: Vec<u32> = (0..f32s.len() as u32)
        .filter(|&i| f32s[i as usize] != [0.0; 3])
        .collect();
    let (mut lo, mut hi) = ([0f32; 3], [0f32; 3]);
    for d in &f32s {
        for k in 0..3 {
            lo[k] = lo[k].min(d[k]);
            hi[k] = hi[k].max(d[k]);
        }
    }
    // Sparse (indices and values of the moved vertices over zeros) when that is smaller than
    // every vertex's delta: 16 bytes a moved vertex against 12 a vertex.
    if !moved.is_empty() && 4 * moved.len() < 3 * f32s.len() {
        let indices: Vec<u8> = moved.iter().flat_map(|i| i.to_le_bytes()).collect();
        let values: Vec<u8> = moved
            .iter()
            .flat_map(|&i| f32s[i as usize])
            .flat_map(f32::to_le_bytes)
            .collect();
        let indices = append_view(root, bin, &indices, None);
        let values = append_view(root, bin, &values, None);
        accessor["sparse"] = json!({
            "count": moved.len(),
            "indices": {"bufferView": indices, "componentType": 5125},
            "values": {"bufferView": values},
        });
    } else if !moved.is_empty() {
        let bytes: Vec<u8> = f32s
            .iter()
            .flatten()
            .flat_map(|c| c.to_le_bytes())
            .collect();
        accessor["bufferView"] = json!(append_view(root, bin, &bytes, Some(34962)));
    } else {
        let view = *zeros.entry(count).or_insert_with(|| {
            let view = append_view(root, bin, &vec![0u8; 12 * count as usize], Some(34962));
            // Vertex accessors sharing a view need its stride.
            root["bufferViews"][view]["byteStride"] = json!(12);
            view
        });
        accessor["bufferView"] = json!(view);
    }
    accessor["min"] = json!(lo);
    accessor["max"] = json!(hi);
    Ok(json!(push(root, "accessors", accessor)))
}

/// Appends `bytes` (4-aligned) to `bin` as a new buffer view (with the vertex-data `target`
/// when given) and returns the view's index.
fn append_view(root: &mut Value, bin: &mut Vec<u8>, bytes: &[u8], target: Option<u32>) -> usize {
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut view = json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len()});
    if let Some(t) = target {
        view["target"] = json!(t);
    }
    bin.extend(bytes);
    push(root, "bufferViews", view)
}

/// Appends `value` to the array `key` of `root` (made when missing) and returns its index.
fn push(root: &mut Value, key: &str, value: Value) -> usize {
    if !root[key].is_array() {
        root[key] = json!([]);
    }
    match root[key].as_array_mut() {
        Some(a) => {
            a.push(value);
            a.len() - 1
        }
        None => 0,
    }
}

/// Adds the targets (their accessors per `POSITION` accessor) to every primitive of `mesh`,
/// with their names and zero weights; returns the index of the first one added.
fn append_to_mesh(
    root: &mut Value,
    mesh: usize,
    targets: &[(String, Vec<DVec3>)],
    accessors: &[(u32, Vec<Value>)],
    normal_accessors: &[Vec<Value>],
) -> Result<usize, UserGltfError> {
    let m = &mut root["meshes"][mesh];
    let primitives = m["primitives"].as_array().map_or(0, Vec::len);
    let existing = m["primitives"][0]["targets"].as_array().map_or(0, Vec::len);
    let mut names: Vec<Value> = m["extras"]["targetNames"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    names.resize_with(existing, || json!(""));
    for (name, _) in targets {
        if names.iter().any(|n| n.as_str() == Some(name)) {
            return Err(UserGltfError::NameTaken {
                mesh,
                name: name.clone(),
            });
        }
    }
    for p in 0..primitives {
        let prim = &mut m["primitives"][p];
        let own = prim["targets"].as_array().map_or(0, Vec::len);
        if own != existing {
            return Err(UserGltfError::Mismatch(format!(
                "mesh {mesh}'s primitives have {existing} and {own} morph targets"
            )));
        }
        let position = prim["attributes"]["POSITION"].as_u64();
        let Some(slot) = accessors
            .iter()
            .position(|a| Some(u64::from(a.0)) == position)
        else {
            return Err(UserGltfError::Mismatch(format!(
                "mesh {mesh} primitive {p}'s POSITION"
            )));
        };
        let normals = prim["attributes"].get("NORMAL").is_some();
        if !prim["targets"].is_array() {
            prim["targets"] = json!([]);
        }
        if let Some(list) = prim["targets"].as_array_mut() {
            for (k, id) in accessors[slot].1.iter().enumerate() {
                match normal_accessors.get(slot).and_then(|n| n.get(k)) {
                    Some(normal) if normals => {
                        list.push(json!({"POSITION": id, "NORMAL": normal}));
                    }
                    _ => list.push(json!({"POSITION": id})),
                }
            }
        }
    }
    names.extend(targets.iter().map(|(n, _)| json!(n)));
    let total = names.len();
    if !m["extras"].is_object() {
        m["extras"] = Value::Object(Map::new());
    }
    m["extras"]["targetNames"] = Value::Array(names);
    let mut weights: Vec<Value> = m["weights"].as_array().cloned().unwrap_or_default();
    weights.resize(total, json!(0.0));
    m["weights"] = Value::Array(weights);
    Ok(existing)
}

/// Normal deltas shorter than this (a turn of 0.22°, below what shading shows) are written as
/// zero, so that a target's normals are stored only where it bends the surface.
pub const NORMAL_DELTA_FLOOR: f64 = 1.0 / 256.0;

/// Whether any primitive of `mesh` has a `NORMAL` attribute (its targets then get normal
/// deltas, so that the lighting follows the moved surface).
fn primitives_with_normals(root: &Value, mesh: usize) -> bool {
    root["meshes"][mesh]["primitives"]
        .as_array()
        .is_some_and(|ps| ps.iter().any(|p| p["attributes"].get("NORMAL").is_some()))
}

/// The normal deltas of one target on one `POSITION` accessor of `count` vertices (the
/// primitives' `ranges` of scene vertices): the turn of the surface's unit vertex normal from
/// the neutral to the moved one, each in the mesh's frame, at each vertex's first copy at the
/// same place (`first`), only where the mesh's triangles use the vertex (`used`), applied to
/// the file's own normal (`file`, by local vertex; its hard edges and seams differ from the
/// surface's) so that the morphed normal stays a unit vector, or the surface normal's change
/// where the file has none. Deltas under [`NORMAL_DELTA_FLOOR`] are written as zero.
fn normal_deltas(
    (neutral, moved): (&[DVec3], &[DVec3]),
    file: Option<&[DVec3]>,
    first: &[u32],
    (ranges, used): (&[std::ops::Range<usize>], &[bool]),
    count: u32,
    mesh_from_world_normal: DMat3,
) -> Vec<DVec3> {
    let mut local = vec![DVec3::ZERO; count as usize];
    for r in ranges {
        for (i, (out, v)) in local.iter_mut().zip(r.clone()).enumerate() {
            if !used[v] {
                continue;
            }
            let w = first.get(v).map_or(v, |&f| f as usize);
            let to_mesh = |n: DVec3| (mesh_from_world_normal * n).normalize_or_zero();
            let (from, to) = (to_mesh(neutral[w]), to_mesh(moved[w]));
            let own = file.and_then(|f| f.get(i)).copied().unwrap_or(DVec3::ZERO);
            let d = if own != DVec3::ZERO && from != DVec3::ZERO && to != DVec3::ZERO {
                DQuat::from_rotation_arc(from, to) * own - own
            } else {
                to - from
            };
            if d.length() >= NORMAL_DELTA_FLOOR && d.length_squared() > out.length_squared() {
                *out = d;
            }
        }
    }
    local
}

/// Binds the VRM expressions (1.0 or 0.x) to the added targets; returns the names bound.
fn bind_vrm(
    root: &mut Value,
    first_target: &[(usize, usize)],
    targets: &[(String, Vec<DVec3>)],
    same_as: &[(String, String)],
) -> Vec<String> {
    let index_of = |name: &str| {
        let name = same_as
            .iter()
            .find(|(left_out, _)| left_out == name)
            .map_or(name, |(_, kept)| kept.as_str());
        targets.iter().position(|(n, _)| n == name)
    };
    let nodes_of = |root: &Value, mesh: usize| -> Vec<usize> {
        root["nodes"].as_array().map_or(Vec::new(), |nodes| {
            (0..nodes.len())
                .filter(|&i| nodes[i]["mesh"].as_u64() == Some(mesh as u64))
                .collect()
        })
    };
    let mut bound = Vec::new();
    let vrm1 = root["extensions"]["VRMC_vrm"].is_object();
    let vrm0 = root["extensions"]["VRM"].is_object();
    for (name, preset0) in VRM0_PRESETS {
        let Some(t) = index_of(name) else { continue };
        if vrm1 {
            let binds: Vec<Value> = first_target
                .iter()
                .flat_map(|&(mesh, base)| {
                    nodes_of(root, mesh)
                        .into_iter()
                        .map(move |node| json!({"node": node, "index": base + t, "weight": 1.0}))
                })
                .collect();
            let e = &mut root["extensions"]["VRMC_vrm"]["expressions"]["preset"][name];
            if !e.is_object() {
                *e = json!({});
            }
            e["morphTargetBinds"] = Value::Array(binds);
        }
        if vrm0 {
            let binds: Vec<Value> = first_target
                .iter()
                .map(|&(mesh, base)| json!({"mesh": mesh, "index": base + t, "weight": 100}))
                .collect();
            let master = &mut root["extensions"]["VRM"]["blendShapeMaster"];
            if !master["blendShapeGroups"].is_array() {
                master["blendShapeGroups"] = json!([]);
            }
            if let Some(groups) = master["blendShapeGroups"].as_array_mut() {
                match groups
                    .iter_mut()
                    .find(|g| g["presetName"].as_str() == Some(preset0))
                {
                    Some(g) => g["binds"] = Value::Array(binds),
                    None => groups.push(json!({
                        "name": name, "presetName": preset0, "binds": binds,
                        "materialValues": [], "isBinary": false
                    })),
                }
            }
        }
        if vrm0 || vrm1 {
            bound.push(name.to_string());
        }
    }
    bound
}

/// The GLB of `root` and `bin` (JSON padded with spaces, the binary chunk with zeros).
fn write_glb(root: &Value, bin: &[u8]) -> Result<Vec<u8>, UserGltfError> {
    let mut json =
        serde_json::to_vec(root).map_err(|e| UserGltfError::Container(format!("its JSON: {e}")))?;
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let bin_padded = bin.len().div_ceil(4) * 4;
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin_padded };
    let total32 = u32::try_from(total).map_err(|_| UserGltfError::TooLarge)?;
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend(total32.to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(&json);
    if !bin.is_empty() {
        out.extend((bin_padded as u32).to_le_bytes());
        out.extend(0x004E_4942u32.to_le_bytes());
        out.extend(bin);
        out.resize(total, 0);
    }
    Ok(out)
}
