//! The user's textured face in the real viewer on wgpu (issue 35): the bundled default face
//! given texture coordinates (a planar projection, with a UV seam down the middle) and a
//! checker texture through an OBJ material library, then the same face exported as a GLB and
//! opened again (glTF's `baseColorTexture`). Also the heat map and compare mode on it.
//! Update the images with `UPDATE_SNAPSHOTS=1 cargo test --release -p viewer --test texture`.

mod common;

use std::path::{Path, PathBuf};

use egui_kittest::SnapshotOptions;
use egui_kittest::kittest::Queryable;
use facebem::report::contact_sheet::heat;

const CHECKS: u32 = 8;
const TEXTURE_PX: u32 = 256;
const RED: [u8; 3] = [220, 60, 50];
const BLUE: [u8; 3] = [50, 80, 220];

/// Writes the textured default face into `dir`: `face.obj` (planar UVs; triangles left of the
/// middle use a second set of texture coordinates shifted by half the texture, so the midline's
/// vertices are split by a seam while the checker stays continuous), `face.mtl`, `checker.png`.
fn textured_face(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(viewer::source::default_face_path()).unwrap();
    let v = v_lines(&text);
    let (lo, hi) = v
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        });
    let mid_x = 0.5 * (lo[0] + hi[0]);
    let n = v.len();
    let mut obj = String::from("mtllib face.mtl\n");
    for p in &v {
        obj += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for shift in [0.0, 0.5] {
        for p in &v {
            let u = (p[0] - lo[0]) / (hi[0] - lo[0]) + shift;
            let t = (p[1] - lo[1]) / (hi[1] - lo[1]);
            obj += &format!("vt {u} {t}\n");
        }
    }
    obj += "usemtl checker\n";
    for l in text.lines().filter_map(|l| l.strip_prefix("f ")) {
        let idx: Vec<usize> = l
            .split_whitespace()
            .map(|w| w.split('/').next().unwrap().parse().unwrap())
            .collect();
        let cx: f64 = idx.iter().map(|&i| v[i - 1][0]).sum::<f64>() / idx.len() as f64;
        let off = if cx < mid_x { n } else { 0 };
        obj += "f";
        for i in idx {
            obj += &format!(" {i}/{}", i + off);
        }
        obj += "\n";
    }
    std::fs::write(
        dir.join("face.mtl"),
        "newmtl checker\nKd 1 1 1\nmap_Kd checker.png\n",
    )
    .unwrap();
    let img = image::RgbaImage::from_fn(TEXTURE_PX, TEXTURE_PX, |x, y| {
        let c = TEXTURE_PX / CHECKS;
        let [r, g, b] = if (x / c + y / c).is_multiple_of(2) {
            RED
        } else {
            BLUE
        };
        image::Rgba([r, g, b, 255])
    });
    img.save(dir.join("checker.png")).unwrap();
    let path = dir.join("face.obj");
    std::fs::write(&path, obj).unwrap();
    path
}

/// The positions of an OBJ text's `v` lines.
fn v_lines(text: &str) -> Vec<[f64; 3]> {
    text.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            [x[0], x[1], x[2]]
        })
        .collect()
}

fn harness_opening(path: &Path, cache: &Path) -> egui_kittest::Harness<'static, viewer::ViewerApp> {
    let (path, cache) = (path.to_path_buf(), cache.to_path_buf());
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 760.0])
        .with_render_cursor(false)
        .wgpu()
        .build_eframe(move |cc| {
            viewer::ViewerApp::new(
                cc,
                viewer::ViewerOptions {
                    open: Some(path.clone()),
                    cache_dir: Some(cache.clone()),
                    ..Default::default()
                },
            )
        });
    common::wait_idle(&mut harness);
    assert!(
        harness.state().model().is_some(),
        "{:?}",
        harness.state().message()
    );
    // Machine-dependent text (the temporary folder, timings) stays out of the images.
    harness.state_mut().clear_message();
    harness.state_mut().set_export_dir(Path::new("/exports"));
    harness.get_by_label("Path").focus();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    harness.get_by_label("Path").type_text("face.obj");
    harness.key_press(egui::Key::Escape);
    harness.run();
    harness
}

/// Viewport pixels (right of the control panel) of a rendered image, in `x_range` (fractions
/// of the width).
fn pixels(img: &image::RgbaImage, x_range: (f32, f32)) -> Vec<[u8; 3]> {
    let (w, h) = img.dimensions();
    let (x0, x1) = ((w as f32 * x_range.0) as u32, (w as f32 * x_range.1) as u32);
    let mut out = Vec::new();
    for y in (h / 8)..(h * 7 / 8) {
        for x in x0..x1.min(w - 8) {
            let [r, g, b, _] = img.get_pixel(x, y).0;
            out.push([r, g, b]);
        }
    }
    out
}

/// Counts of pixels showing the checker's red and blue (shaded).
fn checker_counts(px: &[[u8; 3]]) -> (usize, usize) {
    let red = px
        .iter()
        .filter(|p| i32::from(p[0]) > i32::from(p[2]) + 60)
        .count();
    let blue = px
        .iter()
        .filter(|p| i32::from(p[2]) > i32::from(p[0]) + 60)
        .count();
    (red, blue)
}

#[test]
fn a_textured_face_shows_its_texture_heat_map_and_compare() {
    common::test_env();
    let dir = tempfile::tempdir().unwrap();
    let cache = tempfile::tempdir().unwrap();
    let obj = textured_face(dir.path());
    let mut harness = harness_opening(&obj, cache.path());
    let options = SnapshotOptions::new().threshold(0.6).max_failed_pixels(60);

    // The layout: the seam splits the midline's vertices; every drawn vertex sits at its
    // welded vertex with the UV the OBJ gave it.
    let app = harness.state();
    let basis = app.basis().unwrap().clone();
    let surface = app.surface().unwrap().clone();
    assert_eq!(surface.textures.len(), 1);
    assert_eq!(
        (surface.textures[0].width, surface.textures[0].height),
        (TEXTURE_PX, TEXTURE_PX)
    );
    let copies = surface.welded.len() - basis.neutral.len();
    assert!(copies >= 8, "only {copies} seam copies");
    let drawn = app.surface_vertices();
    assert_eq!(drawn.len(), surface.welded.len());
    for (j, (d, w)) in drawn.iter().zip(&surface.welded).enumerate() {
        let w = w.expect("every vertex of the face is used") as usize;
        let p = basis.neutral[w].as_vec3().to_array();
        assert_eq!(d.position, p, "drawn vertex {j}");
        assert!(d.uv[0] >= 0.0 && d.uv[0] <= 1.5 && d.uv[1] >= 0.0 && d.uv[1] <= 1.0);
    }

    // The picture: both checker colours cover the face, in comparable amounts.
    let textured = harness.render().expect("wgpu render");
    let (red, blue) = checker_counts(&pixels(&textured, (0.4, 1.0)));
    let total = pixels(&textured, (0.4, 1.0)).len();
    assert!(
        red * 20 > total && blue * 20 > total,
        "red {red}, blue {blue} of {total}"
    );
    assert!(red * 3 > blue && blue * 3 > red, "red {red}, blue {blue}");
    harness.snapshot_options("textured_face", &options);

    // The heat map over the texture: the vertex that moves most has the colour of its bin.
    harness.state_mut().apply_preset("happy");
    harness.state_mut().set_heat_map(true);
    harness.run();
    let app = harness.state();
    let mm = app.model().unwrap().rig.mm_per_unit();
    let posed = basis.pose(app.sliders()).unwrap();
    let (far, far_mm) = (0..basis.neutral.len())
        .map(|i| (i, basis.neutral[i].distance(posed[i]) * mm))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    assert!(far_mm > 3.0, "happy moves at most {far_mm} mm");
    let drawn = app.surface_vertices();
    let j = surface
        .welded
        .iter()
        .position(|w| *w == Some(far as u32))
        .unwrap();
    let bin = heat::bin(far_mm).unwrap();
    let expected = heat::COLOURS[bin].map(|c| f32::from(c) / 255.0 * viewer::surface::HEAT_OPACITY);
    assert_eq!(
        drawn[j].heat[..3],
        expected[..],
        "vertex {far} moves {far_mm} mm"
    );
    let still = drawn.iter().filter(|d| d.heat[3] == 0.0).count();
    assert!(
        still > 0 && still < drawn.len(),
        "{still} still of {}",
        drawn.len()
    );

    // Compare: the neutral face in the left half, the posed one in the right.
    harness.state_mut().set_compare(true);
    harness.run();
    let compare = harness.render().expect("wgpu render");
    let background = compare
        .get_pixel(compare.width() - 4, compare.height() / 2)
        .0;
    let face_px = |px: Vec<[u8; 3]>| {
        let n = px.len();
        let face = px
            .iter()
            .filter(|p| p.iter().zip(background).any(|(a, b)| a.abs_diff(b) > 8))
            .count();
        (face, n)
    };
    // The viewport starts at about 30 % of the window; its halves meet at about 65 %.
    let (left, n_left) = face_px(pixels(&compare, (0.32, 0.63)));
    let (right, n_right) = face_px(pixels(&compare, (0.67, 1.0)));
    assert!(left * 8 > n_left, "left half: {left} of {n_left}");
    assert!(right * 8 > n_right, "right half: {right} of {n_right}");
    harness.snapshot_options("textured_face_heat_compare", &options);
    let (left_red, _) = checker_counts(&pixels(&compare, (0.32, 0.63)));
    assert!(left_red > 0, "the neutral face shows its texture");

    smile_like_the_command_line(&mut harness, &basis, dir.path());
    glb_keeps_the_texture(&harness, &obj, &surface, cache.path());
}

/// mouthSmileLeft at 1 in the browser poses the rig as `facebem pose --preset mouthSmileLeft`
/// does: the same sliders (expressions::sliders_for_name) and the same OBJ positions
/// (FaceModel::write_obj), to 1e-6 of the face's size.
fn smile_like_the_command_line(
    harness: &mut egui_kittest::Harness<'static, viewer::ViewerApp>,
    basis: &facebem::MuscleBasis,
    dir: &Path,
) {
    assert!(
        harness
            .state_mut()
            .set_expression_weight("mouthSmileLeft", 1.0)
    );
    harness.run();
    let model = harness.state().model().unwrap().clone();
    let (sliders, _) =
        facebem::expressions::sliders_for_name("mouthSmileLeft", model.muscle_ids()).unwrap();
    assert_eq!(harness.state().sliders(), &sliders[..]);
    let posed_obj = dir.join("smile.obj");
    model.write_obj(&posed_obj, &sliders).unwrap();
    let cli = v_lines(&std::fs::read_to_string(&posed_obj).unwrap());
    let size = viewer::posed_mesh::bounding_sphere(&basis.neutral)
        .unwrap()
        .1;
    let uploaded = harness.state().uploaded_vertices();
    // The OBJ has the input's `v` lines; the viewer the welded vertices they map to.
    assert_eq!(cli.len(), model.mesh.input_to_vertex.len());
    for (c, w) in cli.iter().zip(&model.mesh.input_to_vertex) {
        let u = uploaded[w.expect("every v line is used") as usize];
        for k in 0..3 {
            let d = (c[k] - f64::from(u.position[k])).abs();
            assert!(d <= 1e-6 * size, "{c:?} vs {:?}", u.position);
        }
    }
}

/// The same face as a GLB with its material (baseColorTexture), opened again, keeps its texture
/// and texture coordinates.
fn glb_keeps_the_texture(
    harness: &egui_kittest::Harness<'static, viewer::ViewerApp>,
    obj: &Path,
    surface: &viewer::surface::Surface,
    cache: &Path,
) {
    let dir = obj.parent().unwrap();
    let glb = dir.join("face.glb");
    let text = std::fs::read_to_string(obj).unwrap();
    let materials = facebem::export::material::ObjMaterials::load(&text, dir).unwrap();
    let params = facebem::export::GltfParams {
        materials: Some(materials),
        ..Default::default()
    };
    harness
        .state()
        .model()
        .unwrap()
        .write_gltf(&glb, &params)
        .unwrap();
    let reopened = harness_opening(&glb, cache);
    let s = reopened.state().surface().unwrap();
    assert_eq!(s.textures.len(), 1);
    assert_eq!(*s.textures[0], *surface.textures[0]);
    assert_eq!(s.welded.len(), surface.welded.len());
    // glTF's TEXCOORD_0 is f32: the OBJ's (u, 1 − v) to within its rounding.
    for (a, b) in s.uvs.iter().zip(&surface.uvs) {
        assert!(
            (a[0] - b[0]).abs() < 1e-6 && (a[1] - b[1]).abs() < 1e-6,
            "{a:?} {b:?}"
        );
    }
}
