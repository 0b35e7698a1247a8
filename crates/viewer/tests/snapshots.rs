//! Rendered images of the default face (wgpu on lavapipe), compared with committed snapshots.
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
fn default_face_neutral_and_smile_snapshots() {
    let mut harness = common::harness_with(Some(common::synthetic_default_basis()));
    let options = SnapshotOptions::new().threshold(0.6).max_failed_pixels(40);
    harness.run();
    let neutral = harness.render().expect("wgpu render");
    let (w, h) = neutral.dimensions();
    let background = neutral.get_pixel(w - 4, h / 2).0;
    let face = viewport_pixels(&neutral)
        .into_iter()
        .filter(|p| differs(*p, background))
        .count();
    let total = viewport_pixels(&neutral).len();
    assert!(
        face * 10 > total,
        "face covers only {face} of {total} viewport pixels"
    );
    harness.snapshot_options("default_face_neutral", &options);

    harness.get_by_label("Smile").click();
    harness.run();
    let smile = harness.render().expect("wgpu render");
    let changed = viewport_pixels(&neutral)
        .into_iter()
        .zip(viewport_pixels(&smile))
        .filter(|(a, b)| differs(*a, *b))
        .count();
    assert!(
        changed > 200,
        "the Smile preset changed only {changed} viewport pixels"
    );
    harness.snapshot_options("default_face_smile", &options);

    harness.get_by_label("Wireframe").click();
    harness.run();
    harness.snapshot_options("default_face_smile_wireframe", &options);
}
