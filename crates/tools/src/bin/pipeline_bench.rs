//! Release figures of the pipeline, one line per bundled face:
//! precompute time (prep, BEM, transfer) and peak memory, cache size and load time, pose update
//! time for all controls.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin pipeline_bench            # every face in assets/
//! cargo run --release -p facebem-tools --bin pipeline_bench -- FACE    # one face
//! ```
//!
//! Each face runs in its own child process so that its peak memory (VmHWM) is its own.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use facebem::{Control, PipelineParams, build_face_model, cache};

const FACES: [&str; 4] = [
    "mediapipe_canonical_4loop.obj",
    "ict_narrow_face_dec2500_4loop.obj",
    "leeperrysmith_face_open_4loop.obj",
    "ict_narrow_face_4loop.obj",
];

fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|kb| kb.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn bench_one(path: &Path) -> Result<()> {
    let (mesh, obj) = facebem::input::read_face(path)?;
    let t = Instant::now();
    let mut model = build_face_model(&mesh, &PipelineParams::default(), &Control::new())?;
    let precompute = t.elapsed().as_secs_f64();
    model.obj_source = obj;
    let peak = peak_rss_mib();

    let dir = tempfile::tempdir()?;
    let file = dir.path().join("face.rig");
    cache::save(&file, &model)?;
    let size = std::fs::metadata(&file)?.len() as f64 / (1024.0 * 1024.0);
    let loads = 20;
    let t = Instant::now();
    for _ in 0..loads {
        let back = cache::load_for(&file, &mesh, &model.params)?;
        std::hint::black_box(back);
    }
    let load_ms = t.elapsed().as_secs_f64() * 1e3 / f64::from(loads);

    let n = model.basis.muscle_count();
    // Spread over [-0.9, 0.9] whatever the number of controls (a fixed step left [-1, 1]
    // from the 13th control on).
    let step = 1.8 / n.saturating_sub(1).max(1) as f64;
    let sliders: Vec<f64> = (0..n).map(|k| -0.9 + step * k as f64).collect();
    let mut out = Vec::new();
    let poses: u32 = 2000;
    let t = Instant::now();
    for i in 0..poses {
        let mut s = sliders.clone();
        s[i as usize % n] = 0.5;
        model.basis.pose_into(&s, &mut out)?;
        std::hint::black_box(&out);
    }
    let pose_us = t.elapsed().as_secs_f64() * 1e6 / f64::from(poses);
    let r = &model.report;
    println!(
        "{:<36} {:>6} tri {:>5} sim {:>5} elem | precompute {:>6.1} s (prep {:.2}, BEM {:.1}, transfer {:.2}) peak {:>6.0} MiB | cache {:>5.1} MiB load {:>6.1} ms | pose {n} muscles {:>6.1} us",
        path.file_name().and_then(|n| n.to_str()).unwrap_or("?"),
        r.input_triangles,
        r.simulated_triangles,
        r.shell_elements,
        precompute,
        r.prep_seconds,
        r.solve_seconds,
        r.transfer_seconds,
        peak,
        size,
        load_ms,
        pose_us,
    );
    Ok(())
}

fn main() -> Result<()> {
    if let Some(face) = std::env::args().nth(1) {
        return bench_one(Path::new(&face));
    }
    let exe = std::env::current_exe()?;
    let assets = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("assets");
    for face in FACES {
        let status = Command::new(&exe)
            .arg(assets.join(face))
            .status()
            .with_context(|| format!("running the bench for {face}"))?;
        if !status.success() {
            bail!("bench for {face} failed");
        }
    }
    Ok(())
}
