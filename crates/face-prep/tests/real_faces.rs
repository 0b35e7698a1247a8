//! Rig building on the four real faces of `assets/`: loading, features, muscles, invariance
//! and the preparation time (the shells: `real_face_shells.rs`).

mod support;

use face_prep::{ElementTag, FaceMesh, FaceRig, MuscleKind, load_face};
use glam::{DAffine3, DMat3, DQuat, DVec3};
use rand::{Rng, SeedableRng};
use std::collections::{HashMap, HashSet};
use support::{FACES, asset, rig_of, thesis};

#[test]
fn loads_real_faces_with_documented_sizes() {
    for (name, nv, nt) in FACES {
        let face = load_face(&asset(name)).unwrap();
        assert_eq!(face.vertices.len(), nv, "{name}");
        assert_eq!(face.triangles.len(), nt, "{name}");
        // Every `v` line is used and maps to the vertex at the same position.
        let text = std::fs::read_to_string(asset(name)).unwrap();
        let vs: Vec<DVec3> = text
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let c: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
                DVec3::new(c[0], c[1], c[2])
            })
            .collect();
        assert_eq!(face.input_to_vertex.len(), vs.len());
        for (i, p) in vs.iter().enumerate() {
            let v = face.input_to_vertex[i].unwrap();
            assert_eq!(face.vertices[v as usize], *p, "{name} input {i}");
        }
    }
}

#[test]
fn nose_tip_in_nose_box_and_skull_above_eyes() {
    for (name, _, _) in FACES {
        let (face, rig) = rig_of(name);
        let front = &rig.shell.vertices[..face.vertices.len()];
        let tip = front
            .iter()
            .copied()
            .max_by(|a, b| a.z.total_cmp(&b.z))
            .unwrap();
        let b = &rig.boxes;
        assert!(
            b.nose.contains(tip.truncate()),
            "{name}: nose tip {tip} outside FBNose {:?}",
            b.nose
        );
        assert!(
            b.skull.min.y >= b.eye_l.max.y && b.skull.min.y >= b.eye_r.max.y,
            "{name}"
        );
        assert!(
            b.eye_l.center().x > b.eye_r.center().x,
            "{name}: left eye must be at +x"
        );
        assert!(
            b.eye_l.min.y > b.mouth.max.y && b.eye_r.min.y > b.mouth.max.y,
            "{name}: eyes above mouth"
        );
    }
}

#[test]
fn ten_muscles_ordered_chains_disjoint_from_skull() {
    for (name, _, _) in FACES {
        let (_, rig) = rig_of(name);
        let s = &rig.shell;
        let skull: HashSet<u32> = rig.skull.iter().copied().collect();
        assert!(
            rig.skull.windows(2).all(|w| w[0] < w[1]),
            "{name}: skull sorted"
        );
        for e in 0..s.element_count() {
            if s.tags[e] == ElementTag::Rim {
                assert!(
                    skull.contains(&(e as u32)),
                    "{name}: rim element {e} not in skull"
                );
            }
        }
        assert_eq!(rig.muscles.len(), 10);
        for (m, kind) in rig.muscles.iter().zip(MuscleKind::THESIS) {
            assert_eq!(m.kind, Some(kind));
            assert!(
                !m.front_chain.is_empty(),
                "{name}: {} has no front elements",
                m.name
            );
            if matches!(kind, MuscleKind::FrontalisL | MuscleKind::FrontalisR) {
                assert!(
                    m.back_chain.is_empty(),
                    "{name}: frontalis has a back chain"
                );
            } else {
                assert!(
                    !m.back_chain.is_empty(),
                    "{name}: {} has no back elements",
                    m.name
                );
            }
            let (start, end) = face_prep::muscles::muscle_definer(kind, &rig.boxes).unwrap();
            let dir = (end - start).normalize();
            for (chain, tag) in [
                (&m.front_chain, ElementTag::Front),
                (&m.back_chain, ElementTag::Back),
            ] {
                let mut seen = HashSet::new();
                let mut last = f64::NEG_INFINITY;
                for &e in chain {
                    assert_eq!(s.tags[e as usize], tag, "{name}: {}", m.name);
                    assert!(
                        !skull.contains(&e),
                        "{name}: {} uses skull element {e}",
                        m.name
                    );
                    assert!(seen.insert(e), "{name}: {} repeats {e}", m.name);
                    // Ordered start → end: the projection on the definer never steps back by
                    // more than one element size (elements straddle the ray positions).
                    let c = s.centroid(e as usize).truncate();
                    let along = (c - start).dot(dir);
                    let size = s
                        .corners(e as usize)
                        .iter()
                        .map(|p| p.truncate().distance(c))
                        .fold(0.0, f64::max);
                    assert!(
                        along >= last - 2.0 * size,
                        "{name}: {} chain goes backwards at {e}",
                        m.name
                    );
                    last = last.max(along);
                }
            }
            eprintln!(
                "{name}: {:<30} front {:>3} back {:>3}",
                m.name,
                m.front_chain.len(),
                m.back_chain.len()
            );
        }
    }
}

#[test]
fn muscle_pattern_moves_each_element_away_from_the_next_path_point_and_keeps_the_end() {
    let (_, rig) = rig_of("ict_narrow_face_dec2500_4loop.obj");
    for (k, m) in rig.muscles.iter().enumerate() {
        let p = rig.muscle_pattern(k);
        assert_eq!(p.len(), m.front_chain.len() + m.back_chain.len());
        let map: HashMap<u32, DVec3> = p.iter().copied().collect();
        for chain in [&m.front_chain, &m.back_chain] {
            let centroids: Vec<DVec3> = chain
                .iter()
                .map(|&e| rig.shell.centroid(e as usize))
                .collect();
            let path = face_prep::muscles::chain_path(&centroids);
            for (k, w) in chain.windows(2).enumerate() {
                let expect = path[k] - path[k + 1];
                assert!((map[&w[0]] - expect).length() <= 1e-12 * rig.face_size);
            }
            if let Some(last) = chain.last() {
                assert_eq!(map[last], DVec3::ZERO);
            }
        }
    }
    assert!(rig.muscle_pattern(rig.muscles.len()).is_empty());
}

fn random_similarity(rng: &mut impl Rng) -> DAffine3 {
    let axis = DVec3::new(
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
    )
    .normalize();
    let rot = DQuat::from_axis_angle(axis, rng.random_range(0.3..6.0));
    let scale = rng.random_range(0.2..5.0);
    let t = DVec3::new(
        rng.random_range(-50.0..50.0),
        rng.random_range(-50.0..50.0),
        rng.random_range(-50.0..50.0),
    );
    DAffine3::from_mat3_translation(DMat3::from_quat(rot) * scale, t)
}

#[test]
fn randomly_rotated_faces_give_the_same_features_and_muscles() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    for (name, _, _) in FACES {
        let (face, rig) = rig_of(name);
        let m = random_similarity(&mut rng);
        let scale = m.matrix3.x_axis.length();
        let moved = FaceMesh::from_triangles(
            &face
                .vertices
                .iter()
                .map(|&p| m.transform_point3(p))
                .collect::<Vec<_>>(),
            &face.triangles,
        )
        .unwrap();
        let r2 = FaceRig::build(&moved, &thesis()).unwrap();
        assert_eq!(rig.loops, r2.loops, "{name}: loop classification differs");
        let tol = 1e-9 * rig.face_size;
        let b1 = [
            rig.boxes.face,
            rig.boxes.eye_l,
            rig.boxes.eye_r,
            rig.boxes.mouth,
            rig.boxes.nose,
            rig.boxes.skull,
        ];
        let b2 = [
            r2.boxes.face,
            r2.boxes.eye_l,
            r2.boxes.eye_r,
            r2.boxes.mouth,
            r2.boxes.nose,
            r2.boxes.skull,
        ];
        for (a, b) in b1.iter().zip(&b2) {
            assert!(
                (a.min * scale - b.min).length() <= tol * scale
                    && (a.max * scale - b.max).length() <= tol * scale,
                "{name}: {a:?} vs {b:?}"
            );
        }
        for (a, b) in rig.muscles.iter().zip(&r2.muscles) {
            assert_eq!(a.front_chain, b.front_chain, "{name}: {}", a.name);
            assert_eq!(a.back_chain, b.back_chain, "{name}: {}", a.name);
        }
        assert_eq!(rig.skull, r2.skull, "{name}");
        // The transform maps the moved input onto the same canonical vertices.
        for (p, q) in face.vertices.iter().zip(&moved.vertices) {
            let a = rig.canonical_from_input.transform_point3(*p) * scale;
            let b = r2.canonical_from_input.transform_point3(*q);
            assert!(a.distance(b) <= tol * scale);
            assert!(
                r2.input_from_canonical().transform_point3(b).distance(*q)
                    <= 1e-9 * scale * rig.face_size + 1e-9 * 50.0
            );
        }
    }
}

#[test]
fn mediapipe_left_and_right_muscles_mirror_each_other() {
    let (_, rig) = rig_of("mediapipe_canonical_4loop.obj");
    let s = &rig.shell;
    // Mean front edge length as the tolerance unit.
    let edge = {
        let t = &s.triangles[..rig.face_triangle_count];
        t.iter()
            .map(|t| s.vertices[t[0] as usize].distance(s.vertices[t[1] as usize]))
            .sum::<f64>()
            / t.len() as f64
    };
    for pair in MuscleKind::THESIS.chunks(2) {
        let l = &rig.muscles[pair[0].index()];
        let r = &rig.muscles[pair[1].index()];
        for (cl, cr) in [
            (&l.front_chain, &r.front_chain),
            (&l.back_chain, &r.back_chain),
        ] {
            let diff = cl.len().abs_diff(cr.len());
            assert!(
                diff <= 2 + cl.len().max(cr.len()) / 5,
                "{}: {} vs {} elements",
                l.name,
                cl.len(),
                cr.len()
            );
            // Every left element's mirror image lies near some right element.
            for &e in cl {
                let c = s.centroid(e as usize);
                let mirrored = DVec3::new(-c.x, c.y, c.z);
                let d = cr
                    .iter()
                    .map(|&f| s.centroid(f as usize).distance(mirrored))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d <= 1.5 * edge,
                    "{}: element {e} mirror is {d:.3} from the right chain (edge {edge:.3})",
                    l.name
                );
            }
        }
    }
}

#[test]
fn prep_time_figure_for_the_largest_face() {
    let face = load_face(&asset("ict_narrow_face_4loop.obj")).unwrap();
    let t0 = std::time::Instant::now();
    let rig = FaceRig::build(&face, &thesis()).unwrap();
    // Figure only (no timing assertion): printed for the notes.
    eprintln!(
        "FIGURE prep time ict_narrow_face_4loop (13120 triangles, {} shell elements): {:.3} s",
        rig.shell.element_count(),
        t0.elapsed().as_secs_f64()
    );
    let t1 = std::time::Instant::now();
    let _ = load_face(&asset("ict_narrow_face_4loop.obj")).unwrap();
    eprintln!(
        "FIGURE load time ict_narrow_face_4loop: {:.3} s",
        t1.elapsed().as_secs_f64()
    );
}

/// Regression (issue 36): vertices 1e-12 apart (a float round trip between a mesh's parts)
/// were not welded, and the face was refused as "non-manifold vertex". Every third face of
/// MediaPipe is given its own copy of its first corner, moved 1e-12 (1e-13 of the face's
/// size); the face loads as the original. Copies 1e-6 of the size apart stay apart (and the
/// face is then refused: they are a real gap).
#[test]
fn vertices_a_rounding_error_apart_are_welded() {
    let text = std::fs::read_to_string(asset(FACES[0].0)).unwrap();
    let original = FaceMesh::from_obj_str(&text).unwrap();
    let with_copies = |offset: f64| {
        let mut vertex_lines = Vec::new();
        let mut face_lines = Vec::new();
        let mut count = 0usize;
        for line in text.lines() {
            if line.starts_with("v ") {
                count += 1;
                vertex_lines.push(line.to_string());
            } else if line.starts_with("f ") {
                face_lines.push(line.to_string());
            }
        }
        let mut extra = Vec::new();
        for (k, face) in face_lines
            .iter_mut()
            .enumerate()
            .filter(|(k, _)| k % 3 == 0)
        {
            let words: Vec<&str> = face.split_whitespace().collect();
            let first: usize = words[1].split('/').next().unwrap().parse().unwrap();
            let p = original.vertices[original.input_to_vertex[first - 1].unwrap() as usize];
            let shifted = p + DVec3::splat(offset * (1.0 + (k % 5) as f64));
            extra.push(format!("v {} {} {}", shifted.x, shifted.y, shifted.z));
            let index = count + extra.len();
            *face = format!("f {index} {}", words[2..].join(" "));
        }
        vertex_lines.extend(extra);
        format!("{}\n{}\n", vertex_lines.join("\n"), face_lines.join("\n"))
    };
    let welded = FaceMesh::from_obj_str(&with_copies(1e-12)).expect("welded");
    assert_eq!(welded.vertices.len(), original.vertices.len());
    assert_eq!(welded.triangles.len(), original.triangles.len());
    assert_eq!(
        welded.input_to_vertex.len(),
        original.input_to_vertex.len() + 284
    );
    // Every input position (originals and copies) maps to a welded vertex within 1e-11.
    let positions = |m: &FaceMesh, i: usize| m.input_to_vertex[i].map(|v| m.vertices[v as usize]);
    for i in 0..original.input_to_vertex.len() {
        let (a, b) = (
            positions(&original, i).unwrap(),
            positions(&welded, i).unwrap(),
        );
        assert!(a.distance(b) < 1e-11, "input {i}: {a} against {b}");
    }
    assert!(welded.input_to_vertex.iter().all(Option::is_some));
    let size = {
        let (lo, hi) = face_prep::topology::bounding_box(original.vertices.iter().copied());
        (hi - lo).length()
    };
    assert!(FaceMesh::from_obj_str(&with_copies(1e-6 * size)).is_err());
}
