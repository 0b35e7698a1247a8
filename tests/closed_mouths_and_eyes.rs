//! Issue 30, item 2: mouths as they come. Test faces made from the bundled MediaPipe face
//! (its mouth loop is 20 vertices: two corners and nine on each lip, in mirror pairs):
//!
//! - **(b) slit**: each upper-lip vertex of the mouth loop welded with its lower partner (in loop
//!   order from the corners) at their midpoint; the corners folded into the first and last pair
//!   (a vertex next to both lips there would otherwise be pinched off) and the triangles that
//!   collapse dropped. Three boundary loops: the lips share one line of vertices.
//! - **(c) touching**: the same midpoints, but the lips keep separate vertices 10⁻⁶ of the face's
//!   size apart (vertices closer than [`face_prep::WELD_RELATIVE_TOLERANCE`] are one vertex on
//!   load, so exactly coincident lips are face (b)). Four loops, a mouth loop of zero width.
//!
//! What the issue asks, and what the capture says: jawOpen lowers the lower-lip midpoint 25–45 mm
//! while the upper lip stays (< 5 mm) and the corners move < 20 mm; pucker narrows the mouth
//! ≥ 20 % with no triangle turned over outside the lips; no target moves a vertex > 60 mm.
//! ICT's captured jawOpen (`tests/data/calibration/ict_narrow_face_jawOpen.obj`) moves the
//! upper lip's margin 2.6 mm at the middle but 15 mm beside the corners, and the corners
//! 15.8 mm: the 5 mm bound holds for the upper lip's middle 70 % (by width), the upper margin
//! beside the corners is held to the corners' 20 mm.

mod support;

use facebem::expressions::{arkit, vrm};
use facebem::report::measure::{FaceLandmarks, flipped_by};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::{DAffine3, DQuat, DVec3};

/// A loop of `mesh` split at its corners (the loop's extreme vertices along the eye line, x
/// here) into two chains running from one corner to the other, the upper one first.
struct Chains {
    corners: [u32; 2],
    upper: Vec<u32>,
    lower: Vec<u32>,
}

fn loops_of(mesh: &face_prep::FaceMesh) -> Vec<Vec<u32>> {
    face_prep::topology::validate(&mesh.vertices, &mesh.triangles).unwrap()
}

/// The mouth loop and the two eye loops of a bundled face (its y is up).
fn mouth_and_eyes(mesh: &face_prep::FaceMesh) -> (Vec<u32>, [Vec<u32>; 2]) {
    let v = &mesh.vertices;
    let mut loops = loops_of(mesh);
    loops.sort_by_key(|l| std::cmp::Reverse(l.len()));
    let mean_y = |l: &[u32]| l.iter().map(|&i| v[i as usize].y).sum::<f64>() / l.len() as f64;
    let mut inner = loops[1..].to_vec();
    inner.sort_by(|a, b| mean_y(a).total_cmp(&mean_y(b)));
    (inner[0].clone(), [inner[1].clone(), inner[2].clone()])
}

fn chains(mesh: &face_prep::FaceMesh, lp: &[u32]) -> Chains {
    let v = &mesh.vertices;
    let mean_y = |l: &[u32]| l.iter().map(|&i| v[i as usize].y).sum::<f64>() / l.len() as f64;
    let by_x = |f: fn(f64, f64) -> bool| {
        (0..lp.len())
            .reduce(|a, b| {
                if f(v[lp[b] as usize].x, v[lp[a] as usize].x) {
                    b
                } else {
                    a
                }
            })
            .unwrap()
    };
    let (i0, i1) = (by_x(|a, b| a < b), by_x(|a, b| a > b));
    let m: Vec<u32> = lp[i0..].iter().chain(&lp[..i0]).copied().collect();
    let j = (i1 + lp.len() - i0) % lp.len();
    let a: Vec<u32> = m[1..j].to_vec();
    let b: Vec<u32> = m[j + 1..].iter().rev().copied().collect();
    let (upper, lower) = if mean_y(&a) > mean_y(&b) {
        (a, b)
    } else {
        (b, a)
    };
    Chains {
        corners: [m[0], m[j]],
        upper,
        lower,
    }
}

/// `mesh` as written with the loops `welded` closed: each upper vertex welded with its lower
/// partner (in loop order from the corners) at their midpoint, the corners folded into the
/// first and last pair (a vertex next to both sides there would otherwise be pinched off), the
/// triangles that collapse dropped, the unused positions dropped.
fn welded_raw(mesh: &face_prep::FaceMesh, welded: &[&[u32]]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut v = mesh.vertices.clone();
    let mut replace: Vec<u32> = (0..v.len() as u32).collect();
    for lp in welded {
        let c = chains(mesh, lp);
        assert_eq!(c.upper.len(), c.lower.len());
        for (&u, &l) in c.upper.iter().zip(&c.lower) {
            let mid = 0.5 * (v[u as usize] + v[l as usize]);
            v[u as usize] = mid;
            v[l as usize] = mid;
            replace[l as usize] = u;
        }
        replace[c.corners[0] as usize] = c.upper[0];
        replace[c.corners[1] as usize] = c.upper[c.upper.len() - 1];
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| replace[i as usize]))
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    let mut index = vec![u32::MAX; v.len()];
    let mut positions = Vec::new();
    let triangles = triangles
        .iter()
        .map(|t| {
            t.map(|i| {
                if index[i as usize] == u32::MAX {
                    index[i as usize] = positions.len() as u32;
                    positions.push(v[i as usize]);
                }
                index[i as usize]
            })
        })
        .collect();
    (positions, triangles)
}

/// Face (b) as written: the lips welded along the mouth line (see the module docs).
fn slit_raw(mesh: &face_prep::FaceMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mouth, _) = mouth_and_eyes(mesh);
    welded_raw(mesh, &[&mouth])
}

/// Face (b) (see the module docs).
fn slit(mesh: &face_prep::FaceMesh) -> face_prep::FaceMesh {
    let (v, t) = slit_raw(mesh);
    face_prep::FaceMesh::from_triangles(&v, &t).unwrap()
}

fn obj_text(positions: &[DVec3], triangles: &[[u32; 3]]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for p in positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for t in triangles {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

/// Face (c): the lips meet at the midpoints, 10⁻⁶ of the face's size apart (see the module docs).
fn touching(mesh: &face_prep::FaceMesh) -> face_prep::FaceMesh {
    let c = chains(mesh, &mouth_and_eyes(mesh).0);
    let (lo, hi) = face_prep::topology::bounding_box(mesh.vertices.iter().copied());
    let gap = 1e-6 * (hi - lo).length();
    let mut v = mesh.vertices.clone();
    for (&u, &l) in c.upper.iter().zip(&c.lower) {
        let mid = 0.5 * (v[u as usize] + v[l as usize]);
        v[u as usize] = mid + 0.5 * gap * DVec3::Y;
        v[l as usize] = mid - 0.5 * gap * DVec3::Y;
    }
    face_prep::FaceMesh::from_triangles(&v, &mesh.triangles).unwrap()
}

fn mediapipe() -> face_prep::FaceMesh {
    face_prep::load_face(&support::asset("mediapipe_canonical_4loop.obj")).unwrap()
}

fn build(mesh: &face_prep::FaceMesh) -> FaceModel {
    build_face_model(mesh, &PipelineParams::default(), &Control::new()).unwrap()
}

/// What a closed mouth's targets do, in mm (canonical frame).
#[derive(Debug)]
struct MouthFigures {
    /// jawOpen: how far the lower lip's middle margin vertex drops.
    lower_lip_drop_mm: f64,
    /// jawOpen: largest motion of the upper lip's margin over the middle 70 % of the width.
    upper_middle_mm: f64,
    /// jawOpen: largest motion of the upper margin anywhere (beside the corners too).
    upper_margin_mm: f64,
    /// jawOpen: the mouth corners.
    corners_mm: f64,
    /// mouthPucker: mouth width (corner to corner in the front plane) over the neutral's.
    pucker_width: f64,
    /// mouthPucker: triangles turned over with no corner within 0.15 iod of the mouth loop.
    pucker_flips_outside_lips: usize,
    /// Largest motion of any vertex in any ARKit or VRM target, and the target.
    largest_mm: (f64, &'static str),
}

fn field(m: &FaceModel, name: &str) -> Vec<DVec3> {
    support::named_field(m, name)
}

fn figures(m: &FaceModel) -> MouthFigures {
    let lm = FaceLandmarks::of(m).expect("four loops");
    let c = lm.canonical_points(&m.mesh.vertices);
    let mouth = &lm.loops.mouth;
    // The loop runs with the surface on its left seen from the front: along the upper lip
    // from the corner at −x to the corner at +x.
    let (left, right) = if c[lm.mouth_corner_l as usize].x < c[lm.mouth_corner_r as usize].x {
        (lm.mouth_corner_l, lm.mouth_corner_r)
    } else {
        (lm.mouth_corner_r, lm.mouth_corner_l)
    };
    let start = mouth.iter().position(|&v| v == left).unwrap();
    let walk: Vec<u32> = mouth[start..]
        .iter()
        .chain(&mouth[..start])
        .copied()
        .collect();
    let split = walk.iter().position(|&v| v == right).unwrap();
    let upper: Vec<u32> = walk[1..split].to_vec();
    let lower: Vec<u32> = walk[split + 1..].to_vec();
    let (x0, x1) = (c[left as usize].x, c[right as usize].x);
    let (cx, half) = (0.5 * (x0 + x1), 0.5 * (x1 - x0));
    let mm = |d: DVec3| lm.canonical_mm(d);
    let jaw = field(m, "jawOpen");
    let lower_mid = *lower
        .iter()
        .min_by(|&&a, &&b| {
            (c[a as usize].x - cx)
                .abs()
                .total_cmp(&(c[b as usize].x - cx).abs())
        })
        .unwrap();
    let max_of = |f: &[DVec3], vs: &mut dyn Iterator<Item = u32>| {
        vs.map(|v| mm(f[v as usize]).length()).fold(0.0, f64::max)
    };
    let upper_middle_mm = max_of(
        &jaw,
        &mut upper
            .iter()
            .copied()
            .filter(|&v| (c[v as usize].x - cx).abs() <= 0.7 * half),
    );
    let upper_margin_mm = max_of(&jaw, &mut upper.iter().copied());
    let corners_mm = max_of(&jaw, &mut [left, right].into_iter());
    let pucker = field(m, "mouthPucker");
    let width = |f: Option<&[DVec3]>| {
        let at = |v: u32| {
            c[v as usize]
                + f.map_or(DVec3::ZERO, |f| {
                    lm.canonical_from_input.transform_vector3(f[v as usize])
                })
        };
        at(left).truncate().distance(at(right).truncate())
    };
    let centroid = |l: &[u32]| l.iter().map(|&v| c[v as usize]).sum::<DVec3>() / l.len() as f64;
    let iod = centroid(&lm.loops.eye_l).distance(centroid(&lm.loops.eye_r));
    let near_lips: Vec<bool> = c
        .iter()
        .map(|p| {
            mouth
                .iter()
                .any(|&v| c[v as usize].distance(*p) < 0.15 * iod)
        })
        .collect();
    let flips = flipped_by(&m.mesh.vertices, &pucker, &m.mesh.triangles);
    let pucker_flips_outside_lips = flips
        .iter()
        .filter(|&&t| {
            !m.mesh.triangles[t as usize]
                .iter()
                .any(|&v| near_lips[v as usize])
        })
        .count();
    let mut largest_mm = (0.0, "");
    for e in arkit::EXPRESSIONS.iter().chain(&vrm::EXPRESSIONS) {
        if e.resolve(m.muscle_ids()).is_none() {
            continue;
        }
        let f = field(m, e.name);
        let l = f
            .iter()
            .map(|d| d.length() * lm.mm_per_unit)
            .fold(0.0, f64::max);
        if l > largest_mm.0 {
            largest_mm = (l, e.name);
        }
    }
    MouthFigures {
        lower_lip_drop_mm: -mm(jaw[lower_mid as usize]).y,
        upper_middle_mm,
        upper_margin_mm,
        corners_mm,
        pucker_width: width(Some(&pucker)) / width(None),
        pucker_flips_outside_lips,
        largest_mm,
    }
}

/// The bounds (see the module docs).
fn assert_mouth_works(name: &str, f: &MouthFigures) {
    eprintln!("{name}: {f:?}");
    assert!(
        (25.0..=45.0).contains(&f.lower_lip_drop_mm),
        "{name}: jawOpen drops the lower lip {:.1} mm",
        f.lower_lip_drop_mm
    );
    assert!(
        f.upper_middle_mm < 5.0,
        "{name}: upper lip {:.1} mm",
        f.upper_middle_mm
    );
    assert!(
        f.upper_margin_mm < 20.0,
        "{name}: upper margin {:.1} mm",
        f.upper_margin_mm
    );
    assert!(
        f.corners_mm < 20.0,
        "{name}: corners {:.1} mm",
        f.corners_mm
    );
    assert!(
        f.pucker_width <= 0.8,
        "{name}: pucker width {:.2}",
        f.pucker_width
    );
    assert_eq!(
        f.pucker_flips_outside_lips, 0,
        "{name}: pucker turns triangles over"
    );
    assert!(
        f.largest_mm.0 <= 60.0,
        "{name}: {} moves {:.1} mm",
        f.largest_mm.1,
        f.largest_mm.0
    );
}

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

/// Face (c) as written: the lips' separate vertices (see the module docs).
fn touching_raw(mesh: &face_prep::FaceMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    (touching(mesh).vertices, mesh.triangles.clone())
}

/// Builds `raw` and `raw` written differently — `input_from_original` applied, the vertices
/// renumbered (new index `i` holds vertex `(7 i + 3) mod n`... any step coprime with `n`), the
/// triangles reversed in order — with the unit stated, and returns the worst ARKit target's
/// RMS difference over its largest motion and the ratio of the near-singular figures.
fn invariance(
    raw: &(Vec<DVec3>, Vec<[u32; 3]>),
    input_from_original: DAffine3,
) -> (f64, &'static str, f64) {
    let (positions, triangles) = raw;
    let n = positions.len();
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let step = (1..n).map(|s| 7 * s + 3).find(|&s| gcd(s, n) == 1).unwrap();
    let mut new_of_old = vec![0u32; n];
    for new in 0..n {
        new_of_old[(new * step) % n] = new as u32;
    }
    let moved: Vec<DVec3> = (0..n)
        .map(|new| input_from_original.transform_point3(positions[(new * step) % n]))
        .collect();
    let renumbered: Vec<[u32; 3]> = triangles
        .iter()
        .rev()
        .map(|t| t.map(|v| new_of_old[v as usize]))
        .collect();
    let base = build(&face_prep::FaceMesh::from_triangles(positions, triangles).unwrap());
    let scale = input_from_original.matrix3.x_axis.length();
    let mut params = PipelineParams::default();
    params.rig.units = face_prep::units::Units::Fixed(face_prep::units::LengthUnit::Scaled(
        base.rig.mm_per_unit() / scale,
    ));
    let other_mesh = face_prep::FaceMesh::from_triangles(&moved, &renumbered).unwrap();
    let other = build_face_model(&other_mesh, &params, &Control::new()).unwrap();
    // Vertex correspondence by position (the lower lip's copies are apart from the upper lip's
    // vertices by the same fraction of the face's size in both).
    let of_base: Vec<usize> = base
        .mesh
        .vertices
        .iter()
        .map(|&p| {
            let q = input_from_original.transform_point3(p);
            (0..other.mesh.vertices.len())
                .min_by(|&a, &b| {
                    other.mesh.vertices[a]
                        .distance_squared(q)
                        .total_cmp(&other.mesh.vertices[b].distance_squared(q))
                })
                .unwrap()
        })
        .collect();
    let back = input_from_original.matrix3.inverse();
    let mut worst = (0.0f64, "");
    for e in arkit::EXPRESSIONS {
        if e.resolve(base.muscle_ids()).is_none() {
            continue;
        }
        let (a, b) = (field(&base, e.name), field(&other, e.name));
        let largest = a.iter().map(|d| d.length()).fold(0.0, f64::max);
        if largest == 0.0 {
            continue;
        }
        let rms = (a
            .iter()
            .zip(&of_base)
            .map(|(d, &o)| (back * b[o] - *d).length_squared())
            .sum::<f64>()
            / a.len() as f64)
            .sqrt();
        if rms / largest > worst.0 {
            worst = (rms / largest, e.name);
        }
    }
    let ratio = other.report.response_amplification / base.report.response_amplification;
    (worst.0, worst.1, ratio)
}

/// Issue 30, item 3, on faces (b) and (c): rotated 30° about a tilted axis, ×10 and moved by
/// 1 000 units, renumbered; and ×0.001. Every ARKit target within 2 % RMS of its largest motion,
/// the near-singular ratio within 10 %.
#[test]
fn closed_mouths_are_invariant_to_how_the_file_is_written() {
    let face = mediapipe();
    let rotated = DAffine3::from_scale_rotation_translation(
        DVec3::splat(10.0),
        DQuat::from_axis_angle(DVec3::new(0.3, -0.8, 0.5).normalize(), 30f64.to_radians()),
        DVec3::new(1000.0, -1000.0, 1000.0),
    );
    let tiny = DAffine3::from_scale(DVec3::splat(0.001));
    for (name, raw) in [("slit", slit_raw(&face)), ("touching", touching_raw(&face))] {
        for (how, t) in [("rotated x10 moved", rotated), ("x0.001", tiny)] {
            let (worst, target, ratio) = invariance(&raw, t);
            eprintln!("{name}, {how}: worst ARKit target {worst:.2e} ({target}), ratio {ratio:.4}");
            assert!(worst <= 0.02, "{name}, {how}: {target} {worst:.4}");
            assert!(
                (0.9..=1.1).contains(&ratio),
                "{name}, {how}: ratio {ratio:.3}"
            );
        }
    }
}
