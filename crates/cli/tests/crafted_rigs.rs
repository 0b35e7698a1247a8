//! Rig files are validated after decoding, not just checksummed (issue 13): a crafted rig with
//! a recomputed checksum but NaN, absurd or short fields, or indices out of range, is refused
//! with a clear error by the loader and by `facebem pose`, which writes nothing.

use facebem::{Control, FaceModel, PipelineParams, build_face_model, cache};
use std::path::Path;

/// The rig of the MediaPipe face with its OBJ text, computed once for the tests of this file.
fn model() -> FaceModel {
    static MODEL: std::sync::OnceLock<FaceModel> = std::sync::OnceLock::new();
    MODEL
        .get_or_init(|| {
            let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
                .join("assets/mediapipe_canonical_4loop.obj");
            let (mesh, obj_source) = facebem::input::read_face(&path).unwrap();
            let mut m =
                build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
            m.obj_source = obj_source;
            m
        })
        .clone()
}

/// Saves `m` (a crafted model) with a valid checksum as `{name}.rig` in `dir`; the loader must
/// refuse it as invalid naming `needle`, and `facebem pose` must fail in one line, writing
/// nothing.
fn assert_crafted_rig_refused(dir: &Path, name: &str, m: &FaceModel, needle: &str) {
    let path = dir.join(format!("{name}.rig"));
    std::fs::write(&path, cache::to_bytes(m).unwrap()).unwrap();
    let err = cache::load(&path).unwrap_err();
    assert!(
        matches!(err, cache::CacheError::Invalid { .. }),
        "{name}: {err}"
    );
    assert!(err.to_string().contains(needle), "{name}: {err}");
    let out_obj = dir.join(format!("{name}.obj"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(["pose", path.to_str().unwrap(), "--preset", "happy", "-o"])
        .arg(&out_obj)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{name}: {stderr}");
    assert!(stderr.contains("is not a valid rig"), "{name}: {stderr}");
    assert!(!out_obj.exists(), "{name}");
}

type Craft = (&'static str, fn(&mut FaceModel), &'static str);

#[test]
fn crafted_rigs_with_valid_checksums_are_refused() {
    let good = model();
    let dir = tempfile::tempdir().unwrap();
    let crafts: [Craft; 8] = [
        (
            "nan_neutral",
            |m| m.basis.neutral[0].x = f64::NAN,
            "basis neutral vertex 0 is not finite",
        ),
        (
            "huge_displacement",
            |m| m.basis.displacements[2][5].y = 1e300,
            "displacement of muscle 2, value 5",
        ),
        (
            "short_displacement",
            |m| {
                m.basis.displacements[3].pop();
            },
            "displacement of muscle 3 has 467 entries, expected 468",
        ),
        (
            "dropped_muscle",
            |m| {
                m.basis.muscle_ids.pop();
            },
            // (the default face has one muscle per standard control)
            "muscle displacements has",
        ),
        (
            "chain_out_of_range",
            |m| m.rig.muscles[0].front_chain.push(1 << 30),
            "refers to 1073741824",
        ),
        (
            "triangle_out_of_range",
            |m| m.mesh.triangles[7][1] = 468,
            "face triangles: entry 22 refers to 468",
        ),
        (
            "nan_shell_response",
            |m| m.shell_element_response[1][0].z = f64::INFINITY,
            "shell element response of muscle 1",
        ),
        (
            "bad_poisson",
            |m| m.params.poisson = 0.7,
            "Poisson ratio 0.7",
        ),
    ];
    for (name, craft, needle) in crafts {
        let mut m = good.clone();
        craft(&mut m);
        assert_crafted_rig_refused(dir.path(), name, &m, needle);
    }
    // The untouched model passes.
    let path = dir.path().join("good.rig");
    cache::save(&path, &good).unwrap();
    assert!(cache::load(&path).is_ok());
}

/// A rig is held to the rules of the face reader and the exports when it is read: its OBJ text
/// (non-finite numbers, a face referring to a later `v` line), its muscle ids (unique: they name
/// the sliders and morph targets) and its other numbers (length unit, feature boxes, rig
/// parameters), so a rig that loads always exports.
#[test]
fn crafted_rigs_that_could_not_export_are_refused_at_read() {
    let good = model();
    let dir = tempfile::tempdir().unwrap();
    let crafts: [Craft; 7] = [
        (
            "nan_texture_coordinate_in_obj_text",
            |m| m.obj_source.as_mut().unwrap().push_str("vt nan nan\n"),
            "holds a number that is not finite",
        ),
        (
            "infinite_w_in_obj_text",
            |m| {
                // Line 4, the first `v` line: 1e300 / 1e-300 overflows.
                let text = m.obj_source.take().unwrap();
                let mut lines: Vec<&str> = text.lines().collect();
                lines[3] = "v 1e300 0 0 1e-300";
                m.obj_source = Some(lines.join("\n") + "\n");
            },
            "its OBJ text: OBJ line 4: \"v 1e300 0 0 1e-300\" holds a number that is not finite",
        ),
        (
            "vertex_after_its_face_in_obj_text",
            |m| {
                let text = m.obj_source.take().unwrap();
                let mut lines: Vec<&str> = text.lines().collect();
                let last_v = lines.iter().rposition(|l| l.starts_with("v ")).unwrap();
                let v = lines.remove(last_v);
                lines.push(v);
                m.obj_source = Some(lines.join("\n") + "\n");
            },
            "refers to a `v` line that does not come before the face",
        ),
        (
            "duplicate_muscle_id",
            |m| m.basis.muscle_ids[3] = m.basis.muscle_ids[1].clone(),
            "two muscles are named",
        ),
        (
            "nan_length_unit",
            |m| m.rig.unit = face_prep::units::LengthUnit::Scaled(f64::NAN),
            "length unit of NaN m per unit",
        ),
        (
            "infinite_feature_box",
            |m| m.rig.boxes.mouth.max.y = f64::INFINITY,
            "feature box mouth is not finite",
        ),
        (
            "nan_rig_parameter",
            |m| m.rig.params.thickness = f64::NAN,
            "rig parameter thickness = NaN is not finite",
        ),
    ];
    for (name, craft, needle) in crafts {
        let mut m = good.clone();
        craft(&mut m);
        assert_crafted_rig_refused(dir.path(), name, &m, needle);
    }
    // The untouched model with its OBJ text passes and exports.
    let path = dir.path().join("good.rig");
    cache::save(&path, &good).unwrap();
    let back = cache::load(&path).unwrap();
    assert!(
        back.gltf_bytes(&facebem::export::GltfParams::default())
            .is_ok()
    );
}
