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

use glam::{DMat3, DVec3};
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
        let moves = targets.iter().any(|(_, field)| {
            by_accessor
                .iter()
                .flat_map(|a| a.2.iter())
                .any(|r| field[r.clone()].iter().any(|d| *d != DVec3::ZERO))
        });
        if !moves {
            continue;
        }
        // One target and one accessor at a time (memory: one accessor's deltas): the local
        // deltas, the largest of the primitives' copies of each vertex.
        let mut accessors: Vec<(u32, Vec<Value>)> =
            by_accessor.iter().map(|a| (a.0, Vec::new())).collect();
        for (_, field) in targets {
            for (slot, (_, count, ranges)) in by_accessor.iter().enumerate() {
                let mut local = vec![DVec3::ZERO; *count as usize];
                for r in ranges {
                    for (out, d) in local.iter_mut().zip(&field[r.clone()]) {
                        let l = inverse * *d;
                        if l.length_squared() > out.length_squared() {
                            *out = l;
                        }
                    }
                }
                let id = delta_accessor(&mut root, &mut bin, *count, &local)?;
                accessors[slot].1.push(id);
            }
        }
        let base = append_to_mesh(&mut root, mesh, targets, &accessors)?;
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

/// Appends one target's deltas (`count` of them) as an accessor (no buffer view when all
/// zero) and returns its index as JSON.
fn delta_accessor(
    root: &mut Value,
    bin: &mut Vec<u8>,
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
        let Some((_, ids)) = accessors.iter().find(|a| Some(u64::from(a.0)) == position) else {
            return Err(UserGltfError::Mismatch(format!(
                "mesh {mesh} primitive {p}'s POSITION"
            )));
        };
        if !prim["targets"].is_array() {
            prim["targets"] = json!([]);
        }
        if let Some(list) = prim["targets"].as_array_mut() {
            list.extend(ids.iter().map(|id| json!({"POSITION": id})));
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
