//! `sheet`: the contact sheet PNG.

use anyhow::Result;
use facebem::expressions::{self, NameSet, NameSets};

use crate::args::SheetArgs;
use crate::rig::{model_from, pipeline_params};

pub(crate) fn sheet(args: &SheetArgs) -> Result<()> {
    use facebem::report::contact_sheet::{self, Selection, SheetOptions};
    let params = pipeline_params(&args.solver)?;
    facebem::check_output(
        &args.output,
        &[&args.rig],
        &["png"],
        "a contact sheet (PNG)",
    )?;
    let model = model_from(&args.rig, &params, args.solver.no_cache)?;
    let selection = match args.only.as_deref() {
        Some("muscles") => Selection::Muscles,
        Some("presets") => Selection::Presets,
        Some("arkit") => Selection::Named(NameSet::Arkit),
        Some("vrm") => Selection::Named(NameSet::Vrm),
        _ => Selection::All,
    };
    let cells = contact_sheet::standard_cells(&model, selection);
    if let Selection::Named(set) = selection {
        let (_, left_out) = expressions::for_rig(
            NameSets {
                facebem: false,
                arkit: set == NameSet::Arkit,
                vrm: set == NameSet::Vrm,
            },
            model.muscle_ids(),
        );
        if !left_out.is_empty() {
            let names: Vec<&str> = left_out.iter().map(|(e, _)| e.name).collect();
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
            cells.len(),
            set.standard_size()
        ),
        _ => String::new(),
    };
    let opts = SheetOptions {
        title: format!("{name}  (unit: {unit}{detected}){page}"),
        ..SheetOptions::default()
    };
    let start = std::time::Instant::now();
    let image = contact_sheet::render(&model, &cells, &opts)?;
    contact_sheet::write_png(&args.output, &image)?;
    outln!(
        "{}: {} cells, {} x {} px, drawn and written in {:.2} s",
        args.output.display(),
        cells.len(),
        image.width,
        image.height,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
