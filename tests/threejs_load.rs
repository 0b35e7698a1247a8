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
    let (named, _) = facebem::expressions::for_rig(Default::default(), model.muscle_ids());
    assert_eq!(
        names.len(),
        named.len() + 2 * model.basis.muscle_count() + facebem::expressions::presets::ALL.len() - 1
    );
    // morphTargetDictionary resolves the ARKit and VRM names, which come first.
    for name in ["happy", "mouthSmileLeft", "mouthSmileRight", "neutral"] {
        assert!(names.contains(&name), "{name}: {names:?}");
    }
    for (k, n) in named.iter().enumerate() {
        assert_eq!(names[k], n.expression.name);
    }
    for id in model.muscle_ids() {
        assert!(
            names.contains(&format!("{id}_contract").as_str()),
            "{names:?}"
        );
        assert!(names.contains(&format!("{id}_relax").as_str()), "{names:?}");
    }
    assert!(names.contains(&"preset_happy"), "{names:?}");
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
    let readme = std::fs::read_to_string(support::root().join("README.md")).unwrap();
    let start = readme.find("```js\n").expect("the README has a js block") + "```js\n".len();
    let end = start + readme[start..].find("```").unwrap();
    let snippet: String = readme[start..end]
        .lines()
        .map(|l| l.trim_start())
        .collect::<Vec<_>>()
        .join("\n");
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
