//! The user's own mesh in the glTF export: an OBJ with texture coordinates and normals (the
//! bundled default face, given a UV layout with a seam down the middle and per-vertex normals)
//! is rigged and exported; the GLB keeps the `v` line order, carries the `vt` as TEXCOORD_0
//! and the `vn` as NORMAL, and maps its seam copies back to their `v` lines.

mod support;

use facebem::export::GltfParams;
use facebem::{Control, PipelineParams, build_face_model};
use glam::DVec3;

/// The default face with `vt` and `vn` lines: the left half (x < 0) of the face uses one UV
/// island, the right half another, so every vertex on the midline has two texture coordinates.
fn textured_default_face() -> String {
    let src = facebem::input::DEFAULT_FACE_OBJ;
    let v: Vec<DVec3> = src
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            DVec3::new(c[0], c[1], c[2])
        })
        .collect();
    let faces: Vec<[usize; 3]> = src
        .lines()
        .filter_map(|l| l.strip_prefix("f "))
        .map(|l| {
            let c: Vec<usize> = l
                .split_whitespace()
                .map(|t| t.parse::<usize>().unwrap() - 1)
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let (lo, hi) = v.iter().fold((DVec3::MAX, DVec3::MIN), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let size = hi - lo;
    let mut out = String::from("# test face: the bundled MediaPipe face with a UV seam\n");
    for p in &v {
        out.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
    }
    // vt 1..n: left island; vt n+1..2n: right island (shifted in u).
    for island in 0..2 {
        for p in &v {
            let u = 0.45 * (p.x - lo.x) / size.x + 0.5 * island as f64;
            let w = (p.y - lo.y) / size.y;
            out.push_str(&format!("vt {u} {w}\n"));
        }
    }
    // One normal per vertex: the direction from a point behind the face (not unit length).
    let centre = (lo + hi) / 2.0 - DVec3::Z * size.y;
    for p in &v {
        let n = (*p - centre) * 3.0;
        out.push_str(&format!("vn {} {} {}\n", n.x, n.y, n.z));
    }
    let n = v.len();
    for f in &faces {
        let right = f.iter().map(|&i| v[i].x).sum::<f64>() > 0.0;
        let t = if right { n } else { 0 };
        out.push('f');
        for &i in f {
            out.push_str(&format!(" {}/{}/{}", i + 1, i + 1 + t, i + 1));
        }
        out.push('\n');
    }
    out
}

/// The rigged model of the file `path` (OBJ or glTF), with its layout.
fn rigged(path: &std::path::Path) -> facebem::FaceModel {
    let (mesh, obj_source) = facebem::input::read_face(path).unwrap();
    let mut model = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
    model.obj_source = obj_source;
    model
}

#[test]
fn glb_keeps_v_line_order_texcoords_and_normals_of_the_obj() {
    let text = textured_default_face();
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("textured.obj");
    std::fs::write(&obj, &text).unwrap();
    let model = rigged(&obj);
    let glb = dir.path().join("textured.glb");
    model.write_gltf(&glb, &GltfParams::default()).unwrap();
    support::assert_valid(&glb);

    // The OBJ's own lists, parsed independently of facebem.
    let words = |tag: &str| -> Vec<Vec<f64>> {
        text.lines()
            .filter_map(|l| l.strip_prefix(tag))
            .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
            .collect()
    };
    let v = words("v ");
    let vt = words("vt ");
    let vn = words("vn ");
    let corners: Vec<[usize; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("f "))
        .flat_map(|l| {
            l.split_whitespace()
                .map(|c| {
                    let i: Vec<usize> = c.split('/').map(|t| t.parse().unwrap()).collect();
                    [i[0] - 1, i[1] - 1, i[2] - 1]
                })
                .collect::<Vec<_>>()
        })
        .collect();

    let (doc, buffers, _) = gltf::import(&glb).unwrap();
    let mesh = doc.meshes().next().unwrap();
    let prim = mesh.primitives().next().unwrap();
    let reader = prim.reader(|b| Some(&buffers[b.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let uvs: Vec<[f32; 2]> = reader
        .read_tex_coords(0)
        .expect("TEXCOORD_0")
        .into_f32()
        .collect();
    let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    let extras: serde_json::Value =
        serde_json::from_str(mesh.extras().as_ref().unwrap().get()).unwrap();
    let seam_copy_of: Vec<usize> = extras["seamCopyOf"]
        .as_array()
        .expect("seam copies listed")
        .iter()
        .map(|x| x.as_u64().unwrap() as usize)
        .collect();

    // Position i is `v` line i, in metres, for every i; then one copy per seam vertex.
    let metres = model.metres_per_unit();
    let n = v.len();
    assert_eq!(positions.len(), n + seam_copy_of.len());
    let midline = (0..n).filter(|&i| v[i][0] == 0.0).count();
    assert!(
        !seam_copy_of.is_empty() && seam_copy_of.len() <= midline,
        "{} copies, {midline} midline vertices",
        seam_copy_of.len()
    );
    let source_v = |g: usize| if g < n { g } else { seam_copy_of[g - n] };
    for (g, p) in positions.iter().enumerate() {
        let q = &v[source_v(g)];
        let want = (DVec3::new(q[0], q[1], q[2]) * metres).as_vec3().to_array();
        assert_eq!(*p, want, "glTF vertex {g}");
    }
    // Every face corner, in file order: same `v`, TEXCOORD_0 = (u, 1 - v) of its `vt`, NORMAL
    // = its `vn` normalised.
    assert_eq!(indices.len(), corners.len());
    for (k, (&g, c)) in indices.iter().zip(&corners).enumerate() {
        let g = g as usize;
        assert_eq!(source_v(g), c[0], "corner {k}");
        let t = &vt[c[1]];
        assert_eq!(uvs[g], [t[0] as f32, (1.0 - t[1]) as f32], "corner {k}");
        let want = DVec3::new(vn[c[2]][0], vn[c[2]][1], vn[c[2]][2]).normalize();
        let got = glam::Vec3::from(normals[g]).as_dvec3();
        assert!((got - want).length() < 1e-6, "corner {k}: {got} vs {want}");
    }
}

#[test]
fn glb_input_keeps_its_vertex_order_and_texcoords() {
    // A GLB with UVs and a seam: the textured OBJ's export, read back as the input.
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("textured.obj");
    std::fs::write(&obj, textured_default_face()).unwrap();
    let input = dir.path().join("input.glb");
    rigged(&obj)
        .write_gltf(&input, &GltfParams::default())
        .unwrap();
    let from_glb = rigged(&input);
    let output = dir.path().join("output.glb");
    from_glb
        .write_gltf(&output, &GltfParams::default())
        .unwrap();
    support::assert_valid(&output);

    let read = |path: &std::path::Path| {
        let (doc, buffers, _) = gltf::import(path).unwrap();
        let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
        let r = prim.reader(|b| Some(&buffers[b.index()]));
        let p: Vec<[f32; 3]> = r.read_positions().unwrap().collect();
        let t: Vec<[f32; 2]> = r.read_tex_coords(0).unwrap().into_f32().collect();
        let i: Vec<u32> = r.read_indices().unwrap().into_u32().collect();
        (p, t, i)
    };
    let (p_in, t_in, i_in) = read(&input);
    let (p_out, t_out, i_out) = read(&output);
    assert_eq!(t_out, t_in, "TEXCOORD_0 kept exactly, in the input's order");
    assert_eq!(i_out, i_in, "same triangles over the same vertex indices");
    assert_eq!(p_out.len(), p_in.len());
    // The input GLB is already in metres; the export scales by the rig's unit for it.
    let scale = from_glb.metres_per_unit() as f32;
    for (g, (a, b)) in p_out.iter().zip(&p_in).enumerate() {
        for c in 0..3 {
            assert!(
                (a[c] - b[c] * scale).abs() <= 1e-6 * b[c].abs().max(1e-3),
                "vertex {g}: {a:?} vs {b:?} x {scale}"
            );
        }
    }
}

/// What the face reader accepts, the exports read: for the bundled faces, the textured face and
/// edits of it (lines moved before or after the faces, indices past the lists, non-finite
/// numbers), either the reader refuses the text or the export layout and the pose writer both
/// take it. The edits that make a corner refer to a later line are refused by the reader.
#[test]
fn reader_and_export_layout_accept_the_same_obj_texts() {
    use facebem::export::{ExportLayout, obj};
    let textured = textured_default_face();
    let lines: Vec<&str> = textured.lines().collect();
    let first = |p: &str| lines.iter().position(|l| l.starts_with(p)).unwrap();
    let last = |p: &str| lines.iter().rposition(|l| l.starts_with(p)).unwrap();
    let moved = |from: usize, to: usize| {
        let mut l = lines.clone();
        let x = l.remove(from);
        l.insert(to.min(l.len()), x);
        l.join("\n") + "\n"
    };
    let replaced = |at: usize, with: &str| {
        let mut l = lines.clone();
        l[at] = with;
        l.join("\n") + "\n"
    };
    let (fv, lv, fvt, lvt, fvn, lvn, ff, lf) = (
        first("v "),
        last("v "),
        first("vt "),
        last("vt "),
        first("vn "),
        last("vn "),
        first("f "),
        last("f "),
    );
    // The `v`, `vt` and `vn` of the first face's first corner (1-based).
    let corner: Vec<usize> = lines[ff]
        .split_whitespace()
        .nth(1)
        .unwrap()
        .split('/')
        .map(|i| i.parse().unwrap())
        .collect();
    let refused = [
        moved(fv + corner[0] - 1, lines.len()), // the first face's `v` after the faces
        moved(fvt + corner[1] - 1, lines.len()), // its `vt` after the faces
        moved(fvn + corner[2] - 1, lines.len()), // its `vn` after the faces
        moved(lf, fv),                          // a face before every `v`
        replaced(ff, "f 1/1/1 2/2/2 3/3/9999"),
        replaced(fvt, "vt nan 0"),
        replaced(fvn, "vn 0 inf 1"),
        replaced(fv, "v 0 0 0 0"),
        replaced(fv, "v 1 2 3 1e-320"),
        replaced(fvt, "vt 0 3.5e38"),
    ];
    for (k, text) in refused.iter().enumerate() {
        let read = face_prep::FaceMesh::from_obj_str(text);
        assert!(
            matches!(read, Err(face_prep::PrepError::ObjLine(_))),
            "edit {k}: {read:?}"
        );
    }
    let mut accepted: Vec<String> = support::FACES
        .iter()
        .map(|f| std::fs::read_to_string(support::asset(f)).unwrap())
        .collect();
    accepted.push(textured.clone());
    accepted.push(moved(fvt, fv)); // a `vt` before the `v` lines
    accepted.push(moved(lv, fvn)); // the last `v` among the `vn` lines, still before the faces
    accepted.push(moved(ff, lines.len())); // the first face last
    // The first face with relative indices (counted back from the face).
    let (nv, nvt, nvn) = (lv - fv + 1, lvt - fvt + 1, lvn - fvn + 1);
    let relative: Vec<String> = lines[ff]
        .split_whitespace()
        .skip(1)
        .map(|c| {
            let i: Vec<i64> = c.split('/').map(|i| i.parse().unwrap()).collect();
            let back = |i: i64, n: usize| i - n as i64 - 1;
            format!("{}/{}/{}", back(i[0], nv), back(i[1], nvt), back(i[2], nvn))
        })
        .collect();
    accepted.push(replaced(ff, &format!("f {}", relative.join(" "))));
    for (k, text) in accepted.iter().enumerate() {
        let mesh = face_prep::FaceMesh::from_obj_str(text)
            .unwrap_or_else(|e| panic!("text {k} is refused: {e}"));
        let layout = ExportLayout::from_obj(text, &mesh.input_to_vertex);
        assert!(layout.is_ok(), "text {k}: {layout:?}");
        let pose = obj::pose_from_template(text, &mesh.input_to_vertex, &mesh.vertices);
        assert!(pose.is_ok(), "text {k}: {pose:?}");
    }
}
