//! egui_kittest tests of the real viewer app on wgpu, on a synthetic basis (no rig to compute):
//! sliders, presets, the viewport, opening a bad file and exports. Widgets are found through the
//! accessibility tree, as a user would find them. The tests with the real rig are in `ui_rig.rs`
//! and `ui_rig_editing.rs`.

mod common;

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;

#[test]
fn moving_a_slider_moves_the_uploaded_vertices_exactly_as_the_basis_says() {
    common::test_env();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    let neutral: Vec<[f32; 3]> = harness
        .state()
        .uploaded_vertices()
        .iter()
        .map(|v| v.position)
        .collect();
    assert_eq!(neutral.len(), basis.neutral.len());

    harness
        .get_by_role_and_label(Role::Slider, "Zygomaticus major L")
        .set_value_accesskit(-0.6);
    harness.run();
    harness
        .get_by_role_and_label(Role::Slider, "Frontalis R")
        .set_value_accesskit(0.25);
    harness.run();

    let k_zyg = basis.muscle_index("zygomaticus_major_l").unwrap();
    let k_fro = basis.muscle_index("frontalis_r").unwrap();
    let sliders = harness.state().sliders().to_vec();
    assert_eq!(sliders[k_zyg], -0.6);
    assert_eq!(sliders[k_fro], 0.25);
    assert_eq!(sliders.iter().filter(|s| **s != 0.0).count(), 2);

    let expected = basis.pose(&sliders).unwrap();
    let uploaded = harness.state().uploaded_vertices();
    assert_eq!(uploaded.len(), expected.len());
    let mut moved = 0;
    for (i, (u, e)) in uploaded.iter().zip(&expected).enumerate() {
        // Exact: the renderer gets the f64 blend rounded once to f32.
        assert_eq!(u.position, e.as_vec3().to_array(), "vertex {i}");
        if u.position != neutral[i] {
            moved += 1;
        }
    }
    assert!(moved > expected.len() / 10, "only {moved} vertices moved");

    // What the GPU holds after drawing the frame is exactly that buffer.
    harness.render().expect("wgpu render");
    let gpu = harness
        .state()
        .read_back_gpu_vertices()
        .expect("GPU read-back");
    assert_eq!(gpu.as_slice(), harness.state().uploaded_vertices());

    // Reset brings every vertex back to neutral.
    harness.get_by_label("Reset muscles").click();
    harness.run();
    let back: Vec<[f32; 3]> = harness
        .state()
        .uploaded_vertices()
        .iter()
        .map(|v| v.position)
        .collect();
    assert_eq!(back, neutral);
}

#[test]
fn a_preset_button_sets_its_sliders_and_pose() {
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    harness.get_by_label("Smile").click();
    harness.run();
    let sliders = harness.state().sliders().to_vec();
    let want = facebem::expressions::presets::find("smile")
        .unwrap()
        .sliders_for(&basis.muscle_ids);
    assert!(want.iter().any(|s| *s != 0.0));
    assert_eq!(sliders, want);
    let expected = basis.pose(&want).unwrap();
    for (u, e) in harness.state().uploaded_vertices().iter().zip(&expected) {
        assert_eq!(u.position, e.as_vec3().to_array());
    }
}

#[test]
fn arkit_and_vrm_names_apply_like_presets() {
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    assert!(harness.state_mut().apply_preset("mouthSmileLeft"));
    harness.run();
    let want = facebem::expressions::find("mouthSmileLeft")
        .unwrap()
        .resolve(&basis.muscle_ids)
        .unwrap()
        .sliders;
    assert!(want.iter().any(|s| *s != 0.0));
    assert_eq!(harness.state().sliders(), &want[..]);
    assert_eq!(harness.state().active_preset(), Some("mouthSmileLeft"));
    let expected = basis.pose(&want).unwrap();
    for (u, e) in harness.state().uploaded_vertices().iter().zip(&expected) {
        assert_eq!(u.position, e.as_vec3().to_array());
    }
    // A name the rig has no control for, or no name at all, changes nothing.
    let blink = facebem::expressions::find("blinkLeft").unwrap();
    if blink.resolve(&basis.muscle_ids).is_none() {
        assert!(!harness.state_mut().apply_preset("blinkLeft"));
    }
    assert!(!harness.state_mut().apply_preset("grin"));
    assert_eq!(harness.state().sliders(), &want[..]);
}

/// A file dropped on the window, as the windowing integration hands it to egui.
#[derive(Debug)]
struct DroppedPath(std::path::PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &std::path::Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn a_file_dropped_on_the_window_is_opened() {
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis));
    let face = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/ict_narrow_face_dec2500_4loop.obj");
    harness
        .input_mut()
        .dropped_files
        .push(std::sync::Arc::new(DroppedPath(face.clone())));
    harness.step();
    // The file is read in the background, shown at once, and its rig started: cancelled here
    // (this test checks the drop, not the rig).
    while !harness.state().is_rigging() {
        assert!(harness.state().is_busy(), "{:?}", harness.state().message());
        std::thread::sleep(std::time::Duration::from_millis(5));
        harness.step();
    }
    harness.state_mut().cancel_rig();
    common::wait_idle(&mut harness);
    let (mesh, _) = facebem::input::read_face(&face).unwrap();
    assert_eq!(harness.state().basis().unwrap().neutral, mesh.vertices);
    harness.get_by_label("ict_narrow_face_dec2500_4loop.obj");
}

/// The Open button takes a whole head: shown whole at once, saying what it holds, its rig
/// started in the background (cancelled here; `ui_head.rs` waits for it).
#[test]
fn opening_a_whole_head_shows_it_whole_and_says_what_it_holds() {
    let head = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/heads/ict_generic_head.obj");
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis));
    common::open_via_path_field(&mut harness, &head);
    let t0 = std::time::Instant::now();
    while harness
        .state()
        .basis()
        .is_none_or(|b| b.neutral.len() != 26_719)
    {
        assert!(
            t0.elapsed().as_secs() < 60,
            "{:?}",
            harness.state().message()
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
        harness.step();
    }
    let message = harness.state().message().cloned().expect("a message");
    assert!(!message.is_error, "{}", message.text);
    for needle in ["a head (skin, 2 eyeballs", "16 upper and 16 lower teeth"] {
        assert!(message.text.contains(needle), "{}", message.text);
    }
    harness.state_mut().cancel_rig();
    common::wait_idle(&mut harness);
    assert_eq!(harness.state().basis().unwrap().neutral.len(), 26_719);
    harness.get_by_label("ict_generic_head.obj");
}

#[test]
fn opening_a_bad_file_shows_the_message_and_keeps_the_face() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("broken_face.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));

    harness.get_by_label("Path").focus();
    harness
        .get_by_label("Path")
        .type_text(&bad.display().to_string());
    harness.run();
    harness.get_by_label("Open").click();
    harness.run();
    common::wait_idle(&mut harness);

    let message = harness
        .state()
        .message()
        .cloned()
        .expect("a message is shown");
    assert!(message.is_error);
    assert!(message.text.contains("Could not open"), "{}", message.text);
    assert!(message.text.contains("broken_face.obj"), "{}", message.text);
    harness.get_by_label_contains("broken_face.obj");
    // The app keeps running with the previous face and its sliders.
    assert_eq!(harness.state().basis(), Some(&basis));
    harness
        .get_by_role_and_label(egui::accesskit::Role::Slider, "Mentalis L")
        .set_value_accesskit(-1.0);
    harness.run();
    assert_eq!(
        harness.state().sliders()[basis.muscle_index("mentalis_l").unwrap()],
        -1.0
    );
}

#[test]
fn export_buttons_write_the_posed_obj_and_a_glb() {
    let dir = tempfile::tempdir().unwrap();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    harness.state_mut().set_export_dir(dir.path());
    harness
        .get_by_role_and_label(Role::Slider, "Depressor labii inferioris R")
        .set_value_accesskit(-0.75);
    harness.run();
    harness.get_by_label("Export OBJ pose").click();
    harness.step();
    common::wait_idle(&mut harness);
    let obj = dir.path().join("mediapipe_canonical_4loop_pose.obj");
    let msg = harness.state().message().cloned().unwrap();
    assert!(!msg.is_error, "{}", msg.text);
    let written = viewer::source::load_neutral(&obj).unwrap();
    let expected = basis.pose(harness.state().sliders()).unwrap();
    assert_eq!(written.triangles, basis.triangles);
    for (w, e) in written.neutral.iter().zip(&expected) {
        // tobj reads f32: the written pose matches to f32 precision.
        assert!(
            (*w - *e).abs().max_element() <= 1e-6 * e.abs().max_element().max(1.0),
            "{w} vs {e}"
        );
    }

    harness.get_by_label("Export glTF").click();
    harness.step();
    common::wait_idle(&mut harness);
    let glb = std::fs::read(dir.path().join("mediapipe_canonical_4loop.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
}

#[test]
fn viewport_drag_orbits_wheel_zooms_click_picks_and_reset_view_restores() {
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    let home = harness.state_mut().camera_mut().clone();
    // The viewport fills the window right of the control panel; its centre shows the face.
    let centre = egui::pos2(700.0, 360.0);

    harness.hover_at(centre);
    harness.drag_at(centre);
    harness.step();
    harness.hover_at(centre + egui::vec2(60.0, 0.0));
    harness.step();
    harness.drop_at(centre + egui::vec2(60.0, 0.0));
    harness.run();
    let cam = harness.state_mut().camera_mut().clone();
    assert!(
        (cam.yaw - home.yaw).abs() > 0.1,
        "drag did not orbit: yaw {}",
        cam.yaw
    );
    assert_eq!(cam.distance, home.distance);

    harness.hover_at(centre);
    harness.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, 120.0),
        phase: egui::TouchPhase::Move,
        modifiers: egui::Modifiers::NONE,
        source: egui::MouseWheelSource::Wheel,
    });
    harness.run();
    let zoomed = harness.state_mut().camera_mut().distance;
    assert!(
        zoomed < home.distance,
        "wheel up should zoom in: {zoomed} vs {}",
        home.distance
    );

    harness.get_by_label("Reset view").click();
    harness.run();
    assert_eq!(*harness.state_mut().camera_mut(), home);

    // Click the centre: the picked triangle is the one the camera ray hits first.
    harness.hover_at(centre);
    harness.event(egui::Event::PointerButton {
        pos: centre,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    harness.event(egui::Event::PointerButton {
        pos: centre,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    harness.run();
    let hit = harness
        .state()
        .selected()
        .expect("a triangle under the viewport centre");
    harness.get_by_label(&format!("Selected triangle {}", hit.triangle));
    // Independent check: the picked triangle, projected to the screen, contains the click.
    let rect = harness.state().viewport_rect().unwrap();
    let aspect = rect.width() / rect.height();
    let clip_from_world = harness.state_mut().camera_mut().clip_from_world(aspect);
    let corners: Vec<glam::Vec2> = basis.triangles[hit.triangle]
        .iter()
        .map(|&i| {
            let ndc = clip_from_world.project_point3(basis.neutral[i as usize].as_vec3());
            glam::Vec2::new(
                rect.left() + (ndc.x + 1.0) * 0.5 * rect.width(),
                rect.top() + (1.0 - ndc.y) * 0.5 * rect.height(),
            )
        })
        .collect();
    let p = glam::Vec2::new(centre.x, centre.y);
    let side = |a: glam::Vec2, b: glam::Vec2| (b - a).perp_dot(p - a);
    let s = [
        side(corners[0], corners[1]),
        side(corners[1], corners[2]),
        side(corners[2], corners[0]),
    ];
    assert!(
        s.iter().all(|v| *v >= -1e-3) || s.iter().all(|v| *v <= 1e-3),
        "click {p} is outside the picked triangle {corners:?}"
    );
}

#[test]
fn exporting_twice_keeps_the_first_file_and_writes_a_numbered_one() {
    let dir = tempfile::tempdir().unwrap();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis));
    harness.state_mut().set_export_dir(dir.path());
    let first = dir.path().join("mediapipe_canonical_4loop.glb");
    let second = dir.path().join("mediapipe_canonical_4loop (2).glb");
    harness.get_by_label("Export glTF").click();
    harness.step();
    common::wait_idle(&mut harness);
    assert_eq!(&std::fs::read(&first).unwrap()[..4], b"glTF");
    // The user's own file of that name (e.g. an edited export) must survive.
    std::fs::write(&first, b"the user's file").unwrap();
    harness.get_by_label("Export glTF").click();
    harness.step();
    common::wait_idle(&mut harness);
    assert_eq!(std::fs::read(&first).unwrap(), b"the user's file");
    assert_eq!(&std::fs::read(&second).unwrap()[..4], b"glTF");
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        !msg.is_error && msg.text.contains("(2).glb"),
        "{}",
        msg.text
    );
}

#[test]
fn the_active_preset_is_highlighted_until_a_slider_moves() {
    use egui_kittest::kittest::NodeT;
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis));
    assert_eq!(harness.state().active_preset(), None);
    harness.get_by_label("Laugh").click();
    harness.run();
    assert_eq!(harness.state().active_preset(), Some("laugh"));
    let toggled = |h: &egui_kittest::Harness<'_, viewer::ViewerApp>, label: &str| {
        h.get_by_label(label).accesskit_node().toggled() == Some(egui::accesskit::Toggled::True)
    };
    assert!(toggled(&harness, "Laugh"));
    assert!(!toggled(&harness, "Smile"));
    harness
        .get_by_role_and_label(Role::Slider, "Mentalis L")
        .set_value_accesskit(-0.3);
    harness.run();
    assert_eq!(harness.state().active_preset(), None);
    assert!(!toggled(&harness, "Laugh"));
}

#[test]
fn the_export_folder_is_shown_relative_to_home() {
    let Some(home) = std::env::var_os("HOME").filter(|h| !h.is_empty()) else {
        eprintln!("SKIPPED: HOME is not set");
        return;
    };
    let mut harness = common::harness_with(None);
    let dir = std::path::Path::new(&home).join("facebem-exports");
    harness.state_mut().set_export_dir(&dir);
    harness.run();
    assert_eq!(harness.state().export_dir_text(), "~/facebem-exports");
    assert_eq!(harness.state().export_dir(), dir);
    assert!(
        harness
            .get_all_by_value("~/facebem-exports")
            .next()
            .is_some()
    );
}
