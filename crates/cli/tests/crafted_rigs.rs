//! Rig files are validated after decoding, not just checksummed (issue 13): a crafted rig with
//! a recomputed checksum but NaN, absurd or short fields, or indices out of range, is refused
//! with a clear error by the loader and by `facebem pose`, which writes nothing.

use facebem::{Control, FaceModel, PipelineParams, build_face_model, cache};
use std::path::Path;

fn model() -> FaceModel {
    let mesh = face_prep::load_face(
        &Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
            .join("assets/mediapipe_canonical_4loop.obj"),
    )
    .unwrap();
    build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap()
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
        let path = dir.path().join(format!("{name}.rig"));
        std::fs::write(&path, cache::to_bytes(&m).unwrap()).unwrap();
        let err = cache::load(&path).unwrap_err();
        assert!(
            matches!(err, cache::CacheError::Invalid { .. }),
            "{name}: {err}"
        );
        assert!(err.to_string().contains(needle), "{name}: {err}");
        let out_obj = dir.path().join(format!("{name}.obj"));
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
    // The untouched model passes.
    let path = dir.path().join("good.rig");
    cache::save(&path, &good).unwrap();
    assert!(cache::load(&path).is_ok());
}
