//! Prints the figures a rig's trust is judged by (`facebem::model::distrust`) for each face:
//! the near-singular ratio, crossing shell element pairs, the largest motion of a control other
//! than the jaw's and of a jaw control, and the largest ratio of a muscle band's motion to its
//! shortening — with the control that reaches each, and the causes if the rig is refused.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin trust_report [-- face.obj|rig ...]
//! ```

use std::path::{Path, PathBuf};

use face_prep::Generator;
use facebem::{Control, FaceModel, PipelineParams};

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let args: Vec<String> = std::env::args().skip(1).collect();
    let faces: Vec<PathBuf> = facebem::input::faces_from_args(
        &args,
        &root.join("assets"),
        &facebem::input::BUNDLED_FACES,
    );
    println!(
        "{:<36} {:>7} {:>6} {:>28} {:>24} {:>30}",
        "face",
        "ratio",
        "cross",
        "largest non-jaw mm",
        "largest jaw mm",
        "largest motion/shortening"
    );
    for face in &faces {
        let model = match facebem::input::open(face)? {
            facebem::input::Opened::Model(m) => *m,
            facebem::input::Opened::Face { mesh, .. } => {
                facebem::build_face_model(&mesh, &PipelineParams::default(), &Control::new())?
            }
        };
        let (muscle, jaw, ratio) = extremes(&model);
        println!(
            "{:<36} {:>7.2} {:>6} {:>28} {:>24} {:>30}",
            face.file_name().and_then(|n| n.to_str()).unwrap_or("?"),
            model.report.response_amplification,
            model.report.shell_self_intersections,
            format!("{:.1} ({})", muscle.0, muscle.1),
            format!("{:.1} ({})", jaw.0, jaw.1),
            format!("{:.2} ({})", ratio.0, ratio.1),
        );
        for cause in facebem::model::distrust(&model) {
            println!("    REFUSED: {cause}");
        }
    }
    Ok(())
}

type Extreme = (f64, String);

/// The largest non-jaw motion, the largest jaw motion and the largest motion-to-shortening
/// ratio of `model`'s controls (mm, mm, ratio), each with its control.
fn extremes(model: &FaceModel) -> (Extreme, Extreme, Extreme) {
    let mm = model.rig.mm_per_unit();
    let mut muscle = (0.0, String::new());
    let mut jaw = (0.0, String::new());
    let mut ratio = (0.0, String::new());
    for (k, id) in model.basis.muscle_ids.iter().enumerate() {
        let largest = model.basis.displacements[k]
            .iter()
            .map(|d| d.length())
            .fold(0.0, f64::max)
            * mm;
        let kind = model.rig.muscles[k].kind;
        let is_jaw = kind.is_some_and(|k| matches!(k.generator(), Generator::Jaw(_)));
        let slot = if is_jaw { &mut jaw } else { &mut muscle };
        if largest > slot.0 {
            *slot = (largest, id.clone());
        }
        if let Some(shortening) = kind.and_then(|k| facebem::model::shortening_mm(model, k))
            && shortening > 0.0
            && largest / shortening > ratio.0
        {
            ratio = (largest / shortening, id.clone());
        }
    }
    (muscle, jaw, ratio)
}
