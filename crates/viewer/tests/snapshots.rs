//! Rendered images of the default face with its real rig (computed by the pipeline into a
//! fresh cache folder), wgpu on lavapipe, compared with committed snapshots.
//! Create or update them with `UPDATE_SNAPSHOTS=1 cargo test --release -p viewer --test snapshots`.

mod common;

use egui_kittest::SnapshotOptions;
use egui_kittest::kittest::Queryable;

/// Pixels of the viewport (right of the control panel, between tool and status bars).
fn viewport_pixels(img: &image::RgbaImage) -> Vec<[u8; 4]> {
    let (w, h) = img.dimensions();
    let mut out = Vec::new();
    for y in (h / 8)..(h * 7 / 8) {
        for x in (w * 2 / 5)..(w - 8) {
            out.push(img.get_pixel(x, y).0);
        }
    }
    out
}

fn differs(a: [u8; 4], b: [u8; 4]) -> bool {
    a.iter().zip(b).any(|(x, y)| x.abs_diff(y) > 8)
}

#[test]
fn default_face_snapshots_neutral_happy_and_overlays() {
    let cache = tempfile::tempdir().unwrap();
    let mut harness = egui_kittest::Harness::builder()
        .with_size([1100.0, 760.0])
        .with_render_cursor(false)
        .wgpu()
        .build_eframe(|cc| {
            viewer::ViewerApp::new(
                cc,
                viewer::ViewerOptions {
                    cache_dir: Some(cache.path().to_path_buf()),
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
    // Machine-dependent text (timings, working directory) stays out of the images.
    harness.state_mut().clear_message();
    harness
        .state_mut()
        .set_export_dir(std::path::Path::new("/exports"));
    harness.run();
    let options = SnapshotOptions::new().threshold(0.6).max_failed_pixels(40);

    // Neutral (the muscle overlay is off by default), then with the muscle overlay.
    let neutral = harness.render().expect("wgpu render");
    harness.snapshot_options("default_face_neutral", &options);
    harness.get_by_label("Muscles").click();
    harness.run();
    let with_muscles = harness.render().expect("wgpu render");
    // Hovering a muscle's line names it by the pointer (the zygomaticus major: a long line
    // over the cheek).
    let index = harness
        .state()
        .pending_muscles()
        .unwrap()
        .iter()
        .position(|m| m.kind == Some(face_prep::MuscleKind::ZygomaticusMajorL))
        .expect("the default rig has a left zygomaticus major");
    let at = harness.state().muscle_line_point(index).expect("on screen");
    harness.hover_at(at);
    harness.run();
    assert_eq!(
        harness.state().muscle_at(at).as_deref(),
        Some("Zygomaticus major L")
    );
    harness.snapshot_options("default_face_muscle_hover", &options);
    harness.hover_at(egui::pos2(5.0, 700.0));
    harness.get_by_label("Muscles").click();
    harness.run();
    let (w, h) = neutral.dimensions();
    let background = neutral.get_pixel(w - 4, h / 2).0;
    let total = viewport_pixels(&neutral).len();
    let face = viewport_pixels(&neutral)
        .into_iter()
        .filter(|p| differs(*p, background))
        .count();
    assert!(
        face * 10 > total,
        "face covers only {face} of {total} viewport pixels"
    );
    let overlay = viewport_pixels(&with_muscles)
        .into_iter()
        .zip(viewport_pixels(&neutral))
        .filter(|(a, b)| differs(*a, *b))
        .count();
    assert!(
        overlay > 100,
        "the muscle overlay changed only {overlay} pixels"
    );

    harness.get_by_label("Happy").click();
    harness.run();
    let happy = harness.render().expect("wgpu render");
    let changed = viewport_pixels(&neutral)
        .into_iter()
        .zip(viewport_pixels(&happy))
        .filter(|(a, b)| differs(*a, *b))
        .count();
    assert!(
        changed > 200,
        "the Happy preset changed only {changed} viewport pixels"
    );
    harness.snapshot_options("default_face_happy", &options);

    for label in [
        "Muscles",
        "Skull",
        "Feature boxes",
        "Whole shell",
        "Wireframe",
    ] {
        harness.get_by_label(label).click();
        harness.run();
    }
    harness.snapshot_options("default_face_happy_overlays", &options);
}
