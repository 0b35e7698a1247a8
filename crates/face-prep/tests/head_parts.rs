//! The parts of a whole head found from its geometry (issue 32, items 1 and 2): ICT-FaceKit's
//! generic head as it is (`assets/heads/`, whose README lists the parts by index range, a list
//! the code does not use), the same head moved, turned, scaled and renumbered, and heads that
//! are not one head.

use std::path::{Path, PathBuf};

use face_prep::InputLimits;
use face_prep::parts::{PartKind, Scene, Side, find_parts};
use glam::{DQuat, DVec3};

fn head_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/heads/ict_generic_head.obj")
}

/// The kind of every vertex (by the component holding it); `None` for vertices no face uses.
fn vertex_kinds(scene: &Scene) -> Vec<Option<PartKind>> {
    let parts = find_parts(scene).unwrap();
    let mut out = vec![None; scene.positions.len()];
    for (c, kind) in parts.components.iter().zip(&parts.kinds) {
        for &v in &c.vertices {
            assert!(out[v as usize].is_none(), "vertex {v} in two components");
            out[v as usize] = Some(*kind);
        }
    }
    out
}

/// ICT-FaceKit's own part of vertex `v` (assets/heads README), as the kind facebem should find.
fn documented_kind(v: usize) -> PartKind {
    match v {
        0..=14061 => PartKind::Skin,
        14062..=17038 => PartKind::GumsAndTongue,
        17039..=19246 => PartKind::UpperTooth,
        19247..=21450 => PartKind::LowerTooth,
        21451..=23020 => PartKind::Eyeball(Side::Left),
        23021..=24590 => PartKind::Eyeball(Side::Right),
        _ => PartKind::LidPart,
    }
}

#[test]
fn every_part_of_the_ict_head_is_found_from_its_geometry() {
    let scene = Scene::read(&head_path(), &InputLimits::default()).unwrap();
    assert_eq!(scene.positions.len(), 26_719);
    let kinds = vertex_kinds(&scene);
    let mut wrong = Vec::new();
    for (v, k) in kinds.iter().enumerate() {
        let expected = documented_kind(v);
        if *k != Some(expected) {
            wrong.push((v, *k, expected));
        }
    }
    assert!(
        wrong.is_empty(),
        "{} vertices misread, e.g. {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(5)]
    );
    let parts = find_parts(&scene).unwrap();
    let frame = parts.frame.unwrap();
    // The file's own axes: +x the subject's left, +y up, +z forward.
    assert!(frame.left.dot(DVec3::X) > 0.99, "{:?}", frame.left);
    assert!(frame.up.dot(DVec3::Y) > 0.95, "{:?}", frame.up);
    assert!(frame.forward.dot(DVec3::Z) > 0.95, "{:?}", frame.forward);
    // The eyeballs: about 1.2 cm in radius, 6 cm apart.
    let [l, r] = parts.eyeballs.unwrap();
    for e in [l, r] {
        assert!((1.0..1.8).contains(&e.radius), "{e:?}");
    }
    assert!((5.5..7.0).contains(&l.centre.distance(r.centre)));
}

#[test]
fn the_parts_do_not_depend_on_pose_size_or_numbering() {
    let text = std::fs::read_to_string(head_path()).unwrap();
    let scene = Scene::from_obj(&text, &InputLimits::default()).unwrap();
    let reference = vertex_kinds(&scene);
    // Turned 30° about a tilted axis, ×10, moved; vertices renumbered (reversed) and every
    // triangle's corners rotated.
    let q = DQuat::from_axis_angle(DVec3::new(0.3, 1.0, 0.2).normalize(), 30f64.to_radians());
    let n = scene.positions.len() as u32;
    let moved = Scene {
        positions: scene
            .positions
            .iter()
            .rev()
            .map(|p| q * (10.0 * *p) + DVec3::new(100.0, -50.0, 7.0))
            .collect(),
        sources: scene.sources.iter().rev().copied().collect(),
        triangles: scene
            .triangles
            .iter()
            .rev()
            .map(|t| [t[1], t[2], t[0]].map(|v| n - 1 - v))
            .collect(),
        triangle_label: scene.triangle_label.iter().rev().copied().collect(),
        labels: scene.labels.clone(),
        gltf_meshes: Vec::new(),
        normals: Vec::new(),
    };
    let kinds = vertex_kinds(&moved);
    for v in 0..n as usize {
        assert_eq!(kinds[n as usize - 1 - v], reference[v], "vertex {v}");
    }
    let frame = find_parts(&moved).unwrap().frame.unwrap();
    assert!(frame.left.dot(q * DVec3::X) > 0.99);
    assert!(frame.up.dot(q * DVec3::Y) > 0.95);
}

#[test]
fn two_heads_in_one_file_are_refused() {
    let text = std::fs::read_to_string(head_path()).unwrap();
    let scene = Scene::from_obj(&text, &InputLimits::default()).unwrap();
    let n = scene.positions.len() as u32;
    let mut two = scene.clone();
    two.positions.extend(
        scene
            .positions
            .iter()
            .map(|p| *p + DVec3::new(40.0, 0.0, 0.0)),
    );
    two.sources.extend(scene.sources.iter().copied());
    two.triangles
        .extend(scene.triangles.iter().map(|t| t.map(|v| v + n)));
    two.triangle_label
        .extend(scene.triangle_label.iter().copied());
    let err = find_parts(&two).unwrap_err();
    assert!(err.to_string().contains("two heads or two faces"), "{err}");
}

/// The head as a glTF with one mesh per material, all under one parent node that turns,
/// scales and moves them (positions stored in the parent's frame, one external buffer).
fn head_as_gltf(scene: &Scene, dir: &Path) -> (PathBuf, Vec<Vec<u32>>) {
    let q = DQuat::from_axis_angle(DVec3::new(-0.2, 0.4, 1.0).normalize(), 25f64.to_radians());
    let (scale, shift) = (0.01, DVec3::new(0.3, 1.2, -0.5));
    let mut bin: Vec<u8> = Vec::new();
    let (mut views, mut accessors, mut meshes, mut children) = (vec![], vec![], vec![], vec![]);
    let mut vertex_maps = Vec::new();
    for label in 0..scene.labels.len() as u32 {
        let tris: Vec<[u32; 3]> = (0..scene.triangles.len())
            .filter(|&t| scene.triangle_label[t] == label)
            .map(|t| scene.triangles[t])
            .collect();
        let mut local = std::collections::HashMap::new();
        let mut map: Vec<u32> = Vec::new();
        let indices: Vec<u32> = tris
            .iter()
            .flatten()
            .map(|&v| {
                *local.entry(v).or_insert_with(|| {
                    map.push(v);
                    map.len() as u32 - 1
                })
            })
            .collect();
        // Stored so that the parent's transform gives back the file's positions.
        let stored: Vec<[f32; 3]> = map
            .iter()
            .map(|&v| {
                (q.inverse() * ((scene.positions[v as usize] - shift) / scale))
                    .as_vec3()
                    .to_array()
            })
            .collect();
        let (lo, hi) = stored
            .iter()
            .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
                (
                    [0, 1, 2].map(|k| lo[k].min(p[k])),
                    [0, 1, 2].map(|k| hi[k].max(p[k])),
                )
            });
        let pos_offset = bin.len();
        bin.extend(stored.iter().flatten().flat_map(|c| c.to_le_bytes()));
        let idx_offset = bin.len();
        bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
        let n = views.len();
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{pos_offset},"byteLength":{}}}"#,
            idx_offset - pos_offset
        ));
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{idx_offset},"byteLength":{}}}"#,
            bin.len() - idx_offset
        ));
        accessors.push(format!(
            r#"{{"bufferView":{n},"componentType":5126,"count":{},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}}"#,
            map.len(), lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
        ));
        accessors.push(format!(
            r#"{{"bufferView":{},"componentType":5125,"count":{},"type":"SCALAR"}}"#,
            n + 1,
            indices.len()
        ));
        meshes.push(format!(
            r#"{{"name":"part{label}","primitives":[{{"attributes":{{"POSITION":{n}}},"indices":{}}}]}}"#,
            n + 1
        ));
        children.push(format!(r#"{{"mesh":{label}}}"#));
        vertex_maps.push(map);
    }
    std::fs::write(dir.join("head.bin"), &bin).unwrap();
    let child_indices: Vec<String> = (1..=children.len()).map(|i| i.to_string()).collect();
    let r = q;
    let gltf = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
        "nodes":[{{"rotation":[{},{},{},{}],"scale":[{scale},{scale},{scale}],"translation":[{},{},{}],"children":[{}]}},{}],
        "meshes":[{}],"accessors":[{}],"bufferViews":[{}],
        "buffers":[{{"uri":"head.bin","byteLength":{}}}]}}"#,
        r.x,
        r.y,
        r.z,
        r.w,
        shift.x,
        shift.y,
        shift.z,
        child_indices.join(","),
        children.join(","),
        meshes.join(","),
        accessors.join(","),
        views.join(","),
        bin.len()
    );
    let path = dir.join("head.gltf");
    std::fs::write(&path, gltf).unwrap();
    (path, vertex_maps)
}

#[test]
fn a_gltf_head_of_several_meshes_under_a_transformed_node_gives_the_same_parts() {
    let scene = Scene::read(&head_path(), &InputLimits::default()).unwrap();
    let reference = vertex_kinds(&scene);
    let dir = tempfile::tempdir().unwrap();
    let (path, maps) = head_as_gltf(&scene, dir.path());
    let gltf = Scene::read(&path, &InputLimits::default()).unwrap();
    assert_eq!(gltf.labels.len(), scene.labels.len());
    let kinds = vertex_kinds(&gltf);
    let mut checked = 0;
    for (v, source) in gltf.sources.iter().enumerate() {
        let face_prep::parts::VertexSource::Gltf { mesh, vertex } = *source else {
            panic!("{source:?}");
        };
        let original = maps[mesh as usize][vertex as usize] as usize;
        // Positions come back in the file's frame (to f32 rounding).
        assert!(gltf.positions[v].distance(scene.positions[original]) < 1e-4);
        assert_eq!(
            kinds[v], reference[original],
            "glTF vertex {v} (OBJ {original})"
        );
        checked += 1;
    }
    assert!(checked > scene.positions.len());
}

#[test]
fn the_front_face_cut_from_the_head_has_four_openings_where_the_features_are() {
    let scene = Scene::read(&head_path(), &InputLimits::default()).unwrap();
    let parts = find_parts(&scene).unwrap();
    let face = face_prep::parts::front_face(&scene, &parts).unwrap();
    // Only skin, and a valid face of four loops.
    assert!(face.scene_vertex.iter().all(|&v| v < 14_062));
    let mesh = face_prep::FaceMesh::from_triangles(&face.positions, &face.triangles).unwrap();
    let loops = face_prep::topology::validate(&mesh.vertices, &mesh.triangles).unwrap();
    assert_eq!(loops.len(), 4);
    let centre = |lp: &Vec<u32>| {
        lp.iter().map(|&v| mesh.vertices[v as usize]).sum::<DVec3>() / lp.len() as f64
    };
    let [l, r] = parts.eyeballs.unwrap();
    let mut found = Vec::new();
    for lp in &loops {
        let c = centre(lp);
        found.push(if c.distance(l.centre) < l.radius {
            "eye L"
        } else if c.distance(r.centre) < r.radius {
            "eye R"
        } else if (c.y - (-3.1)).abs() < 1.0 && c.x.abs() < 0.5 && c.z > 9.0 {
            // ICT's lips part at y ≈ −3.1 cm, in front of the incisors (z ≈ 10.8).
            "mouth"
        } else {
            "contour"
        });
    }
    found.sort_unstable();
    assert_eq!(
        found,
        ["contour", "eye L", "eye R", "mouth"],
        "{:?}",
        loops.iter().map(centre).collect::<Vec<_>>()
    );
    // The same cut on the head turned, scaled and moved.
    let q = DQuat::from_axis_angle(DVec3::new(0.3, 1.0, 0.2).normalize(), 30f64.to_radians());
    let mut moved = scene.clone();
    for p in &mut moved.positions {
        *p = q * (10.0 * *p) + DVec3::new(100.0, -50.0, 7.0);
    }
    let moved_face = face_prep::parts::front_face(&moved, &find_parts(&moved).unwrap()).unwrap();
    let set = |f: &face_prep::parts::FrontFace| {
        let mut v = f.scene_vertex.clone();
        v.sort_unstable();
        v
    };
    assert_eq!(set(&moved_face), set(&face));
}
