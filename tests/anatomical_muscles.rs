//! The anatomical muscle model (the default) held to human motion, in millimetres, on every
//! bundled face scaled by its detected unit, and to the captured ICT-FaceKit expressions on
//! `assets/ict_narrow_face_4loop.obj` (`tests/data/calibration`, MIT).
//!
//! Human 3D motion capture (Jorge Jr. et al., Braz J Otorhinolaryngol 2012, 12 adults): smile
//! mouth corner 9.3 ± 2.8 mm (range 6.5–12.1), up and out; brow raise 10.6 ± 2.5 mm.
//! `cargo run --release -p facebem-tools --bin calibrate` prints every figure these tests check.

//!
//! Left/right symmetry, resolution independence and simulated copies of other sizes are held
//! in `tests/anatomical_symmetry.rs`.

mod anatomical_common;
mod support;

use anatomical_common::{contraction, landmarks, max_mm, model};
use face_prep::MuscleKind;
use facebem::report::measure::{
    SurfacePoint, cosine, elevation_deg, flipped_by, flipped_triangles,
};
use facebem::{Control, FaceModel, PipelineParams, build_face_model, expressions::presets};
use glam::DVec3;

/// Displacement field of a preset.
fn preset_field(m: &FaceModel, name: &str) -> Vec<DVec3> {
    assert!(presets::find(name).is_some(), "{name} is a preset");
    support::named_field(m, name)
}

/// Zygomaticus major at full contraction, the corner on its own side: 7–15 mm, 25°–70° above
/// the horizontal, outward, and at least `share` of the largest displacement on the face.
fn zygomaticus_moves_its_corner(face: usize, kind: MuscleKind, share: f64) {
    let m = model(face);
    let lm = landmarks(m);
    let field = contraction(m, kind);
    let (corner, lateral) = match kind.side() {
        face_prep::Side::Left => (lm.mouth_corner_l, 1.0),
        face_prep::Side::Right => (lm.mouth_corner_r, -1.0),
        face_prep::Side::Center => panic!("the zygomaticus is paired"),
    };
    let d = lm.canonical_mm(field[corner as usize]);
    let elevation = elevation_deg(d, lateral);
    let max = max_mm(&lm, &field);
    eprintln!(
        "{} {}: corner {:.2} mm at {elevation:.1}°, largest {max:.2} mm",
        support::FACES[face],
        kind.id(),
        d.length()
    );
    assert!(
        (7.0..=15.0).contains(&d.length()),
        "corner moves {:.2} mm",
        d.length()
    );
    assert!(
        (25.0..=70.0).contains(&elevation),
        "elevation {elevation:.1}°"
    );
    assert!(d.x * lateral > 0.0, "outward: {d:?}");
    assert!(
        d.length() >= share * max,
        "corner {:.2} of largest {max:.2}",
        d.length()
    );
}

/// Frontalis at full contraction: the brow point above each eye centre rises 7–13 mm; the
/// outer contour (the forehead's top edge) moves less than the brow.
fn frontalis_raises_the_brow(face: usize) {
    let m = model(face);
    let lm = landmarks(m);
    for (kind, brow) in [
        (MuscleKind::FrontalisL, lm.brow_point_l),
        (MuscleKind::FrontalisR, lm.brow_point_r),
    ] {
        let field = contraction(m, kind);
        let up = lm.canonical_mm(brow.sample(&field)).y;
        let contour = lm.contour_motion_mm(&field);
        eprintln!(
            "{} {}: brow up {up:.2} mm, contour {contour:.3} mm",
            support::FACES[face],
            kind.id()
        );
        assert!((7.0..=13.0).contains(&up), "brow rises {up:.2} mm");
        assert!(contour < up, "contour {contour:.3} vs brow {up:.2}");
    }
}

/// Every muscle band at full contraction and every preset, by name.
fn bands_and_presets(m: &FaceModel) -> Vec<(String, Vec<DVec3>)> {
    let mut fields: Vec<(String, Vec<DVec3>)> = MuscleKind::ALL
        .iter()
        .filter(|k| k.band().is_some())
        .map(|&k| (k.id().to_string(), contraction(m, k)))
        .collect();
    fields.extend(
        presets::ALL
            .iter()
            .map(|p| (p.name.to_string(), preset_field(m, p.name))),
    );
    fields
}

/// Every muscle at full contraction and every preset leaves the outer contour within 0.5 mm.
fn contour_stays_put(face: usize) {
    let m = model(face);
    let lm = landmarks(m);
    // The jaw moves its own part of the contour (tests/jaw.rs holds the rest of it still).
    let fields = bands_and_presets(m);
    for (name, field) in &fields {
        let c = lm.contour_motion_mm(field);
        assert!(
            c <= 0.5,
            "{}: {name} moves the contour {c:.3} mm",
            support::FACES[face]
        );
    }
}

/// Each muscle's largest displacement lies in its anatomical region: within the band's
/// half-width plus 10 mm of the origin–insertion segment (plus its spread past the insertion),
/// in the canonical front plane.
fn largest_motion_in_the_muscles_region(face: usize) {
    let m = model(face);
    let lm = landmarks(m);
    let mm = lm.mm_per_unit;
    for kind in MuscleKind::ALL {
        let field = contraction(m, kind);
        let (v, _) = field
            .iter()
            .enumerate()
            .map(|(i, d)| (i, d.length()))
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        let p = lm
            .canonical_from_input
            .transform_point3(m.mesh.vertices[v])
            .truncate();
        let Some(a) = face_prep::muscle_kind::attachment(kind, &m.rig.boxes) else {
            continue; // not a muscle band
        };
        let seg = a.insertion - a.origin;
        let t = ((p - a.origin).dot(seg) / seg.length_squared()).clamp(0.0, 1.0);
        let dist_mm = p.distance(a.origin + seg * t) * mm;
        let allowed = a.half_width_mm + a.spread_mm + 10.0;
        assert!(
            dist_mm <= allowed,
            "{} {}: largest motion {dist_mm:.1} mm from its line (allowed {allowed:.1})",
            support::FACES[face],
            kind.id()
        );
    }
}

/// Flipped triangles (normal reversed) of any muscle at full contraction or preset lie only
/// at the lips: within 12 mm of the mouth loop in the front plane.
fn flips_only_at_the_lips(face: usize) {
    let m = model(face);
    let lm = landmarks(m);
    let c: Vec<DVec3> = lm.canonical_points(&m.mesh.vertices);
    let mouth: Vec<glam::DVec2> = lm
        .loops
        .mouth
        .iter()
        .map(|&v| c[v as usize].truncate())
        .collect();
    // The muscle bands; the eyelid controls fold the lids, checked in tests/eyelids.rs.
    let mut fields: Vec<Vec<DVec3>> = MuscleKind::ALL
        .iter()
        .filter(|k| k.band().is_some())
        .map(|&k| contraction(m, k))
        .collect();
    fields.extend(presets::ALL.iter().map(|p| preset_field(m, p.name)));
    for field in &fields {
        let posed: Vec<DVec3> = m
            .mesh
            .vertices
            .iter()
            .zip(field)
            .map(|(a, b)| *a + *b)
            .collect();
        for t in flipped_triangles(&m.mesh.vertices, &posed, &m.mesh.triangles) {
            let centre = m.mesh.triangles[t as usize]
                .iter()
                .map(|&v| c[v as usize])
                .sum::<DVec3>()
                .truncate()
                / 3.0;
            let d = face_prep::muscle_model::distance_to_loop(centre, &mouth) * lm.mm_per_unit;
            assert!(
                d <= 12.0,
                "{}: triangle {t} flips {d:.1} mm from the lips",
                support::FACES[face]
            );
        }
    }
}

macro_rules! face_tests {
    ($name:ident, $face:expr) => {
        mod $name {
            #[test]
            fn frontalis_raises_the_brow() {
                super::frontalis_raises_the_brow($face);
            }
            #[test]
            fn contour_stays_put() {
                super::contour_stays_put($face);
            }
            #[test]
            fn largest_motion_in_the_muscles_region() {
                super::largest_motion_in_the_muscles_region($face);
            }
        }
    };
}

face_tests!(mediapipe, 0);
face_tests!(ict_2500, 1);
face_tests!(lee_perry_smith, 2);
face_tests!(ict_13k, 3);

#[test]
fn mediapipe_flips_only_at_the_lips() {
    flips_only_at_the_lips(0);
}

/// Issue 10: no triangle of the default face turns over at any muscle band's full contraction
/// or at any preset. Regression: the zygomatici turned 5 of MediaPipe's 852 triangles over at
/// the mouth corners (the lower lip's top surface overtaken by its margin), happy 4 and laugh
/// 8, before the lips were relaxed where they would turn over (`facebem::settle::untangle`).
#[test]
fn the_default_face_turns_no_triangle_over() {
    let m = model(0);
    let cases = bands_and_presets(m);
    assert!(cases.len() >= 20, "{} cases", cases.len());
    for (name, field) in cases {
        let flipped = flipped_by(&m.mesh.vertices, &field, &m.mesh.triangles);
        assert!(
            flipped.is_empty(),
            "{name}: triangles {flipped:?} turn over"
        );
    }
}

/// Issue 10 on the other three faces. Regressions: ICT 2500's frontalis turned 2–3 triangles
/// over on the brow line, 87 mm from the lips (one-vertex peaks of its response on the
/// 1 500-triangle copy), before the shell's vertex values were fitted linearly
/// (`bem_core::element_to_vertex_linear`) and the forehead relaxed; ICT 13k's `disgust` turned
/// 16 upper-lid triangles over, 81 mm from the lips (the frontalis lengthened by 0.3), before
/// the half-lengthened direction was relaxed over the lids (a pass replaced since by
/// `settle::project_at_the_lids`);
/// earlier, ICT 13k turned one 22 mm and Lee Perry-Smith one 14 mm from the lips.
#[test]
fn other_faces_flip_only_at_the_lips() {
    for face in 1..4 {
        flips_only_at_the_lips(face);
    }
}

#[test]
fn zygomaticus_ict_13k_left() {
    zygomaticus_moves_its_corner(3, MuscleKind::ZygomaticusMajorL, 0.8);
}

#[test]
fn zygomaticus_ict_13k_right() {
    zygomaticus_moves_its_corner(3, MuscleKind::ZygomaticusMajorR, 0.8);
}

/// Lee Perry-Smith: both corners move 12.6 mm, the largest motion on the face. Regression: its
/// simplified copy collapsed the corner vertices along the mouth loop, and they moved 9.8 mm at
/// 46° and 9.0 mm at 52° (77 % and 71 %) with the largest motion on the lower lip 5 mm medial;
/// the copy now keeps the input corners it holds (`pipeline::kept_mouth_corners`).
#[test]
fn zygomaticus_lee_perry_smith_share() {
    zygomaticus_moves_its_corner(2, MuscleKind::ZygomaticusMajorL, 0.8);
    zygomaticus_moves_its_corner(2, MuscleKind::ZygomaticusMajorR, 0.8);
}

/// Lee Perry-Smith without the share: 7–15 mm, 25°–70°, outward (the share is the known gap
/// above).
#[test]
fn zygomaticus_lee_perry_smith_moves_its_corners_up_and_out() {
    zygomaticus_moves_its_corner(2, MuscleKind::ZygomaticusMajorL, 0.0);
    zygomaticus_moves_its_corner(2, MuscleKind::ZygomaticusMajorR, 0.0);
}

/// ICT 2500, right: 13.7 mm at 60°, the largest motion on the face (its rolled-in corner
/// follows the copy's margin, `pipeline::missing_mouth_corners`; hanging between the lips it
/// moved 12.7 mm).
#[test]
fn zygomaticus_ict_2500_right() {
    zygomaticus_moves_its_corner(1, MuscleKind::ZygomaticusMajorR, 0.8);
}

/// MediaPipe: 13.7 mm at 44°, the largest motion on the face.
#[test]
fn zygomaticus_mediapipe_both_sides() {
    zygomaticus_moves_its_corner(0, MuscleKind::ZygomaticusMajorL, 0.8);
    zygomaticus_moves_its_corner(0, MuscleKind::ZygomaticusMajorR, 0.8);
}

/// Regression (issue 10): as a force pulling on the lips, the zygomaticus moved the decimated
/// ICT face's left corner 9.2 mm (77 % of the largest motion), the right one 13.7 mm; pinning
/// the modiolus ([`face_prep::modiolus`]) moves both about 13.7 mm, the largest motion.
#[test]
fn zygomaticus_ict_2500_left() {
    zygomaticus_moves_its_corner(1, MuscleKind::ZygomaticusMajorL, 0.8);
}

/// The same face rotated arbitrarily, scaled ×10 (so detected in mm instead of cm) and with
/// its vertex order shuffled gives the same happy field, within 2 % RMS of its largest
/// displacement.
fn happy_is_invariant_to_how_the_file_is_written(face: usize) {
    let base = model(face);
    let happy = preset_field(base, "happy");
    let n = base.mesh.vertices.len();
    let support::Rewritten {
        mesh,
        new_of_old,
        input_from_original,
    } = support::rewritten(&base.mesh);
    let mut params = PipelineParams::default();
    let in_cm = base.rig.unit == face_prep::units::LengthUnit::Centimetre;
    if !in_cm {
        // Model units have no tenth that `auto` would find: state it.
        params.rig.units = face_prep::units::Units::Fixed(face_prep::units::LengthUnit::Scaled(
            base.rig.mm_per_unit() / 10.0,
        ));
    }
    let other = build_face_model(&mesh, &params, &Control::new()).unwrap();
    if in_cm {
        assert_eq!(other.rig.unit, face_prep::units::LengthUnit::Millimetre);
    }
    let field = preset_field(&other, "happy");
    let back = input_from_original.matrix3.inverse();
    let mut sum = 0.0;
    for (old, d) in happy.iter().enumerate() {
        let e = back * field[new_of_old[old] as usize] - *d;
        sum += e.length_squared();
    }
    let rms = (sum / n as f64).sqrt();
    let max = happy.iter().map(|d| d.length()).fold(0.0, f64::max);
    eprintln!(
        "face {face}: happy RMS difference {:.2e} of largest {max:.4}",
        rms
    );
    assert!(
        rms <= 0.02 * max,
        "RMS difference {rms:.4} of largest {max:.4}"
    );
}

/// MediaPipe, simulated whole but for its peeled mouth corners.
#[test]
fn mediapipe_happy_is_invariant_to_how_the_file_is_written() {
    happy_is_invariant_to_how_the_file_is_written(0);
}

/// The decimated ICT face, simulated on a simplified copy in canonical order
/// (`facebem::copy::simplify`); issue 10 measured 3–13 % RMS before.
#[test]
fn ict_2500_happy_is_invariant_to_how_the_file_is_written() {
    happy_is_invariant_to_how_the_file_is_written(1);
}

/// ICT 13k, simulated on a mirrored half.
#[test]
fn ict_13k_happy_is_invariant_to_how_the_file_is_written() {
    happy_is_invariant_to_how_the_file_is_written(3);
}

/// Lee Perry-Smith, a scan with no mirror symmetry, simulated on a simplified copy in
/// canonical order.
#[test]
fn lee_perry_smith_happy_is_invariant_to_how_the_file_is_written() {
    happy_is_invariant_to_how_the_file_is_written(2);
}

/// Against the captured ICT expressions on the same mesh: cosine similarity of the whole
/// displacement fields ≥ 0.7 and the landmark magnitude ratio within 0.7–1.4.
#[test]
fn ict_responses_match_captured_expressions() {
    let m = model(3);
    let lm = landmarks(m);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/calibration");
    let captured = |name: &str| -> Vec<DVec3> {
        let c = face_prep::load_face(&dir.join(format!("ict_narrow_face_{name}.obj"))).unwrap();
        assert_eq!(c.vertices.len(), m.mesh.vertices.len());
        c.vertices
            .iter()
            .zip(&m.mesh.vertices)
            .map(|(a, b)| *a - *b)
            .collect()
    };
    let sum = |a: Vec<DVec3>, b: Vec<DVec3>| -> Vec<DVec3> {
        a.iter().zip(&b).map(|(x, y)| *x + *y).collect()
    };
    let cases = [
        (
            MuscleKind::ZygomaticusMajorL,
            captured("mouthSmile_L"),
            SurfacePoint::vertex(lm.mouth_corner_l),
        ),
        (
            MuscleKind::ZygomaticusMajorR,
            captured("mouthSmile_R"),
            SurfacePoint::vertex(lm.mouth_corner_r),
        ),
        (
            MuscleKind::FrontalisL,
            sum(captured("browInnerUp_L"), captured("browOuterUp_L")),
            lm.brow_point_l,
        ),
        (
            MuscleKind::FrontalisR,
            sum(captured("browInnerUp_R"), captured("browOuterUp_R")),
            lm.brow_point_r,
        ),
    ];
    for (kind, c, at) in cases {
        let r = contraction(m, kind);
        let cos = cosine(&r, &c);
        let ratio = at.sample(&r).length() / at.sample(&c).length();
        eprintln!("{}: cosine {cos:.3}, landmark ratio {ratio:.2}", kind.id());
        assert!(cos >= 0.7, "{}: cosine {cos:.3}", kind.id());
        assert!(
            (0.7..=1.4).contains(&ratio),
            "{}: ratio {ratio:.2}",
            kind.id()
        );
    }
}

/// The force-driven band muscles of the four bundled faces at default settings are not flagged
/// as set by a few elements ([`facebem::PrecomputeReport::force_peak_ratio`]: 0.5–2.6).
#[test]
fn bundled_faces_force_responses_are_not_flagged() {
    for face in 0..support::FACES.len() {
        let report = &model(face).report;
        eprintln!(
            "{}: force peak ratio {:.2} ({})",
            support::FACES[face],
            report.force_peak_ratio,
            report.force_peak_control
        );
        assert!(
            report.force_peak_ratio > 0.0
                && report.force_peak_ratio < facebem::SUSPICIOUS_FORCE_PEAK,
            "{}: {:.2} ({})",
            support::FACES[face],
            report.force_peak_ratio,
            report.force_peak_control
        );
        assert!(
            report
                .warnings()
                .iter()
                .all(|w| !w.contains("largest motion is")),
            "{:?}",
            report.warnings()
        );
    }
}

/// The modiolus muscles ([`face_prep::modiolus`]) move the modiolus's elements exactly by their
/// pin in their own response, and leave them free (moving less) in the other muscles'
/// responses: checked on the shell's element responses of MediaPipe (simulated whole) and of
/// ICT 13k's copy.
#[test]
fn modiolus_elements_move_by_their_pin() {
    for face in [0, 3] {
        let m = model(face);
        let rig = &m.rig;
        let mut pinned = 0;
        for k in 0..rig.muscles.len() {
            let Some(pin) = rig.modiolus_pin(k) else {
                continue;
            };
            pinned += 1;
            let elements = rig.modiolus_elements(pin.side);
            assert!(elements.len() >= 3, "{} elements", elements.len());
            let response = &m.shell_element_response[k];
            let size = pin.displacement.length();
            for &e in &elements {
                let off = (response[e as usize] - pin.displacement).length();
                assert!(
                    off <= 1e-6 * size,
                    "{} element {e}: off its pin by {off:e} of {size}",
                    support::FACES[face]
                );
            }
            // Away from the modiolus the face moves less than the modiolus itself does.
            let front = rig.face_vertex_count;
            let largest_vertex = m.shell_vertex_response[k][..front]
                .iter()
                .map(|u| u.length())
                .fold(0.0, f64::max);
            assert!(
                largest_vertex <= 1.05 * size,
                "{}: {largest_vertex} against the pin's {size}",
                rig.muscles[k].name
            );
        }
        // zygomaticus major, levator and depressor anguli oris, risorius, buccinator, both sides
        assert_eq!(pinned, 10, "{}", support::FACES[face]);
    }
}

/// Every bundled face's default rig is within every trust threshold (issue 30): the command
/// line writes it without `--force`. The figures the thresholds are set against: each control's
/// largest motion and its ratio to its muscle's shortening.
#[test]
fn every_bundled_face_is_trusted() {
    for face in 0..support::FACES.len() {
        let m = model(face);
        let causes = facebem::model::distrust(m);
        assert!(causes.is_empty(), "{}: {causes:?}", support::FACES[face]);
        assert!(
            m.report.response_amplification < facebem::SUSPICIOUS_AMPLIFICATION,
            "{}",
            support::FACES[face]
        );
    }
}
