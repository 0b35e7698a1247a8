//! The timeline strip (issue 35) in the real viewer app on wgpu: two poses keyed through the
//! panel's button, the pose half-way between them, and playback moving the face without making
//! undo steps.

mod common;

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;

#[test]
fn keyed_poses_play_back_between_the_keys_without_undo_steps() {
    common::test_env();
    let basis = common::synthetic_default_basis();
    let mut harness = common::harness_with(Some(basis.clone()));
    harness.get_by_label("Timeline (0 keys)").click();
    harness.run();

    // Key A: the happy preset; key B: two sliders set by hand.
    harness.get_by_role_and_label(Role::Button, "Happy").click();
    harness.run();
    let a = harness.state().sliders().to_vec();
    harness.get_by_label("Key pose").click();
    harness.run();
    let mut b = vec![0.0; a.len()];
    b[0] = 0.8;
    b[5] = -0.6;
    harness.state_mut().set_sliders(&b);
    harness.run();
    harness.get_by_label("Key pose").click();
    harness.run();
    let keys = harness.state().timeline().keys().to_vec();
    assert_eq!(keys.len(), 2);
    assert_eq!(keys[0].label, "happy");
    assert_eq!(keys[0].sliders, a);
    assert_eq!(keys[1].sliders, b);
    assert!(harness.query_by_label("Timeline (2 keys)").is_some());

    // Half-way (1 s between keys): the smoothstep's middle, the mean of the keys, and the
    // vertices the renderer gets are that pose's.
    harness.state_mut().set_timeline_time(0.5);
    harness.run();
    let mid: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + 0.5 * (y - x)).collect();
    for (s, m) in harness.state().sliders().iter().zip(&mid) {
        assert!((s - m).abs() < 1e-12, "{s} vs {m}");
    }
    let expected = basis.pose(harness.state().sliders()).unwrap();
    for (u, e) in harness.state().uploaded_vertices().iter().zip(&expected) {
        assert_eq!(u.position, e.as_vec3().to_array());
    }

    let options = egui_kittest::SnapshotOptions::new()
        .threshold(0.6)
        .max_failed_pixels(60);
    // Machine-dependent text (the working directory) stays out of the image.
    harness
        .state_mut()
        .set_export_dir(std::path::Path::new("/exports"));
    harness.run();
    harness.snapshot_options("timeline_panel", &options);

    // Playing moves the sliders between the keys, frame by frame, and makes no undo steps.
    let depth = harness.state().history_depth();
    harness.get_by_role_and_label(Role::Button, "Play").click();
    harness.step();
    assert!(harness.state().timeline().playing());
    let mut seen = Vec::new();
    for _ in 0..6 {
        std::thread::sleep(std::time::Duration::from_millis(60));
        harness.step();
        seen.push(harness.state().sliders()[0]);
        for (k, s) in harness.state().sliders().iter().enumerate() {
            let (lo, hi) = (a[k].min(b[k]), a[k].max(b[k]));
            assert!(*s >= lo - 1e-12 && *s <= hi + 1e-12, "slider {k} = {s}");
        }
    }
    seen.dedup();
    assert!(seen.len() >= 3, "the pose moved only through {seen:?}");
    assert_eq!(harness.state().history_depth(), depth);
    harness.get_by_role_and_label(Role::Button, "Stop").click();
    harness.run();
    assert!(!harness.state().timeline().playing());
    // Stopping leaves the reached pose as one undo step.
    assert_eq!(harness.state().history_depth().0, depth.0 + 1);
}
