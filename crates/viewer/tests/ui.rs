//! egui_kittest tests of the real viewer app on wgpu: widgets are found through the
//! accessibility tree, as a user would find them.

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
    let want = facebem::presets::find("smile")
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
fn the_default_face_opens_in_the_background_on_start() {
    let mut harness = egui_kittest::Harness::builder()
        .with_size([900.0, 600.0])
        .wgpu()
        .build_eframe(|cc| viewer::ViewerApp::new(cc, viewer::ViewerOptions::default()));
    common::wait_idle(&mut harness);
    let basis = harness
        .state()
        .basis()
        .expect("default face loaded")
        .clone();
    assert_eq!(basis.triangles.len(), 852);
    assert_eq!(
        harness.state().uploaded_vertices().len(),
        basis.neutral.len()
    );
    let msg = harness.state().message().cloned().unwrap();
    assert!(!msg.is_error, "{}", msg.text);
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
