//! Licence and attribution of the bundled faces, carried into the exports made from them.
//!
//! A face is recognised by [`crate::cache::mesh_hash`] of its welded mesh (positions bit-exact,
//! triangles and the input order map), so a bundled face is recognised however it is opened
//! (file, rig, viewer default) as long as its geometry is unchanged; an edited copy is the
//! user's own work and carries nothing. The entries repeat `assets/README.md`; a test
//! recomputes every hash from `assets/`.
//!
//! For any OBJ input, the comment lines (`#`) before its first `v` line are also copied into the
//! glTF's `asset.extras.sourceHeader`, so a user's own header (licence, author) travels too.

use face_prep::FaceMesh;

/// Source, licence and attribution of a bundled face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KnownFace {
    /// File name in `assets/`.
    pub file: &'static str,
    /// [`crate::cache::mesh_hash`] of the face, hex.
    pub mesh_hash: &'static str,
    /// SPDX licence identifier.
    pub licence: &'static str,
    /// The attribution the licence asks for (written as glTF `asset.copyright`).
    pub copyright: &'static str,
}

/// The four bundled faces (see `assets/README.md`).
pub const BUNDLED: [KnownFace; 4] = [
    KnownFace {
        file: "mediapipe_canonical_4loop.obj",
        mesh_hash: "cf0c9507ac07077b61558e722497728aa39ffdb8c8bc9056413dd569457eb132",
        licence: "Apache-2.0",
        copyright: "Derived from the MediaPipe canonical face model, Copyright The MediaPipe \
                    Authors, Apache License 2.0",
    },
    KnownFace {
        file: "ict_narrow_face_dec2500_4loop.obj",
        mesh_hash: "773e01b5c0165dff5af10b83debd673998a2b9ac8ddd9d869427227e404ccced",
        licence: "MIT",
        copyright: "Derived from ICT-FaceKit, Copyright (c) 2020 USC Institute for Creative \
                    Technologies, MIT License",
    },
    KnownFace {
        file: "leeperrysmith_face_open_4loop.obj",
        mesh_hash: "3bc9b0aa6ac649d8f54a2c3209a460654dc3b2054f5fb74c18640c99b50dbc00",
        licence: "CC-BY-3.0",
        copyright: "Infinite, 3D Head Scan by Lee Perry-Smith is licensed under a Creative \
                    Commons Attribution 3.0 Unported License. Based on a work at \
                    www.triplegangers.com.",
    },
    KnownFace {
        file: "ict_narrow_face_4loop.obj",
        mesh_hash: "af6147d2b87cb2d75cd767bceb1c98b2b452594d3b96d7039f578ad5adc2c0ae",
        licence: "MIT",
        copyright: "Derived from ICT-FaceKit, Copyright (c) 2020 USC Institute for Creative \
                    Technologies, MIT License",
    },
];

/// The bundled face `mesh` is, if any.
///
/// ```
/// let face = facebem::input::default_face().unwrap();
/// let known = facebem::export::attribution::identify(&face).unwrap();
/// assert_eq!(known.licence, "Apache-2.0");
/// ```
pub fn identify(mesh: &FaceMesh) -> Option<&'static KnownFace> {
    let hash = hex(&crate::cache::mesh_hash(mesh));
    BUNDLED.iter().find(|k| k.mesh_hash == hash)
}

/// Lower-case hex of bytes.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The comment lines before the first `v` line of an OBJ text, without their `#`, one per line.
///
/// ```
/// let h = facebem::export::attribution::obj_header("# by me\n#  CC0\nv 0 0 0\n# later\n");
/// assert_eq!(h, "by me\nCC0");
/// ```
pub fn obj_header(text: &str) -> String {
    text.lines()
        .map(str::trim_start)
        .take_while(|l| !l.starts_with("v ") && !l.starts_with("v\t"))
        .filter_map(|l| l.strip_prefix('#'))
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_bundled_face_is_recognised_by_its_hash() {
        for known in &BUNDLED {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("assets")
                .join(known.file);
            let mesh = face_prep::load_face(&path).unwrap();
            assert_eq!(
                hex(&crate::cache::mesh_hash(&mesh)),
                known.mesh_hash,
                "{}",
                known.file
            );
            assert_eq!(identify(&mesh), Some(known));
        }
        // Any edit makes it the user's own face.
        let mut mesh = crate::input::default_face().unwrap();
        mesh.vertices[0].x += 1e-9;
        assert_eq!(identify(&mesh), None);
    }
}
