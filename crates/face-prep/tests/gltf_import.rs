//! glTF/GLB import: node transforms, mesh selection by name, vertex order map.

use face_prep::{FaceMesh, FaceRig, LoadOptions, PrepError, RigParams, load_face};

/// The glTF mesh named `name` of the file at `path`.
fn load_face_mesh_named(path: &std::path::Path, name: &str) -> Result<FaceMesh, PrepError> {
    LoadOptions {
        mesh_name: Some(name.to_string()),
        ..LoadOptions::default()
    }
    .load(path)
}
use glam::{DAffine3, DQuat, DVec3};
use std::path::PathBuf;

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name)
}

/// A GLB with two meshes: mesh 0 "dummy" (one triangle) and mesh 1 "face" under a parent node
/// (translation) and a child node (rotation + uniform scale).
fn glb(face: &FaceMesh, rotation: DQuat, scale: DVec3, translation: DVec3) -> Vec<u8> {
    let (json, bin) = gltf_parts(face, rotation, scale, translation, None);
    pack_glb(json.into_bytes(), bin)
}

/// JSON and binary buffer of the test document; `uri` names an external buffer file.
fn gltf_parts(
    face: &FaceMesh,
    rotation: DQuat,
    scale: DVec3,
    translation: DVec3,
    uri: Option<&str>,
) -> (String, Vec<u8>) {
    let mut bin: Vec<u8> = Vec::new();
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in &face.vertices {
        for k in 0..3 {
            let c = p[k] as f32;
            lo[k] = lo[k].min(c);
            hi[k] = hi[k].max(c);
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    let pos_len = bin.len();
    for t in &face.triangles {
        for i in t {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let idx_len = bin.len() - pos_len;
    for i in [0u32, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let q = rotation;
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
"nodes":[{{"children":[1],"translation":[{},{},{}]}},{{"mesh":1,"rotation":[{},{},{},{}],"scale":[{},{},{}]}}],
"meshes":[{{"name":"dummy","primitives":[{{"attributes":{{"POSITION":0}},"indices":2}}]}},
{{"name":"face","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{{}"byteLength":{}}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{pos_len}}},{{"buffer":0,"byteOffset":{pos_len},"byteLength":{idx_len}}},{{"buffer":0,"byteOffset":{},"byteLength":12}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}},
{{"bufferView":1,"componentType":5125,"count":{},"type":"SCALAR"}},{{"bufferView":2,"componentType":5125,"count":3,"type":"SCALAR"}}]}}"#,
        translation.x,
        translation.y,
        translation.z,
        q.x,
        q.y,
        q.z,
        q.w,
        scale.x,
        scale.y,
        scale.z,
        uri.map(|u| format!(r#""uri":"{u}","#)).unwrap_or_default(),
        bin.len(),
        pos_len + idx_len,
        face.vertices.len(),
        lo[0],
        lo[1],
        lo[2],
        hi[0],
        hi[1],
        hi[2],
        face.triangles.len() * 3,
    );
    (json, bin)
}

fn pack_glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x4E4F_534Au32.to_le_bytes());
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x004E_4942u32.to_le_bytes());
    out.extend_from_slice(&bin);
    out
}

#[test]
fn glb_node_transforms_and_named_mesh() {
    let face = load_face(&asset("ict_narrow_face_dec2500_4loop.obj")).unwrap();
    let rot = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 2.1);
    let (scale, t) = (3.0, DVec3::new(5.0, -7.0, 2.0));
    let bytes = glb(&face, rot, DVec3::splat(scale), t);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("face.glb");
    std::fs::write(&path, &bytes).unwrap();

    // First mesh is the one-triangle dummy: one loop.
    assert!(matches!(
        load_face(&path),
        Err(PrepError::WrongLoopCount { count: 1, .. })
    ));
    match load_face_mesh_named(&path, "nope") {
        Err(PrepError::GltfMeshNotFound { available, .. }) => {
            assert_eq!(available, vec!["dummy", "face"])
        }
        other => panic!("{other:?}"),
    }
    let g = load_face_mesh_named(&path, "face").unwrap();
    assert_eq!(g.vertices.len(), face.vertices.len());
    assert_eq!(g.triangles, face.triangles);
    let world = DAffine3::from_scale_rotation_translation(DVec3::splat(scale), rot, t);
    let size = 20.0 * scale;
    for (i, p) in face.vertices.iter().enumerate() {
        let v = g.input_to_vertex[i].unwrap() as usize;
        let expect = world.transform_point3(DVec3::new(
            p.x as f32 as f64,
            p.y as f32 as f64,
            p.z as f32 as f64,
        ));
        assert!(g.vertices[v].distance(expect) <= 1e-6 * size, "vertex {i}");
    }
    // Same features as the OBJ (boxes scale with the node's scale; f32 storage → 1e-5).
    let a = FaceRig::build(&face, &RigParams::default()).unwrap();
    let b = FaceRig::build(&g, &RigParams::default()).unwrap();
    assert_eq!(a.loops, b.loops);
    assert!((b.face_size - scale * a.face_size).abs() <= 1e-5 * b.face_size);
    for (x, y) in [
        (a.boxes.nose, b.boxes.nose),
        (a.boxes.mouth, b.boxes.mouth),
        (a.boxes.eye_l, b.boxes.eye_l),
    ] {
        assert!(
            (x.min * scale - y.min).length() <= 1e-5 * b.face_size,
            "{x:?} {y:?}"
        );
        assert!(
            (x.max * scale - y.max).length() <= 1e-5 * b.face_size,
            "{x:?} {y:?}"
        );
    }
    for (m, n) in a.muscles.iter().zip(&b.muscles) {
        let common = m
            .front_chain
            .iter()
            .filter(|e| n.front_chain.contains(e))
            .count();
        assert!(
            common * 10 >= m.front_chain.len() * 9,
            "{}: {:?} vs {:?}",
            m.name,
            m.front_chain,
            n.front_chain
        );
    }
}

#[test]
fn gltf_with_external_buffer_loads_relative_to_its_file() {
    let face = load_face(&asset("mediapipe_canonical_4loop.obj")).unwrap();
    let (json, bin) = gltf_parts(
        &face,
        DQuat::IDENTITY,
        DVec3::ONE,
        DVec3::ZERO,
        Some("face.bin"),
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("face.gltf"), json).unwrap();
    std::fs::write(dir.path().join("face.bin"), bin).unwrap();
    let g = load_face_mesh_named(&dir.path().join("face.gltf"), "face").unwrap();
    assert_eq!(g.triangles, face.triangles);
    for (a, b) in g.vertices.iter().zip(&face.vertices) {
        assert!(a.distance(*b) <= 1e-6 * 20.0);
    }
    // The buffer file missing is a glTF error, not a panic.
    std::fs::remove_file(dir.path().join("face.bin")).unwrap();
    let err = load_face_mesh_named(&dir.path().join("face.gltf"), "face").unwrap_err();
    assert!(matches!(err, PrepError::Gltf(_)), "{err}");
}

#[test]
fn mirroring_node_keeps_the_mesh_valid() {
    // A negative scale flips handedness; the loader reverses the winding so the face still
    // faces its viewer, and the rig builds with the muscles on the mirrored sides.
    let face = load_face(&asset("mediapipe_canonical_4loop.obj")).unwrap();
    let bytes = glb(
        &face,
        DQuat::IDENTITY,
        DVec3::new(-1.0, 1.0, 1.0),
        DVec3::ZERO,
    );
    let g = FaceMesh::from_gltf_slice(&bytes, Some("face")).unwrap();
    assert_eq!(
        g.triangles[0],
        [
            face.triangles[0][0],
            face.triangles[0][2],
            face.triangles[0][1]
        ]
    );
    let rig = FaceRig::build(&g, &RigParams::default()).unwrap();
    let orig = FaceRig::build(&face, &RigParams::default()).unwrap();
    assert!(rig.shell.signed_volume() > 0.0);
    // The face's left eye is the mirror image of the original right eye (same vertex set).
    let sorted = |l: &[u32]| {
        let mut v = l.to_vec();
        v.sort_unstable();
        v
    };
    assert_eq!(sorted(&rig.loops.eye_l), sorted(&orig.loops.eye_r));
    assert_eq!(sorted(&rig.loops.eye_r), sorted(&orig.loops.eye_l));
}
