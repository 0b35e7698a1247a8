//! The cheek puff (issue 11 item 4): air pressure inside the mouth as a traction load on the
//! deep layer of both cheeks, on the bundled default face (MediaPipe, mirror-symmetric) and the
//! decimated ICT face, at full value (slider −1).

mod support;

use face_prep::MuscleKind;
use facebem::report::measure::{FaceLandmarks, flipped_triangles};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

fn model(face: usize) -> FaceModel {
    let mesh = face_prep::load_face(&support::asset(support::FACES[face])).unwrap();
    build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap()
}

/// Canonical-frame displacements in mm of the full cheek puff.
fn puff_mm(m: &FaceModel, lm: &FaceLandmarks) -> Vec<DVec3> {
    let k = m.basis.muscle_index(MuscleKind::CheekPuff.id()).unwrap();
    m.basis.displacements[k]
        .iter()
        .map(|d| lm.canonical_mm(-*d))
        .collect()
}

fn check(face: usize) -> (FaceModel, FaceLandmarks, Vec<DVec3>) {
    let m = model(face);
    let lm = FaceLandmarks::of(&m).unwrap();
    let d = puff_mm(&m, &lm);
    let canon = |v: usize| lm.canonical_mm(m.mesh.vertices[v] - DVec3::ZERO);
    let mouth = (canon(lm.mouth_corner_l as usize) + canon(lm.mouth_corner_r as usize)) * 0.5;
    let half_width =
        0.5 * (canon(lm.mouth_corner_l as usize).x - canon(lm.mouth_corner_r as usize).x);
    // Scaled to 8 mm at its largest, and that is in a cheek, moving out of the face.
    let (top, peak) = d
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.length().total_cmp(&b.1.length()))
        .map(|(i, v)| (i, *v))
        .unwrap();
    let name = support::FACES[face];
    assert!((peak.length() - 8.0).abs() < 0.05, "{name}: peak {peak}");
    let at = canon(top) - mouth;
    assert!(
        at.x.abs() > half_width && at.y.abs() < 3.0 * half_width,
        "{name}: peak at {at} mm from the mouth's centre (half-width {half_width} mm)"
    );
    assert!(
        peak.x * at.x > 0.0,
        "{name}: the cheek moves inward: {peak}"
    );
    assert!(peak.z > 0.0, "{name}: the cheek moves backward: {peak}");
    // The outer contour stays put, nothing flips.
    let field: Vec<DVec3> = {
        let k = m.basis.muscle_index(MuscleKind::CheekPuff.id()).unwrap();
        m.basis.displacements[k].iter().map(|u| -*u).collect()
    };
    let contour = lm.contour_motion_mm(&field);
    assert!(contour <= 0.5, "{name}: contour moves {contour} mm");
    let posed: Vec<DVec3> = m
        .mesh
        .vertices
        .iter()
        .zip(&field)
        .map(|(p, u)| *p + *u)
        .collect();
    let flips = flipped_triangles(&m.mesh.vertices, &posed, &m.mesh.triangles);
    assert!(flips.is_empty(), "{name}: {} triangles flip", flips.len());
    (m, lm, d)
}

#[test]
fn mediapipe_cheeks_puff_out_symmetrically() {
    let (m, lm, d) = check(0);
    // Mirror-symmetric face: each vertex's mirror twin moves as its mirror image.
    let canon: Vec<DVec3> = m
        .mesh
        .vertices
        .iter()
        .map(|p| lm.canonical_mm(*p - DVec3::ZERO))
        .collect();
    let mut worst: f64 = 0.0;
    for (i, p) in canon.iter().enumerate() {
        let mirror = DVec3::new(-p.x, p.y, p.z);
        let j = (0..canon.len())
            .min_by(|&a, &b| {
                canon[a]
                    .distance(mirror)
                    .total_cmp(&canon[b].distance(mirror))
            })
            .unwrap();
        if canon[j].distance(mirror) < 0.01 {
            let twin = DVec3::new(-d[j].x, d[j].y, d[j].z);
            worst = worst.max(d[i].distance(twin));
        }
    }
    assert!(worst < 0.5, "left and right differ by {worst} mm");
}

#[test]
fn ict_2500_cheeks_puff_out() {
    check(1);
}

/// The cheek puff loads only traction-type elements: none of them is a skull element or an
/// element of a displacement-driven control, so every other response is what it was without it.
#[test]
fn cheek_puff_leaves_the_prescribed_elements_alone() {
    let mesh = face_prep::load_face(&support::asset(support::FACES[0])).unwrap();
    let rig = facebem::prep_rig(&mesh, &PipelineParams::default()).unwrap();
    let k = rig.muscle_index(MuscleKind::CheekPuff).unwrap();
    assert!(rig.is_force_control(k));
    let mine: Vec<u32> = rig.muscles[k].elements().collect();
    assert!(mine.len() > 10, "{} elements", mine.len());
    // Other force-driven controls may load the same elements (a traction in their own response).
    for (j, m) in rig.muscles.iter().enumerate() {
        if j != k && !rig.is_force_control(j) {
            assert!(
                m.elements().all(|e| !mine.contains(&e)),
                "shares with {}",
                m.name
            );
        }
    }
    assert!(rig.skull.iter().all(|e| !mine.contains(e)));
}
