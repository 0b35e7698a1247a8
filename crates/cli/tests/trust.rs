//! A rig past the documented trust thresholds (`facebem::model::distrust`, issue 30) is refused
//! by `pose` and `export` with one line naming the cause and writes nothing; `--force` writes
//! it, with the cause as a warning. Never a morph target that moves the skin by metres.

use std::path::Path;
use std::process::{Command, Output};

use facebem::{Control, FaceModel, PipelineParams, build_face_model, cache};

fn default_model() -> FaceModel {
    let face = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("assets/mediapipe_canonical_4loop.obj");
    let mesh = face_prep::load_face(&face).unwrap();
    build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap()
}

fn facebem(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(args)
        .output()
        .unwrap()
}

fn largest_mm(m: &FaceModel, k: usize) -> f64 {
    m.basis.displacements[k]
        .iter()
        .map(|d| d.length())
        .fold(0.0, f64::max)
        * m.rig.mm_per_unit()
}

/// Scales control `k`'s field so that its largest motion is `target_mm`.
fn scale_to(m: &mut FaceModel, k: usize, target_mm: f64) {
    let factor = target_mm / largest_mm(m, k);
    for d in &mut m.basis.displacements[k] {
        *d *= factor;
    }
}

/// The largest shortening, mm, of a muscle band control (strain × length).
fn shortening_mm(m: &FaceModel, k: usize) -> Option<f64> {
    facebem::model::shortening_mm(m, m.rig.muscles[k].kind?)
}

#[test]
fn a_rig_that_moves_the_skin_by_metres_is_refused_unless_forced() {
    let mut m = default_model();
    let healthy = facebem::model::distrust(&m);
    assert!(
        healthy.is_empty(),
        "the default face is trusted: {healthy:?}"
    );
    let k = m.basis.muscle_index("zygomaticus_major_l").unwrap();
    scale_to(&mut m, k, 5000.0);
    let causes = facebem::model::distrust(&m);
    assert_eq!(causes.len(), 1, "{causes:?}");
    assert!(
        causes[0].starts_with("zygomaticus_major_l: moves the skin 5000 mm"),
        "{causes:?}"
    );
    let dir = tempfile::tempdir().unwrap();
    let rig = dir.path().join("metres.rig");
    cache::save(&rig, &m).unwrap();
    let rig = rig.to_str().unwrap();
    let glb = dir.path().join("out.glb");
    let obj = dir.path().join("out.obj");
    for (args, output) in [
        (vec!["export", rig, "--gltf", glb.to_str().unwrap()], &glb),
        (
            vec![
                "pose",
                rig,
                "--preset",
                "happy",
                "-o",
                obj.to_str().unwrap(),
            ],
            &obj,
        ),
    ] {
        let out = facebem(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        for needle in [
            "not trustworthy",
            "zygomaticus_major_l",
            "5000 mm",
            "--force",
        ] {
            assert!(err.contains(needle), "{args:?}: {err}");
        }
        assert!(!output.exists(), "{args:?} wrote {}", output.display());
        let mut forced = args.clone();
        forced.push("--force");
        let out = facebem(&forced);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{forced:?}: {err}");
        assert!(
            err.lines().any(|l| l.starts_with(
                "warning: untrustworthy rig, written because of --force: zygomaticus_major_l"
            )),
            "{forced:?}: {err}"
        );
        assert!(output.exists(), "{forced:?} wrote nothing");
    }
}

#[test]
fn a_control_moving_three_times_its_shortening_is_not_trusted() {
    let mut m = default_model();
    // The muscle band with the smallest shortening, so that 3.5 times it stays below the
    // 60 mm limit and the shortening rule is the one that refuses it.
    let (k, shortening) = (0..m.basis.muscle_count())
        .filter_map(|k| shortening_mm(&m, k).map(|s| (k, s)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    assert!(
        3.5 * shortening < facebem::model::MAX_MOTION_OUTSIDE_JAW_MM,
        "shortening {shortening:.1} mm"
    );
    let id = m.basis.muscle_ids[k].clone();
    scale_to(&mut m, k, 2.9 * shortening);
    let causes = facebem::model::distrust(&m);
    assert!(causes.is_empty(), "2.9 times is trusted: {causes:?}");
    scale_to(&mut m, k, 3.5 * shortening);
    let causes = facebem::model::distrust(&m);
    assert_eq!(causes.len(), 1, "{causes:?}");
    assert!(
        causes[0].starts_with(&format!("{id}: moves the skin"))
            && causes[0].contains("3.5 times its muscle's shortening"),
        "{causes:?}"
    );
}

#[test]
fn a_jaw_may_move_further_than_a_muscle_but_not_past_its_own_limit() {
    let mut m = default_model();
    let k = m.basis.muscle_index("jaw_open").unwrap();
    scale_to(&mut m, k, 80.0);
    assert!(facebem::model::distrust(&m).is_empty());
    scale_to(&mut m, k, 120.0);
    let causes = facebem::model::distrust(&m);
    assert_eq!(causes.len(), 1, "{causes:?}");
    assert!(causes[0].contains("trusted up to 100 mm"), "{causes:?}");
}
