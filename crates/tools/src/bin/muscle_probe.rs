//! Prints, per control of the bundled faces at full contraction (slider −1): the largest
//! displacement and where it is (canonical mm from the mouth centre), the mouth corners' and
//! brows' motion, the contour's motion, flipped triangles, and the mouth width change.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin muscle_probe [-- face.obj ...] [-- --only id,id] [-- --max-triangles N] [-- --target N] [-- --border-spacing F] [-- --normal-weight F] [-- --copy remesh] [-- --offset F] [-- --taper F]
//! ```

use std::path::Path;

use facebem::report::measure::{FaceLandmarks, flipped_triangles};
use facebem::{Control, PipelineParams, build_face_model};
use glam::DVec3;

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let args: Vec<String> = std::env::args().skip(1).collect();
    let only: Vec<String> = args
        .windows(2)
        .find(|w| w[0] == "--only")
        .map(|w| w[1].split(',').map(str::to_owned).collect())
        .unwrap_or_default();
    let mut params = PipelineParams::default();
    if let Some(w) = args.windows(2).find(|w| w[0] == "--max-triangles") {
        params.large_face.max_triangles = w[1].parse()?;
    }
    // Triangle count of the simplified copy (1500 by default).
    if let Some(w) = args.windows(2).find(|w| w[0] == "--target") {
        params.large_face.target_triangles = w[1].parse()?;
    }
    // Spacing of the copy's locked border vertices, in target edge lengths (0.5 by default).
    if let Some(w) = args.windows(2).find(|w| w[0] == "--border-spacing") {
        params.large_face.border_spacing = w[1].parse()?;
    }
    // How the copy is made: collapse (default) or remesh.
    if let Some(w) = args.windows(2).find(|w| w[0] == "--copy") {
        params.large_face.method = facebem::copy::CopyMethod::parse(&w[1])
            .ok_or_else(|| anyhow::anyhow!("--copy takes collapse or remesh"))?;
    }
    // Weight of the vertex normals in the simplifier's error (2 by default).
    if let Some(w) = args.windows(2).find(|w| w[0] == "--normal-weight") {
        params.large_face.normal_weight = w[1].parse()?;
    }
    // The shell's back-face offset and rim thickness, fraction of the face size (both 0.015 by
    // default).
    if let Some(w) = args.windows(2).find(|w| w[0] == "--offset") {
        params.rig.offset = w[1].parse()?;
        params.rig.thickness = params.rig.offset;
    }
    // Distance from the eye and mouth contours over which the back face's offset grows from 0
    // (knife edge) to its full value, fraction of the face size (0.05 by default).
    if let Some(w) = args.windows(2).find(|w| w[0] == "--taper") {
        params.rig.taper = w[1].parse()?;
    }
    let faces = facebem::input::faces_from_args(
        &args,
        &root.join("assets"),
        &[facebem::input::DEFAULT_FACE_NAME],
    );
    for face in &faces {
        let mesh = face_prep::load_face(face)?;
        let t = std::time::Instant::now();
        let model = build_face_model(&mesh, &params, &Control::new())?;
        println!(
            "{}: {} controls, {:.1} s, {} triangles simulated ({:?}), force peak ratio {:.2} ({})",
            face.display(),
            model.basis.muscle_ids.len(),
            t.elapsed().as_secs_f64(),
            model.report.simulated_triangles,
            model.report.simplify_path,
            model.report.force_peak_ratio,
            model.report.force_peak_control
        );
        for w in model.report.warnings() {
            println!("  warning: {w}");
        }
        let lm = FaceLandmarks::of(&model).ok_or_else(|| anyhow::anyhow!("no landmarks"))?;
        let c = |v: u32| lm.canonical_mm(model.mesh.vertices[v as usize] - DVec3::ZERO);
        let mouth_c = (c(lm.mouth_corner_l) + c(lm.mouth_corner_r)) * 0.5;
        let width0 = c(lm.mouth_corner_l).x - c(lm.mouth_corner_r).x;
        let n = model.basis.muscle_ids.len();
        for (k, id) in model.basis.muscle_ids.iter().enumerate() {
            if !only.is_empty() && !only.contains(id) {
                continue;
            }
            let mut s = vec![0.0; n];
            s[k] = -1.0;
            let posed = model.pose(&s)?;
            let d: Vec<DVec3> = posed
                .iter()
                .zip(&model.mesh.vertices)
                .map(|(p, q)| lm.canonical_mm(*p - *q))
                .collect();
            let (imax, dmax) = d
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.length().total_cmp(&b.1.length()))
                .map(|(i, v)| (i, *v))
                .unwrap_or((0, DVec3::ZERO));
            let at = c(imax as u32) - mouth_c;
            let cl = d[lm.mouth_corner_l as usize];
            let cr = d[lm.mouth_corner_r as usize];
            let bl = lm.brow_point_l.sample(&d);
            let br = lm.brow_point_r.sample(&d);
            let width = (c(lm.mouth_corner_l) + cl).x - (c(lm.mouth_corner_r) + cr).x;
            let flips = flipped_triangles(&model.mesh.vertices, &posed, &model.mesh.triangles);
            println!(
                "  {id:40} max {:5.1} mm at ({:5.0},{:5.0}) | corner L ({:5.1},{:5.1},{:5.1}) R ({:5.1},{:5.1},{:5.1}) | brow L ({:4.1},{:4.1}) R ({:4.1},{:4.1}) | width {:+5.1}% | contour {:.2} | flips {}",
                dmax.length(),
                at.x,
                at.y,
                cl.x,
                cl.y,
                cl.z,
                cr.x,
                cr.y,
                cr.z,
                bl.x,
                bl.y,
                br.x,
                br.y,
                100.0 * (width / width0 - 1.0),
                lm.contour_motion_mm(
                    &posed
                        .iter()
                        .zip(&model.mesh.vertices)
                        .map(|(p, q)| *p - *q)
                        .collect::<Vec<_>>()
                ),
                flips.len()
            );
        }
    }
    Ok(())
}
