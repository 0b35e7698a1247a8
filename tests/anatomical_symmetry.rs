//! The anatomical muscle model (the default) on every bundled face: left and right responses
//! mirror each other, the same face at another resolution (subdivided, decimated, simulated on
//! a copy of another size or made another way) moves alike, and the thesis mode keeps its rule.
//! In millimetres, each face scaled by its detected unit; the per-face motion figures are in
//! `tests/anatomical_muscles.rs`.

mod anatomical_common;
mod support;

use std::sync::OnceLock;

use anatomical_common::{contraction, landmarks, max_mm, model};
use face_prep::MuscleKind;
use face_prep::muscle_model::MuscleModel;
use facebem::report::measure::{FaceLandmarks, SurfacePoint};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

/// On the mirror-symmetric MediaPipe face, left and mirrored right responses agree within
/// 0.5 mm at every vertex.
#[test]
fn mediapipe_left_and_right_mirror_within_half_a_millimetre() {
    let m = model(0);
    let lm = landmarks(m);
    let c: Vec<DVec3> = lm.canonical_points(&m.mesh.vertices);
    let mirror_of: Vec<usize> = c
        .iter()
        .map(|p| {
            let q = DVec3::new(-p.x, p.y, p.z);
            (0..c.len())
                .min_by(|&a, &b| {
                    c[a].distance_squared(q)
                        .total_cmp(&c[b].distance_squared(q))
                })
                .unwrap()
        })
        .collect();
    for kind in MuscleKind::ALL
        .into_iter()
        .filter(|k| k.side() == face_prep::Side::Left)
    {
        let l = contraction(m, kind);
        let r = contraction(m, kind.mirror());
        let worst = (0..c.len())
            .map(|v| {
                let a = lm.canonical_mm(l[v]);
                let b = lm.canonical_mm(r[mirror_of[v]]);
                (a - DVec3::new(-b.x, b.y, b.z)).length()
            })
            .fold(0.0, f64::max);
        assert!(worst <= 0.5, "{}: {worst:.3} mm", kind.id());
    }
}

/// Left and mirrored right responses at the mouth corners and brows of a nearly symmetric face:
/// the largest difference over every paired control, in mm.
fn landmark_asymmetry_mm(face: usize) -> f64 {
    landmark_asymmetry_at_mm(
        face,
        &[Landmarks::Corners, Landmarks::Brows, Landmarks::InnerBrows],
    )
}

/// [`landmark_asymmetry_mm`] at the given landmarks only.
fn landmark_asymmetry_at_mm(face: usize, which: &[Landmarks]) -> f64 {
    landmark_asymmetry_of(model(face), face, which)
}

/// [`landmark_asymmetry_at_mm`] of a model (`face` labels the report).
fn landmark_asymmetry_of(m: &FaceModel, face: usize, which: &[Landmarks]) -> f64 {
    let lm = landmarks(m);
    let all = [
        (
            SurfacePoint::vertex(lm.mouth_corner_l),
            SurfacePoint::vertex(lm.mouth_corner_r),
        ),
        (lm.brow_point_l, lm.brow_point_r),
        (lm.brow_inner_point_l, lm.brow_inner_point_r),
    ];
    let kinds = [Landmarks::Corners, Landmarks::Brows, Landmarks::InnerBrows];
    let pairs: Vec<(SurfacePoint, SurfacePoint)> = all
        .iter()
        .zip(kinds)
        .filter(|(_, k)| which.contains(k))
        .map(|(&p, _)| p)
        .collect();
    let mut worst: f64 = 0.0;
    for kind in MuscleKind::ALL
        .into_iter()
        .filter(|k| k.side() == face_prep::Side::Left)
    {
        let l = contraction(m, kind);
        let r = contraction(m, kind.mirror());
        for &(vl, vr) in &pairs {
            let a = lm.canonical_mm(vl.sample(&l));
            let b = lm.canonical_mm(vr.sample(&r));
            let d = (a - DVec3::new(-b.x, b.y, b.z)).length();
            if d > 0.5 {
                eprintln!(
                    "{} face {face}: landmark {:?}/{:?} differs by {d:.2} mm ({:.2} / {:.2} mm)",
                    kind.id(),
                    vl.corners,
                    vr.corners,
                    a.length(),
                    b.length()
                );
            }
            worst = worst.max(d);
        }
    }
    worst
}

/// ICT-FaceKit's mesh is mirror-symmetric to 0.05 mm and simulated on a mirror-symmetric copy
/// (`facebem::copy::simplify`): every paired control mirrors within 1 mm at the mouth corners
/// and brows (issue 10: the copy was asymmetric and the left and right smiles differed by up to
/// 90 %).
#[test]
fn ict_13k_left_and_right_mirror_within_a_millimetre_at_corners_and_brows() {
    assert_eq!(
        model(3).report.simplify_path,
        Some(facebem::copy::simplify::SimplifyPath::Mirrored)
    );
    let worst = landmark_asymmetry_mm(3);
    eprintln!("ICT 13k: worst landmark asymmetry {worst:.3} mm");
    assert!(worst <= 1.0, "{worst:.3} mm");
}

/// The decimated ICT face is only nearly symmetric (its simplified copy is not mirrored), but
/// every paired control mirrors within 1 mm at the brow points above the eye centres (issue
/// 10; measured 0.91 mm, the frontales, 10.0 / 9.2 mm; 0.71 mm before the forehead was relaxed,
/// when the right brow was measured on a one-vertex peak; read at the nearest vertices
/// instead, 3.9 mm apart).
/// Known gaps, measured: the inner brows differ by up to 2.5 mm (the corrugators, 1.35 / 3.85
/// mm; the decimated eye loops' medial ends are not mirror images).
#[test]
fn ict_2500_left_and_right_mirror_within_a_millimetre_at_the_brows() {
    let worst = landmark_asymmetry_at_mm(1, &[Landmarks::Brows]);
    eprintln!("ICT 2500: worst brow asymmetry {worst:.3} mm");
    assert!(worst <= 1.0, "{worst:.3} mm");
}

/// A copy of another size must not break the smile. Regression (found this session, not yet
/// fixed): ICT 2500 simulated on an 1 800-triangle copy (`facebem --target-triangles 1800`, or
/// `muscle_probe --max-triangles 1000 --target 1800`) gets a strip of sliver triangles along
/// its upper lip that moves 7–14 mm against the zygomaticus's pull; as the largest motion it sets
/// the force muscle's scale, and the left corner moves 1.3 mm, nothing else more than 5.4 mm.
/// The rig is flagged (`an_1800_triangle_copy_of_ict_2500_is_flagged`); a remeshed copy keeps
/// the smile (`remeshed_ict_2500_on_an_1800_triangle_copy_keeps_its_smile`).
/// Since the modiolus is pinned ([`face_prep::modiolus`]) the slivers no longer set the scale.
#[test]
fn zygomaticus_ict_2500_left_on_an_1800_triangle_copy() {
    let mesh = face_prep::load_face(&support::asset(support::FACES[1])).unwrap();
    let mut params = PipelineParams::default();
    params.large_face.target_triangles = 1800;
    params.large_face.max_triangles = 1000;
    let m = build_face_model(&mesh, &params, &Control::new()).unwrap();
    let lm = landmarks(&m);
    let field = contraction(&m, MuscleKind::ZygomaticusMajorL);
    let corner_mm = lm.canonical_mm(field[lm.mouth_corner_l as usize]).length();
    let max = max_mm(&lm, &field);
    eprintln!("ICT 2500 on 1800 triangles: left corner {corner_mm:.2} mm, largest {max:.2} mm");
    assert!(
        (7.0..=15.0).contains(&corner_mm),
        "corner moves {corner_mm:.2} mm"
    );
    assert!(
        corner_mm >= 0.8 * max,
        "corner {corner_mm:.2} of {max:.2} mm"
    );
}

/// Issue 10's symmetry criterion at ICT 2500's mouth corners (within 1 mm). Regression: with
/// the zygomaticus a plain force the mirrored corner motions differed by up to 5.1 mm (9.2 /
/// 13.7 mm); with the modiolus pinned but pulled along each side's own modiolus elements'
/// plane, 1.24 mm (the copy's asymmetric fold tilted the planes; [`face_prep::modiolus::SKIN_STEP_MM`]).
#[test]
fn ict_2500_left_and_right_mirror_within_a_millimetre_at_the_corners() {
    let worst = landmark_asymmetry_at_mm(1, &[Landmarks::Corners]);
    eprintln!("ICT 2500: worst corner asymmetry {worst:.3} mm");
    assert!(worst <= 1.0, "{worst:.3} mm");
}

/// `MuscleModel::Thesis` keeps the thesis's rule: its patterns are exactly the chain rule of
/// `face_prep::muscles::muscle_pattern`, and the anatomical patterns are not.
#[test]
fn thesis_mode_keeps_the_chain_rule() {
    let mesh = face_prep::load_face(&support::asset(support::FACES[0])).unwrap();
    let mut params = PipelineParams::default();
    params.rig.muscle_model = MuscleModel::Thesis;
    let thesis = facebem::prep_rig(&mesh, &params).unwrap();
    for k in 0..thesis.muscles.len() {
        assert_eq!(
            thesis.muscle_pattern(k),
            face_prep::muscles::muscle_pattern(&thesis.shell, &thesis.muscles[k])
        );
    }
    let anatomical = facebem::prep_rig(&mesh, &PipelineParams::default()).unwrap();
    assert_ne!(anatomical.muscle_pattern(4), thesis.muscle_pattern(4));
}

/// The face split 1 → 4 (a vertex at every edge midpoint, the input's vertices first).
fn subdivided(mesh: &face_prep::FaceMesh) -> face_prep::FaceMesh {
    let mut vertices = mesh.vertices.clone();
    let mut midpoint = std::collections::HashMap::new();
    let mut mid = |a: u32, b: u32, vertices: &mut Vec<DVec3>| -> u32 {
        *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
            vertices.push(0.5 * (vertices[a as usize] + vertices[b as usize]));
            (vertices.len() - 1) as u32
        })
    };
    let mut triangles = Vec::new();
    for &[a, b, c] in &mesh.triangles {
        let ab = mid(a, b, &mut vertices);
        let bc = mid(b, c, &mut vertices);
        let ca = mid(c, a, &mut vertices);
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    face_prep::FaceMesh::from_triangles(&vertices, &triangles).unwrap()
}

/// Which landmarks [`landmark_motion_agrees`] compares.
#[derive(Clone, Copy, PartialEq)]
enum Landmarks {
    /// The mouth corners under the zygomatici.
    Corners,
    /// The brow points (above the eye centres) under the frontales.
    Brows,
    /// The inner brow points (above the eyes' medial ends) under the corrugators.
    InnerBrows,
}

/// Mouth-corner (zygomaticus major) or brow (frontalis) displacements of two models of the
/// same face at the given landmarks agree within 15 % (vector difference against the larger).
fn landmark_motion_agrees(
    a: (&FaceModel, &FaceLandmarks),
    b: (&FaceModel, &FaceLandmarks),
    which: Landmarks,
    what: &str,
) {
    let cases = match which {
        Landmarks::Corners => [
            (
                MuscleKind::ZygomaticusMajorL,
                SurfacePoint::vertex(a.1.mouth_corner_l),
                SurfacePoint::vertex(b.1.mouth_corner_l),
            ),
            (
                MuscleKind::ZygomaticusMajorR,
                SurfacePoint::vertex(a.1.mouth_corner_r),
                SurfacePoint::vertex(b.1.mouth_corner_r),
            ),
        ],
        Landmarks::Brows => [
            (MuscleKind::FrontalisL, a.1.brow_point_l, b.1.brow_point_l),
            (MuscleKind::FrontalisR, a.1.brow_point_r, b.1.brow_point_r),
        ],
        Landmarks::InnerBrows => [
            (
                MuscleKind::CorrugatorSuperciliiL,
                a.1.brow_inner_point_l,
                b.1.brow_inner_point_l,
            ),
            (
                MuscleKind::CorrugatorSuperciliiR,
                a.1.brow_inner_point_r,
                b.1.brow_inner_point_r,
            ),
        ],
    };
    let mut worst = (0.0, "");
    for (kind, va, vb) in cases {
        let da = a.1.canonical_mm(va.sample(&contraction(a.0, kind)));
        let db = b.1.canonical_mm(vb.sample(&contraction(b.0, kind)));
        let rel = (da - db).length() / da.length().max(db.length());
        eprintln!(
            "{what} {}: {:.2} / {:.2} mm, difference {:.0} %",
            kind.id(),
            da.length(),
            db.length(),
            100.0 * rel
        );
        if rel > worst.0 {
            worst = (rel, kind.id());
        }
    }
    assert!(
        worst.0 <= 0.15,
        "{what} {}: {:.0} %",
        worst.1,
        100.0 * worst.0
    );
}

/// MediaPipe split 1 → 4 (3 408 triangles, so simulated on a simplified copy), computed once,
/// with its landmarks: the original's corner vertices (the subdivision keeps the input's
/// vertices first) and its own brow points (the same points: the eye loops' centres and tops do
/// not change under midpoint subdivision).
fn mediapipe_subdivided() -> &'static (FaceModel, FaceLandmarks) {
    static FINE: OnceLock<(FaceModel, FaceLandmarks)> = OnceLock::new();
    FINE.get_or_init(|| {
        let base = model(0);
        let lm = landmarks(base);
        let fine = build_face_model(
            &subdivided(&base.mesh),
            &PipelineParams::default(),
            &Control::new(),
        )
        .unwrap();
        let own = landmarks(&fine);
        let fine_lm = FaceLandmarks {
            canonical_from_input: fine.rig.canonical_from_input,
            mm_per_unit: fine.rig.mm_per_unit(),
            brow_point_l: own.brow_point_l,
            brow_point_r: own.brow_point_r,
            ..lm
        };
        (fine, fine_lm)
    })
}

/// Resolution independence (issue 10) at the brows: MediaPipe and its 1 → 4 subdivided copy
/// raise the brow points alike (measured 10.9 / 10.8 mm). Read at the nearest vertex instead,
/// they seemed 14 % apart (9.6 / 11.3 mm): a vertex 4 mm off the point on the coarse face.
#[test]
fn mediapipe_and_its_subdivided_copy_raise_the_brows_alike() {
    let base = model(0);
    let (fine, fine_lm) = mediapipe_subdivided();
    landmark_motion_agrees(
        (base, &landmarks(base)),
        (fine, fine_lm),
        Landmarks::Brows,
        "MediaPipe 1 -> 4",
    );
}

/// Resolution independence (issue 10) at the mouth corners, MediaPipe against its subdivided
/// copy. Known gap: 13.7 / 9.6 mm (34 %; 8.0 mm, 45 %, before the copy kept the corner
/// vertices). The elastic solve is not the cause: the subdivided face simulated whole (`cargo
/// run --release -p facebem-tools --bin muscle_probe -- sub.obj --max-triangles 4000`, 78 s) moves its
/// corners 13.7 mm; its 1 500-triangle copy now keeps the corner vertex, but the margin beside
/// it is coarser than MediaPipe's own.
/// Regression (issue 10): 9.5 against 13.7 mm while the zygomaticus was a plain force; the
/// pinned modiolus moves both about 13.7 mm.
#[test]
fn mediapipe_and_its_subdivided_copy_agree_at_the_corners() {
    let base = model(0);
    let (fine, fine_lm) = mediapipe_subdivided();
    landmark_motion_agrees(
        (base, &landmarks(base)),
        (fine, fine_lm),
        Landmarks::Corners,
        "MediaPipe 1 -> 4",
    );
}

/// Resolution independence (issue 10) at the brows: the decimated ICT face against the 13k
/// original (measured: left 10.0 / 10.1 mm, right 9.2 / 10.1 mm; at the nearest vertices the
/// right one seemed 34 % apart, 7.3 / 10.9 mm).
#[test]
fn ict_2500_and_13k_raise_the_brows_alike() {
    let (coarse, fine) = (model(1), model(3));
    landmark_motion_agrees(
        (coarse, &landmarks(coarse)),
        (fine, &landmarks(fine)),
        Landmarks::Brows,
        "ICT 2500 / 13k",
    );
}

/// Resolution independence (issue 10) at the mouth corners, ICT 2500 against 13k.
/// Before the modiolus was pinned: left corner 9.2 / 13.8 mm (43 %), right corner 13.7 / 13.8
/// mm but 19 % apart in direction.
/// Regression: the pinned modiolus ([`face_prep::modiolus`]) closed the gap.
#[test]
fn ict_2500_and_13k_agree_at_the_corners() {
    let (coarse, fine) = (model(1), model(3));
    landmark_motion_agrees(
        (coarse, &landmarks(coarse)),
        (fine, &landmarks(fine)),
        Landmarks::Corners,
        "ICT 2500 / 13k",
    );
}

/// ICT 2500 simulated on a remeshed copy (`--copy remesh`, [`facebem::copy::CopyMethod`])
/// of `target` triangles.
fn remeshed_ict_2500(target: usize) -> FaceModel {
    let mesh = face_prep::load_face(&support::asset(support::FACES[1])).unwrap();
    let mut params = PipelineParams::default();
    params.large_face.method = facebem::copy::CopyMethod::Remesh;
    params.large_face.target_triangles = target;
    params.large_face.max_triangles = target.min(1500);
    build_face_model(&mesh, &params, &Control::new()).unwrap()
}

/// The 1 800-triangle failure above, on a remeshed copy: no slivers, and the left smile keeps
/// its corner (the collapse copy: 1.3 mm).
#[test]
fn remeshed_ict_2500_on_an_1800_triangle_copy_keeps_its_smile() {
    let m = remeshed_ict_2500(1800);
    let lm = landmarks(&m);
    for kind in [MuscleKind::ZygomaticusMajorL, MuscleKind::ZygomaticusMajorR] {
        let field = contraction(&m, kind);
        let corner = if kind == MuscleKind::ZygomaticusMajorL {
            lm.mouth_corner_l
        } else {
            lm.mouth_corner_r
        };
        let corner_mm = lm.canonical_mm(field[corner as usize]).length();
        let max = max_mm(&lm, &field);
        eprintln!(
            "remeshed ICT 2500 on 1800 triangles, {}: corner {corner_mm:.2} mm, largest {max:.2} mm",
            kind.id()
        );
        assert!(
            (7.0..=15.0).contains(&corner_mm),
            "{}: corner moves {corner_mm:.2} mm",
            kind.id()
        );
    }
}

/// ICT 2500's corners mirror on its remeshed copy too (0.51 mm; 0.82 mm before the modiolus
/// was pinned, when the collapse copy's were 5.1 mm apart).
#[test]
fn remeshed_ict_2500_mirrors_at_the_corners() {
    let m = remeshed_ict_2500(1500);
    let worst = landmark_asymmetry_of(&m, 1, &[Landmarks::Corners]);
    let brows = landmark_asymmetry_of(&m, 1, &[Landmarks::Brows]);
    eprintln!("remeshed ICT 2500: worst corner asymmetry {worst:.3} mm, brows {brows:.3} mm");
    assert!(worst <= 1.0, "{worst:.3} mm");
}

/// The 1 800-triangle failure above is flagged: `rig` and `info` warn that a few elements set
/// a force muscle's scale (its slivers moved 7–14 mm against the pull).
#[test]
fn an_1800_triangle_copy_of_ict_2500_is_flagged() {
    let mesh = face_prep::load_face(&support::asset(support::FACES[1])).unwrap();
    let mut params = PipelineParams::default();
    params.large_face.target_triangles = 1800;
    params.large_face.max_triangles = 1000;
    let m = build_face_model(&mesh, &params, &Control::new()).unwrap();
    let report = &m.report;
    eprintln!(
        "ICT 2500 on 1800 triangles: force peak ratio {:.2} ({})",
        report.force_peak_ratio, report.force_peak_control
    );
    assert!(
        report.force_peak_ratio > facebem::SUSPICIOUS_FORCE_PEAK,
        "{:.2}",
        report.force_peak_ratio
    );
    let warning = report
        .warnings()
        .into_iter()
        .find(|w| w.contains("largest motion is"))
        .expect("a warning");
    assert!(warning.starts_with(&report.force_peak_control), "{warning}");
}
