//! Shared helpers of the viewer's integration tests.
#![allow(dead_code)]

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use facebem::MuscleBasis;
use glam::DVec3;
use viewer::{ViewerApp, ViewerOptions};

/// Sets the environment the tests need (lavapipe through Vulkan, a private runtime dir).
pub fn test_env() {
    // SAFETY-free: set_var is safe to call before any thread reads it (tests set the same values).
    if std::env::var_os("WGPU_BACKEND").is_none() {
        // Edition 2024 makes set_var unsafe; the CI script sets WGPU_BACKEND=vulkan instead.
        eprintln!("note: WGPU_BACKEND is not set; CI sets WGPU_BACKEND=vulkan");
    }
}

/// A basis on the bundled default face with one smooth synthetic field per standard muscle:
/// muscle k pushes a Gaussian neighbourhood of vertex `17 * k + 5` along a fixed direction.
/// (Stands in for the BEM basis in tests that check the viewer, not the physics.)
pub fn synthetic_default_basis() -> MuscleBasis {
    let mut basis = viewer::source::load_neutral(&viewer::source::default_face_path())
        .expect("the bundled default face loads");
    let (_, radius) = viewer::posed_mesh::bounding_sphere(&basis.neutral).expect("finite face");
    let sigma = 0.18 * radius;
    for (k, kind) in face_prep::MuscleKind::ALL.into_iter().enumerate() {
        let centre = basis.neutral[(17 * k + 5) % basis.neutral.len()];
        let dir = DVec3::new(
            if k % 2 == 0 { 1.0 } else { -1.0 },
            0.6 - 0.15 * k as f64,
            0.3,
        )
        .normalize()
            * (0.12 * radius);
        let field = basis
            .neutral
            .iter()
            .map(|p| dir * (-(p.distance_squared(centre)) / (2.0 * sigma * sigma)).exp())
            .collect();
        basis.muscle_ids.push(kind.id().to_owned());
        basis.displacements.push(field);
    }
    basis
}

/// A harness running the real app on wgpu (lavapipe in CI), starting empty.
pub fn harness_with(basis: Option<MuscleBasis>) -> Harness<'static, ViewerApp> {
    let mut harness = Harness::builder()
        .with_size([1100.0, 1500.0])
        .with_render_cursor(false)
        .wgpu()
        .build_eframe(|cc| {
            ViewerApp::new(
                cc,
                ViewerOptions {
                    start_empty: true,
                    ..Default::default()
                },
            )
        });
    if let Some(b) = basis {
        harness
            .state_mut()
            .set_face("mediapipe_canonical_4loop.obj", b);
    }
    harness.run();
    harness
}

/// Steps the harness until no background job runs (bounded so a hang fails instead of blocking).
pub fn wait_idle(harness: &mut Harness<'_, ViewerApp>) {
    let start = Instant::now();
    while harness.state().is_busy() {
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "background job never finished"
        );
        std::thread::sleep(Duration::from_millis(5));
        harness.step();
    }
    harness.run();
}

/// Types `path` into the Path field and clicks Open (one frame; the opening runs in the
/// background).
pub fn open_via_path_field(harness: &mut Harness<'_, ViewerApp>, path: &std::path::Path) {
    harness.get_by_label("Path").focus();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    harness
        .get_by_label("Path")
        .type_text(&path.display().to_string());
    harness.run();
    harness.get_by_label("Open").click();
    harness.step();
}
