//! Draws the contact sheet of a face with a chosen muscle model, plus a second page of custom
//! named slider vectors (how other expression sets get their own page).
//!
//! ```text
//! cargo run --release -p facebem-tools --bin contact_sheet -- [face.obj] [out.png] [--anatomical|--thesis]
//! ```
//!
//! Writes `out.png` (default `contact_sheet.png`) and `out-mixes.png`.

use std::path::PathBuf;

use face_prep::muscle_model::MuscleModel;
use facebem::report::contact_sheet::{self, Selection, SheetCell, SheetOptions};
use facebem::{Control, PipelineParams, build_face_model};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut files = args
        .iter()
        .filter(|a| !a.starts_with("--"))
        .map(PathBuf::from);
    let face = files.next().unwrap_or_else(|| {
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
            .join("assets/mediapipe_canonical_4loop.obj")
    });
    let out = files
        .next()
        .unwrap_or_else(|| PathBuf::from("contact_sheet.png"));
    let mut params = PipelineParams::default();
    if args.iter().any(|a| a == "--anatomical") {
        params.rig.muscle_model = MuscleModel::Anatomical;
    }
    if args.iter().any(|a| a == "--thesis") {
        params.rig.muscle_model = MuscleModel::Thesis;
    }
    let mesh = face_prep::load_face(&face)?;
    let model = build_face_model(&mesh, &params, &Control::new())?;
    let name = face
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let title = format!(
        "{name}  ({:?} muscles, unit {})",
        params.rig.muscle_model, model.rig.unit
    );

    let cells = contact_sheet::standard_cells(&model, Selection::All);
    let opts = SheetOptions {
        title: title.clone(),
        ..SheetOptions::default()
    };
    contact_sheet::write_png(&out, &contact_sheet::render(&model, &cells, &opts)?)?;
    println!("{}: {} cells", out.display(), cells.len());

    // A page of arbitrary named slider vectors: each muscle at half contraction with its mirror.
    let ids = model.muscle_ids();
    let mixes: Vec<SheetCell> = ids
        .iter()
        .enumerate()
        .filter(|(_, id)| id.ends_with("_l"))
        .map(|(k, id)| {
            let mut sliders = vec![0.0; ids.len()];
            sliders[k] = 0.5 * contact_sheet::FULL_CONTRACTION;
            let mirror = format!("{}_r", id.trim_end_matches("_l"));
            if let Some(j) = model.basis.muscle_index(&mirror) {
                sliders[j] = 0.5 * contact_sheet::FULL_CONTRACTION;
            }
            SheetCell::new(
                id.trim_end_matches("_l"),
                "both sides, half contraction",
                sliders,
            )
        })
        .collect();
    let page = out.with_file_name(format!(
        "{}-mixes.png",
        out.file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
    ));
    let opts = SheetOptions {
        title: format!("{title}: both sides at half contraction"),
        columns: 3,
        ..SheetOptions::default()
    };
    contact_sheet::write_png(&page, &contact_sheet::render(&model, &mixes, &opts)?)?;
    println!("{}: {} cells", page.display(), mixes.len());
    Ok(())
}
