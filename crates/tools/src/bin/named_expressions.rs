//! Measures every ARKit and VRM name a face's rig can make at full weight: largest motion (mm),
//! motion of the outer contour (mm), flipped front triangles, and which controls it lacks.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin named_expressions [-- face.obj ...]
//! ```

use std::path::{Path, PathBuf};

use facebem::expressions::{self, NameSets};
use facebem::report::measure::{FaceLandmarks, flipped_triangles};
use facebem::{Control, PipelineParams, build_face_model};
use glam::DVec3;

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let mut faces: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    if faces.is_empty() {
        faces = facebem::export::attribution::BUNDLED
            .iter()
            .map(|k| root.join("assets").join(k.file))
            .collect();
    }
    for face in &faces {
        let mesh = face_prep::load_face(face)?;
        let model = build_face_model(&mesh, &PipelineParams::default(), &Control::new())?;
        let lm = FaceLandmarks::of(&model).ok_or_else(|| anyhow::anyhow!("no landmarks"))?;
        let (made, left_out) = expressions::for_rig(NameSets::ALL, model.muscle_ids());
        let n_tris = model.mesh.triangles.len();
        println!(
            "\n== {} ({} controls, {} front triangles): {} names made, {} left out",
            face.file_name().and_then(|n| n.to_str()).unwrap_or("?"),
            model.muscle_ids().len(),
            n_tris,
            made.len(),
            left_out.len()
        );
        println!(
            "{:<20} {:>8} {:>10} {:>7} {:>7}  missing controls",
            "name", "max mm", "contour mm", "flips", "flip %"
        );
        for m in &made {
            let posed = model.pose(&m.resolved.sliders)?;
            let field: Vec<DVec3> = posed
                .iter()
                .zip(&model.mesh.vertices)
                .map(|(p, q)| *p - *q)
                .collect();
            let max_mm = field.iter().map(|d| d.length()).fold(0.0, f64::max) * lm.mm_per_unit;
            let flips =
                flipped_triangles(&model.mesh.vertices, &posed, &model.mesh.triangles).len();
            println!(
                "{:<20} {:>8.2} {:>10.2} {:>7} {:>7.2}  {}",
                m.expression.name,
                max_mm,
                lm.contour_motion_mm(&field),
                flips,
                100.0 * flips as f64 / n_tris as f64,
                m.resolved.missing.join(" ")
            );
        }
        let names: Vec<&str> = left_out.iter().map(|(e, _)| e.name).collect();
        println!("left out: {}", names.join(" "));
    }
    Ok(())
}
