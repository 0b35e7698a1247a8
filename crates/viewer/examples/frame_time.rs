//! Measures the viewer's per-frame cost on the current wgpu adapter (lavapipe in CI):
//! the CPU blend alone, and whole frames (egui pass + blend + upload + 3D pass + read-back)
//! through egui_kittest while a slider changes every frame: the face in its skin colour, then
//! textured (planar texture coordinates and a 1024² checker through an OBJ material library),
//! then textured with the heat map and compare mode (two faces drawn).
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

/// The viewer in a 1280×800 window on wgpu, with no face.
fn empty_window() -> Harness<'static, ViewerApp> {
    Harness::builder()
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
        })
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
    let mut empty = empty_window();
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

        let textured = textured_copy(&file)?;
        let mut modes = Vec::new();
        for mode in ["skin", "texture", "texture + heat + compare"] {
            let mut harness = empty_window();
            if mode == "skin" {
                harness.state_mut().set_face("face", basis.clone());
            } else {
                let (mesh, text) = facebem::input::read_face(&textured.1)?;
                let text = text.unwrap_or_default();
                let looks = viewer::surface::Looks::load(&textured.1, Some(&text));
                let basis = synthetic(viewer::source::preview_basis(&mesh));
                harness
                    .state_mut()
                    .set_face_with_looks("face", basis, (mesh, text), looks);
                let on = mode.contains("compare");
                harness.state_mut().set_heat_map(on);
                harness.state_mut().set_compare(on);
            }
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
            modes.push(format!(
                "{mode} {frame_ms:.1} ms ({:.0} fps)",
                1e3 / frame_ms
            ));
        }
        println!(
            "{}: {} vertices, {} triangles: CPU blend {:.3} ms; full frame 1280x800: {}",
            file.file_name().unwrap_or_default().to_string_lossy(),
            basis.neutral.len(),
            basis.triangles.len(),
            blend_ms,
            modes.join("; ")
        );
    }
    Ok(())
}

/// A copy of the OBJ `face` in a temporary folder with planar texture coordinates, a material
/// library and a 1024² checker texture; returns the folder (kept alive) and the OBJ's path.
fn textured_copy(
    face: &std::path::Path,
) -> anyhow::Result<(tempfile::TempDir, std::path::PathBuf)> {
    let text = std::fs::read_to_string(face)?;
    let v: Vec<[f64; 2]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            [
                x.first().copied().unwrap_or(0.0),
                x.get(1).copied().unwrap_or(0.0),
            ]
        })
        .collect();
    let (lo, hi) = v
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        });
    // Texture coordinates come before the faces that use them.
    let mut obj = String::from("mtllib face.mtl\n");
    let mut faces = String::from("usemtl checker\n");
    for line in text.lines() {
        if let Some(f) = line.strip_prefix("f ") {
            faces += "f";
            for w in f.split_whitespace() {
                let i = w.split('/').next().unwrap_or(w);
                faces += &format!(" {i}/{i}");
            }
            faces += "\n";
        } else if !line.starts_with("vt ") && !line.starts_with("vn ") {
            obj += line;
            obj += "\n";
        }
    }
    for p in &v {
        let u = (p[0] - lo[0]) / (hi[0] - lo[0]).max(f64::MIN_POSITIVE);
        let t = (p[1] - lo[1]) / (hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        obj += &format!("vt {u} {t}\n");
    }
    obj += &faces;
    let dir = tempfile::tempdir()?;
    std::fs::write(
        dir.path().join("face.mtl"),
        "newmtl checker\nmap_Kd checker.png\n",
    )?;
    image::RgbaImage::from_fn(1024, 1024, |x, y| {
        let c = if (x / 64 + y / 64).is_multiple_of(2) {
            220
        } else {
            60
        };
        image::Rgba([c, 120, 255 - c, 255])
    })
    .save(dir.path().join("checker.png"))?;
    let path = dir.path().join("face.obj");
    std::fs::write(&path, obj)?;
    Ok((dir, path))
}
