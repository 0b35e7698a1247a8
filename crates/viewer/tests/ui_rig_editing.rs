//! egui_kittest tests of editing the default face's real rig in the viewer (wgpu): muscles edited
//! element by element, the muscle file, rebuilding with a new offset, and feature boxes edited in
//! the viewport and the box editor.

mod common;

use std::path::Path;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use facebem::FaceModel;
use viewer::ViewerApp;

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
    click_the_viewport_centre(&mut harness);
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

    // Add it to the target muscle (the first one), then remove it from every muscle; the
    // muscle overlay (off by default) shows the edit.
    harness.get_by_label("Muscles").click();
    harness.run();
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
    // Each edit is an undo step: back to the added element, back to the rig's muscles, and
    // forward again to the removal.
    let removed = pending.clone();
    let added_only = {
        let mut m = model.rig.muscles.clone();
        if !m[0].front_chain.contains(&element) {
            m[0].front_chain.push(element);
        }
        m
    };
    let z = egui::Key::Z;
    harness.key_press_modifiers(egui::Modifiers::COMMAND, z);
    harness.run();
    let undone = harness.state().pending_muscles().unwrap().to_vec();
    assert!(undone[0].front_chain.contains(&element));
    assert_eq!(undone.len(), added_only.len());
    harness.key_press_modifiers(egui::Modifiers::COMMAND, z);
    harness.run();
    assert_eq!(
        harness.state().pending_muscles().unwrap(),
        &model.rig.muscles[..]
    );
    let redo = egui::Modifiers::COMMAND | egui::Modifiers::SHIFT;
    harness.key_press_modifiers(redo, z);
    harness.run();
    harness.key_press_modifiers(redo, z);
    harness.run();
    assert_eq!(harness.state().pending_muscles().unwrap(), &removed[..]);
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
    a_new_offset_rebuilds_in_the_background(&mut harness, &model, cache.path());
}

/// Clicks (press and release, no drag) the centre of the viewport.
fn click_the_viewport_centre(harness: &mut Harness<'_, ViewerApp>) {
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
}

/// A new offset rebuilds the rig in the background; cancelling keeps the old rig (`model`),
/// rebuilding again completes with the new offset and caches a second file in `cache`.
fn a_new_offset_rebuilds_in_the_background(
    harness: &mut Harness<'_, ViewerApp>,
    model: &FaceModel,
    cache: &Path,
) {
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
    common::wait_idle(harness);
    let msg = harness.state().message().cloned().unwrap();
    assert!(
        msg.is_error && msg.text.contains("cancelled"),
        "{}",
        msg.text
    );
    assert_eq!(harness.state().model().unwrap().basis, model.basis);

    harness.get_by_label("Rebuild rig").click();
    harness.step();
    common::wait_idle(harness);
    let rebuilt = harness.state().model().unwrap();
    assert!(
        (rebuilt.params.rig.offset - 0.03).abs() < 1e-12,
        "{}",
        rebuilt.params.rig.offset
    );
    assert_ne!(rebuilt.basis.displacements, model.basis.displacements);
    assert_eq!(rebuilt.basis.neutral, model.basis.neutral);
    assert_eq!(
        std::fs::read_dir(cache).unwrap().count(),
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
    drag_the_mouth_box_bottom_edge_then_revert(&mut harness, &model);

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
    let expected = model.rig.clone().with_boxes(boxes).unwrap();
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
    an_inverted_eye_box_is_refused(&mut harness);
}

/// Drags the mouth box's bottom edge down in the viewport (only mouth min y changes, the camera
/// does not orbit), then reverts the boxes to the rig's.
fn drag_the_mouth_box_bottom_edge_then_revert(
    harness: &mut Harness<'_, ViewerApp>,
    model: &FaceModel,
) {
    let b = model.rig.boxes;
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
    // The drag is one undo step, and redo brings it back.
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state_mut().box_edit_mut().unwrap()[3], b.mouth);
    harness.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    harness.run();
    assert_eq!(harness.state_mut().box_edit_mut().unwrap()[3], dragged[3]);
    harness.get_by_label("Revert boxes").click();
    harness.run();
    assert_eq!(harness.state_mut().box_edit_mut().unwrap()[3], b.mouth);
}

/// Applying boxes with the left eye box inverted is refused with a message, without a rebuild.
fn an_inverted_eye_box_is_refused(harness: &mut Harness<'_, ViewerApp>) {
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
