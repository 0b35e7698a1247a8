//! The README's three.js recipe, tested: the GLB of the default face loaded by three.js's own
//! GLTFLoader (node, `tests/support/three_load.mjs`) is a face-sized mesh in metres with its
//! morph targets by name, the replaceable skin material (metalness 0), no animation by default
//! and the source's licence.

mod support;

use facebem::export::GltfParams;
use facebem::{Control, PipelineParams, build_face_model};

/// The default face's model and its GLB (default export) written in `dir`.
fn default_face_glb(dir: &std::path::Path) -> (facebem::FaceModel, std::path::PathBuf) {
    let (mesh, obj) = facebem::input::read_face(&support::asset(support::FACES[0])).unwrap();
    let mut model = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
    model.obj_source = obj;
    let glb = dir.join("face.glb");
    model.write_gltf(&glb, &GltfParams::default()).unwrap();
    (model, glb)
}

/// The flat `key` arrays of three.js's report as f64.
fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Issue 34, lean exports: the default face's default GLB is at most 0.62 MB (606 572 bytes; 0.58
/// MB before the cheek raiser's targets moved the whole cheek, docs/benchmarks.md) and its
/// `--compress` one (EXT_meshopt_compression) at most 0.35 MB; both pass the Khronos validator,
/// three.js loads both (the compressed one with its MeshoptDecoder) with every ARKit name in
/// its dictionary, and the decoded compressed file holds the plain one's numbers to the
/// precision `--compress` states: each neutral coordinate within 2⁻¹⁹ of the largest of its
/// axis, each delta within 2⁻¹⁵ of its target's largest on that axis (half a step of a signed
/// K-bit mantissa whose exponent rounds the largest up to a power of two).
#[test]
fn default_and_compressed_exports_are_small_and_load_alike_in_threejs() {
    let dir = tempfile::tempdir().unwrap();
    let (model, glb) = default_face_glb(dir.path());
    let packed = dir.path().join("packed.glb");
    let params = GltfParams {
        compress: true,
        ..GltfParams::default()
    };
    model.write_gltf(&packed, &params).unwrap();
    let (plain_bytes, packed_bytes) = (
        std::fs::metadata(&glb).unwrap().len(),
        std::fs::metadata(&packed).unwrap().len(),
    );
    println!("default GLB {plain_bytes} bytes, --compress {packed_bytes} bytes");
    assert!(plain_bytes <= 620_000, "{plain_bytes}");
    assert!(packed_bytes <= 350_000, "{packed_bytes}");
    let mut reports = vec![];
    for file in [&glb, &packed] {
        support::assert_valid(file);
        match support::load_with_threejs(file) {
            support::Validation::NodeMissing => {
                eprintln!("SKIPPED three.js load: node is not installed");
                return;
            }
            support::Validation::Report(r) => reports.push(r),
        }
    }
    let (plain, decoded) = (&reports[0]["meshes"][0], &reports[1]["meshes"][0]);
    let (named, _) = facebem::expressions::for_rig(Default::default(), model.muscle_ids());
    for m in [plain, decoded] {
        let names = m["morphTargets"].as_array().unwrap();
        for e in &named {
            if e.expression.set == facebem::expressions::NameSet::Arkit {
                assert!(
                    names.iter().any(|n| n == e.expression.name),
                    "{}",
                    e.expression.name
                );
            }
        }
    }
    assert_eq!(plain["morphTargets"], decoded["morphTargets"]);
    let within = |a: &[f64], b: &[f64], bits: i32| {
        assert_eq!(a.len(), b.len());
        for axis in 0..3 {
            let largest = a
                .iter()
                .skip(axis)
                .step_by(3)
                .fold(0.0f64, |m, x| m.max(x.abs()));
            for i in (axis..a.len()).step_by(3) {
                let tolerance = largest * 2f64.powi(1 - bits) + 1e-12;
                assert!(
                    (a[i] - b[i]).abs() <= tolerance,
                    "{i}: {} vs {}",
                    a[i],
                    b[i]
                );
            }
        }
    };
    within(
        &floats(&plain["positions"]),
        &floats(&decoded["positions"]),
        20,
    );
    let (p, d) = (
        plain["morphPositions"].as_array().unwrap(),
        decoded["morphPositions"].as_array().unwrap(),
    );
    assert_eq!(p.len(), d.len());
    for (a, b) in p.iter().zip(d) {
        within(&floats(a), &floats(b), 16);
    }
}

#[test]
fn threejs_gltfloader_gets_a_face_sized_mesh_with_named_morph_targets() {
    let dir = tempfile::tempdir().unwrap();
    let (model, glb) = default_face_glb(dir.path());
    let report = match support::load_with_threejs(&glb) {
        support::Validation::NodeMissing => {
            eprintln!("SKIPPED three.js load: node is not installed");
            return;
        }
        support::Validation::Report(r) => r,
    };
    assert_eq!(report["revision"], "187", "{report}");
    let meshes = report["meshes"].as_array().unwrap();
    assert_eq!(meshes.len(), 1, "{report}");
    let m = &meshes[0];
    assert_eq!(m["vertices"], 468);
    let names: Vec<&str> = m["morphTargets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    // The default export: the ARKit and VRM names (those that repeat none before them), in
    // order; morphTargetDictionary resolves every ARKit name the rig makes.
    let (named, _) = facebem::expressions::for_rig(Default::default(), model.muscle_ids());
    let written: Vec<&str> = named
        .iter()
        .map(|n| n.expression.name)
        .filter(|n| !["blinkLeft", "blinkRight", "neutral"].contains(n))
        .collect();
    assert_eq!(names, written);
    for name in ["happy", "mouthSmileLeft", "mouthSmileRight", "eyeBlinkLeft"] {
        assert!(names.contains(&name), "{name}: {names:?}");
    }
    assert!(
        m["morphTargetInfluences"]
            .as_array()
            .unwrap()
            .iter()
            .all(|w| w.as_f64() == Some(0.0))
    );
    assert_eq!(m["material"]["type"], "MeshStandardMaterial");
    assert_eq!(m["material"]["name"], facebem::export::MATERIAL_NAME);
    assert_eq!(m["material"]["metalness"], 0.0);
    // Metres: a face 12 to 30 cm tall, so a camera at the usual (0, 0, 5) sees it whole.
    let height = report["size"][1].as_f64().unwrap();
    assert!((0.12..=0.30).contains(&height), "height {height} m");
    assert_eq!(report["animations"].as_array().unwrap().len(), 0);
    assert!(
        report["copyright"]
            .as_str()
            .is_some_and(|c| c.contains("MediaPipe")),
        "{report}"
    );
}

/// The README's three.js snippet (its `js` block), run as written on the default face's GLB by
/// three.js's own GLTFLoader: it finds the mesh by name and sets mouthSmileLeft to 1, and only
/// that. Regression (issue 34): the scene was named `face` too, so three.js renamed the mesh
/// `face_1` and `getObjectByName('face')` returned the scene, which has no morph targets.
#[test]
fn the_readmes_threejs_snippet_runs() {
    let snippet = support::readme_block("js");
    assert!(snippet.contains("getObjectByName('face')"), "{snippet}");
    let dir = tempfile::tempdir().unwrap();
    let (_, glb) = default_face_glb(dir.path());
    let js = dir.path().join("snippet.js");
    std::fs::write(&js, &snippet).unwrap();
    let report = match support::load_with_threejs_running(&glb, &js) {
        support::Validation::NodeMissing => {
            eprintln!("SKIPPED three.js snippet: node is not installed");
            return;
        }
        support::Validation::Report(r) => r,
    };
    let m = &report["meshes"][0];
    assert_eq!(m["name"], "face", "{report}");
    let names = m["morphTargets"].as_array().unwrap();
    let smile = names.iter().position(|n| n == "mouthSmileLeft").unwrap();
    let weights: Vec<f64> = m["morphTargetInfluences"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_f64().unwrap())
        .collect();
    assert_eq!(weights.len(), names.len());
    for (k, w) in weights.iter().enumerate() {
        assert_eq!(*w, if k == smile { 1.0 } else { 0.0 }, "{}", names[k]);
    }
}
