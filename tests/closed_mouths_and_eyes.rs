//! Issue 30, item 2: mouths and eyes as they come. Test faces made from the bundled MediaPipe
//! face (its mouth loop is 20 vertices: two corners and nine on each lip, in mirror pairs):
//!
//! - **(b) slit**: each upper-lip vertex of the mouth loop welded with its lower partner (in loop
//!   order from the corners) at their midpoint; the corners folded into the first and last pair
//!   (a vertex next to both lips there would otherwise be pinched off) and the triangles that
//!   collapse dropped. Three boundary loops: the lips share one line of vertices.
//! - **(c) touching**: the same midpoints, but the lips keep separate vertices 10⁻⁶ of the face's
//!   size apart (vertices closer than [`face_prep::WELD_RELATIVE_TOLERANCE`] are one vertex on
//!   load, so exactly coincident lips are face (b)). Four loops, a mouth loop of zero width.
//! - **(c') coincident**: face (b) written with the lower lip's own `v` lines at exactly the
//!   upper lip's positions: on load the weld makes it face (b), and the export gives each lip its
//!   own lines back.
//!
//! - **(e) mouth bag**: the mouth loop carried back in four rings and closed behind (see
//!   [`closed_common::bag_raw`]). Three boundary loops: the mouth opens into a closed pouch.
//!
//! - **(f) everything closed**: the lips and both eyes welded as (b) and (d). One boundary loop:
//!   the contour.
//!
//! - **(g) one eye closed**: the eye loop of larger x welded as (d). Three boundary loops: the
//!   contour, the mouth and the open eye.
//!
//! - **(d) closed eyes**: each eye loop (sixteen vertices: two corners and seven on each lid)
//!   welded the same way as (b). Two boundary loops: the contour and the mouth.
//!
//! What the issue asks of (b) and (c), and what the capture says: jawOpen lowers the lower-lip midpoint 25–45 mm
//! while the upper lip stays (< 5 mm) and the corners move < 20 mm; pucker narrows the mouth
//! ≥ 20 % with no triangle turned over outside the lips; no target moves a vertex > 60 mm.
//! ICT's captured jawOpen (`tests/data/calibration/ict_narrow_face_jawOpen.obj`) moves the
//! upper lip's margin 2.6 mm at the middle but 15 mm beside the corners, and the corners
//! 15.8 mm: the 5 mm bound holds for the upper lip's middle 70 % (by width), the upper margin
//! beside the corners is held to the corners' 20 mm.

mod closed_common;
mod support;

use closed_common::*;
use facebem::report::measure::FaceLandmarks;
use glam::{DAffine3, DVec3};

#[test]
fn a_slit_mouth_is_cut_open_along_the_lips() {
    let face = mediapipe();
    let s = slit(&face);
    let line = s.lip_line.as_ref().expect("the lip line is found");
    // The nine welded vertices and, past each end, the vertex where the corner was folded in.
    assert_eq!(line.upper.len(), 11, "{line:?}");
    assert_eq!(line.lower.len(), 9);
    assert_eq!(s.vertices.len(), slit_raw(&face).0.len() + 9);
    assert_eq!(loops_of(&s).len(), 4);
    let m = build(&s);
    assert_mouth_works("slit", &figures(&m));
    // `facebem info` says so.
    let info = facebem::report::describe::describe("slit.obj".as_ref(), &m.mesh, &m.rig, Some(&m));
    assert!(
        info.contains("mouth: closed in the neutral (the lips meet along 11 vertices"),
        "{info}"
    );
}

#[test]
fn touching_lips_work() {
    let m = build(&touching(&mediapipe()));
    assert_mouth_works("touching", &figures(&m));
}

/// The bundled open mouth against the same bounds (printed beside the closed ones): the jaw,
/// the pucker and the largest motion hold; its corners follow the jaw further (34.6 mm; the
/// captured jawOpen moves them 15.8 mm), which the closed mouths' bound does not ask of it.
#[test]
fn the_open_mouth_meets_the_same_jaw_and_pucker_bounds() {
    let f = figures(&build(&mediapipe()));
    eprintln!("open: {f:?}");
    assert!((25.0..=45.0).contains(&f.lower_lip_drop_mm), "{f:?}");
    assert!(
        f.pucker_width <= 0.8 && f.pucker_flips_outside_lips == 0,
        "{f:?}"
    );
    assert!(f.largest_mm.0 <= 60.0, "{f:?}");
}

#[test]
fn an_exported_slit_mouth_opens() {
    let (positions, triangles) = slit_raw(&mediapipe());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("slit.obj");
    std::fs::write(&path, obj_text(&positions, &triangles)).unwrap();
    let (mesh, obj_source) = facebem::input::read_face(&path).unwrap();
    let mut m = build(&mesh);
    m.obj_source = obj_source;
    let line = m.mesh.lip_line.clone().unwrap();
    let layout = m.export_layout().unwrap();
    // The user's `v` lines first, then one copy per lower-lip vertex of the slit.
    assert_eq!(layout.input_count, positions.len());
    assert_eq!(layout.len(), positions.len() + line.lower.len());
    let jaw = field(&m, "jawOpen");
    let lm = FaceLandmarks::of(&m).unwrap();
    for (j, copy) in layout.welded[layout.input_count..].iter().enumerate() {
        let copy = copy.unwrap();
        let k = line
            .lower
            .iter()
            .position(|&l| l == copy)
            .unwrap_or_else(|| {
                panic!(
                    "{copy} not a lower-lip copy: {:?} {:?} tail {:?}",
                    line.upper,
                    line.lower,
                    &layout.welded[layout.input_count..]
                )
            });
        let upper = line.upper[k + 1];
        assert_eq!(
            layout.welded[layout.input_index[layout.input_count + j] as usize],
            Some(upper)
        );
        // The middle of the lower lip drops with the jaw, its upper partner stays.
        let (down, stays) = (
            lm.canonical_mm(jaw[copy as usize]),
            lm.canonical_mm(jaw[upper as usize]),
        );
        if 2 * k + 1 == line.lower.len() {
            assert!(down.y < -20.0 && stays.length() < 5.0, "{down} {stays}");
        }
    }
    // The GLB of it is valid (Khronos glTF-Validator) and the pose OBJ keeps the user's lines.
    let glb = dir.path().join("slit.glb");
    m.write_gltf(&glb, &facebem::export::GltfParams::default())
        .unwrap();
    support::assert_valid(&glb);
    let (sliders, _) = facebem::expressions::sliders_for_name("jawOpen", m.muscle_ids()).unwrap();
    let pose = m.obj_text(&sliders).unwrap();
    assert_eq!(
        pose.lines().filter(|l| l.starts_with("v ")).count(),
        positions.len()
    );
}

/// Face (c'): the lips as separate `v` lines at exactly the same positions load as the slit (b)
/// and work as it does; the export gives the lower lip's own lines the lower lip's motion, with
/// no vertex appended.
#[test]
fn coincident_lips_load_as_a_slit_and_export_as_written() {
    let face = mediapipe();
    let (positions, triangles) = coincident_raw(&face);
    let (slit_positions, slit_triangles) = slit_raw(&face);
    assert_eq!(positions.len(), slit_positions.len() + 9);
    assert_eq!(triangles.len(), slit_triangles.len());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("coincident.obj");
    std::fs::write(&path, obj_text(&positions, &triangles)).unwrap();
    let (mesh, obj_source) = facebem::input::read_face(&path).unwrap();
    assert_eq!(mesh.vertices.len(), slit(&face).vertices.len());
    let mut m = build(&mesh);
    m.obj_source = obj_source;
    assert_mouth_works("coincident", &figures(&m));
    let line = m.mesh.lip_line.clone().expect("the lip line is found");
    let layout = m.export_layout().unwrap();
    assert_eq!(layout.len(), positions.len(), "no vertex appended");
    let jaw = field(&m, "jawOpen");
    let lm = FaceLandmarks::of(&m).unwrap();
    let mut pairs = 0;
    for i in 0..positions.len() {
        for j in i + 1..positions.len() {
            if positions[i] != positions[j] {
                continue;
            }
            pairs += 1;
            let (a, b) = (layout.welded[i].unwrap(), layout.welded[j].unwrap());
            let (lower, upper) = if line.lower.contains(&a) {
                (a, b)
            } else {
                (b, a)
            };
            let k = line.lower.iter().position(|&l| l == lower).unwrap();
            assert_eq!(line.upper[k + 1], upper, "{i} {j}: {a} {b}");
            let (down, stays) = (
                lm.canonical_mm(jaw[lower as usize]),
                lm.canonical_mm(jaw[upper as usize]),
            );
            if 2 * k + 1 == line.lower.len() {
                assert!(down.y < -20.0 && stays.length() < 5.0, "{down} {stays}");
            }
        }
    }
    assert_eq!(pairs, 9);
}

/// Face (e): the bag is found and taken off, the face rigs as an open mouth (the jaw drops the
/// lower lip 25–45 mm, pucker narrows the mouth ≥ 20 % with no triangle turned over outside the
/// lips, no target moves a vertex > 60 mm), and the export keeps every `v` line, the bag's
/// following the lips: under the lower lip's middle it drops with the jaw, under the upper
/// lip's it stays.
#[test]
fn a_mouth_bag_is_taken_off_and_follows_the_lips() {
    let face = mediapipe();
    let ((positions, triangles), lp) = bag_raw(&face);
    let written = face_prep::FaceMesh {
        vertices: positions.clone(),
        triangles: triangles.clone(),
        input_to_vertex: Vec::new(),
        lip_line: None,
        lid_lines: Vec::new(),
        mouth_bag_vertices: 0,
    };
    assert_eq!(loops_of(&written).len(), 3);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bag.obj");
    std::fs::write(&path, obj_text(&positions, &triangles)).unwrap();
    let (mesh, obj_source) = facebem::input::read_face(&path).unwrap();
    assert_eq!(loops_of(&mesh).len(), 4);
    let taken = positions.len() - mesh.vertices.len();
    let mut m = build(&mesh);
    m.obj_source = obj_source;
    let f = figures(&m);
    eprintln!("mouth bag: {taken} vertices taken off, {f:?}");
    assert!(taken >= lp.len(), "{taken} vertices taken off");
    assert_eq!(mesh.mouth_bag_vertices, taken);
    let info = facebem::report::describe::describe("bag.obj".as_ref(), &mesh, &m.rig, Some(&m));
    assert!(
        info.contains(&format!(
            "opens into a closed mouth bag; its {taken} vertices"
        )),
        "{info}"
    );
    assert!((25.0..=45.0).contains(&f.lower_lip_drop_mm), "{f:?}");
    assert!(
        f.pucker_width <= 0.8 && f.pucker_flips_outside_lips == 0,
        "{f:?}"
    );
    assert!(f.largest_mm.0 <= 60.0, "{f:?}");
    // Every line exported; the deepest ring follows its lip.
    let layout = m.export_layout().unwrap();
    assert_eq!(layout.len(), positions.len());
    let jaw = field(&m, "jawOpen");
    let lm = FaceLandmarks::of(&m).unwrap();
    let deepest = face.vertices.len() + (BAG_RINGS - 1) * lp.len();
    let ys: Vec<f64> = lp.iter().map(|&v| face.vertices[v as usize].y).collect();
    let (lowest, highest) = (0..lp.len()).fold((0, 0), |(lo, hi), i| {
        (
            if ys[i] < ys[lo] { i } else { lo },
            if ys[i] > ys[hi] { i } else { hi },
        )
    });
    let motion = |i: usize| lm.canonical_mm(jaw[layout.welded[deepest + i].unwrap() as usize]);
    let (under_lower, under_upper) = (motion(lowest), motion(highest));
    eprintln!("mouth bag: deepest ring under the lower lip {under_lower}, upper {under_upper} mm");
    assert!(under_lower.y < -15.0, "{under_lower}");
    assert!(under_upper.length() < 5.0, "{under_upper}");
    // The pose OBJ moves each bag line with its lip from where it is drawn (not onto the lip).
    let (sliders, _) = facebem::expressions::sliders_for_name("jawOpen", m.muscle_ids()).unwrap();
    let pose = m.obj_text(&sliders).unwrap();
    let posed: Vec<DVec3> = pose
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let x: Vec<f64> = l
                .split_whitespace()
                .skip(1)
                .map(|t| t.parse().unwrap())
                .collect();
            DVec3::new(x[0], x[1], x[2])
        })
        .collect();
    assert_eq!(posed.len(), positions.len());
    for i in [lowest, highest] {
        let line = deepest + i;
        let anchor = layout.welded[line].unwrap() as usize;
        let moved = posed[line] - positions[line];
        assert!(
            (moved - jaw[anchor]).length() < 1e-9,
            "{moved} {}",
            jaw[anchor]
        );
        assert!(positions[line].distance(m.mesh.vertices[anchor]) * lm.mm_per_unit > 20.0);
    }
    let glb = dir.path().join("bag.glb");
    m.write_gltf(&glb, &facebem::export::GltfParams::default())
        .unwrap();
    support::assert_valid(&glb);
}

/// A face with eye openings and no mouth at all (a smooth sheet below the nose) is refused with
/// one line naming the cause.
#[test]
fn a_face_without_a_mouth_is_refused_in_one_line() {
    // A 40 × 40 grid over [−1, 1]² with a nose bump, two rectangular eye holes.
    let n = 40;
    let at = |i: usize, j: usize| {
        let (x, y) = (
            -1.0 + 2.0 * i as f64 / n as f64,
            -1.0 + 2.0 * j as f64 / n as f64,
        );
        DVec3::new(x, y, 0.3 * (-(x * x + (y + 0.1) * (y + 0.1)) / 0.02).exp())
    };
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push(at(i, j));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let eye = |i: usize, j: usize| {
        let (x, y) = (i as i64 - 20, j as i64 - 20);
        (4..=8).contains(&x.abs()) && (5..=7).contains(&y)
    };
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if eye(i, j) {
                continue;
            }
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let err = face_prep::FaceMesh::from_triangles(&positions, &triangles).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, face_prep::PrepError::NoMouth { .. }), "{msg}");
    assert!(
        msg.contains("no closed mouth") && !msg.contains('\n'),
        "{msg}"
    );
}

/// Face (d): both eyes closed in the neutral. The lid lines are found and cut, `info` says the
/// eyes are closed, the lid controls leave them as they are (no response), no target that
/// moves the lids or the skin around them (blink, wide, squint, cheek squint) turns a triangle
/// over, and the rest of the face still works (the jaw, the smile, the brows).
#[test]
fn closed_eyes_are_found_and_their_lids_stay_as_they_are() {
    let (v, t) = closed_eyes_raw(&mediapipe());
    let mesh = face_prep::FaceMesh::from_triangles(&v, &t).unwrap();
    assert_eq!(mesh.lid_lines.len(), 2);
    for line in &mesh.lid_lines {
        // The seven welded vertices of each eye and the vertices the corners were folded into.
        assert!((7..=11).contains(&line.upper.len()), "{line:?}");
    }
    let m = build(&mesh);
    let info = facebem::report::describe::describe("eyes.obj".as_ref(), &m.mesh, &m.rig, Some(&m));
    assert!(
        info.contains("eyes: closed in the neutral (both; lid lines cut open: 10"),
        "{info}"
    );
    assert_eq!(
        facebem::model::closed_eyes(&m.mesh, m.rig.canonical_from_input),
        [true, true]
    );
    for id in [
        "orbicularis_oculi_palpebral_l",
        "orbicularis_oculi_palpebral_r",
        "levator_palpebrae_l",
        "levator_palpebrae_r",
    ] {
        let k = m.muscle_ids().iter().position(|i| i == id).unwrap();
        let largest = m.basis.displacements[k]
            .iter()
            .map(|d| d.length())
            .fold(0.0, f64::max);
        assert_eq!(largest, 0.0, "{id} moves a closed eye");
    }
    let lm = FaceLandmarks::of(&m).unwrap();
    assert_no_flips(
        &m,
        &[
            "eyeBlinkLeft",
            "eyeBlinkRight",
            "eyeWideLeft",
            "eyeWideRight",
            "eyeSquintLeft",
            "eyeSquintRight",
            "cheekSquintLeft",
            "cheekSquintRight",
            "browDownLeft",
            "browInnerUp",
        ],
    );
    let jaw = field(&m, "jawOpen");
    let smile = field(&m, "mouthSmileLeft");
    let brows = field(&m, "browInnerUp");
    let largest_mm = |f: &[DVec3]| {
        f.iter()
            .map(|d| d.length() * lm.mm_per_unit)
            .fold(0.0, f64::max)
    };
    assert!(
        (30.0..=60.0).contains(&largest_mm(&jaw)),
        "jaw {:.1}",
        largest_mm(&jaw)
    );
    assert!(largest_mm(&smile) > 5.0 && largest_mm(&brows) > 2.0);
}

/// Face (d'): both eyes' lids touching at separate vertices 10⁻⁶ of the face's size apart (four
/// loops). The eyes count as closed (`facebem::model::closed_eyes`) and the lid controls leave
/// them as they are; the bundled faces' open eyes do not count as closed.
#[test]
fn touching_lids_count_as_closed_and_open_eyes_do_not() {
    let face = mediapipe();
    let (_, [e1, e2]) = mouth_and_eyes(&face);
    let v = touching_positions(&face, &[&e1, &e2]);
    let m = build(&face_prep::FaceMesh::from_triangles(&v, &face.triangles).unwrap());
    let openings = facebem::model::eye_openings(&m.mesh, m.rig.canonical_from_input).unwrap();
    assert!(openings.iter().all(|&o| o < 1e-4), "{openings:?}");
    assert_eq!(
        facebem::model::closed_eyes(&m.mesh, m.rig.canonical_from_input),
        [true, true]
    );
    for id in ["orbicularis_oculi_palpebral_l", "levator_palpebrae_r"] {
        let k = m.muscle_ids().iter().position(|i| i == id).unwrap();
        assert!(
            m.basis.displacements[k].iter().all(|d| *d == DVec3::ZERO),
            "{id}"
        );
    }
    assert_no_flips(
        &m,
        &[
            "eyeBlinkLeft",
            "eyeWideRight",
            "eyeSquintLeft",
            "cheekSquintRight",
        ],
    );
    let info = facebem::report::describe::describe("lids.obj".as_ref(), &m.mesh, &m.rig, Some(&m));
    assert!(
        info.contains("eyes: closed in the neutral (both; lid lines cut open: none"),
        "{info}"
    );
    // The bundled faces' open eyes: at least six times the threshold.
    for name in support::FACES {
        let mesh = face_prep::load_face(&support::asset(name)).unwrap();
        let m = build(&mesh);
        let openings = facebem::model::eye_openings(&m.mesh, m.rig.canonical_from_input).unwrap();
        eprintln!("{name}: eye openings {openings:?}");
        assert!(
            openings
                .iter()
                .all(|&o| o > 6.0 * facebem::model::CLOSED_EYE_AREA_FRACTION),
            "{name}: {openings:?}"
        );
    }
}

/// Issue 30, item 3, on faces (b), (c), (d) and (e): rotated 30° about a tilted axis, ×10 and moved by
/// 1 000 units, renumbered; and ×0.001. Every ARKit target within 2 % RMS of its largest motion,
/// the near-singular ratio within 10 %.
#[test]
fn closed_mouths_are_invariant_to_how_the_file_is_written() {
    let face = mediapipe();
    let rotated = rotated_scaled_moved();
    let tiny = DAffine3::from_scale(DVec3::splat(0.001));
    for (name, raw) in [
        ("slit", slit_raw(&face)),
        ("touching", touching_raw(&face)),
        ("closed eyes", closed_eyes_raw(&face)),
        ("mouth bag", bag_raw(&face).0),
    ] {
        for (how, t) in [("rotated x10 moved", rotated), ("x0.001", tiny)] {
            assert_invariant(name, how, &raw, t);
        }
    }
}

/// Issue 30, item 3: a face read from its OBJ and from the GLB facebem exports of it (float32
/// positions in metres; a cut lip or lid line keeps its lower side's own vertices): the worst
/// ARKit target's RMS difference over its largest motion (in mm), the target, and the ratio of
/// the near-singular ratios.
fn obj_against_glb(positions: &[DVec3], triangles: &[[u32; 3]]) -> (f64, &'static str, f64) {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("face.obj");
    std::fs::write(&obj, obj_text(positions, triangles)).unwrap();
    let (mesh, obj_source) = facebem::input::read_face(&obj).unwrap();
    let mut base = build(&mesh);
    base.obj_source = obj_source;
    let glb = dir.path().join("face.glb");
    base.write_gltf(&glb, &facebem::export::GltfParams::default())
        .unwrap();
    let (glb_mesh, _) = facebem::input::read_face(&glb).unwrap();
    // The GLB holds every vertex the rig has: a cut line's lower side 2 µm below its upper side,
    // so read back the lips or lids touch and there is nothing to cut.
    assert_eq!(glb_mesh.vertices.len(), base.mesh.vertices.len());
    assert!(glb_mesh.lip_line.is_none() && glb_mesh.lid_lines.is_empty());
    let other = build(&glb_mesh);
    let (mm_a, mm_b) = (base.rig.mm_per_unit(), other.rig.mm_per_unit());
    // glTF is in metres.
    assert!((mm_b - 1000.0).abs() < 1e-6, "{mm_a} {mm_b}");
    let of_base: Vec<usize> = base
        .mesh
        .vertices
        .iter()
        .map(|&p| {
            (0..other.mesh.vertices.len())
                .min_by(|&a, &b| {
                    let d = |i: usize| (other.mesh.vertices[i] * mm_b).distance(p * mm_a);
                    d(a).total_cmp(&d(b))
                })
                .unwrap()
        })
        .collect();
    let (worst, target) = worst_arkit_target(&base, &other, &of_base, |d| d * (mm_b / mm_a));
    let ratio = other.report.response_amplification / base.report.response_amplification;
    (worst, target, ratio)
}

/// Issue 30, item 3, OBJ against GLB on every test face made from MediaPipe: the bundled face
/// and (a) re-triangulated to (g) one eye closed. (The other bundled faces are not held to it
/// yet: ICT 2500, Lee Perry-Smith and ICT 13k differ by 5.3 %, 2.6 % and 7.7 %, see
/// `docs/journal.md`.) Every ARKit target within
/// 2 % RMS of its largest motion, the near-singular ratio within 10 %.
#[test]
fn every_test_face_read_from_its_glb_makes_the_same_expressions() {
    let face = mediapipe();
    let retriangulated = support::retriangulated(&face, 1);
    for (name, (positions, triangles)) in [
        ("bundled", (face.vertices.clone(), face.triangles.clone())),
        (
            "(a) re-triangulated",
            (retriangulated.vertices, retriangulated.triangles),
        ),
        ("(b) slit", slit_raw(&face)),
        ("(c) touching lips", touching_raw(&face)),
        ("(d) closed eyes", closed_eyes_raw(&face)),
        ("(e) mouth bag", bag_raw(&face).0),
        ("(f) everything closed", all_closed_raw(&face)),
        ("(g) one eye closed", one_eye_closed_raw(&face)),
    ] {
        let (worst, target, ratio) = obj_against_glb(&positions, &triangles);
        eprintln!(
            "{name}, OBJ against GLB: worst ARKit target {worst:.2e} ({target}), ratio {ratio:.4}"
        );
        assert!(worst <= 0.02, "{name}: {target} {worst:.4}");
        assert!((0.9..=1.1).contains(&ratio), "{name}: ratio {ratio:.3}");
    }
}

/// Face (f): with the mouth and both eyes closed (one loop) the lips' line is found from the
/// surface alone, then the lids' lines from the mouth: the mouth works as on (b), the eyes count
/// as closed, and the whole is invariant to a rotation about a tilted axis with scale and shift.
#[test]
fn a_face_with_mouth_and_eyes_closed_is_opened() {
    let face = mediapipe();
    let raw = all_closed_raw(&face);
    let written = face_prep::FaceMesh {
        vertices: raw.0.clone(),
        triangles: raw.1.clone(),
        input_to_vertex: Vec::new(),
        lip_line: None,
        lid_lines: Vec::new(),
        mouth_bag_vertices: 0,
    };
    assert_eq!(loops_of(&written).len(), 1);
    let mesh = face_prep::FaceMesh::from_triangles(&raw.0, &raw.1).unwrap();
    assert_eq!(loops_of(&mesh).len(), 4);
    let lips = mesh.lip_line.as_ref().expect("the lips' line is found");
    assert_eq!(
        (lips.upper.len(), mesh.lid_lines.len()),
        (11, 2),
        "{lips:?}"
    );
    let m = build(&mesh);
    assert_mouth_works("everything closed", &figures(&m));
    assert_eq!(
        facebem::model::closed_eyes(&m.mesh, m.rig.canonical_from_input),
        [true, true]
    );
    assert_invariant(
        "everything closed",
        "rotated x10 moved",
        &raw,
        rotated_scaled_moved(),
    );
}

/// Face (g): one eye closed (three loops: contour, mouth, open eye). The closed eye's lid line
/// is found on the side away from the open eye and cut; only that eye counts as closed, its
/// lid controls do nothing while the open eye's still blink, no eye or brow target turns a
/// triangle over, and the whole is invariant to a rotation about a tilted axis with scale and
/// shift.
#[test]
fn a_face_with_one_eye_closed_is_opened() {
    let face = mediapipe();
    let raw = one_eye_closed_raw(&face);
    let mesh = face_prep::FaceMesh::from_triangles(&raw.0, &raw.1).unwrap();
    assert_eq!(loops_of(&mesh).len(), 4);
    assert!(mesh.lip_line.is_none());
    assert_eq!(mesh.lid_lines.len(), 1);
    let m = build(&mesh);
    let closed = facebem::model::closed_eyes(&m.mesh, m.rig.canonical_from_input);
    // The welded eye has the larger x: the face's left (+x) in the bundled face's frame.
    assert_eq!(closed, [true, false]);
    let largest = |id: &str| {
        let k = m.muscle_ids().iter().position(|i| i == id).unwrap();
        m.basis.displacements[k]
            .iter()
            .map(|d| d.length())
            .fold(0.0, f64::max)
    };
    assert_eq!(largest("orbicularis_oculi_palpebral_l"), 0.0);
    assert!(largest("orbicularis_oculi_palpebral_r") > 0.0);
    // The closed eye's controls and the brows turn nothing over; the open eye's blink no more
    // than on the bundled face (whose closing lids turn one sliver over).
    assert_no_flips(
        &m,
        &[
            "eyeBlinkLeft",
            "eyeWideLeft",
            "eyeSquintLeft",
            "eyeWideRight",
            "browDownLeft",
            "browInnerUp",
        ],
    );
    let blink_flips = |mm: &facebem::FaceModel| {
        let f = field(mm, "eyeBlinkRight");
        let posed: Vec<DVec3> = mm
            .mesh
            .vertices
            .iter()
            .zip(&f)
            .map(|(a, b)| *a + *b)
            .collect();
        facebem::report::measure::flipped_triangles(&mm.mesh.vertices, &posed, &mm.mesh.triangles)
            .len()
    };
    let bundled = blink_flips(&build(&face));
    assert!(
        blink_flips(&m) <= bundled,
        "{} > {bundled}",
        blink_flips(&m)
    );
    assert_invariant(
        "one eye closed",
        "rotated x10 moved",
        &raw,
        rotated_scaled_moved(),
    );
}
