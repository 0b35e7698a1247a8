//! `sheet`: the contact sheet PNG, of a face or of a whole head.

use anyhow::Result;
use facebem::expressions::{self, NameSet, NameSets};
use facebem::report::contact_sheet::{
    self, RgbImage, Selection, SheetError, SheetMesh, SheetOptions,
};

use crate::args::SheetArgs;
use crate::rig::{model_from_opened, pipeline_params};

pub(crate) fn sheet(args: &SheetArgs) -> Result<()> {
    let params = pipeline_params(&args.solver)?;
    facebem::check_output(
        &args.output,
        &[&args.rig],
        &["png"],
        "a contact sheet (PNG)",
    )?;
    let selection = match args.only.as_deref() {
        Some("muscles") => Selection::Muscles,
        Some("presets") => Selection::Presets,
        Some("arkit") => Selection::Named(NameSet::Arkit),
        Some("vrm") => Selection::Named(NameSet::Vrm),
        _ => Selection::All,
    };
    let opened = match crate::open_face(&args.rig) {
        Ok(opened) => opened,
        // A whole head: its front face rigged, the sheet drawn on every part.
        Err(e @ facebem::input::OpenError::Face { .. }) => {
            return match facebem::input::heads::WholeFile::examine(&args.rig) {
                Some(Ok(whole)) => {
                    let (model, head) =
                        crate::head::rig_head(&args.rig, &whole, &params, &args.solver, true)?;
                    let cells = contact_sheet::head::head_cells(&model, &head, selection);
                    let mesh = SheetMesh {
                        neutral: &head.basis.neutral,
                        triangles: &head.basis.triangles,
                        ..SheetMesh::of(&model)
                    };
                    let labels: Vec<&str> = cells.iter().map(|c| c.label.as_str()).collect();
                    draw(args, &model, selection, &labels, |opts| {
                        contact_sheet::render_fields(&mesh, &cells, opts)
                    })
                }
                Some(Err(refusal)) => Err(anyhow::anyhow!("{refusal}")),
                None => Err(e.into()),
            };
        }
        Err(e) => return Err(e.into()),
    };
    let (model, _) = model_from_opened(&args.rig, opened, &params, args.solver.no_cache)?;
    let cells = contact_sheet::standard_cells(&model, selection);
    let labels: Vec<&str> = cells.iter().map(|c| c.label.as_str()).collect();
    draw(args, &model, selection, &labels, |opts| {
        contact_sheet::render(&model, &cells, opts)
    })
}

/// Draws the cells `labels` (of the rig `model`'s face, or of a whole head carried from it)
/// with `render` and writes the PNG, saying which names of the selected standard the rig
/// leaves out.
fn draw(
    args: &SheetArgs,
    model: &facebem::FaceModel,
    selection: Selection,
    labels: &[&str],
    render: impl FnOnce(&SheetOptions) -> Result<RgbImage, SheetError>,
) -> Result<()> {
    if let Selection::Named(set) = selection {
        let (_, left_out) = expressions::for_rig(
            NameSets {
                facebem: false,
                arkit: set == NameSet::Arkit,
                vrm: set == NameSet::Vrm,
            },
            model.muscle_ids(),
        );
        let names: Vec<&str> = left_out
            .iter()
            .map(|(e, _)| e.name)
            .filter(|n| !labels.contains(n))
            .collect();
        if !names.is_empty() {
            outln!(
                "{} names left out (their controls are not in this rig): {}",
                set.display_name(),
                names.join(" ")
            );
        }
    }
    let name = args.rig.file_name().map_or_else(
        || args.rig.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let unit = &model.rig.unit;
    let detected = if model.rig.unit_detected {
        ", detected"
    } else {
        ""
    };
    let page = match selection {
        Selection::Named(set) => format!(
            "  {} names: {} of {}",
            set.display_name(),
            labels.len(),
            set.standard_size()
        ),
        _ => String::new(),
    };
    let opts = SheetOptions {
        title: format!("{name}  (unit: {unit}{detected}){page}"),
        ..SheetOptions::default()
    };
    let start = std::time::Instant::now();
    let image = render(&opts)?;
    contact_sheet::write_png(&args.output, &image)?;
    outln!(
        "{}: {} cells, {} x {} px, drawn and written in {:.2} s",
        args.output.display(),
        labels.len(),
        image.width,
        image.height,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
