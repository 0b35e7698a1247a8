//! The user's look in the GLB (issue 34, item 4): an OBJ with `mtllib` and `map_Kd` exports its
//! materials (the texture embedded as the base colour, a `Kd`-only material as its colour, one
//! primitive each, sharing the morph targets) instead of the fixed skin, validator clean; a
//! texture path outside the OBJ's folder is refused in one line before any work; a missing
//! texture is a warning and the material keeps its colour.

#[path = "../../../tests/support/mod.rs"]
mod support;

use std::path::Path;
use std::process::{Command, Output};

fn facebem(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(args)
        .env("XDG_CACHE_HOME", dir.join("cache"))
        .output()
        .expect("run facebem")
}

/// Writes `face.obj` in `dir`: the default face with planar texture coordinates, `mtllib
/// face.mtl`, its first half of faces `usemtl skin_tex` and the rest `usemtl lips`.
fn textured_face(dir: &Path, mtl: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(support::asset(support::FACES[0])).unwrap();
    let v = support::obj_v_lines(&support::asset(support::FACES[0]));
    let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
    let (lo, hi) = v
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        });
    let mut out = String::from("mtllib face.mtl\n");
    for p in &v {
        out += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for p in &v {
        let u = (p[0] - lo[0]) / (hi[0] - lo[0]);
        let w = (p[1] - lo[1]) / (hi[1] - lo[1]);
        out += &format!("vt {u} {w}\n");
    }
    out += "usemtl skin_tex\n";
    for (k, f) in faces.iter().enumerate() {
        if k == faces.len() / 2 {
            out += "usemtl lips\n";
        }
        let ids: Vec<&str> = f.split_whitespace().skip(1).collect();
        out += "f";
        for id in ids {
            let i = id.split('/').next().unwrap();
            out += &format!(" {i}/{i}");
        }
        out += "\n";
    }
    let obj = dir.join("face.obj");
    std::fs::write(&obj, out).unwrap();
    std::fs::write(dir.join("face.mtl"), mtl).unwrap();
    obj
}

/// A 4 × 4 RGB PNG.
fn png_bytes() -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, 4, 4);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&[200u8; 48]).unwrap();
    writer.finish().unwrap();
    bytes
}

/// The JSON chunk and BIN chunk of a GLB.
fn glb_parts(path: &Path) -> (serde_json::Value, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
    (json, bytes[20 + len + 8..].to_vec())
}

const MTL: &str = "newmtl skin_tex\nKd 0.8 0.8 0.8\nmap_Kd -s 1 1 1 tex/skin.png\n\nnewmtl lips\nKd 0.6 0.2 0.2\n";

#[test]
fn an_objs_materials_and_texture_are_exported() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("tex")).unwrap();
    let png = png_bytes();
    std::fs::write(dir.path().join("tex/skin.png"), &png).unwrap();
    let obj = textured_face(dir.path(), MTL);
    let glb = dir.path().join("out.glb");
    let out = facebem(
        dir.path(),
        &[
            "export",
            obj.to_str().unwrap(),
            "--gltf",
            glb.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    support::assert_valid(&glb);
    let (json, bin) = glb_parts(&glb);
    let materials = json["materials"].as_array().unwrap();
    assert_eq!(materials.len(), 2, "{json}");
    assert_eq!(materials[0]["name"], "skin_tex");
    assert_eq!(
        materials[0]["pbrMetallicRoughness"]["baseColorTexture"]["index"],
        0
    );
    assert_eq!(materials[1]["name"], "lips");
    let lips = &materials[1]["pbrMetallicRoughness"]["baseColorFactor"];
    for (got, want) in lips.as_array().unwrap().iter().zip([0.6, 0.2, 0.2, 1.0]) {
        assert!((got.as_f64().unwrap() - want).abs() < 1e-6, "{lips}");
    }
    // The texture is the file, byte for byte.
    let image = &json["images"][0];
    assert_eq!(image["mimeType"], "image/png");
    assert_eq!(json["textures"][0]["source"], 0);
    let view = &json["bufferViews"][image["bufferView"].as_u64().unwrap() as usize];
    let start = view["byteOffset"].as_u64().unwrap() as usize;
    let end = start + view["byteLength"].as_u64().unwrap() as usize;
    assert_eq!(&bin[start..end], &png[..]);
    // Two primitives, one per material, sharing the vertices and the morph targets, and
    // holding every triangle between them.
    let primitives = json["meshes"][0]["primitives"].as_array().unwrap();
    assert_eq!(primitives.len(), 2);
    assert_eq!(primitives[0]["attributes"], primitives[1]["attributes"]);
    assert_eq!(primitives[0]["targets"], primitives[1]["targets"]);
    assert_eq!(primitives[0]["material"], 0);
    assert_eq!(primitives[1]["material"], 1);
    let count = |p: &serde_json::Value| {
        json["accessors"][p["indices"].as_u64().unwrap() as usize]["count"]
            .as_u64()
            .unwrap()
    };
    let (mesh, _) = facebem::input::read_face(&obj).unwrap();
    assert_eq!(
        count(&primitives[0]) + count(&primitives[1]),
        3 * mesh.triangles.len() as u64
    );
    assert!(json["meshes"][0]["extras"]["materialWarnings"].is_null());

    // A texture the OBJ's folder does not hold: a warning; the material keeps its colour.
    std::fs::remove_file(dir.path().join("tex/skin.png")).unwrap();
    let missing = dir.path().join("missing.glb");
    let out = facebem(
        dir.path(),
        &[
            "export",
            obj.to_str().unwrap(),
            "--gltf",
            missing.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: texture tex/skin.png of material \"skin_tex\""),
        "{stderr}"
    );
    support::assert_valid(&missing);
    let (json, _) = glb_parts(&missing);
    assert!(json["images"].is_null());
    let kd = json["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][0].as_f64();
    assert!((kd.unwrap() - 0.8).abs() < 1e-6, "{kd:?}");
}

#[test]
fn a_texture_outside_the_objs_folder_is_refused_before_any_work() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("face");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(root.path().join("outside.png"), png_bytes()).unwrap();
    for (mtl, what) in [
        (
            "newmtl skin\nmap_Kd ../outside.png\n",
            "texture \"../outside.png\"",
        ),
        (
            "newmtl skin\nmap_Kd /etc/hostname\n",
            "texture \"/etc/hostname\"",
        ),
    ] {
        let obj = textured_face(&dir, &mtl.replace("skin", "skin_tex"));
        let glb = dir.join("out.glb");
        let out = facebem(
            root.path(),
            &[
                "export",
                obj.to_str().unwrap(),
                "--gltf",
                glb.to_str().unwrap(),
            ],
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(what) && stderr.contains("outside the OBJ's folder"),
            "{stderr}"
        );
        // Refused before the rig was computed.
        assert!(
            !String::from_utf8_lossy(&out.stdout).contains("computing"),
            "{stderr}"
        );
        assert!(!glb.exists());
    }
    // A material library outside is refused the same way.
    let obj = textured_face(&dir, MTL);
    let text = std::fs::read_to_string(&obj)
        .unwrap()
        .replace("mtllib face.mtl", "mtllib ../x.mtl");
    std::fs::write(&obj, text).unwrap();
    let out = facebem(
        root.path(),
        &[
            "export",
            obj.to_str().unwrap(),
            "--gltf",
            dir.join("o.glb").to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("material library \"../x.mtl\" is outside"),
        "{stderr}"
    );
}
