//! glTF buffers are read from `data:` URIs and from regular files inside the glTF's own folder
//! only: a file one level up, an absolute path, a symlink leading out and a FIFO are refused
//! (the FIFO without being opened: opening it would block forever).

use face_prep::{GltfError, PrepError, load_face};
use std::path::Path;

/// A one-triangle glTF whose buffer is `uri` (48 bytes: 3 positions, 3 indices).
fn gltf_with_uri(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{"byteLength":48,"uri":{uri:?}}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":12}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}}]}}"#
    )
}

fn triangle_bytes() -> Vec<u8> {
    let mut b = Vec::new();
    for c in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
        b.extend_from_slice(&c.to_le_bytes());
    }
    for i in [0u32, 1, 2] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

fn buffer_error(dir: &Path, uri: &str) -> String {
    let path = dir.join("face.gltf");
    std::fs::write(&path, gltf_with_uri(uri)).unwrap();
    match load_face(&path) {
        Err(PrepError::Gltf(e @ GltfError::Buffer { .. })) => e.to_string(),
        other => panic!("{uri}: {other:?}"),
    }
}

#[test]
fn a_buffer_inside_the_folder_is_read() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(dir.path().join("sub/tri angle.bin"), triangle_bytes()).unwrap();
    std::fs::write(
        dir.path().join("face.gltf"),
        gltf_with_uri("sub/tri%20angle.bin"),
    )
    .unwrap();
    // The buffer loads; the single triangle is then (rightly) not a face.
    let err = load_face(&dir.path().join("face.gltf")).unwrap_err();
    assert!(
        matches!(err, PrepError::WrongLoopCount { count: 1, .. }),
        "{err}"
    );
}

#[test]
fn files_outside_the_folder_are_never_opened() {
    let root = tempfile::tempdir().unwrap();
    let inner = root.path().join("inner");
    std::fs::create_dir(&inner).unwrap();
    // Outside files are FIFOs: opening one would block this test forever.
    let outside = root.path().join("secret.bin");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&outside)
            .status()
            .unwrap()
            .success()
    );
    let err = buffer_error(&inner, "../secret.bin");
    assert!(err.contains("leaves the folder"), "{err}");
    let err = buffer_error(&inner, outside.to_str().unwrap());
    assert!(err.contains("is absolute"), "{err}");
    let err = buffer_error(&inner, &format!("file://{}", outside.display()));
    assert!(err.contains("has a scheme"), "{err}");
    // A symlink inside the folder that leads out of it.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&outside, inner.join("link.bin")).unwrap();
        let err = buffer_error(&inner, "link.bin");
        assert!(err.contains("outside the folder"), "{err}");
    }
    // A FIFO inside the folder: refused as not a regular file, unopened.
    let fifo = inner.join("fifo.bin");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let err = buffer_error(&inner, "fifo.bin");
    assert!(err.contains("is not a regular file"), "{err}");
    // A file shorter than its declared byteLength.
    std::fs::write(inner.join("short.bin"), [0u8; 10]).unwrap();
    let err = buffer_error(&inner, "short.bin");
    assert!(err.contains("has 10 bytes, byteLength is 48"), "{err}");
    // A GLB given as bytes without its folder cannot name external files.
    let err =
        face_prep::FaceMesh::from_gltf_slice(gltf_with_uri("a.bin").as_bytes(), None).unwrap_err();
    assert!(err.to_string().contains("without its folder"), "{err}");
}

/// A one-triangle glTF (buffer `tri.bin` beside it) with TEXCOORD_0 (accessor 2) and NORMAL
/// (accessor 3), and `extra` positions no triangle uses; `edit` changes the floats first.
fn write_attributed_triangle(dir: &Path, extra: usize, edit: impl FnOnce(&mut Attributes)) {
    let mut a = Attributes {
        positions: [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].to_vec(),
        texcoords: [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].to_vec(),
        normals: [[0.0, 0.0, 1.0]; 3].to_vec(),
    };
    a.positions.extend((0..extra).map(|k| [k as f32, 2.0, 0.0]));
    a.texcoords.extend((0..extra).map(|_| [0.5, 0.5]));
    a.normals.extend((0..extra).map(|_| [0.0, 0.0, 1.0]));
    edit(&mut a);
    let n = a.positions.len();
    let mut bin: Vec<u8> = Vec::new();
    let floats = a
        .positions
        .iter()
        .flatten()
        .chain(a.texcoords.iter().flatten())
        .chain(a.normals.iter().flatten());
    for c in floats {
        bin.extend_from_slice(&c.to_le_bytes());
    }
    for i in [0u32, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let (p, t, q) = (12 * n, 8 * n, 12 * n);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":2,"NORMAL":3}},"indices":1}}]}}],
"buffers":[{{"byteLength":{len},"uri":"tri.bin"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{p}}},{{"buffer":0,"byteOffset":{i},"byteLength":12}},
{{"buffer":0,"byteOffset":{p},"byteLength":{t}}},{{"buffer":0,"byteOffset":{pt},"byteLength":{q}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3"}},
{{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}},
{{"bufferView":2,"componentType":5126,"count":{n},"type":"VEC2"}},
{{"bufferView":3,"componentType":5126,"count":{n},"type":"VEC3"}}]}}"#,
        len = bin.len(),
        i = p + t + q,
        pt = p + t,
    );
    std::fs::write(dir.join("tri.bin"), bin).unwrap();
    std::fs::write(dir.join("face.gltf"), json).unwrap();
}

struct Attributes {
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    normals: Vec<[f32; 3]>,
}

/// The error reading the `face.gltf` of `dir`, as a [`GltfError`].
fn gltf_error(dir: &Path) -> GltfError {
    match load_face(&dir.join("face.gltf")) {
        Err(PrepError::Gltf(e)) => e,
        other => panic!("expected a glTF error, got {other:?}"),
    }
}

#[test]
fn gltf_with_finite_attributes_reads_as_far_as_its_topology() {
    let dir = tempfile::tempdir().unwrap();
    write_attributed_triangle(dir.path(), 0, |_| {});
    // Read and welded; one triangle is (rightly) not a face.
    let err = load_face(&dir.path().join("face.gltf")).unwrap_err();
    assert!(
        matches!(err, PrepError::WrongLoopCount { count: 1, .. }),
        "{err}"
    );
}

#[test]
fn gltf_with_nan_texture_coordinate_is_refused_at_read() {
    let dir = tempfile::tempdir().unwrap();
    write_attributed_triangle(dir.path(), 0, |a| a.texcoords[1][0] = f32::NAN);
    let err = gltf_error(dir.path());
    assert!(
        matches!(
            err,
            GltfError::NonFinite {
                accessor: 2,
                attribute: "TEXCOORD_0",
                element: 1
            }
        ),
        "{err}"
    );
    assert_eq!(
        err.to_string(),
        "accessor 2 (TEXCOORD_0): element 1 is not finite"
    );
}

#[test]
fn gltf_with_infinite_normal_is_refused_at_read() {
    let dir = tempfile::tempdir().unwrap();
    write_attributed_triangle(dir.path(), 0, |a| a.normals[2][1] = f32::NEG_INFINITY);
    let err = gltf_error(dir.path());
    assert!(
        matches!(
            err,
            GltfError::NonFinite {
                accessor: 3,
                attribute: "NORMAL",
                element: 2
            }
        ),
        "{err}"
    );
}

#[test]
fn gltf_with_nan_position_no_triangle_uses_is_refused_at_read() {
    // Unused positions are exported too (the user's vertex order), so they must be finite.
    let dir = tempfile::tempdir().unwrap();
    write_attributed_triangle(dir.path(), 2, |a| a.positions[4][2] = f32::NAN);
    let err = gltf_error(dir.path());
    assert!(
        matches!(
            err,
            GltfError::NonFinite {
                accessor: 0,
                attribute: "POSITION",
                element: 4
            }
        ),
        "{err}"
    );
}
