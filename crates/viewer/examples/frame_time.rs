//! Measures the viewer's per-frame cost on the current wgpu adapter (lavapipe in CI):
//! the CPU blend alone, and whole frames (egui pass + blend + upload + 3D pass + read-back)
//! through egui_kittest while a slider changes every frame.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p viewer --example frame_time [FACE.obj ...]`

use std::time::Instant;

use egui_kittest::Harness;
use facebem::MuscleBasis;
use glam::DVec3;
use viewer::posed_mesh::{PosedMesh, bounding_sphere};
use viewer::{ViewerApp, ViewerOptions};

fn synthetic(mut basis: MuscleBasis) -> MuscleBasis {
    let (_, r) = bounding_sphere(&basis.neutral).unwrap_or((DVec3::ZERO, 1.0));
    for (k, kind) in face_prep::MuscleKind::ALL.into_iter().enumerate() {
        let c = basis.neutral[(97 * k) % basis.neutral.len()];
        let field = basis
            .neutral
            .iter()
            .map(|p| {
                DVec3::new(0.1, 0.05, 0.02) * r * (-p.distance_squared(c) / (0.05 * r * r)).exp()
            })
            .collect();
        basis.muscle_ids.push(kind.id().to_owned());
        basis.displacements.push(field);
    }
    basis
}

fn main() -> anyhow::Result<()> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    let mut files: Vec<std::path::PathBuf> = std::env::args_os().skip(1).map(Into::into).collect();
    if files.is_empty() {
        files = vec![
            root.join("mediapipe_canonical_4loop.obj"),
            root.join("ict_narrow_face_4loop.obj"),
        ];
    }
    // Baseline: the same window with no face (egui + lavapipe + read-back, no 3D pass).
    let mut empty = Harness::builder()
        .with_size([1280.0, 800.0])
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
    empty.run();
    let _ = empty.render();
    let frames = 60;
    let t = Instant::now();
    for _ in 0..frames {
        empty.step();
        empty.render().map_err(anyhow::Error::msg)?;
    }
    let empty_ms = t.elapsed().as_secs_f64() * 1e3 / frames as f64;
    println!("no face (baseline): full frame 1280x800 {empty_ms:.1} ms");
    for file in files {
        let basis = synthetic(viewer::source::load_neutral(&file)?);
        let n = basis.muscle_count();
        let mut sliders = vec![0.0; n];
        let mut mesh = PosedMesh::default();
        let reps = 200;
        let t = Instant::now();
        for i in 0..reps {
            sliders
                .iter_mut()
                .enumerate()
                .for_each(|(k, s)| *s = ((i + k) as f64 * 0.1).sin());
            mesh.update(&basis, &sliders)?;
        }
        let blend_ms = t.elapsed().as_secs_f64() * 1e3 / reps as f64;

        let mut harness = Harness::builder()
            .with_size([1280.0, 800.0])
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
        harness.state_mut().set_face("face", basis.clone());
        harness.run();
        let _ = harness.render();
        let t = Instant::now();
        for i in 0..frames {
            // Drive the pose through the app as a slider would.
            let s = ((i as f64) * 0.2).sin();
            harness.state_mut().set_sliders(&vec![s; n]);
            harness.step();
            harness.render().map_err(anyhow::Error::msg)?;
        }
        let frame_ms = t.elapsed().as_secs_f64() * 1e3 / frames as f64;
        println!(
            "{}: {} vertices, {} triangles: CPU blend {:.3} ms; full frame 1280x800 {:.1} ms ({:.0} fps)",
            file.file_name().unwrap_or_default().to_string_lossy(),
            basis.neutral.len(),
            basis.triangles.len(),
            blend_ms,
            frame_ms,
            1e3 / frame_ms
        );
    }
    Ok(())
}
