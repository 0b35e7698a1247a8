//! Shell building on a synthetic flat face whose L-shaped eye hole leaves a chord (an interior
//! edge joining two vertices of the same eye contour), and the self-intersection checker.

use face_prep::{ElementTag, FaceMesh, FaceRig, RigParams};
use glam::DVec3;
use std::collections::{HashMap, HashSet};

const W: u32 = 14; // vertices per row
const H: u32 = 12; // rows

/// 13×11 quads in the x-y plane facing +z, diagonals SW→NE. Holes: right eye = 2×2 block at
/// quads (3..5, 7..9); left eye = the L formed by quads (8..10, 7..9) minus quad (9, 7), whose
/// diagonal (9,7)–(10,8) joins two eye-contour vertices; mouth = quads (5..9, 2).
fn chord_face() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let v: Vec<DVec3> = (0..H)
        .flat_map(|j| (0..W).map(move |i| DVec3::new(i as f64, j as f64, 0.0)))
        .collect();
    let id = |i: u32, j: u32| i + W * j;
    let hole = |i: u32, j: u32| {
        ((3..5).contains(&i) && (7..9).contains(&j))
            || ((8..10).contains(&i) && (7..9).contains(&j) && (i, j) != (9, 7))
            || ((5..9).contains(&i) && j == 2)
    };
    let mut t = Vec::new();
    for j in 0..H - 1 {
        for i in 0..W - 1 {
            if !hole(i, j) {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    (v, t)
}

#[test]
fn chord_on_an_eye_contour_is_split_on_the_back() {
    let (v, t) = chord_face();
    let face = FaceMesh::from_triangles(&v, &t).unwrap();
    let rig = FaceRig::build(&face, &RigParams::default()).unwrap();
    let s = &rig.shell;
    // Left eye (+x) is the L-shaped hole with 8 contour edges.
    assert_eq!(rig.loops.eye_l.len(), 8);
    // The right eye's centre vertex (4, 8) is unused and dropped, so map input indices.
    assert_eq!(face.input_to_vertex[(4 + W * 8) as usize], None);
    let welded = |i: u32, j: u32| face.input_to_vertex[(i + W * j) as usize].unwrap();
    assert!(rig.loops.eye_l.contains(&welded(9, 7)) && rig.loops.eye_l.contains(&welded(10, 8)));
    let inner: HashSet<u32> = rig
        .loops
        .eye_l
        .iter()
        .chain(&rig.loops.eye_r)
        .chain(&rig.loops.mouth)
        .copied()
        .collect();
    let n = face.vertices.len();
    // One back copy per non-inner-contour vertex, plus exactly one chord mid-point.
    assert_eq!(s.vertices.len(), n + (n - inner.len()) + 1);
    // The two front triangles on the chord give four back triangles.
    let nt = face.triangles.len();
    let back = s.tags.iter().filter(|t| **t == ElementTag::Back).count();
    assert_eq!(back, nt + 2);
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &s.triangles {
        for k in 0..3 {
            *directed.entry((tri[k], tri[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &c) in &directed {
        assert_eq!(c, 1, "edge {a}->{b}");
        assert_eq!(directed.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
    }
    assert_eq!(s.euler_characteristic(), -4);
    assert!(s.signed_volume() > 0.0);
    assert!(s.self_intersections().is_empty());
    // The chord mid-point lies behind the chord's mid-point.
    let mid = s.vertices.last().unwrap();
    assert!(
        (mid.truncate()
            - rig
                .canonical_from_input
                .transform_point3(DVec3::new(9.5, 7.5, 0.0))
                .truncate())
        .length()
            < 1e-9
    );
    assert!(mid.z < -1e-6);
}

#[test]
fn self_intersection_checker_finds_a_back_vertex_pushed_through_the_front() {
    let (v, t) = chord_face();
    let face = FaceMesh::from_triangles(&v, &t).unwrap();
    let rig = FaceRig::build(&face, &RigParams::default()).unwrap();
    let mut s = rig.shell.clone();
    assert!(s.self_intersections().is_empty());
    // Back copy of the vertex at (1, 1): the first back copy is of face vertex 0 (0, 0), so
    // find it by position instead.
    let target = rig
        .canonical_from_input
        .transform_point3(DVec3::new(1.0, 1.0, 0.0));
    let k = (face.vertices.len()..s.vertices.len())
        .min_by(|&a, &b| {
            s.vertices[a]
                .truncate()
                .distance(target.truncate())
                .total_cmp(&s.vertices[b].truncate().distance(target.truncate()))
        })
        .unwrap();
    assert!(s.vertices[k].z < target.z);
    let lift = target.z + 0.5 - s.vertices[k].z;
    s.vertices[k] += DVec3::new(0.3, 0.2, lift);
    let hits = s.self_intersections();
    assert!(!hits.is_empty());
    assert!(hits.iter().all(|h| {
        h.iter()
            .any(|&e| s.triangles[e as usize].contains(&(k as u32)))
    }));
}
