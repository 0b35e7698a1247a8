//! Muscle files (thesis format), edited muscles, adjusted boxes, serialisation.

use face_prep::{
    FaceRig, MuscleFileError, MuscleKind, PrepError, RigParams, load_face, muscle_file,
};
use glam::DVec2;
use std::path::PathBuf;

fn rig() -> FaceRig {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/ict_narrow_face_dec2500_4loop.obj");
    FaceRig::build(&load_face(&p).unwrap(), &RigParams::default()).unwrap()
}

#[test]
fn round_trip_is_exact_through_a_file() {
    let rig = rig();
    let n = rig.shell.element_count();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("face.muscles");
    muscle_file::save(&path, &rig.muscles).unwrap();
    let back = muscle_file::load(&path, n).unwrap();
    assert_eq!(back, rig.muscles);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(muscle_file::to_string(&back).unwrap(), text);
    assert!(text.starts_with("[Name]\nFrontalis L\n[Size]\n"));
    // No temporary file left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn thesis_file_without_back_chain_reads() {
    let text = "[Name]\nZygomaticus major R\n[Size]\n2\n[Data]\n5\n7\n\n[Name]\nmy muscle\n[Size]\n0\n[Data]\n";
    let m = muscle_file::read_str(text, 10).unwrap();
    assert_eq!(m.len(), 2);
    assert_eq!(m[0].kind, Some(MuscleKind::ZygomaticusMajorR));
    assert_eq!(m[0].front_chain, vec![5, 7]);
    assert!(m[0].back_chain.is_empty());
    assert_eq!(m[1].kind, None);
    assert_eq!(m[1].name, "my muscle");
}

#[test]
fn errors_carry_line_numbers() {
    type Check = Box<dyn Fn(&MuscleFileError) -> bool>;
    let cases: Vec<(&str, Check)> = vec![
        (
            "[Name]\nA\n[Size]\n2\n[Data]\n1\n99\n",
            Box::new(|e| {
                matches!(
                    e,
                    MuscleFileError::IndexOutOfRange {
                        line: 7,
                        index: 99,
                        element_count: 10,
                        ..
                    }
                )
            }),
        ),
        (
            "[Name]\nA\n[Size]\n3\n[Data]\n1\n2\n[Name]\nB\n",
            Box::new(|e| {
                matches!(
                    e,
                    MuscleFileError::SizeMismatch {
                        line: 8,
                        declared: 3,
                        found: 2,
                        ..
                    }
                )
            }),
        ),
        (
            "[Name]\nA\n[Size]\n1\n[Data]\n1\n2\n3\n",
            Box::new(|e| {
                matches!(
                    e,
                    MuscleFileError::SizeMismatch {
                        line: 7,
                        declared: 1,
                        found: 3,
                        ..
                    }
                )
            }),
        ),
        (
            "[Name]\nA\n[Size]\ntwo\n",
            Box::new(|e| matches!(e, MuscleFileError::BadNumber { line: 4, .. })),
        ),
        (
            "hello\n",
            Box::new(|e| matches!(e, MuscleFileError::Unexpected { line: 1, .. })),
        ),
        (
            "[Name]\nA\n[Data]\n1\n",
            Box::new(|e| matches!(e, MuscleFileError::Unexpected { line: 3, .. })),
        ),
        (
            "[Name]\nA\n[Size]\n",
            Box::new(|e| matches!(e, MuscleFileError::Truncated { line: 3, .. })),
        ),
        (
            "[Name]\nA\n[Size]\n2\n[Data]\n4\n4\n",
            Box::new(|e| {
                matches!(
                    e,
                    MuscleFileError::DuplicateElement {
                        line: 7,
                        index: 4,
                        ..
                    }
                )
            }),
        ),
        (
            "[Name]\nA\n[Size]\n1\n[Data]\n-3\n",
            Box::new(|e| matches!(e, MuscleFileError::BadNumber { line: 6, .. })),
        ),
    ];
    for (text, check) in cases {
        let err = muscle_file::read_str(text, 10).unwrap_err();
        assert!(check(&err), "{text:?} gave {err:?}");
        assert!(err.to_string().contains("line "), "{err}");
    }
}

#[test]
fn muscle_file_with_duplicate_names_is_refused() {
    // The same custom name twice, and two names of one standard muscle (display name and id):
    // their sliders and morph targets would share a name.
    let cases = [
        (
            "[Name]\nm\n[Size]\n1\n[Data]\n0\n[Name]\nm\n[Size]\n1\n[Data]\n1\n",
            8,
            2,
            "m",
        ),
        (
            "[Name]\nFrontalis L\n[Size]\n1\n[Data]\n0\n\n[Name]\nfrontalis_l\n[Size]\n0\n[Data]\n",
            9,
            2,
            "frontalis_l",
        ),
    ];
    for (text, line, first, id) in cases {
        match muscle_file::read_str(text, 10) {
            Err(
                e @ MuscleFileError::DuplicateName {
                    line: l,
                    first_line: f,
                    ..
                },
            ) => {
                assert_eq!((l, f), (line, first), "{e}");
                assert!(e.to_string().contains(&format!("both are {id:?}")), "{e}");
                assert!(e.to_string().contains("muscle names must be unique"), "{e}");
            }
            other => panic!("{text:?}: expected a duplicate name, got {other:?}"),
        }
    }
    // Names differing in case are different custom muscles.
    assert_eq!(
        muscle_file::read_str(
            "[Name]\nm\n[Size]\n0\n[Data]\n[Name]\nM\n[Size]\n0\n[Data]\n",
            10
        )
        .unwrap()
        .len(),
        2
    );
}

#[test]
fn rig_with_duplicate_muscle_ids_is_refused() {
    let rig = rig();
    let mut muscles = rig.muscles.clone();
    muscles[3].name = muscles[1].name.clone();
    muscles[3].kind = muscles[1].kind;
    let id = muscles[1].id().to_owned();
    match rig.clone().with_muscles(muscles) {
        Err(e @ PrepError::DuplicateMuscle(_)) => {
            assert_eq!(
                e.to_string(),
                format!("two muscles are named {id:?} (muscle names must be unique)")
            );
        }
        other => panic!("expected a duplicate muscle, got {other:?}"),
    }
}

#[test]
fn muscle_file_with_unwritable_name_is_refused() {
    // A carriage return inside a name: `to_string` could not write it back.
    let err = muscle_file::read_str("[Name]\na\rb\n[Size]\n0\n[Data]\n", 10).unwrap_err();
    assert!(
        matches!(err, MuscleFileError::Unexpected { line: 2, .. }),
        "{err}"
    );
}

#[test]
fn muscle_file_with_utf8_bom_is_read() {
    let text = "[Name]\nZygomaticus major R\n[Size]\n2\n[Data]\n5\n7\n";
    let plain = muscle_file::read_str(text, 10).unwrap();
    let with_bom = muscle_file::read_str(&format!("\u{feff}{text}"), 10).unwrap();
    assert_eq!(with_bom, plain);
    assert_eq!(with_bom[0].kind, Some(MuscleKind::ZygomaticusMajorR));
    // From a file too, with CRLF line ends; line numbers still count from the first line.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bom.muscles");
    std::fs::write(&path, format!("\u{feff}{}", text.replace('\n', "\r\n"))).unwrap();
    assert_eq!(muscle_file::load(&path, 10).unwrap(), plain);
    let bad = format!("\u{feff}{text}[Name]\nx\n[Size]\n1\n[Data]\n99\n");
    let err = muscle_file::read_str(&bad, 10).unwrap_err();
    assert!(
        matches!(err, MuscleFileError::IndexOutOfRange { line: 13, .. }),
        "{err}"
    );
}

#[test]
fn edited_muscles_are_checked_against_the_rig() {
    let rig = rig();
    let mut muscles = rig.muscles.clone();
    // Remove one, shorten one, add a custom one: accepted.
    muscles.remove(9);
    muscles[0].front_chain.truncate(3);
    let custom = face_prep::Muscle {
        name: "custom".into(),
        kind: None,
        front_chain: vec![rig.muscles[4].front_chain[0], rig.muscles[4].front_chain[1]],
        back_chain: vec![],
    };
    muscles.push(custom);
    let text = muscle_file::to_string(&muscles).unwrap();
    let edited = rig
        .clone()
        .with_muscles(muscle_file::read_str(&text, rig.shell.element_count()).unwrap())
        .unwrap();
    assert_eq!(edited.muscles.len(), rig.muscles.len());
    assert_eq!(
        edited.muscle_index(MuscleKind::DepressorLabiiInferiorisR),
        None
    );
    assert_eq!(edited.muscle_pattern(edited.muscles.len() - 1).len(), 2);
    // A skull element in a muscle is refused, naming it.
    let skull_back = *rig
        .skull
        .iter()
        .find(|&&e| rig.shell.tags[e as usize] == face_prep::ElementTag::Back)
        .unwrap();
    let mut bad = rig.muscles.clone();
    bad[2].back_chain.push(skull_back);
    match rig.clone().with_muscles(bad) {
        Err(PrepError::InvalidMuscle { element, .. }) => assert_eq!(element, skull_back),
        other => panic!("{other:?}"),
    }
    // A front element in a back chain is refused.
    let mut bad = rig.muscles.clone();
    bad[2].back_chain.push(0);
    assert!(matches!(
        rig.clone().with_muscles(bad),
        Err(PrepError::InvalidMuscle { element: 0, .. })
    ));
}

#[test]
fn adjusted_boxes_move_the_muscles_and_skull() {
    let rig = rig();
    let mut boxes = rig.boxes;
    // Grow the forehead box down to the nose: more back elements become skull.
    boxes.skull.min.y = boxes.nose.center().y;
    let moved = rig.clone().with_boxes(boxes).unwrap();
    assert!(moved.skull.len() > rig.skull.len());
    let skull: std::collections::HashSet<u32> = moved.skull.iter().copied().collect();
    for m in &moved.muscles {
        assert!(m.elements().all(|e| !skull.contains(&e)), "{}", m.name);
    }
    // Moving the mouth box moves the mentalis start.
    let mut boxes = rig.boxes;
    boxes.mouth = boxes
        .mouth
        .translated(DVec2::new(0.0, -0.1 * boxes.mouth.height()));
    let derived =
        face_prep::FeatureBoxes::derive(boxes.face, boxes.eye_l, boxes.eye_r, boxes.mouth).unwrap();
    let moved = rig.clone().with_boxes(derived).unwrap();
    let k = MuscleKind::MentalisL.index();
    assert_ne!(moved.muscles[k].front_chain, rig.muscles[k].front_chain);
    // An empty box is refused.
    let mut bad = rig.boxes;
    bad.nose.max.x = bad.nose.min.x;
    assert!(matches!(
        rig.clone().with_boxes(bad),
        Err(PrepError::InvalidBox { name: "FBNose", .. })
    ));
    // Same boxes → the same muscles on the face loaded and built again.
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/ict_narrow_face_dec2500_4loop.obj");
    let fresh = FaceRig::build(&load_face(&p).unwrap(), &RigParams::default())
        .unwrap()
        .with_boxes(derived)
        .unwrap();
    assert_eq!(fresh.muscles, moved.muscles);
}

#[test]
fn rig_serialises_and_deserialises_identically() {
    let rig = rig();
    // postcard is the format of the pipeline's on-disk cache (exact for f64).
    let bytes = postcard::to_stdvec(&rig).unwrap();
    let back: FaceRig = postcard::from_bytes(&bytes).unwrap();
    assert!(back == rig, "rig changed through serialisation");
}

#[test]
fn invalid_params_are_named() {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/mediapipe_canonical_4loop.obj");
    let face = load_face(&p).unwrap();
    let params = RigParams {
        offset: -0.1,
        ..Default::default()
    };
    assert!(matches!(
        FaceRig::build(&face, &params),
        Err(PrepError::InvalidParam { name: "offset", .. })
    ));
}
