//! Synthetic bad inputs: every one must be rejected with the typed error that names the problem.

use face_prep::{FaceMesh, ObjLineError, PrepError, load_face, topology};
use glam::DVec3;
use std::path::PathBuf;

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name)
}

fn mediapipe() -> FaceMesh {
    load_face(&asset("mediapipe_canonical_4loop.obj")).unwrap()
}

fn mediapipe_text() -> String {
    std::fs::read_to_string(asset("mediapipe_canonical_4loop.obj")).unwrap()
}

/// An octahedron, outward wound: closed, so zero boundary loops.
#[test]
fn closed_sphere_has_zero_loops() {
    let v = vec![
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    let mut t = Vec::new();
    for (xi, sx) in [(0u32, 1.0), (1, -1.0)] {
        for (yi, sy) in [(2u32, 1.0), (3, -1.0)] {
            for (zi, sz) in [(4u32, 1.0), (5, -1.0)] {
                t.push(if sx * sy * sz > 0.0 {
                    [xi, yi, zi]
                } else {
                    [xi, zi, yi]
                });
            }
        }
    }
    match FaceMesh::from_triangles(&v, &t) {
        Err(PrepError::WrongLoopCount { count: 0, loops }) => assert!(loops.is_empty()),
        other => panic!("expected WrongLoopCount 0, got {other:?}"),
    }
}

#[test]
fn filling_the_mouth_leaves_three_loops_and_reports_them() {
    let face = mediapipe();
    let loops = topology::validate(&face.vertices, &face.triangles).unwrap();
    // Sizes per PROVENANCE.md: outer 36, mouth 20, eyes 16 / 16.
    let mut sizes: Vec<usize> = loops.iter().map(Vec::len).collect();
    sizes.sort_unstable();
    assert_eq!(sizes, vec![16, 16, 20, 36]);
    let mouth = loops.iter().find(|l| l.len() == 20).unwrap();
    let mut v = face.vertices.clone();
    let mut t = face.triangles.clone();
    let c = mouth.iter().map(|&i| v[i as usize]).sum::<DVec3>() / mouth.len() as f64;
    v.push(c + DVec3::new(0.0, 0.0, -0.1));
    let ci = (v.len() - 1) as u32;
    for k in 0..mouth.len() {
        let (a, b) = (mouth[k], mouth[(k + 1) % mouth.len()]);
        t.push([b, a, ci]);
    }
    // Three loops: the reader looks for lips that meet (`face_prep::frame::contact`) and finds
    // no fold sharp enough where the mouth was (a cone set 0.1 cm back from the lips).
    let loops = topology::validate(&v, &t).unwrap();
    let mut s: Vec<usize> = loops.iter().map(Vec::len).collect();
    s.sort_unstable();
    assert_eq!(s, vec![16, 16, 36]);
    match FaceMesh::from_triangles(&v, &t) {
        Err(e @ PrepError::NoMouth { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.contains("found 3 and no closed mouth") && msg.contains("sharpest fold"),
                "{msg}"
            );
        }
        other => panic!("expected no mouth, got {other:?}"),
    }
}

#[test]
fn removing_an_interior_triangle_gives_five_loops() {
    let face = mediapipe();
    let loops = topology::validate(&face.vertices, &face.triangles).unwrap();
    let on_loop: std::collections::HashSet<u32> = loops.iter().flatten().copied().collect();
    // A triangle none of whose vertices (nor their neighbours' triangles) touch a loop.
    let k = face
        .triangles
        .iter()
        .position(|t| t.iter().all(|v| !on_loop.contains(v)))
        .unwrap();
    let mut t = face.triangles.clone();
    t.remove(k);
    match FaceMesh::from_triangles(&face.vertices, &t) {
        Err(PrepError::WrongLoopCount { count: 5, loops }) => {
            assert!(loops.iter().any(|l| l.size == 3), "{loops:?}");
        }
        other => panic!("expected 5 loops, got {other:?}"),
    }
}

#[test]
fn third_triangle_on_an_edge_is_a_non_manifold_edge() {
    let face = mediapipe();
    let [a, b, c] = face.triangles[10];
    let mut v = face.vertices.clone();
    let pa = v[a as usize];
    let pb = v[b as usize];
    let pc = v[c as usize];
    v.push(0.5 * (pa + pb) + (pa - pb).cross(pc - pa).normalize() * pa.distance(pb));
    let mut t = face.triangles.clone();
    t.push([a, b, (v.len() - 1) as u32]);
    match FaceMesh::from_triangles(&v, &t) {
        Err(PrepError::NonManifoldEdge {
            a: ea,
            b: eb,
            triangles,
            ..
        }) => {
            assert_eq!((ea, eb), (a.min(b), a.max(b)));
            assert_eq!(triangles.len(), 3);
            assert!(triangles.contains(&10) && triangles.contains(&face.triangles.len()));
        }
        other => panic!("expected non-manifold edge, got {other:?}"),
    }
}

#[test]
fn one_flipped_triangle_is_inconsistent_winding() {
    let face = mediapipe();
    let mut t = face.triangles.clone();
    t[100].swap(1, 2);
    match FaceMesh::from_triangles(&face.vertices, &t) {
        Err(PrepError::InconsistentWinding {
            triangles, a, b, ..
        }) => {
            assert!(triangles.contains(&100), "{triangles:?}");
            assert!(t[100].contains(&a) && t[100].contains(&b));
        }
        other => panic!("expected inconsistent winding, got {other:?}"),
    }
}

#[test]
fn nan_vertex_in_obj_names_its_line() {
    let text = mediapipe_text();
    let mut n = 0;
    let bad: String = text
        .lines()
        .map(|l| {
            if l.starts_with("v ") {
                n += 1;
                if n == 8 {
                    return "v nan 0.0 1.0".to_owned();
                }
            }
            l.to_owned()
        })
        .collect::<Vec<_>>()
        .join("\n");
    // Three comment lines, then the `v` lines: the 8th is line 11.
    match FaceMesh::from_obj_str(&bad) {
        Err(PrepError::ObjLine(ObjLineError::NonFinite { line: 11, text })) => {
            assert_eq!(text, "v nan 0.0 1.0")
        }
        other => panic!("expected NaN on line 11, got {other:?}"),
    }
}

#[test]
fn truncated_obj_is_rejected() {
    let text = mediapipe_text();
    // Cut in the middle of the face list: a ragged mesh, not a face with four holes.
    let cut = &text[..text.len() * 3 / 4];
    let err = FaceMesh::from_obj_str(cut).unwrap_err();
    assert!(
        matches!(
            err,
            PrepError::WrongLoopCount { .. }
                | PrepError::NonManifoldVertex { .. }
                | PrepError::MultipleComponents { .. }
        ),
        "{err}"
    );
    // Cut among the `v` lines: no faces at all.
    let first_f = text.find("\nf ").unwrap();
    assert!(matches!(
        FaceMesh::from_obj_str(&text[..first_f]),
        Err(PrepError::EmptyMesh)
    ));
    // Cut in the middle of a `v` line: a malformed line or no faces, never a mesh.
    assert!(matches!(
        FaceMesh::from_obj_str(&text[..first_f / 2]),
        Err(PrepError::ObjLine(ObjLineError::Malformed { .. }) | PrepError::EmptyMesh)
    ));
    // A face referring past the end of the file.
    let err = FaceMesh::from_obj_str(&format!("{text}\nf 1 2 99999\n")).unwrap_err();
    assert!(
        matches!(
            err,
            PrepError::ObjLine(ObjLineError::UndefinedCorner {
                statement: "v",
                defined: 468,
                ..
            })
        ),
        "{err}"
    );
}

#[test]
fn gltf_without_meshes_is_rejected() {
    let json = br#"{"asset":{"version":"2.0"}}"#;
    assert!(matches!(
        FaceMesh::from_gltf_slice(json, None),
        Err(PrepError::GltfNoMesh)
    ));
}

#[test]
fn two_copies_are_two_components() {
    let face = mediapipe();
    let mut v = face.vertices.clone();
    v.extend(
        face.vertices
            .iter()
            .map(|p| *p + DVec3::new(100.0, 0.0, 0.0)),
    );
    let n = face.vertices.len() as u32;
    let mut t = face.triangles.clone();
    t.extend(face.triangles.iter().map(|tri| tri.map(|i| i + n)));
    match FaceMesh::from_triangles(&v, &t) {
        Err(PrepError::MultipleComponents { sizes }) => assert_eq!(sizes, vec![852, 852]),
        other => panic!("expected two components, got {other:?}"),
    }
}

#[test]
fn collapsed_edge_is_a_degenerate_triangle_after_welding() {
    let face = mediapipe();
    let [a, b, _] = face.triangles[0];
    let mut v = face.vertices.clone();
    v[a as usize] = v[b as usize];
    match FaceMesh::from_triangles(&v, &face.triangles) {
        Err(PrepError::DegenerateTriangle { area, .. }) => assert_eq!(area, 0.0),
        other => panic!("expected degenerate triangle, got {other:?}"),
    }
}

#[test]
fn wrong_extension_and_missing_file() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("face.stl");
    std::fs::write(&p, "solid").unwrap();
    assert!(matches!(
        load_face(&p),
        Err(PrepError::UnsupportedExtension { .. })
    ));
    let missing = dir.path().join("missing.obj");
    match load_face(&missing) {
        Err(e @ PrepError::Io { .. }) => assert!(e.to_string().contains("missing.obj")),
        other => panic!("expected Io, got {other:?}"),
    }
}

#[test]
fn quads_are_triangulated_and_seams_welded() {
    // A 3×3 grid of quads whose bottom row uses a duplicated copy of the y = 1 positions (a UV
    // seam as exporters write it). Welded, it is one disk: one loop of 12 edges, 16 vertices.
    let mut text = String::new();
    for y in 0..4 {
        for x in 0..4 {
            text += &format!("v {x} {y} 0\n"); // 1 + x + 4y
        }
    }
    for x in 0..4 {
        text += &format!("v {x} 1 0\n"); // seam copies: 17 + x
    }
    for y in 0..3 {
        for x in 0..3 {
            let bottom = |x: usize| 1 + x + 4 * y;
            let top = |x: usize| if y == 0 { 17 + x } else { 1 + x + 4 * (y + 1) };
            text += &format!(
                "f {} {} {} {}\n",
                bottom(x),
                bottom(x + 1),
                top(x + 1),
                top(x)
            );
        }
    }
    match FaceMesh::from_obj_str(&text) {
        Err(PrepError::WrongLoopCount { count: 1, loops }) => assert_eq!(loops[0].size, 12),
        other => panic!("{other:?}"),
    }
}

/// The MediaPipe face with `vt` lines (one per `v`, after them) and `vn` lines (one per `v`),
/// every corner `i/i/i`; `edit` changes the lines before they are joined.
fn mediapipe_with_texcoords_and_normals(edit: impl FnOnce(&mut Vec<String>)) -> String {
    let text = mediapipe_text();
    let n = text.lines().filter(|l| l.starts_with("v ")).count();
    let mut lines: Vec<String> = Vec::new();
    let mut v_lines = 0;
    for l in text.lines() {
        v_lines += usize::from(l.starts_with("v "));
        match l.strip_prefix("f ") {
            Some(corners) => {
                let c: Vec<String> = corners
                    .split_whitespace()
                    .map(|i| format!("{i}/{i}/{i}"))
                    .collect();
                lines.push(format!("f {}", c.join(" ")));
            }
            None => lines.push(l.to_owned()),
        }
        if v_lines == n && l.starts_with("v ") {
            lines.extend((0..n).map(|i| format!("vt {} 0.5", i as f64 / n as f64)));
            lines.extend((0..n).map(|_| "vn 0 0 1".to_owned()));
        }
    }
    edit(&mut lines);
    lines.join("\n") + "\n"
}

/// 1-based line number of the first line starting with `prefix`.
fn line_of(text: &str, prefix: &str) -> usize {
    text.lines().position(|l| l.starts_with(prefix)).unwrap() + 1
}

#[test]
fn obj_with_texcoords_and_normals_reads() {
    let text = mediapipe_with_texcoords_and_normals(|_| {});
    let face = FaceMesh::from_obj_str(&text).unwrap();
    assert_eq!(face.vertices.len(), 468);
}

#[test]
fn obj_with_nan_texture_coordinate_is_refused_at_read() {
    let text = mediapipe_with_texcoords_and_normals(|lines| {
        let i = lines.iter().position(|l| l.starts_with("vt ")).unwrap() + 7;
        lines[i] = "vt nan nan".to_owned();
    });
    let line = line_of(&text, "vt nan");
    match FaceMesh::from_obj_str(&text) {
        Err(e @ PrepError::ObjLine(ObjLineError::NonFinite { .. })) => assert_eq!(
            e.to_string(),
            format!("OBJ line {line}: \"vt nan nan\" holds a number that is not finite")
        ),
        other => panic!("expected a non-finite texture coordinate, got {other:?}"),
    }
    // Beyond f32 (glTF stores texture coordinates as f32), it is refused too.
    let text = mediapipe_with_texcoords_and_normals(|lines| {
        let i = lines.iter().position(|l| l.starts_with("vt ")).unwrap();
        lines[i] = "vt 1e39 0".to_owned();
    });
    assert!(matches!(
        FaceMesh::from_obj_str(&text),
        Err(PrepError::ObjLine(ObjLineError::TexcoordOutOfRange { .. }))
    ));
}

#[test]
fn obj_with_infinite_normal_is_refused_at_read() {
    for bad in [
        "vn inf 0 1",
        "vn 0 -infinity 1",
        "vn 0 0 NaN",
        "vn 1e999 0 1",
    ] {
        let text = mediapipe_with_texcoords_and_normals(|lines| {
            let i = lines.iter().position(|l| l.starts_with("vn ")).unwrap() + 3;
            lines[i] = bad.to_owned();
        });
        let line = line_of(&text, bad);
        match FaceMesh::from_obj_str(&text) {
            Err(PrepError::ObjLine(ObjLineError::NonFinite { line: l, text })) => {
                assert_eq!((l, text.as_str()), (line, bad));
            }
            other => panic!("{bad}: expected a non-finite normal, got {other:?}"),
        }
    }
}

#[test]
fn obj_with_non_finite_or_zero_w_is_refused_at_read() {
    let text = mediapipe_text();
    // The 6th `v` line (line 9, after three comments) with a fourth number.
    for (w, zero) in [
        ("inf", false),
        ("-inf", false),
        ("nan", false),
        ("1e-320", false),
        ("0", true),
    ] {
        let mut n = 0;
        let bad: String = text
            .lines()
            .map(|l| {
                if l.starts_with("v ") {
                    n += 1;
                    if n == 6 {
                        return format!("{l} {w}");
                    }
                }
                l.to_owned()
            })
            .collect::<Vec<_>>()
            .join("\n");
        match FaceMesh::from_obj_str(&bad) {
            Err(PrepError::ObjLine(ObjLineError::ZeroW { line: 9, .. })) if zero => {}
            Err(PrepError::ObjLine(ObjLineError::NonFinite { line: 9, text })) if !zero => {
                assert!(text.ends_with(w), "{text}");
            }
            other => panic!("w = {w}: got {other:?}"),
        }
    }
}

#[test]
fn obj_vertex_defined_after_its_face_is_refused_at_read() {
    // The last `v` line (v 468) moved to the end of the file: faces using it come before it.
    let text = mediapipe_text();
    let lines: Vec<&str> = text.lines().collect();
    let last_v = lines.iter().rposition(|l| l.starts_with("v ")).unwrap();
    let mut moved: Vec<&str> = lines.clone();
    let v = moved.remove(last_v);
    moved.push(v);
    let moved = moved.join("\n");
    let first_use = moved
        .lines()
        .position(|l| l.starts_with("f ") && l.split_whitespace().any(|c| c == "468"))
        .unwrap()
        + 1;
    match FaceMesh::from_obj_str(&moved) {
        Err(
            e @ PrepError::ObjLine(ObjLineError::UndefinedCorner {
                statement: "v",
                defined: 467,
                ..
            }),
        ) => assert_eq!(
            e.to_string(),
            format!(
                "OBJ line {first_use}: face corner \"468\" refers to a `v` line that does not \
                 come before the face (there are 467 above it)"
            )
        ),
        other => panic!("expected a forward reference, got {other:?}"),
    }
}

#[test]
fn obj_texture_coordinate_or_normal_defined_after_its_face_is_refused_at_read() {
    // All `vt` lines moved after the faces.
    let text = mediapipe_with_texcoords_and_normals(|lines| {
        let vt: Vec<String> = lines
            .iter()
            .filter(|l| l.starts_with("vt "))
            .cloned()
            .collect();
        lines.retain(|l| !l.starts_with("vt "));
        lines.extend(vt);
    });
    assert!(matches!(
        FaceMesh::from_obj_str(&text),
        Err(PrepError::ObjLine(ObjLineError::UndefinedCorner {
            statement: "vt",
            defined: 0,
            ..
        }))
    ));
    // A normal index past the `vn` lines (tobj alone would only see it at the end).
    let text = mediapipe_with_texcoords_and_normals(|lines| {
        let i = lines.iter().position(|l| l.starts_with("f ")).unwrap();
        lines[i] = "f 1/1/1 2/2/2 3/3/469".to_owned();
    });
    assert!(matches!(
        FaceMesh::from_obj_str(&text),
        Err(PrepError::ObjLine(ObjLineError::UndefinedCorner {
            statement: "vn",
            defined: 468,
            ..
        }))
    ));
}
