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
fn arkit_and_vrm_names_apply_like_presets() {
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    assert!(harness.state_mut().apply_preset("mouthSmileLeft"));
    harness.run();
    let want = facebem::expression_sets::find("mouthSmileLeft")
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
    let blink = facebem::expression_sets::find("blinkLeft").unwrap();
    if blink.resolve(&basis.muscle_ids).is_none() {
        assert!(!harness.state_mut().apply_preset("blinkLeft"));
    }
    assert!(!harness.state_mut().apply_preset("grin"));
    assert_eq!(harness.state().sliders(), &want[..]);
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
fn first_run_computes_and_caches_the_default_rig_and_the_second_run_loads_it() {
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let start = |options: viewer::ViewerOptions| {
        egui_kittest::Harness::builder()
            .with_size([1100.0, 1200.0])
            .wgpu()
            .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()))
    };
    let mut first = start(options.clone());
    // The neutral face appears while the rig is still being computed, with a progress bar:
    // the UI thread is not blocked by the precompute.
    let t0 = std::time::Instant::now();
    while first.state().basis().is_none() {
        assert!(
            t0.elapsed() < std::time::Duration::from_secs(60),
            "the face never appeared"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
        first.step();
    }
    assert!(
        first.state().is_rigging(),
        "the rig is computed in the background"
    );
    assert_eq!(first.state().basis().unwrap().muscle_count(), 0);
    assert_eq!(first.state().uploaded_vertices().len(), 468);
    first.step();
    first.get_by_role(Role::ProgressIndicator);
    first.get_by_label("Cancel");
    common::wait_idle(&mut first);
    let msg = first.state().message().cloned().unwrap();
    assert!(!msg.is_error, "{}", msg.text);
    assert!(msg.text.contains("computed"), "{}", msg.text);
    let model = first.state().model().expect("the rig is computed").clone();
    assert_eq!(model.basis.triangles.len(), 852);
    assert_eq!(model.basis.muscle_count(), face_prep::MuscleKind::ALL.len());
    assert_eq!(first.state().basis(), Some(&model.basis));
    let cached: Vec<_> = std::fs::read_dir(cache.path()).unwrap().collect();
    assert_eq!(cached.len(), 1, "one cache file");
    // Every slider is there.
    for kind in face_prep::MuscleKind::ALL {
        first.get_by_role_and_label(Role::Slider, kind.display_name());
    }
    // The muscle overlay follows the pose: with one slider moved, the chain is drawn through
    // the posed element centroids.
    let before = first.state().overlay_line_vertices().to_vec();
    first
        .get_by_role_and_label(Role::Slider, "Zygomaticus major L")
        .set_value_accesskit(-1.0);
    first.run();
    let after = first.state().overlay_line_vertices().to_vec();
    assert_eq!(before.len(), after.len());
    // (The BEM response is global: every vertex moves a little, the driven chain the most.)
    let largest = before
        .iter()
        .zip(&after)
        .map(|(a, b)| glam::Vec3::from(a.position).distance(glam::Vec3::from(b.position)))
        .fold(0.0f32, f32::max);
    assert!(
        f64::from(largest) > 0.01 * model.rig.face_size,
        "overlay moved by {largest} only"
    );
    // Posed shell vertices (user frame): each moves by its own response. The default face is
    // simulated without its rolled-in mouth corners, so the shell's front vertices are a
    // subset of the face's, and the response, not the face's pose, is what the overlay uses.
    let input_from_canonical = model.rig.input_from_canonical();
    let sliders = first.state().sliders().to_vec();
    let posed: Vec<glam::DVec3> = (0..model.rig.shell.vertices.len())
        .map(|v| {
            let u: glam::DVec3 = sliders
                .iter()
                .zip(&model.shell_vertex_response)
                .map(|(s, r)| *s * r[v])
                .sum();
            input_from_canonical.transform_point3(model.rig.shell.vertices[v])
                + input_from_canonical.matrix3 * u
        })
        .collect();
    let zyg = model
        .rig
        .muscles
        .iter()
        .find(|m| m.kind == Some(face_prep::MuscleKind::ZygomaticusMajorL))
        .unwrap();
    let e = zyg.front_chain[0] as usize;
    let centroid = model.rig.shell.triangles[e]
        .iter()
        .map(|&v| posed[v as usize])
        .sum::<glam::DVec3>()
        / 3.0;
    let want = centroid.as_vec3().to_array();
    assert!(
        after.iter().any(|l| l
            .position
            .iter()
            .zip(want)
            .all(|(a, b)| (a - b).abs() < 1e-4)),
        "no overlay vertex at the posed centroid {want:?} of the chain's first element"
    );
    first.get_by_label("Reset muscles").click();
    first.run();

    let mut second = start(options);
    common::wait_idle(&mut second);
    let msg = second.state().message().cloned().unwrap();
    assert!(msg.text.contains("loaded from the cache"), "{}", msg.text);
    assert_eq!(second.state().basis(), Some(&model.basis));

    // A saved rig opens directly, without recomputing.
    let rig_file = cached[0].as_ref().unwrap().path();
    open_via_path_field(&mut second, &rig_file);
    common::wait_idle(&mut second);
    let msg = second.state().message().cloned().unwrap();
    assert!(msg.text.contains("Opened the saved rig"), "{}", msg.text);
    assert_eq!(second.state().model().unwrap().basis, model.basis);

    // A GLB face opens too (here the viewer's own glTF export); its rig job can be cancelled.
    let out = tempfile::tempdir().unwrap();
    second.state_mut().set_export_dir(out.path());
    second.get_by_label("Export glTF").click();
    second.step();
    common::wait_idle(&mut second);
    let msg = second.state().message().cloned().unwrap();
    assert!(msg.text.contains("Exported"), "{}", msg.text);
    let glb = std::fs::read_dir(out.path())
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    open_via_path_field(&mut second, &glb);
    while second.state().basis().is_some_and(|b| b.muscle_count() > 0) {
        std::thread::sleep(std::time::Duration::from_millis(5));
        second.step();
    }
    second.step();
    second.get_by_label("Cancel").click();
    second.step();
    common::wait_idle(&mut second);
    let basis = second.state().basis().unwrap();
    assert_eq!(basis.muscle_count(), 0, "rig cancelled: the preview stays");
    // The GLB holds the OBJ's `v` lines in order, in metres: its vertex i is the model's
    // vertex input_to_vertex[i].
    let itv: Vec<u32> = model
        .mesh
        .input_to_vertex
        .iter()
        .map(|w| w.unwrap())
        .collect();
    let mapped: Vec<[u32; 3]> = basis
        .triangles
        .iter()
        .map(|t| t.map(|i| itv[i as usize]))
        .collect();
    assert_eq!(mapped, model.basis.triangles);
    let metres = model.metres_per_unit();
    for (i, a) in basis.neutral.iter().enumerate() {
        let b = model.basis.neutral[itv[i] as usize] * metres;
        assert!((*a - b).length() < 1e-5 * metres, "{a} vs {b}");
    }
}

fn open_via_path_field(
    harness: &mut egui_kittest::Harness<'_, viewer::ViewerApp>,
    path: &std::path::Path,
) {
    harness.get_by_label("Path").focus();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    harness
        .get_by_label("Path")
        .type_text(&path.display().to_string());
    harness.run();
    harness.get_by_label("Open").click();
    harness.step();
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
fn editing_muscles_saving_the_muscle_file_and_rebuilding_with_a_new_offset() {
    let cache = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 1500.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    common::wait_idle(&mut harness);
    let model = harness.state().model().expect("rig computed").clone();
    harness.state_mut().set_export_dir(out.path());

    // Pick the front element under the viewport centre.
    let rect = harness.state().viewport_rect().unwrap();
    let c = rect.center();
    harness.hover_at(c);
    for pressed in [true, false] {
        harness.event(egui::Event::PointerButton {
            pos: c,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
    }
    harness.run();
    let sel = harness.state().selection().cloned().expect("selection");
    let element = sel.element.expect("a rig element under the centre");
    assert!((element as usize) < model.rig.face_triangle_count);
    let in_muscles = model
        .rig
        .muscles
        .iter()
        .filter(|m| m.front_chain.contains(&element) || m.back_chain.contains(&element))
        .count();
    assert_eq!(sel.muscles.len(), in_muscles);

    // Add it to the target muscle (the first one), then remove it from every muscle.
    let lines_before = harness.state().overlay_line_vertices().to_vec();
    harness.get_by_label("Add element to muscle").click();
    harness.run();
    let pending = harness.state().pending_muscles().unwrap().to_vec();
    assert!(pending[0].front_chain.contains(&element));
    // The selection info and the muscle overlay show the edit before any rebuild.
    let first = model.rig.muscles[0].kind.unwrap().display_name();
    let sel = harness.state().selection().cloned().unwrap();
    assert!(sel.muscles.iter().any(|m| m == first), "{:?}", sel.muscles);
    if !model.rig.muscles[0].front_chain.contains(&element) {
        assert_ne!(
            harness.state().overlay_line_vertices(),
            lines_before.as_slice()
        );
    }
    assert_eq!(
        pending[0].front_chain.len(),
        model.rig.muscles[0].front_chain.len()
            + usize::from(!model.rig.muscles[0].front_chain.contains(&element))
    );
    harness.get_by_label("Remove element from muscles").click();
    harness.run();
    let pending = harness.state().pending_muscles().unwrap().to_vec();
    assert!(
        pending
            .iter()
            .all(|m| !m.front_chain.contains(&element) && !m.back_chain.contains(&element))
    );
    assert!(harness.state().selection().unwrap().muscles.is_empty());

    // The muscle file holds the rig's muscles.
    harness.get_by_label("Save muscle file").click();
    harness.step();
    common::wait_idle(&mut harness);
    let file = out.path().join("mediapipe_canonical_4loop.muscles");
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        !msg.is_error && msg.text.contains("Exported"),
        "{}",
        msg.text
    );
    let read = face_prep::muscle_file::load(&file, model.rig.shell.triangles.len()).unwrap();
    assert_eq!(read, model.rig.muscles);

    // A new offset rebuilds in the background; cancelling keeps the old rig.
    harness
        .get_by_role_and_label(Role::Slider, "Offset (× face size)")
        .set_value_accesskit(0.03);
    harness.run();
    harness.state_mut().params_mut().muscles = None;
    harness.get_by_label("Rebuild rig").click();
    harness.step();
    assert!(harness.state().is_rigging());
    harness.step(); // the status bar shows the job from the next frame on
    harness.get_by_label("Cancel").click();
    harness.step();
    common::wait_idle(&mut harness);
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        msg.is_error && msg.text.contains("cancelled"),
        "{}",
        msg.text
    );
    assert_eq!(harness.state().model().unwrap().basis, model.basis);

    harness.get_by_label("Rebuild rig").click();
    harness.step();
    common::wait_idle(&mut harness);
    let rebuilt = harness.state().model().unwrap();
    assert!(
        (rebuilt.params.rig.offset - 0.03).abs() < 1e-12,
        "{}",
        rebuilt.params.rig.offset
    );
    assert_ne!(rebuilt.basis.displacements, model.basis.displacements);
    assert_eq!(rebuilt.basis.neutral, model.basis.neutral);
    assert_eq!(
        std::fs::read_dir(cache.path()).unwrap().count(),
        2,
        "one cache file per offset"
    );
}

#[test]
fn edited_feature_boxes_re_place_muscles_and_skull_and_invalid_boxes_are_refused() {
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 1200.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    common::wait_idle(&mut harness);
    let model = harness.state().model().expect("rig computed").clone();

    harness.get_by_label("Feature boxes").click();
    harness.get_by_label("Edit feature boxes").click();
    harness.run();
    let b = model.rig.boxes;
    assert_eq!(
        harness.state_mut().box_edit_mut().map(|e| *e),
        Some([b.face, b.eye_l, b.eye_r, b.mouth])
    );
    let lines_before = harness.state().overlay_line_vertices().to_vec();

    // Drag the mouth box's bottom edge down in the viewport: only mouth min y changes.
    let rect = harness.state().viewport_rect().unwrap();
    let z = model
        .rig
        .shell
        .vertices
        .iter()
        .take(model.rig.face_vertex_count)
        .map(|p| p.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let input_from_canonical = model.rig.canonical_from_input.inverse();
    let aspect = rect.width() / rect.height();
    let clip_from_world = harness.state_mut().camera_mut().clip_from_world(aspect);
    let to_screen = |x: f64, y: f64| {
        let p = input_from_canonical.transform_point3(glam::DVec3::new(x, y, z));
        let ndc = clip_from_world.project_point3(p.as_vec3());
        egui::pos2(
            rect.left() + (ndc.x + 1.0) * 0.5 * rect.width(),
            rect.top() + (1.0 - ndc.y) * 0.5 * rect.height(),
        )
    };
    let p0 = to_screen(0.5 * (b.mouth.min.x + b.mouth.max.x), b.mouth.min.y);
    let p1 = p0 + egui::vec2(0.0, 30.0);
    let yaw = harness.state_mut().camera_mut().yaw;
    harness.hover_at(p0);
    harness.drag_at(p0);
    harness.step();
    harness.hover_at(p0 + egui::vec2(0.0, 15.0));
    harness.step();
    harness.hover_at(p1);
    harness.step();
    harness.drop_at(p1);
    harness.run();
    let dragged = *harness.state_mut().box_edit_mut().unwrap();
    assert!(
        dragged[3].min.y < b.mouth.min.y - 0.01 * model.rig.face_size,
        "{:?}",
        dragged[3]
    );
    assert_eq!(dragged[3].max, b.mouth.max);
    assert_eq!(dragged[3].min.x, b.mouth.min.x);
    assert_eq!(&dragged[..3], &[b.face, b.eye_l, b.eye_r]);
    assert_eq!(
        harness.state_mut().camera_mut().yaw,
        yaw,
        "a box drag does not orbit"
    );
    harness.get_by_label("Revert boxes").click();
    harness.run();
    assert_eq!(harness.state_mut().box_edit_mut().unwrap()[3], b.mouth);

    // Move the mouth box down by 8% of the face size and apply.
    let d = 0.08 * model.rig.face_size;
    harness
        .get_by_label("Mouth min y")
        .set_value_accesskit(b.mouth.min.y - d);
    harness.run();
    harness
        .get_by_label("Mouth max y")
        .set_value_accesskit(b.mouth.max.y - d);
    harness.run();
    let edited = harness.state_mut().box_edit_mut().unwrap()[3];
    assert!(
        (edited.min.y - (b.mouth.min.y - d)).abs() < 1e-9,
        "{edited:?}"
    );
    assert!(
        (edited.max.y - (b.mouth.max.y - d)).abs() < 1e-9,
        "{edited:?}"
    );
    harness.get_by_label("Apply boxes").click();
    harness.step();
    assert!(harness.state().is_rigging());
    common::wait_idle(&mut harness);
    let msg = harness.state().message().cloned().unwrap();
    assert!(!msg.is_error, "{}", msg.text);
    let rebuilt = harness.state().model().unwrap().clone();
    // The pipeline got the boxes: muscles and skull both come from them, exactly as face-prep
    // places them in those boxes on the original rig's shell.
    let boxes = rebuilt
        .params
        .boxes
        .expect("the edited boxes are a pipeline parameter");
    assert_eq!(boxes.mouth, edited);
    assert_eq!(rebuilt.rig.boxes, boxes);
    assert_eq!(rebuilt.params.muscles, None);
    let expected = model.rig.rebuild_with_boxes(boxes).unwrap();
    assert_eq!(rebuilt.rig.muscles, expected.muscles);
    assert_eq!(rebuilt.rig.skull, expected.skull);
    assert_ne!(
        rebuilt.rig.skull, model.rig.skull,
        "the nose box (down to the mouth) and so the skull follow the mouth box"
    );
    let muscles = &rebuilt.rig.muscles;
    let moved = muscles
        .iter()
        .zip(&model.rig.muscles)
        .filter(|(a, b)| a.front_chain != b.front_chain)
        .count();
    assert!(
        moved >= 2,
        "only {moved} muscles changed with the mouth box"
    );
    assert_ne!(rebuilt.basis.displacements, model.basis.displacements);
    // The overlay shows the edited boxes.
    assert_ne!(
        harness.state().overlay_line_vertices(),
        lines_before.as_slice()
    );

    // Inverted eye box: refused with a message, no rebuild.
    {
        let edit = harness.state_mut().box_edit_mut().unwrap();
        std::mem::swap(&mut edit[1].min.x, &mut edit[1].max.x);
    }
    harness.get_by_label("Apply boxes").click();
    harness.step();
    assert!(!harness.state().is_rigging());
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        msg.is_error && msg.text.contains("Feature boxes"),
        "{}",
        msg.text
    );
}

/// Regression: a cache file left by an older build (same name, payload no longer decodes) made
/// `cache::load` fail; the viewer must recompute and overwrite it, not report an error.
#[test]
fn a_stale_or_corrupt_cache_file_is_recomputed_and_replaced() {
    let cache = tempfile::tempdir().unwrap();
    let mesh = facebem::open::default_face().unwrap();
    let path =
        viewer::source::cache_file_for(cache.path(), &mesh, &facebem::PipelineParams::default());
    std::fs::write(&path, b"not a facebem rig at all").unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([900.0, 600.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    common::wait_idle(&mut harness);
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        !msg.is_error && msg.text.contains("computed"),
        "{}",
        msg.text
    );
    let model = harness.state().model().expect("rig computed").clone();
    let reloaded = facebem::cache::load(&path).expect("the cache file was replaced");
    assert_eq!(reloaded.basis, model.basis);
}

/// A face whose shell crosses itself is rigged, but the user is told, in red, that responses
/// there are unreliable — the count is the pipeline's own. The crossing shell: the ICT
/// 2500-triangle face with its rolled-in lips kept and simplified by position only with every
/// border vertex locked, which folds the lips into a pleat at the right mouth corner (the
/// defaults peel the lips, weight normals, resample the borders, and are clean).
#[test]
fn a_rig_with_intersecting_shell_elements_is_flagged() {
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        start_empty: true,
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 1500.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    harness.run();
    let face = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/ict_narrow_face_dec2500_4loop.obj");
    open_via_path_field(&mut harness, &face);
    common::wait_idle(&mut harness);
    let clean = harness.state().model().expect("rig computed").clone();
    assert_eq!(clean.report.shell_self_intersections, 0);
    assert!(!harness.state().message().is_some_and(|m| m.is_error));
    // The status line says how the large face was simplified (the decimated ICT face is not
    // mirror-symmetric).
    let status = harness.state().message().cloned().unwrap().text;
    assert!(
        status.contains(&format!(
            "{} triangles simulated, simplified in the face's canonical frame and order",
            clean.report.simulated_triangles
        )),
        "{status}"
    );
    let params = harness.state_mut().params_mut();
    params.peel_rolled_in = false;
    params.large_face.normal_weight = 0.0;
    params.large_face.border_spacing = 0.0;
    harness.get_by_label("Rebuild rig").click();
    // One frame, not `run()`: the job repaints while it works, so `run()` could exceed its
    // step limit (it did once, "would have settled after 6 steps"); `wait_idle` steps it out.
    harness.step();
    common::wait_idle(&mut harness);
    let model = harness.state().model().expect("rig computed").clone();
    let crossings = model.report.shell_self_intersections;
    assert!(
        crossings > 0,
        "the position-only ICT copy no longer crosses itself: update this test"
    );
    let msg = harness.state().message().cloned().unwrap();
    assert!(msg.is_error, "{}", msg.text);
    assert!(
        msg.text
            .contains(&format!("{crossings} pairs of shell elements intersect")),
        "{}",
        msg.text
    );
}

#[test]
fn the_face_is_drawn_at_once_exports_wait_for_the_rig_and_the_legend_names_every_muscle() {
    use egui_kittest::kittest::NodeT;
    let cache = tempfile::tempdir().unwrap();
    let options = viewer::ViewerOptions {
        cache_dir: Some(cache.path().to_path_buf()),
        ..Default::default()
    };
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 1200.0])
        .wgpu()
        .build_eframe(move |cc| viewer::ViewerApp::new(cc, options.clone()));
    // The first frame already holds the default face (the rig is computed in the background).
    assert_eq!(harness.state().uploaded_vertices().len(), 468);
    assert!(harness.state().is_rigging());
    harness.step();
    for label in ["Export OBJ pose", "Export glTF", "Save muscle file"] {
        assert!(
            harness.get_by_label(label).accesskit_node().is_disabled(),
            "{label} is enabled while the rig computes"
        );
    }
    // One progress bar over all stages, with the elapsed time.
    let bar = harness.get_by_role(Role::ProgressIndicator);
    let label = bar.accesskit_node().label().unwrap_or_default();
    assert!(label.contains("elapsed"), "{label}");
    let why = harness.state().exports_ready().unwrap_err();
    assert!(why.contains("being computed"), "{why}");
    // Clicking a disabled button does nothing; calling export directly is refused.
    let out = tempfile::tempdir().unwrap();
    harness.state_mut().set_export_dir(out.path());
    harness.get_by_label("Export glTF").click();
    harness.step();
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 0);

    common::wait_idle(&mut harness);
    let model = harness.state().model().expect("rig computed").clone();
    for label in ["Export OBJ pose", "Export glTF", "Save muscle file"] {
        assert!(!harness.get_by_label(label).accesskit_node().is_disabled());
    }
    // The legend names every muscle of the rig with its colour.
    assert!(!model.rig.muscles.is_empty());
    for (i, m) in model.rig.muscles.iter().enumerate() {
        let kind = m.kind.expect("standard muscles on the default face");
        let colour = viewer::overlay::muscle_color_name(i);
        harness.get_by_label(&format!("{}: {colour}", kind.display_name()));
    }
    // Every standard muscle has its own colour name.
    let mut names: Vec<String> = (0..model.rig.muscles.len())
        .map(viewer::overlay::muscle_color_name)
        .collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), model.rig.muscles.len());

    // A muscle file that cannot be read is reported (the dialog's answer goes through here).
    let ctx = harness.ctx.clone();
    let missing = out.path().join("missing.muscles");
    harness.state_mut().load_muscle_file_from(&ctx, &missing);
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        msg.is_error && msg.text.contains("missing.muscles"),
        "{}",
        msg.text
    );
    assert!(!harness.state().is_rigging());
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
