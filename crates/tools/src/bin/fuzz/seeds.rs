//! The seed corpus: the bundled MediaPipe face as each target kind, plus the bad inputs of
//! `tests/bad_inputs/`.

use std::path::{Path, PathBuf};

use facebem::face_prep::{FaceMesh, muscle_file};
use facebem::{Control, PipelineParams, cache};

use crate::opts::Opts;

pub(crate) fn face_path() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("assets/mediapipe_canonical_4loop.obj")
}

/// `tests/bad_inputs/`: every hostile file found so far.
pub(crate) fn bad_inputs_dir() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("tests/bad_inputs")
}

/// The files of `tests/bad_inputs/` with one of these extensions (name, bytes), sorted.
pub(crate) fn bad_inputs(kinds: &[&str]) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(bad_inputs_dir())
        .into_iter()
        .flatten()
        .flatten()
    {
        let p = e.path();
        let ext = p.extension().and_then(|x| x.to_str()).unwrap_or("");
        if kinds.contains(&ext)
            && let Ok(bytes) = std::fs::read(&p)
        {
            let name = p.file_name().unwrap_or_default().to_string_lossy();
            out.push((name.into_owned(), bytes));
        }
    }
    out.sort();
    out
}

pub(crate) fn ext(target: &str, case: &[u8]) -> &'static str {
    match target {
        "obj" => "obj",
        "gltf" if case.starts_with(b"glTF") => "glb",
        "gltf" => "gltf",
        "rig" => "rig",
        _ => "muscles",
    }
}

/// One GLB (positions f32, indices u32) of a face mesh, plus a .gltf with a data URI and one
/// with an external `face.bin`.
pub(crate) fn gltf_seeds(face: &FaceMesh) -> (Vec<u8>, String, String, Vec<u8>) {
    let mut bin = Vec::new();
    for p in &face.vertices {
        for c in p.to_array() {
            bin.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    let pos_len = bin.len();
    for t in &face.triangles {
        for i in t {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let json = |uri: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"children":[1]}},{{"mesh":0,"scale":[1,1,1]}}],"meshes":[{{"name":"face","primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"mode":4}}]}}],"buffers":[{{{uri}"byteLength":{}}}],"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{pos_len},"byteStride":12}},{{"buffer":0,"byteOffset":{pos_len},"byteLength":{}}}],"accessors":[{{"bufferView":0,"byteOffset":0,"componentType":5126,"count":{},"type":"VEC3","min":[-9,-9,-9],"max":[9,9,9]}},{{"bufferView":1,"componentType":5125,"count":{},"type":"SCALAR"}}]}}"#,
            bin.len(),
            bin.len() - pos_len,
            face.vertices.len(),
            face.triangles.len() * 3
        )
    };
    let mut j = json("").into_bytes();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut glb = b"glTF".to_vec();
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&((12 + 8 + j.len() + 8 + bin.len()) as u32).to_le_bytes());
    glb.extend_from_slice(&(j.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&j);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    let b64 = base64(&bin);
    let data = json(&format!(
        r#""uri":"data:application/octet-stream;base64,{b64}","#
    ));
    let external = json(r#""uri":"face.bin","#);
    (glb, data, external, bin)
}

/// The face OBJ with a `vt` (planar projection) and a `vn` line per vertex and `f a/a/a`
/// corners, so the texture-coordinate and normal paths of the reader and exports run.
pub(crate) fn textured_obj(text: &str) -> String {
    let mut out = String::new();
    let mut faces = String::new();
    let mut positions: Vec<[f64; 3]> = Vec::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.first() {
            Some(&"f") => {
                let corners: Vec<String> =
                    words[1..].iter().map(|c| format!("{c}/{c}/{c}")).collect();
                faces.push_str(&format!("f {}\n", corners.join(" ")));
            }
            Some(&"v") => {
                let c: Vec<f64> = words[1..].iter().filter_map(|w| w.parse().ok()).collect();
                positions.push([
                    c.first().copied().unwrap_or(0.0),
                    c.get(1).copied().unwrap_or(0.0),
                    c.get(2).copied().unwrap_or(0.0),
                ]);
                out.push_str(line);
                out.push('\n');
            }
            _ => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    let (lo, hi) = positions
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        });
    for p in &positions {
        let u = (p[0] - lo[0]) / (hi[0] - lo[0]).max(1e-9);
        let v = (p[1] - lo[1]) / (hi[1] - lo[1]).max(1e-9);
        out.push_str(&format!("vt {u:.6} {v:.6}\n"));
    }
    for p in &positions {
        let len = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt().max(1e-9);
        out.push_str(&format!(
            "vn {:.6} {:.6} {:.6}\n",
            p[0] / len,
            p[1] / len,
            p[2] / len
        ));
    }
    out + &faces
}

fn base64(b: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in b.chunks(3) {
        let v = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            s.push(if k <= c.len() {
                T[(v >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}

pub(crate) fn prepare_seeds(o: &Opts) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let seeds = o.out.join("seeds");
    std::fs::create_dir_all(&seeds).map_err(|e| err(&e))?;
    std::fs::create_dir_all(o.out.join("work")).map_err(|e| err(&e))?;
    let face_text = std::fs::read_to_string(face_path()).map_err(|e| err(&e))?;
    let face = FaceMesh::from_obj_str(&face_text).map_err(|e| err(&e))?;
    let corpus = bad_inputs_dir();
    let kinds: &[&str] = match o.target.as_str() {
        "obj" => &["obj"],
        "gltf" => &["gltf", "glb"],
        "muscles" => &["muscles"],
        _ => &[],
    };
    for e in std::fs::read_dir(&corpus).map_err(|e| err(&e))?.flatten() {
        let p = e.path();
        if p.extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| kinds.contains(&x))
        {
            let name = p.file_name().unwrap_or_default();
            std::fs::copy(&p, seeds.join(name)).map_err(|e| err(&e))?;
        }
    }
    match o.target.as_str() {
        "obj" => {
            std::fs::write(seeds.join("face.obj"), &face_text).map_err(|e| err(&e))?;
            let textured = textured_obj(&face_text);
            std::fs::write(seeds.join("face_vt_vn.obj"), textured).map_err(|e| err(&e))?;
        }
        "gltf" => {
            let (glb, data, external, bin) = gltf_seeds(&face);
            std::fs::write(seeds.join("face.glb"), glb).map_err(|e| err(&e))?;
            std::fs::write(seeds.join("face_data.gltf"), data).map_err(|e| err(&e))?;
            std::fs::write(seeds.join("face_external.gltf"), external).map_err(|e| err(&e))?;
            let work = o.out.join("work");
            std::fs::write(work.join("face.bin"), &bin).map_err(|e| err(&e))?;
            let fifo = work.join("fifo.bin");
            if !fifo.exists() {
                let _ = std::process::Command::new("mkfifo").arg(&fifo).status();
            }
            // A file one level up that must never be read.
            std::fs::write(o.out.join("face.bin"), &bin).map_err(|e| err(&e))?;
        }
        _ => {
            let model =
                facebem::build_face_model(&face, &PipelineParams::default(), &Control::new())
                    .map_err(|e| err(&e))?;
            let mut model = model;
            model.obj_source = Some(face_text);
            let bytes = cache::to_bytes(&model).map_err(|e| err(&e))?;
            std::fs::write(o.out.join("model.rig"), &bytes).map_err(|e| err(&e))?;
            if o.target == "rig" {
                std::fs::write(seeds.join("face.rig"), &bytes).map_err(|e| err(&e))?;
            } else {
                let text = muscle_file::to_string(&model.rig.muscles).map_err(|e| err(&e))?;
                std::fs::write(seeds.join("face.muscles"), text).map_err(|e| err(&e))?;
            }
        }
    }
    Ok(())
}
