//! Eyelids (issue 11 item 2) on every bundled face at its detected unit: blink
//! (`orbicularis_oculi_palpebral_l/_r` = −1) closes the eye loop's upper margin exactly onto the
//! lower one without crossing it, the other eye and the outer contour stay put, triangles flip
//! only at the lids; squint (`orbicularis_oculi_orbital_l/_r`) raises the lower lid, wide
//! (`levator_palpebrae_l/_r`) the upper one; on the ICT 13k face the blink is held to the captured
//! ICT-FaceKit eyeBlink_L / eyeBlink_R (`tests/data/calibration`, MIT).
//!
//! `cargo run --release -p facebem-tools --bin calibrate` prints the figures.

mod support;

use std::sync::OnceLock;

use face_prep::Side;
use face_prep::eyelid::EyeMargins;
use facebem::report::measure::{FaceLandmarks, cosine, flipped_triangles};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

static MODELS: [OnceLock<FaceModel>; 4] = [const { OnceLock::new() }; 4];

fn model(face: usize) -> &'static FaceModel {
    MODELS[face].get_or_init(|| {
        let mesh = face_prep::load_face(&support::asset(support::FACES[face])).unwrap();
        build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap()
    })
}

/// Radius, mm in the front plane around an eye loop's centre, of what counts as "the eye" (its
/// lids and the skin around them) for the other-eye and flipped-triangle checks: 0.4 of an
/// adult's interocular distance.
const EYE_REGION_MM: f64 = 25.0;

/// A face measured in its canonical frame and mm.
struct Measured<'a> {
    m: &'a FaceModel,
    lm: FaceLandmarks,
    canonical: Vec<DVec3>,
}

impl<'a> Measured<'a> {
    fn of(face: usize) -> Measured<'a> {
        let m = model(face);
        let lm = FaceLandmarks::of(m).expect("four loops");
        let canonical = lm.canonical_points(&m.mesh.vertices);
        Measured { m, lm, canonical }
    }

    /// Displacement field (input frame) of control `id` at slider `s`.
    fn field(&self, id: &str, s: f64) -> Vec<DVec3> {
        let k = self
            .m
            .basis
            .muscle_index(id)
            .unwrap_or_else(|| panic!("no control {id}"));
        self.m.basis.displacements[k]
            .iter()
            .map(|d| *d * s)
            .collect()
    }

    /// Posed canonical positions for a field.
    fn posed(&self, field: &[DVec3]) -> Vec<DVec3> {
        self.canonical
            .iter()
            .zip(field)
            .map(|(p, d)| *p + self.lm.canonical_from_input.transform_vector3(*d))
            .collect()
    }

    fn eye_loop(&self, side: Side) -> &[u32] {
        match side {
            Side::Left => &self.lm.loops.eye_l,
            _ => &self.lm.loops.eye_r,
        }
    }

    fn margins(&self, side: Side) -> EyeMargins {
        EyeMargins::of_loop(&self.canonical, self.eye_loop(side), side).expect("eye margins")
    }

    fn eye_centre(&self, side: Side) -> glam::DVec2 {
        face_prep::orient::loop_centroid(&self.canonical, self.eye_loop(side)).truncate()
    }

    /// Largest motion, mm, of any vertex within [`EYE_REGION_MM`] of the eye on `side`.
    fn eye_motion_mm(&self, side: Side, field: &[DVec3]) -> f64 {
        let c = self.eye_centre(side);
        (0..self.canonical.len())
            .filter(|&v| {
                (self.canonical[v].truncate() - c).length() * self.lm.mm_per_unit < EYE_REGION_MM
            })
            .map(|v| field[v].length() * self.lm.mm_per_unit)
            .fold(0.0, f64::max)
    }

    /// Flipped triangles of a field: their number, and the largest distance, mm, of a flipped
    /// triangle's centroid from the eye centre on `side` (front plane).
    fn flips(&self, side: Side, field: &[DVec3]) -> (usize, f64) {
        let mesh = &self.m.mesh;
        let posed: Vec<DVec3> = mesh
            .vertices
            .iter()
            .zip(field)
            .map(|(a, b)| *a + *b)
            .collect();
        let flipped = flipped_triangles(&mesh.vertices, &posed, &mesh.triangles);
        let c = self.eye_centre(side);
        let far = flipped
            .iter()
            .map(|&t| {
                let centre = mesh.triangles[t as usize]
                    .iter()
                    .map(|&v| self.canonical[v as usize])
                    .sum::<DVec3>()
                    .truncate()
                    / 3.0;
                (centre - c).length() * self.lm.mm_per_unit
            })
            .fold(0.0, f64::max);
        (flipped.len(), far)
    }
}

/// Largest and smallest of the vertical gaps that exist.
fn extremes(gaps: &[Option<f64>]) -> (f64, f64) {
    let g: Vec<f64> = gaps.iter().flatten().copied().collect();
    assert!(!g.is_empty(), "no vertical gap measured");
    (
        g.iter().copied().fold(f64::MIN, f64::max),
        g.iter().copied().fold(f64::MAX, f64::min),
    )
}

/// How far, at worst, an upper-margin vertex lies below the lower margin in a pose (vertical
/// gaps `posed`) beyond where it already lies in the neutral face (`neutral`): 0 or less when
/// the lids do not cross. (The Lee Perry-Smith scan's slit right eye has its lower margin 0.36 mm
/// above the upper one at one vertex in the front view, neutral.)
fn deepest_crossing(neutral: &[Option<f64>], posed: &[Option<f64>]) -> f64 {
    neutral
        .iter()
        .zip(posed)
        .filter_map(|(n, p)| Some(n.unwrap_or(0.0).min(0.0) - (*p)?))
        .fold(f64::MIN, f64::max)
}

/// Neutral opening: the largest vertical gap of the neutral face.
fn neutral_height(f: &Measured, margins: &EyeMargins) -> f64 {
    extremes(&margins.vertical_gaps(&f.canonical)).0
}

fn other(side: Side) -> Side {
    match side {
        Side::Left => Side::Right,
        _ => Side::Left,
    }
}

/// Blink on `side`: the eye loop's upper margin closes onto the lower one (largest vertical gap
/// ≤ 5 % of the neutral opening, no upper-margin vertex below the lower margin at full blink,
/// none further below it than in the neutral scan at a quarter, half and three quarters),
/// the other eye moves < 0.5 mm, the contour ≤ 0.5 mm, flipped triangles ≤ 0.5 % and only at
/// this eye's lids.
fn blink_closes(face: usize, side: Side) {
    let f = Measured::of(face);
    let id = match side {
        Side::Left => "orbicularis_oculi_palpebral_l",
        _ => "orbicularis_oculi_palpebral_r",
    };
    let name = support::FACES[face];
    let margins = f.margins(side);
    let h0 = neutral_height(&f, &margins);
    let field = f.field(id, -1.0);
    let neutral_gaps = margins.vertical_gaps(&f.canonical);
    let (largest, lowest) = extremes(&margins.vertical_gaps(&f.posed(&field)));
    let mm = f.lm.mm_per_unit;
    let other_eye = f.eye_motion_mm(other(side), &field);
    let contour = f.lm.contour_motion_mm(&field);
    let (flipped, far) = f.flips(side, &field);
    let share = flipped as f64 / f.m.mesh.triangles.len() as f64;
    eprintln!(
        "{name} {id}: neutral opening {:.2} mm, largest gap {:.4} mm, lowest {:.4} mm, other \
         eye {other_eye:.3} mm, contour {contour:.3} mm, flipped {flipped} ({:.2} %, farthest \
         {far:.1} mm from the eye centre)",
        h0 * mm,
        largest * mm,
        lowest * mm,
        100.0 * share
    );
    assert!(
        largest <= 0.05 * h0,
        "{name} {id}: gap {:.3} mm",
        largest * mm
    );
    assert!(
        lowest >= -1e-9 * h0,
        "{name} {id}: an upper-margin vertex {:.4} mm below the lower margin",
        lowest * mm
    );
    for s in [-0.25, -0.5, -0.75] {
        let crossing = deepest_crossing(
            &neutral_gaps,
            &margins.vertical_gaps(&f.posed(&f.field(id, s))),
        );
        assert!(
            crossing <= 1e-9 * h0,
            "{name} {id} at {s}: the margins cross by {:.4} mm",
            crossing * mm
        );
    }
    assert!(
        other_eye < 0.5,
        "{name} {id}: the other eye moves {other_eye:.3} mm"
    );
    assert!(contour <= 0.5, "{name} {id}: contour moves {contour:.3} mm");
    assert!(share <= 0.005, "{name} {id}: {flipped} triangles flip");
    assert!(
        far <= EYE_REGION_MM,
        "{name} {id}: a triangle flips {far:.1} mm from the eye"
    );
}

/// Squint raises the lower margin's middle (t = 0.5) and wide the upper margin's middle by 10–50 %
/// of the neutral opening, the margins do not cross (beyond the neutral scan, see
/// [`deepest_crossing`]), both leave the other eye, the contour and all but ≤ 0.5 % of the
/// triangles (at this eye) alone.
fn squint_and_wide(face: usize, side: Side) {
    let f = Measured::of(face);
    let name = support::FACES[face];
    let margins = f.margins(side);
    let mm = f.lm.mm_per_unit;
    let (squint, wide) = match side {
        Side::Left => ("orbicularis_oculi_orbital_l", "levator_palpebrae_l"),
        _ => ("orbicularis_oculi_orbital_r", "levator_palpebrae_r"),
    };
    let h0 = neutral_height(&f, &margins);
    for (id, lower) in [(squint, true), (wide, false)] {
        let field = f.field(id, -1.0);
        let posed = f.posed(&field);
        let rise = if lower {
            margins.lower_at(&posed, 0.5).y - margins.lower_at(&f.canonical, 0.5).y
        } else {
            margins.upper_at(&posed, 0.5).y - margins.upper_at(&f.canonical, 0.5).y
        };
        let (_, lowest) = extremes(&margins.vertical_gaps(&posed));
        let crossing = deepest_crossing(
            &margins.vertical_gaps(&f.canonical),
            &margins.vertical_gaps(&posed),
        );
        let other_eye = f.eye_motion_mm(other(side), &field);
        let contour = f.lm.contour_motion_mm(&field);
        let (flipped, far) = f.flips(side, &field);
        let share = flipped as f64 / f.m.mesh.triangles.len() as f64;
        eprintln!(
            "{name} {id}: margin middle up {:.2} mm ({:.0} % of the opening), lowest gap {:.2} \
             mm, other eye {other_eye:.3} mm, contour {contour:.3} mm, flipped {flipped}",
            rise * mm,
            100.0 * rise / h0,
            lowest * mm
        );
        assert!(
            (0.1 * h0..=0.5 * h0).contains(&rise),
            "{name} {id}: margin rises {:.2} mm of {:.2}",
            rise * mm,
            h0 * mm
        );
        assert!(
            crossing <= 1e-9 * h0,
            "{name} {id}: the margins cross by {:.3} mm",
            crossing * mm
        );
        assert!(
            other_eye < 0.5,
            "{name} {id}: the other eye moves {other_eye:.3} mm"
        );
        assert!(contour <= 0.5, "{name} {id}: contour moves {contour:.3} mm");
        assert!(share <= 0.005, "{name} {id}: {flipped} triangles flip");
        assert!(
            far <= EYE_REGION_MM,
            "{name} {id}: a triangle flips {far:.1} mm from the eye"
        );
    }
}

macro_rules! face_tests {
    ($name:ident, $face:expr) => {
        mod $name {
            use face_prep::Side;
            #[test]
            fn blink_left_closes() {
                super::blink_closes($face, Side::Left);
            }
            #[test]
            fn blink_right_closes() {
                super::blink_closes($face, Side::Right);
            }
            #[test]
            fn squint_and_wide_left() {
                super::squint_and_wide($face, Side::Left);
            }
            #[test]
            fn squint_and_wide_right() {
                super::squint_and_wide($face, Side::Right);
            }
        }
    };
}

face_tests!(mediapipe, 0);
face_tests!(ict_2500, 1);
// Regression: the scan's slit right eye (2.5 mm open, its lids overlapping in the front view)
// had its lower margin lifted 0.13 mm past the upper one by the squint, until
// `facebem::settle::lid_closure`'s squint guard.
face_tests!(lee_perry_smith, 2);
face_tests!(ict_13k, 3);

/// Against the captured ICT eyeBlink_L / eyeBlink_R on the same mesh: cosine similarity of the
/// whole displacement fields ≥ 0.7.
#[test]
fn ict_blink_matches_the_captured_blink() {
    let f = Measured::of(3);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/calibration");
    for (id, name) in [
        ("orbicularis_oculi_palpebral_l", "eyeBlink_L"),
        ("orbicularis_oculi_palpebral_r", "eyeBlink_R"),
    ] {
        let c = face_prep::load_face(&dir.join(format!("ict_narrow_face_{name}.obj"))).unwrap();
        assert_eq!(c.vertices.len(), f.m.mesh.vertices.len());
        let captured: Vec<DVec3> = c
            .vertices
            .iter()
            .zip(&f.m.mesh.vertices)
            .map(|(a, b)| *a - *b)
            .collect();
        let cos = cosine(&f.field(id, -1.0), &captured);
        eprintln!("{id} vs {name}: cosine {cos:.3}");
        assert!(cos >= 0.7, "{id} vs {name}: cosine {cos:.3}");
    }
}
