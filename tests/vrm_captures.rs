//! Issue 33: the VRM emotions on the ICT narrow face against the sums of ICT-FaceKit's captured
//! expressions (`tests/data/calibration/ict_head_deltas/`) that stand for them, by the cosine
//! of the whole displacement field: the exported target, as a user gets it (the table:
//! `cargo run --release -p facebem-tools --bin fit_recipes`).

use std::path::Path;

use facebem::export::gltf::{GltfParams, named_targets};
use facebem::report::captures::{captured, on_input_vertices_mm};
use facebem::report::measure::cosine;
use facebem::{Control, PipelineParams, build_face_model};
use glam::DVec3;

/// `happy` = mouthSmile + cheekSquint, `angry` = browDown + eyeSquint + mouthPress, `sad` =
/// browInnerUp + mouthFrown (left and right each), the sums issue 33 names. Measured when the
/// angry preset was fitted to its sum (2026-11-29): happy 0.82, angry 0.59 (the hand-made
/// preset 0.19), sad 0.80; angry 0.73 with the orbicularis oculi's brow part (browDown 0.52 →
/// 0.82). Issue 33 asks for 0.75 each: angry is short of it, mostly at the chin (mouthPress
/// 0.58).
#[test]
fn vrm_emotions_move_like_the_summed_captures() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let narrow = face_prep::load_face(&root.join("assets/ict_narrow_face_4loop.obj")).unwrap();
    let model = build_face_model(&narrow, &PipelineParams::default(), &Control::new()).unwrap();
    let named = named_targets(&model.basis, &model.gltf_params(&GltfParams::default())).unwrap();
    let field = |name: &str| -> Vec<DVec3> {
        let written = named
            .same_as
            .iter()
            .find(|(left_out, _)| left_out == name)
            .map_or(name, |(_, same)| same.as_str());
        let (_, f) = named
            .targets
            .iter()
            .find(|(n, _)| n == written)
            .unwrap_or_else(|| panic!("no target {name}"));
        on_input_vertices_mm(&narrow.input_to_vertex, f)
    };
    let dir = root.join("tests/data/calibration/ict_head_deltas");
    let n = narrow.input_to_vertex.len();
    let sums: [(&str, &[&str], f64); 3] = [
        ("happy", &["mouthSmile", "cheekSquint"], 0.80),
        ("angry", &["browDown", "eyeSquint", "mouthPress"], 0.71),
        (
            "sad",
            &["browInnerUp", "mouthFrownLeft", "mouthFrownRight"],
            0.78,
        ),
    ];
    for (emotion, parts, floor) in sums {
        let mut capture = vec![DVec3::ZERO; n];
        for part in parts {
            let names: Vec<String> =
                if part.ends_with("Left") || part.ends_with("Right") || *part == "browInnerUp" {
                    vec![part.to_string()]
                } else {
                    vec![format!("{part}Left"), format!("{part}Right")]
                };
            for name in names {
                let c = captured(&dir, &name, n)
                    .unwrap()
                    .unwrap_or_else(|| panic!("no capture {name}"));
                capture.iter_mut().zip(&c).for_each(|(a, b)| *a += *b);
            }
        }
        let cos = cosine(&field(emotion), &capture);
        eprintln!("{emotion}: cosine {cos:.3}");
        assert!(cos >= floor, "{emotion}: cosine {cos:.3} under {floor}");
    }
}
