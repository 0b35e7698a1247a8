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
