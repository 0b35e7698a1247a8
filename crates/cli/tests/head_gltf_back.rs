//! The user's own GLB and VRM back (issue 32, item 6): a GLB head with a skeleton and skin, a
//! texture, an existing morph target and an extra mesh comes back from `facebem export` with
//! all of it intact — the JSON's every other part equal, every accessor that was there with
//! identical bytes — and the named targets added to the head's mesh; a VRM 1.0 head (with the
//! required humanoid bones) comes back with its expressions bound, and three-vrm moves the face
//! with `happy` and `blink`.
//!
//! The inputs are built here from ICT-FaceKit's generic head (`assets/heads/`), in metres.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::{Value, json};

#[path = "../../../tests/support/mod.rs"]
mod support;

/// A 1×1 PNG (the texture; its bytes only need to survive).
const PNG_1X1: &str = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==";

/// VRM 1.0's required humanoid bones, each the child of the one before (hips first).
const BONES: [&str; 15] = [
    "hips",
    "spine",
    "head",
    "leftUpperArm",
    "leftLowerArm",
    "leftHand",
    "rightUpperArm",
    "rightLowerArm",
    "rightHand",
    "leftUpperLeg",
    "leftLowerLeg",
    "leftFoot",
    "rightUpperLeg",
    "rightLowerLeg",
    "rightFoot",
];

fn head_obj() -> PathBuf {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/heads/ict_generic_head.obj"
    ))
    .to_path_buf()
}

/// Appends `bytes` to `bin` (4-aligned) as a buffer view; returns its index.
fn view(root: &mut Value, bin: &mut Vec<u8>, bytes: &[u8]) -> usize {
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let views = root["bufferViews"].as_array_mut().unwrap();
    views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len()}));
    bin.extend(bytes);
    views.len() - 1
}

/// Appends an accessor of f32 `values` (`width` per element) in a new view.
fn floats(root: &mut Value, bin: &mut Vec<u8>, values: &[f32], kind: &str, width: usize) -> usize {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let v = view(root, bin, &bytes);
    let mut acc = json!({"bufferView": v, "componentType": 5126, "count": values.len() / width, "type": kind});
    if kind == "VEC3" {
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in values.chunks(3) {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        acc["min"] = json!(lo);
        acc["max"] = json!(hi);
    }
    let list = root["accessors"].as_array_mut().unwrap();
    list.push(acc);
    list.len() - 1
}

/// The head (one skinned, textured mesh with a morph target `existing`) and a small `hat`
/// mesh above it, on a skeleton of the VRM bones; with `vrm`, the VRMC_vrm extension (and no
/// texture), else a texture.
fn build(vrm: bool) -> Vec<u8> {
    build_with(vrm, false)
}

/// [`build`]; with `vrm0`, a VRM 0.x `VRM` extension with one `joy` group instead.
fn build_with(vrm: bool, vrm0: bool) -> Vec<u8> {
    let scene = face_prep::parts::Scene::read(&head_obj(), &Default::default()).unwrap();
    let mut root = json!({
        "asset": {"version": "2.0", "generator": "facebem test"},
        "buffers": [{}], "bufferViews": [], "accessors": [],
        "scene": 0,
    });
    let mut bin = Vec::new();
    let n = scene.positions.len();
    let positions: Vec<f32> = scene
        .positions
        .iter()
        .flat_map(|p| p.to_array().map(|c| (c / 100.0) as f32))
        .collect();
    let pos = floats(&mut root, &mut bin, &positions, "VEC3", 3);
    let uv: Vec<f32> = positions
        .chunks(3)
        .flat_map(|p| [p[0] * 2.0 + 0.5, 0.5 - p[1] * 2.0])
        .collect();
    let uv = floats(&mut root, &mut bin, &uv, "VEC2", 2);
    let weights: Vec<f32> = (0..n).flat_map(|_| [1.0, 0.0, 0.0, 0.0]).collect();
    let weights = floats(&mut root, &mut bin, &weights, "VEC4", 4);
    let joints: Vec<u8> = (0..n)
        .flat_map(|_| [2u16, 0, 0, 0])
        .flat_map(u16::to_le_bytes)
        .collect();
    let jv = view(&mut root, &mut bin, &joints);
    let existing: Vec<f32> = (0..n).flat_map(|_| [0.0, 0.001, 0.0]).collect();
    let existing = floats(&mut root, &mut bin, &existing, "VEC3", 3);
    let indices: Vec<u8> = scene
        .triangles
        .iter()
        .flatten()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let iv = view(&mut root, &mut bin, &indices);
    let ibm: Vec<f32> = (0..BONES.len())
        .flat_map(|_| glam::Mat4::IDENTITY.to_cols_array())
        .collect();
    let ibm = floats(&mut root, &mut bin, &ibm, "MAT4", 16);
    let hat: Vec<f32> = vec![
        0.0, 0.3, 0.0, 0.05, 0.25, 0.0, -0.05, 0.25, 0.0, 0.0, 0.25, 0.05,
    ];
    let hat = floats(&mut root, &mut bin, &hat, "VEC3", 3);
    let hat_idx: Vec<u8> = [0u16, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let hv = view(&mut root, &mut bin, &hat_idx);
    let png = face_prep::gltf_read::decode_base64(PNG_1X1).unwrap();
    let image = view(&mut root, &mut bin, &png);
    let list = root["accessors"].as_array_mut().unwrap();
    list.push(json!({"bufferView": jv, "componentType": 5123, "count": n, "type": "VEC4"}));
    let joints = list.len() - 1;
    list.push(json!({"bufferView": iv, "componentType": 5125, "count": 3 * scene.triangles.len(), "type": "SCALAR"}));
    let idx = list.len() - 1;
    list.push(json!({"bufferView": hv, "componentType": 5123, "count": 12, "type": "SCALAR"}));
    let hat_indices = list.len() - 1;
    root["buffers"][0]["byteLength"] = json!(bin.len());
    let mut nodes: Vec<Value> = BONES
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let mut node =
                json!({"name": b, "translation": [0.0, if i == 0 { 0.0 } else { 0.01 }, 0.0]});
            if i + 1 < BONES.len() {
                node["children"] = json!([i + 1]);
            }
            node
        })
        .collect();
    let face_node = nodes.len();
    nodes.push(json!({"name": "Face", "mesh": 0, "skin": 0}));
    nodes.push(json!({"name": "Hat", "mesh": 1, "translation": [0.0, 0.1, 0.0]}));
    root["nodes"] = json!(nodes);
    root["scenes"] = json!([{"nodes": [0, face_node, face_node + 1]}]);
    root["skins"] =
        json!([{"joints": (0..BONES.len()).collect::<Vec<_>>(), "inverseBindMatrices": ibm}]);
    root["materials"] = json!([{"name": "skin"}, {"name": "hat"}]);
    // three.js in node cannot decode images: the VRM (loaded by three-vrm) has none.
    if !vrm {
        root["images"] = json!([{"bufferView": image, "mimeType": "image/png"}]);
        root["samplers"] = json!([{"magFilter": 9729}]);
        root["textures"] = json!([{"source": 0, "sampler": 0}]);
        root["materials"][0]["pbrMetallicRoughness"] =
            json!({"baseColorTexture": {"index": 0}, "metallicFactor": 0.0});
    }
    root["meshes"] = json!([
        {"name": "Head", "primitives": [{
            "attributes": {"POSITION": pos, "TEXCOORD_0": uv, "JOINTS_0": joints, "WEIGHTS_0": weights},
            "indices": idx, "material": 0, "targets": [{"POSITION": existing}]}],
         "weights": [0.0], "extras": {"targetNames": ["existing"]}},
        {"name": "Hat", "primitives": [{"attributes": {"POSITION": hat}, "indices": hat_indices, "material": 1}]}
    ]);
    if vrm {
        let bones: serde_json::Map<String, Value> = BONES
            .iter()
            .enumerate()
            .map(|(i, b)| (b.to_string(), json!({"node": i})))
            .collect();
        root["extensionsUsed"] = json!(["VRMC_vrm"]);
        root["extensions"] = json!({"VRMC_vrm": {
            "specVersion": "1.0",
            "meta": {"name": "ICT head", "authors": ["facebem test"], "licenseUrl": "https://vrm.dev/licenses/1.0/"},
            "humanoid": {"humanBones": bones},
            "expressions": {"preset": {"happy": {"morphTargetBinds": [], "isBinary": false}}}
        }});
    }
    if vrm0 {
        root["extensionsUsed"] = json!(["VRM"]);
        root["extensions"] = json!({"VRM": {"exporterVersion": "test", "blendShapeMaster": {
            "blendShapeGroups": [{"name": "Joy", "presetName": "joy", "binds": [], "materialValues": []}]
        }}});
    }
    glb(&root, &bin)
}

fn glb(root: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(root).unwrap();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + json.len() + bin.len()) as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(&bin);
    out
}

/// Runs `facebem export input --gltf output` and returns (input JSON, input BIN, output JSON,
/// output BIN).
fn round_trip(dir: &Path, name: &str, bytes: &[u8]) -> (Value, Vec<u8>, Value, Vec<u8>, PathBuf) {
    let input = dir.join(name);
    std::fs::write(&input, bytes).unwrap();
    valid(&input, name);
    let output = dir.join(format!("out_{name}"));
    let run = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(["export"])
        .arg(&input)
        .arg("--gltf")
        .arg(&output)
        .env("XDG_CACHE_HOME", dir)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    valid(&output, name);
    let split = |b: &[u8]| {
        let (j, bin) = face_prep::gltf_read::split_glb(b).unwrap();
        (
            serde_json::from_slice::<Value>(j).unwrap(),
            bin.unwrap_or_default().to_vec(),
        )
    };
    let (a, abin) = split(bytes);
    let (b, bbin) = split(&std::fs::read(&output).unwrap());
    (a, abin, b, bbin, output)
}

/// Khronos-valid: no error and no warning; a VRM 0.x (`old.vrm`) no error (its extension's
/// name `VRM` is one the validator warns about in every VRM 0.x file).
fn valid(file: &Path, name: &str) {
    if name != "old.vrm" {
        return support::assert_valid(file);
    }
    if let support::Validation::Report(r) = support::validate_gltf(file) {
        assert_eq!(
            r["issues"]["numErrors"].as_u64(),
            Some(0),
            "{}",
            r["issues"]["messages"]
        );
    }
}

/// Everything of `before` is in `after`: the arrays that were there, element for element,
/// except the head mesh (its targets, weights and names grow), and every old buffer view's
/// bytes identical.
fn kept(before: &Value, abin: &[u8], after: &Value, bbin: &[u8]) {
    for key in [
        "nodes",
        "scenes",
        "skins",
        "images",
        "samplers",
        "textures",
        "materials",
        "asset",
    ] {
        assert_eq!(before[key], after[key], "{key}");
    }
    for key in ["accessors", "bufferViews"] {
        let (a, b) = (
            before[key].as_array().unwrap(),
            after[key].as_array().unwrap(),
        );
        assert_eq!(a[..], b[..a.len()], "{key}");
    }
    for v in before["bufferViews"].as_array().unwrap() {
        let (o, l) = (
            v["byteOffset"].as_u64().unwrap() as usize,
            v["byteLength"].as_u64().unwrap() as usize,
        );
        assert_eq!(abin[o..o + l], bbin[o..o + l], "buffer view at {o}");
    }
    assert_eq!(
        before["meshes"][1], after["meshes"][1],
        "the hat does not move"
    );
    let (head0, head1) = (&before["meshes"][0], &after["meshes"][0]);
    let (p0, p1) = (&head0["primitives"][0], &head1["primitives"][0]);
    assert_eq!(p0["attributes"], p1["attributes"]);
    assert_eq!(p0["indices"], p1["indices"]);
    assert_eq!(
        p0["targets"][0], p1["targets"][0],
        "the existing target first"
    );
    let names: Vec<&str> = head1["extras"]["targetNames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    assert_eq!(names[0], "existing");
    for name in facebem::expressions::arkit::NAMES {
        assert!(names.contains(&name), "{name}");
    }
    let targets = p1["targets"].as_array().unwrap().len();
    assert_eq!(targets, names.len());
    assert_eq!(head1["weights"].as_array().unwrap().len(), targets);
}

#[test]
fn a_glb_head_comes_back_with_everything_kept_and_the_targets_added() {
    let dir = tempfile::tempdir().unwrap();
    let (before, abin, after, bbin, _) = round_trip(dir.path(), "head.glb", &build(false));
    kept(&before, &abin, &after, &bbin);
}

#[test]
fn a_vrm_head_comes_back_with_its_expressions_bound() {
    let dir = tempfile::tempdir().unwrap();
    let (before, abin, after, bbin, out) = round_trip(dir.path(), "head.vrm", &build(true));
    kept(&before, &abin, &after, &bbin);
    let names: Vec<String> = after["meshes"][0]["extras"]["targetNames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect();
    let preset = &after["extensions"]["VRMC_vrm"]["expressions"]["preset"];
    for name in ["happy", "blink", "aa", "lookUp", "blinkLeft"] {
        let binds = preset[name]["morphTargetBinds"].as_array().unwrap();
        assert!(!binds.is_empty(), "{name}");
        for b in binds {
            assert_eq!(
                b["node"].as_u64(),
                Some(BONES.len() as u64),
                "{name}: the Face node"
            );
            let bound = &names[b["index"].as_u64().unwrap() as usize];
            // blinkLeft repeats eyeBlinkLeft and is bound to it.
            assert!(
                bound == name || (name == "blinkLeft" && bound == "eyeBlinkLeft"),
                "{name} → {bound}"
            );
        }
    }
    assert_eq!(
        preset["happy"]["isBinary"],
        json!(false),
        "the expression's own fields kept"
    );
    match support::load_with_three_vrm(&out, &["happy", "blink", "neutral"]) {
        support::Validation::NodeMissing => eprintln!("SKIPPED three-vrm: node is not installed"),
        support::Validation::Report(r) => {
            eprintln!("three-vrm: {r}");
            assert_eq!(r["humanBones"].as_u64(), Some(BONES.len() as u64));
            for name in ["happy", "blink"] {
                let m = r["expressions"][name].as_f64().unwrap();
                assert!(m > 0.003, "three-vrm: {name} moves the face {m} m");
            }
        }
    }
}

#[test]
fn a_vrm0_head_gets_its_blend_shape_groups_bound() {
    let dir = tempfile::tempdir().unwrap();
    let (before, abin, after, bbin, _) =
        round_trip(dir.path(), "old.vrm", &build_with(false, true));
    kept(&before, &abin, &after, &bbin);
    let names = after["meshes"][0]["extras"]["targetNames"]
        .as_array()
        .unwrap()
        .clone();
    let groups = after["extensions"]["VRM"]["blendShapeMaster"]["blendShapeGroups"]
        .as_array()
        .unwrap();
    // The user's `Joy` group keeps its name and gets the binds; the other presets are added.
    let joy = groups.iter().find(|g| g["presetName"] == "joy").unwrap();
    assert_eq!(joy["name"], "Joy");
    let bind = &joy["binds"][0];
    assert_eq!(bind["mesh"], 0);
    assert_eq!(bind["weight"], 100);
    assert_eq!(names[bind["index"].as_u64().unwrap() as usize], "happy");
    for preset in ["a", "blink", "blink_l", "lookup"] {
        let g = groups.iter().find(|g| g["presetName"] == preset);
        assert!(
            g.is_some_and(|g| !g["binds"].as_array().unwrap().is_empty()),
            "{preset}"
        );
    }
}

/// Checks the sparse rule on the `POSITION` target accessors from index `old` on.
fn added_targets_are_sparse_where_they_move_few_vertices(json: &Value, bin: &[u8], old: usize) {
    let mut seen = std::collections::HashSet::new();
    for p in json["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|m| m["primitives"].as_array().unwrap().iter())
    {
        for t in &p["targets"].as_array().unwrap()[old..] {
            let a = t["POSITION"].as_u64().unwrap() as usize;
            if !seen.insert(a) {
                continue;
            }
            let accessor = &json["accessors"][a];
            let count = accessor["count"].as_u64().unwrap() as usize;
            if let Some(n) = accessor["sparse"]["count"].as_u64() {
                assert!(
                    n > 0 && 4 * n < 3 * count as u64,
                    "accessor {a}: {n} of {count}"
                );
                continue;
            }
            let view = &json["bufferViews"][accessor["bufferView"].as_u64().unwrap() as usize];
            let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
            let stride = view["byteStride"].as_u64().unwrap_or(12) as usize;
            let moved = (0..count)
                .filter(|i| bin[offset + i * stride..][..12].iter().any(|&b| b != 0))
                .count();
            assert!(
                moved == 0 || 4 * moved >= 3 * count,
                "accessor {a}: {moved} of {count}"
            );
        }
    }
    assert!(!seen.is_empty());
}

/// Regression: the ICT head as facebem's own GLB (UV seams split into separate vertices, one
/// primitive per material sharing one `POSITION` accessor, facebem's own targets already on
/// it) was "not a head": its eyeballs did not count as closed (a seam's copies are one point
/// of the surface) and the front face lost the triangles beyond the seams. It now comes back
/// with the named targets after the existing ones, on every primitive.
#[test]
fn facebems_own_glb_of_a_head_is_a_head() {
    let dir = tempfile::tempdir().unwrap();
    let first = dir.path().join("head.glb");
    let run = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .arg("export")
        .arg(head_obj())
        .args(["--names", "facebem", "--gltf"])
        .arg(&first)
        .env("XDG_CACHE_HOME", dir.path())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    // Its meshes' primitives share one POSITION accessor under one transform: read once
    // (regression: 13 copies, 375 843 scene vertices).
    let scene = face_prep::parts::Scene::read(&first, &Default::default()).unwrap();
    let primitives: Vec<_> = scene
        .gltf_meshes
        .iter()
        .flat_map(|m| &m.primitives)
        .collect();
    assert!(scene.gltf_meshes.len() > 1 && primitives.len() > scene.gltf_meshes.len());
    assert!(primitives.iter().all(|p| *p == primitives[0]));
    assert_eq!(scene.positions.len(), primitives[0].count as usize);
    let bytes = std::fs::read(&first).unwrap();
    let (before, abin, after, bbin, output) = round_trip(dir.path(), "again.glb", &bytes);
    for key in ["nodes", "materials", "asset"] {
        assert_eq!(before[key], after[key], "{key}");
    }
    let old = before["meshes"][0]["extras"]["targetNames"]
        .as_array()
        .unwrap()
        .len();
    let names = after["meshes"][0]["extras"]["targetNames"]
        .as_array()
        .unwrap();
    assert_eq!(
        names[..old],
        before["meshes"][0]["extras"]["targetNames"]
            .as_array()
            .unwrap()[..]
    );
    assert!(names.len() >= old + 52, "{} names after {old}", names.len());
    for p in after["meshes"][0]["primitives"].as_array().unwrap() {
        assert_eq!(p["targets"].as_array().unwrap().len(), names.len());
    }
    // Every added target is sparse where it moves fewer than three quarters of the vertices,
    // dense (or the shared zeros) otherwise: `src/export/user_gltf.rs`'s rule, read back.
    added_targets_are_sparse_where_they_move_few_vertices(&after, &bbin, old);
    for v in before["bufferViews"].as_array().unwrap() {
        let o = v["byteOffset"].as_u64().unwrap_or(0) as usize;
        let l = v["byteLength"].as_u64().unwrap() as usize;
        assert_eq!(abin[o..o + l], bbin[o..o + l], "buffer view at {o}");
    }
    normals_follow_the_surface(&output, old, names);
}

/// The added targets carry normal deltas where the primitive has normals: in jawOpen, every
/// moved normal stays a unit vector (1e-3) and the chin's turn by more than 3°. Read with the
/// `gltf` crate (as Bevy reads glTF), which refuses an accessor without a buffer view: the
/// all-zero targets of the write-back had none (regression; they share a view of zeros now).
/// Regression too: the surface normal's change was added to the file's own normals, which
/// differ from the surface's at ICT's seams; once jawOpen moved the lower lid, 9 of them came
/// out 0.996–1.0046 long. The file's normal is turned with the surface now.
fn normals_follow_the_surface(output: &Path, old: usize, names: &[Value]) {
    let open = names.iter().position(|n| n == "jawOpen").unwrap();
    let (doc, buffers, _) = gltf::import(output).unwrap();
    let (mut checked, mut turned) = (0, 0.0f32);
    for prim in doc.meshes().next().unwrap().primitives() {
        let reader = prim.reader(|b| Some(&buffers[b.index()]));
        let Some(neutral) = reader.read_normals() else {
            continue;
        };
        let neutral: Vec<[f32; 3]> = neutral.collect();
        for (k, (_, normals, _)) in reader.read_morph_targets().enumerate() {
            if k < old {
                continue;
            }
            let normals: Vec<[f32; 3]> = normals.expect("a NORMAL delta").collect();
            if k != open {
                continue;
            }
            for (n, d) in neutral.iter().zip(&normals) {
                let m = [n[0] + d[0], n[1] + d[1], n[2] + d[2]];
                let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
                assert!((len - 1.0).abs() < 1e-3, "moved normal of length {len}");
                turned = turned.max((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
                checked += 1;
            }
        }
    }
    assert!(checked > 1000, "{checked} normals checked");
    assert!(
        turned > 0.05,
        "the most a normal turns in jawOpen: {turned}"
    );
}

/// A `.gltf` head whose buffer is a separate file (item 1: glTF as well as GLB) comes back as
/// that file packed into one GLB, everything kept and the targets added; an output named like
/// its buffer is refused before anything is written.
#[test]
fn a_gltf_head_with_a_separate_buffer_comes_back_as_one_glb() {
    let dir = tempfile::tempdir().unwrap();
    let glb = build(false);
    let (json, bin) = face_prep::gltf_read::split_glb(&glb).unwrap();
    let before: Value = serde_json::from_slice(json).unwrap();
    let bin = bin.unwrap().to_vec();
    let mut root = before.clone();
    root["buffers"][0]["uri"] = Value::from("head.bin");
    let input = dir.path().join("head.gltf");
    std::fs::write(&input, serde_json::to_vec(&root).unwrap()).unwrap();
    std::fs::write(dir.path().join("head.bin"), &bin).unwrap();
    let export = |out: &Path| {
        Command::new(env!("CARGO_BIN_EXE_facebem"))
            .args(["export"])
            .arg(&input)
            .arg("--gltf")
            .arg(out)
            .env("XDG_CACHE_HOME", dir.path())
            .output()
            .unwrap()
    };
    let refused = export(&dir.path().join("head.bin"));
    assert!(!refused.status.success());
    assert_eq!(std::fs::read(dir.path().join("head.bin")).unwrap(), bin);
    let output = dir.path().join("out.glb");
    let run = export(&output);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    valid(&output, "out.glb");
    let written = std::fs::read(&output).unwrap();
    let (j, b) = face_prep::gltf_read::split_glb(&written).unwrap();
    let after: Value = serde_json::from_slice(j).unwrap();
    kept(&before, &bin, &after, b.unwrap());
}
