//! Test faces with closed mouths and eyes, made from the bundled MediaPipe face, and what their
//! targets do (`tests/closed_mouths_and_eyes.rs` describes the faces and the bounds).
#![allow(dead_code)]

use crate::support;
use facebem::expressions::{arkit, vrm};
use facebem::report::measure::{FaceLandmarks, flipped_by};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::{DAffine3, DQuat, DVec3};

/// A loop of `mesh` split at its corners (the loop's extreme vertices along the eye line, x
/// here) into two chains running from one corner to the other, the upper one first.
pub struct Chains {
    pub corners: [u32; 2],
    pub upper: Vec<u32>,
    pub lower: Vec<u32>,
}

pub fn loops_of(mesh: &face_prep::FaceMesh) -> Vec<Vec<u32>> {
    face_prep::topology::validate(&mesh.vertices, &mesh.triangles).unwrap()
}

/// The mouth loop and the two eye loops of a bundled face (its y is up).
pub fn mouth_and_eyes(mesh: &face_prep::FaceMesh) -> (Vec<u32>, [Vec<u32>; 2]) {
    let v = &mesh.vertices;
    let mut loops = loops_of(mesh);
    loops.sort_by_key(|l| std::cmp::Reverse(l.len()));
    let mean_y = |l: &[u32]| l.iter().map(|&i| v[i as usize].y).sum::<f64>() / l.len() as f64;
    let mut inner = loops[1..].to_vec();
    inner.sort_by(|a, b| mean_y(a).total_cmp(&mean_y(b)));
    (inner[0].clone(), [inner[1].clone(), inner[2].clone()])
}

pub fn chains(mesh: &face_prep::FaceMesh, lp: &[u32]) -> Chains {
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
pub fn welded_raw(mesh: &face_prep::FaceMesh, welded: &[&[u32]]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    closed_raw(mesh, welded, false)
}

/// `mesh` with the loops `welded` closed as [`welded_raw`] does; with `own_lower`, each lower
/// vertex keeps its own `v` line at its partner's position (the triangles that collapse in the
/// weld are dropped all the same).
pub fn closed_raw(
    mesh: &face_prep::FaceMesh,
    welded: &[&[u32]],
    own_lower: bool,
) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut v = mesh.vertices.clone();
    let mut replace: Vec<u32> = (0..v.len() as u32).collect();
    let mut kept = replace.clone();
    for lp in welded {
        let c = chains(mesh, lp);
        assert_eq!(c.upper.len(), c.lower.len());
        for (&u, &l) in c.upper.iter().zip(&c.lower) {
            let mid = 0.5 * (v[u as usize] + v[l as usize]);
            v[u as usize] = mid;
            v[l as usize] = mid;
            replace[l as usize] = u;
        }
        for (corner, end) in [(0, c.upper[0]), (1, c.upper[c.upper.len() - 1])] {
            replace[c.corners[corner] as usize] = end;
            kept[c.corners[corner] as usize] = end;
        }
    }
    if !own_lower {
        kept = replace.clone();
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| {
            let t = t.map(|i| replace[i as usize]);
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
        })
        .map(|t| t.map(|i| kept[i as usize]))
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
pub fn slit_raw(mesh: &face_prep::FaceMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mouth, _) = mouth_and_eyes(mesh);
    welded_raw(mesh, &[&mouth])
}

/// Face (c') as written: face (b) with the lower lip's own `v` lines, at exactly the upper
/// lip's positions (see the module docs).
pub fn coincident_raw(mesh: &face_prep::FaceMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mouth, _) = mouth_and_eyes(mesh);
    closed_raw(mesh, &[&mouth], true)
}

/// A face as written: positions and triangles.
pub type RawFace = (Vec<DVec3>, Vec<[u32; 3]>);

/// Rings of the mouth bag of face (e).
pub const BAG_RINGS: usize = 4;

/// Face (e) as written: MediaPipe with its mouth closed by a bag behind the lips. The mouth
/// loop is carried back [`BAG_RINGS`] times, each ring 1 cm (0.16 iod) further back and 15 %
/// narrower toward the loop's centroid, and the last ring is closed by a fan to a vertex
/// behind it. The face's own lines come first, then the rings' (ring by ring, in loop order),
/// then the fan's centre; the second value of the result is the loop in that order.
pub fn bag_raw(mesh: &face_prep::FaceMesh) -> (RawFace, Vec<u32>) {
    let (mut lp, _) = mouth_and_eyes(mesh);
    // The bag's triangles run against the face's along the loop.
    let forward = mesh
        .triangles
        .iter()
        .any(|t| (0..3).any(|k| t[k] == lp[0] && t[(k + 1) % 3] == lp[1]));
    if !forward {
        lp.reverse();
    }
    let mut positions = mesh.vertices.clone();
    let mut triangles = mesh.triangles.clone();
    let centroid = lp.iter().map(|&v| positions[v as usize]).sum::<DVec3>() / lp.len() as f64;
    let mut ring = lp.clone();
    for k in 1..=BAG_RINGS {
        let next: Vec<u32> = lp
            .iter()
            .map(|&v| {
                let p = positions[v as usize];
                positions.push(
                    centroid + (p - centroid) * (1.0 - 0.15 * k as f64) - DVec3::Z * k as f64,
                );
                (positions.len() - 1) as u32
            })
            .collect();
        for i in 0..lp.len() {
            let j = (i + 1) % lp.len();
            let (a, b, a1, b1) = (ring[i], ring[j], next[i], next[j]);
            triangles.push([b, a, a1]);
            triangles.push([b, a1, b1]);
        }
        ring = next;
    }
    positions.push(centroid - DVec3::Z * (BAG_RINGS as f64 + 0.5));
    let centre = (positions.len() - 1) as u32;
    for i in 0..lp.len() {
        triangles.push([ring[(i + 1) % lp.len()], ring[i], centre]);
    }
    ((positions, triangles), lp)
}

/// Face (f) as written: the lips and both eyes' lids welded (one loop: the contour).
pub fn all_closed_raw(mesh: &face_prep::FaceMesh) -> RawFace {
    let (mouth, [e1, e2]) = mouth_and_eyes(mesh);
    welded_raw(mesh, &[&mouth, &e1, &e2])
}

/// Face (g) as written: one eye's lids welded (the eye loop of larger x; three loops).
pub fn one_eye_closed_raw(mesh: &face_prep::FaceMesh) -> RawFace {
    let (_, [e1, e2]) = mouth_and_eyes(mesh);
    let x = |l: &[u32]| l.iter().map(|&v| mesh.vertices[v as usize].x).sum::<f64>();
    let eye = if x(&e1) > x(&e2) { e1 } else { e2 };
    welded_raw(mesh, &[&eye])
}

/// Face (d) as written: both eyes' lids welded along their lid lines (see the module docs).
pub fn closed_eyes_raw(mesh: &face_prep::FaceMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (_, [e1, e2]) = mouth_and_eyes(mesh);
    welded_raw(mesh, &[&e1, &e2])
}

/// Face (b) (see the module docs).
pub fn slit(mesh: &face_prep::FaceMesh) -> face_prep::FaceMesh {
    let (v, t) = slit_raw(mesh);
    face_prep::FaceMesh::from_triangles(&v, &t).unwrap()
}

pub fn obj_text(positions: &[DVec3], triangles: &[[u32; 3]]) -> String {
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
pub fn touching(mesh: &face_prep::FaceMesh) -> face_prep::FaceMesh {
    let mouth = mouth_and_eyes(mesh).0;
    face_prep::FaceMesh::from_triangles(&touching_positions(mesh, &[&mouth]), &mesh.triangles)
        .unwrap()
}

/// `mesh`'s positions with the two sides of each loop of `touched` meeting at the midpoints of
/// their pairs, 10⁻⁶ of the face's size apart.
pub fn touching_positions(mesh: &face_prep::FaceMesh, touched: &[&[u32]]) -> Vec<DVec3> {
    let (lo, hi) = face_prep::topology::bounding_box(mesh.vertices.iter().copied());
    let gap = 1e-6 * (hi - lo).length();
    let mut v = mesh.vertices.clone();
    for lp in touched {
        let c = chains(mesh, lp);
        for (&u, &l) in c.upper.iter().zip(&c.lower) {
            let mid = 0.5 * (v[u as usize] + v[l as usize]);
            v[u as usize] = mid + 0.5 * gap * DVec3::Y;
            v[l as usize] = mid - 0.5 * gap * DVec3::Y;
        }
    }
    v
}

/// Asserts that none of the named expressions turns a triangle of `m` over.
pub fn assert_no_flips(m: &FaceModel, names: &[&str]) {
    for name in names {
        let f = field(m, name);
        let flips = flipped_by(&m.mesh.vertices, &f, &m.mesh.triangles);
        assert!(
            flips.is_empty(),
            "{name} turns {} triangles over",
            flips.len()
        );
    }
}

pub fn mediapipe() -> face_prep::FaceMesh {
    face_prep::load_face(&support::asset("mediapipe_canonical_4loop.obj")).unwrap()
}

pub fn build(mesh: &face_prep::FaceMesh) -> FaceModel {
    build_face_model(mesh, &PipelineParams::default(), &Control::new()).unwrap()
}

/// What a closed mouth's targets do, in mm (canonical frame).
#[derive(Debug)]
pub struct MouthFigures {
    /// jawOpen: how far the lower lip's middle margin vertex drops.
    pub lower_lip_drop_mm: f64,
    /// jawOpen: largest motion of the upper lip's margin over the middle 70 % of the width.
    pub upper_middle_mm: f64,
    /// jawOpen: largest motion of the upper margin anywhere (beside the corners too).
    pub upper_margin_mm: f64,
    /// jawOpen: the mouth corners.
    pub corners_mm: f64,
    /// mouthPucker: mouth width (corner to corner in the front plane) over the neutral's.
    pub pucker_width: f64,
    /// mouthPucker: triangles turned over with no corner within 0.15 iod of the mouth loop.
    pub pucker_flips_outside_lips: usize,
    /// Largest motion of any vertex in any ARKit or VRM target, and the target.
    pub largest_mm: (f64, &'static str),
}

pub fn field(m: &FaceModel, name: &str) -> Vec<DVec3> {
    support::named_field(m, name)
}

pub fn figures(m: &FaceModel) -> MouthFigures {
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
pub fn assert_mouth_works(name: &str, f: &MouthFigures) {
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

/// Face (c) as written: the lips' separate vertices (see the module docs).
pub fn touching_raw(mesh: &face_prep::FaceMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    (touching(mesh).vertices, mesh.triangles.clone())
}

/// Builds `raw` and `raw` written differently — `input_from_original` applied, the vertices
/// renumbered (new index `i` holds vertex `(7 i + 3) mod n`... any step coprime with `n`), the
/// triangles reversed in order — with the unit stated, and returns the worst ARKit target's
/// RMS difference over its largest motion and the ratio of the near-singular figures.
pub fn invariance(
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
    let worst = worst_arkit_target(&base, &other, &of_base, |d| back * d);
    let ratio = other.report.response_amplification / base.report.response_amplification;
    (worst.0, worst.1, ratio)
}

/// The ARKit target of `base` that `other` makes least alike, and by how much: the RMS over
/// `base`'s vertices of `other`'s field (at vertex `of_base[i]`, carried into `base`'s frame and
/// units by `to_base`) minus `base`'s, over the target's largest motion.
pub fn worst_arkit_target(
    base: &FaceModel,
    other: &FaceModel,
    of_base: &[usize],
    to_base: impl Fn(DVec3) -> DVec3,
) -> (f64, &'static str) {
    let mut worst = (0.0f64, "");
    for e in arkit::EXPRESSIONS {
        if e.resolve(base.muscle_ids()).is_none() {
            continue;
        }
        let (a, b) = (field(base, e.name), field(other, e.name));
        let largest = a.iter().map(|d| d.length()).fold(0.0, f64::max);
        if largest == 0.0 {
            continue;
        }
        let rms = (a
            .iter()
            .zip(of_base)
            .map(|(d, &o)| (to_base(b[o]) - *d).length_squared())
            .sum::<f64>()
            / a.len() as f64)
            .sqrt();
        if rms / largest > worst.0 {
            worst = (rms / largest, e.name);
        }
    }
    worst
}

/// Rotation by 30° about a tilted axis, scale ×10 and a move by 1 000 units (issue 30, item 3).
pub fn rotated_scaled_moved() -> DAffine3 {
    DAffine3::from_scale_rotation_translation(
        DVec3::splat(10.0),
        DQuat::from_axis_angle(DVec3::new(0.3, -0.8, 0.5).normalize(), 30f64.to_radians()),
        DVec3::new(1000.0, -1000.0, 1000.0),
    )
}

/// Asserts that `raw` written as `input_from_original` (`how`) makes every ARKit target within
/// 2 % RMS of its largest motion and the same near-singular ratio within 10 % ([`invariance`]).
pub fn assert_invariant(name: &str, how: &str, raw: &RawFace, input_from_original: DAffine3) {
    let (worst, target, ratio) = invariance(raw, input_from_original);
    eprintln!("{name}, {how}: worst ARKit target {worst:.2e} ({target}), ratio {ratio:.4}");
    assert!(worst <= 0.02, "{name}, {how}: {target} {worst:.4}");
    assert!(
        (0.9..=1.1).contains(&ratio),
        "{name}, {how}: ratio {ratio:.3}"
    );
}
