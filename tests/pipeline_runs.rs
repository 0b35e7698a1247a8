//! End-to-end runs of the pipeline on the bundled faces with other controls and parameters:
//! cancelling (before the start and during the solve), progress reports, the cache of
//! `load_or_build`, thin and thick shells (back-face offsets) and user-adjusted feature boxes.
//! The per-face physics, export and cache tests are in `tests/end_to_end.rs`.

mod end_to_end_common;
mod support;

use end_to_end_common::thesis_params;
use face_prep::MuscleKind;
use facebem::{Control, FaceModel, PipelineParams, build_face_model};

/// Cancelling before the start stops the pipeline with `Cancelled`.
#[test]
fn cancelled_control_stops_the_pipeline() {
    let (mesh, _) = facebem::input::read_face(&support::asset(support::FACES[0])).unwrap();
    let control = Control::new();
    control.cancel();
    let err = build_face_model(&mesh, &PipelineParams::default(), &control).unwrap_err();
    assert!(matches!(err, facebem::PipelineError::Cancelled), "{err}");
}

/// Progress reaches the caller for every stage, in order.
#[test]
fn progress_reports_every_stage_in_order() {
    use facebem::Stage;
    use std::sync::{Arc, Mutex};
    let (mesh, _) = facebem::input::read_face(&support::asset(support::FACES[0])).unwrap();
    let stages = Arc::new(Mutex::new(Vec::<Stage>::new()));
    let log = stages.clone();
    let control = Control::new().with_progress(move |p| {
        let mut s = log.lock().unwrap();
        if s.last() != Some(&p.stage) {
            s.push(p.stage);
        }
    });
    let model = build_face_model(&mesh, &PipelineParams::default(), &control).unwrap();
    assert_eq!(model.basis.muscle_count(), MuscleKind::ALL.len());
    let seen = stages.lock().unwrap().clone();
    assert_eq!(
        seen,
        vec![
            Stage::Prep,
            Stage::Assembly,
            Stage::Factorisation,
            Stage::Solves,
            Stage::Transfer,
            Stage::Settle
        ]
    );
}

/// Cancelling while the BEM runs (when the factorisation starts) stops it with `Cancelled`.
#[test]
fn cancel_during_the_solve_stops_it() {
    let (mesh, _) = facebem::input::read_face(&support::asset(support::FACES[0])).unwrap();
    let base = Control::new();
    let handle = base.clone();
    let control = base.with_progress(move |p| {
        if p.stage == facebem::Stage::Factorisation {
            handle.cancel();
        }
    });
    let err = build_face_model(&mesh, &PipelineParams::default(), &control).unwrap_err();
    assert!(matches!(err, facebem::PipelineError::Cancelled), "{err}");
}

/// `load_or_build`: computes and saves on a miss, loads on a hit, recomputes over a corrupt file.
#[test]
fn load_or_build_uses_the_cache_and_recovers_from_corruption() {
    use facebem::input::{CacheStatus, load_or_build};
    let (mesh, obj) = facebem::input::read_face(&support::asset(support::FACES[0])).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("face.rig");
    let params = PipelineParams::default();
    let (first, status) =
        load_or_build(&mesh, obj.clone(), &params, &path, &Control::new()).unwrap();
    assert!(
        matches!(
            status,
            CacheStatus::Computed {
                save_error: None,
                ..
            }
        ),
        "{status:?}"
    );
    let (second, status) =
        load_or_build(&mesh, obj.clone(), &params, &path, &Control::new()).unwrap();
    assert_eq!(status, CacheStatus::Loaded);
    assert_eq!(second.basis, first.basis);
    assert_eq!(second.obj_source, obj);
    std::fs::write(&path, b"FACEBEM\x1a garbage").unwrap();
    let (third, status) = load_or_build(&mesh, obj, &params, &path, &Control::new()).unwrap();
    match status {
        CacheStatus::Computed {
            reason,
            save_error: None,
        } => assert!(reason.contains("face.rig"), "{reason}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(third.basis, first.basis);
    assert!(
        facebem::cache::load(&path).is_ok(),
        "the corrupt cache was replaced"
    );
}

/// The MediaPipe face's model with back-face offset `offset` (fraction of the face size).
fn mediapipe_with_offset(offset: f64) -> FaceModel {
    let mesh = face_prep::load_face(&support::asset(support::FACES[0])).unwrap();
    let mut params = thesis_params();
    params.rig.offset = offset;
    build_face_model(&mesh, &params, &Control::new()).unwrap()
}

/// A paper-thin shell (offset 0.05 % of the face size, about 0.1 mm on MediaPipe: front and
/// back nearly coincide everywhere) is a valid, intersection-free solid on which the solve is
/// near-singular (responses about 60 times the muscles' own motion). The report measures it
/// and warns.
#[test]
fn a_near_singular_solve_is_reported() {
    let m = mediapipe_with_offset(0.0005);
    assert_eq!(m.report.shell_self_intersections, 0);
    let a = m.report.response_amplification;
    assert!(a > 5.0 * facebem::SUSPICIOUS_AMPLIFICATION, "{a}");
    let warnings = m.report.warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("near-singular"), "{}", warnings[0]);
    // The measure is what it says: the largest element response over the largest prescribed
    // displacement, per muscle, maximised over muscles.
    let recomputed = (0..m.rig.muscles.len())
        .map(|k| {
            let d = m
                .rig
                .muscle_pattern(k)
                .iter()
                .map(|(_, d)| d.length())
                .fold(0.0, f64::max);
            let u = m.shell_element_response[k]
                .iter()
                .map(|u| u.length())
                .fold(0.0, f64::max);
            u / d
        })
        .fold(0.0, f64::max);
    assert_eq!(a, recomputed);
}

/// Regression (found 2026-11-24 by raising the shell offset): MediaPipe with offset 0.06 had an
/// intersection-free shell on which the solve was near-singular (amplification 466), because
/// the smoothed back face met the front tangentially beside the mouth's knife edge. With the
/// offset's magnitude set from the knife-edge taper after smoothing, it is well-conditioned
/// (measured 1.00).
#[test]
fn thick_shells_stay_well_conditioned() {
    let m = mediapipe_with_offset(0.06);
    assert_eq!(m.report.shell_self_intersections, 0);
    let a = m.report.response_amplification;
    assert!((0.5..2.0).contains(&a), "amplification {a}");
    assert_eq!(m.report.warnings(), Vec::<String>::new());
}

/// User-adjusted feature boxes are a pipeline parameter: the skull and the muscles both come
/// from them (here the mouth box moved down by 8% of the face size, which also lowers the nose
/// box and so changes the skull), on a plain face and on a simplified large face.
#[test]
fn feature_boxes_parameter_places_skull_and_muscles() {
    for face in [support::FACES[0], support::FACES[3]] {
        let mesh = face_prep::load_face(&support::asset(face)).unwrap();
        let auto = facebem::prepare(&mesh, &PipelineParams::default()).unwrap();
        let b = auto.rig.boxes;
        let d = glam::DVec2::new(0.0, -0.08 * auto.rig.face_size);
        let boxes =
            face_prep::FeatureBoxes::derive(b.face, b.eye_l, b.eye_r, b.mouth.translated(d))
                .unwrap();
        let params = PipelineParams {
            boxes: Some(boxes),
            ..PipelineParams::default()
        };
        let edited = facebem::prepare(&mesh, &params).unwrap();
        assert_eq!(edited.rig.boxes, boxes, "{face}");
        let expected = auto.rig.clone().with_boxes(boxes).unwrap();
        assert_eq!(edited.rig.skull, expected.skull, "{face}");
        assert_eq!(edited.rig.muscles, expected.muscles, "{face}");
        assert_ne!(
            edited.rig.skull, auto.rig.skull,
            "{face}: skull follows the boxes"
        );
        let changed = edited
            .rig
            .muscles
            .iter()
            .zip(&auto.rig.muscles)
            .filter(|(a, b)| a.front_chain != b.front_chain)
            .count();
        assert!(changed >= 4, "{face}: only {changed} muscles moved");
        // An inverted box is a typed error, not a panic.
        let mut bad = boxes;
        std::mem::swap(&mut bad.eye_l.min.x, &mut bad.eye_l.max.x);
        let params = PipelineParams {
            boxes: Some(bad),
            ..PipelineParams::default()
        };
        assert!(matches!(
            facebem::prepare(&mesh, &params),
            Err(facebem::PipelineError::Prep(_))
        ));
    }
}
