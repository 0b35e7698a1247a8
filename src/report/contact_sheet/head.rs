//! Contact sheets of a whole head (issue 32): the same cells as a face's sheet, drawn on every
//! part of the head — the skin carried from the rigged front face, lower teeth and tongue with
//! the jaw, lids kept off the eyeballs, lashes riding on the lids
//! ([`crate::transfer::head::HeadBasis`]) — plus, on the ARKit and VRM pages, the targets only
//! a head makes (the eyeballs' gaze, `tongueOut`).
//!
//! ```no_run
//! use facebem::report::contact_sheet::{self, Selection, SheetMesh, SheetOptions};
//! # fn sheet(model: &facebem::FaceModel, head: &facebem::transfer::head::HeadBasis)
//! # -> Result<(), Box<dyn std::error::Error>> {
//! let cells = contact_sheet::head::head_cells(model, head, Selection::All);
//! let mesh = SheetMesh { neutral: &head.basis.neutral, triangles: &head.basis.triangles,
//!     ..SheetMesh::of(model) };
//! let image = contact_sheet::render_fields(&mesh, &cells, &SheetOptions::default())?;
//! # Ok(()) }
//! ```

use crate::FaceModel;
use crate::expressions::{NameSet, arkit, vrm};
use crate::transfer::head::HeadBasis;

use super::{FieldCell, Selection};

/// The cells of `selection` ([`super::standard_cells`] of the rigged front face `model`) on the
/// whole head `head`, each control's field summed and kept off the eyeballs
/// ([`HeadBasis::field_of`]); a page of one standard also gets the head's own targets of that
/// standard ([`HeadBasis::named_fields`]), every cell in the standard's order.
pub fn head_cells(model: &FaceModel, head: &HeadBasis, selection: Selection) -> Vec<FieldCell> {
    let mut cells: Vec<FieldCell> = super::standard_cells(model, selection)
        .into_iter()
        .map(|c| FieldCell {
            displacement: head.field_of(&c.sliders),
            label: c.label,
            caption: c.caption,
        })
        .collect();
    if let Selection::Named(set) = selection {
        let names: &[&str] = match set {
            NameSet::Arkit => &arkit::NAMES,
            NameSet::Vrm => &vrm::NAMES,
            NameSet::Facebem => &[],
        };
        cells.extend(
            head.named_fields
                .iter()
                .filter(|(name, _)| names.contains(&name.as_str()))
                .map(|(name, field)| FieldCell {
                    label: name.clone(),
                    caption: if name.contains("ongue") {
                        "the tongue out of the half-open mouth".into()
                    } else {
                        "the eyeballs turned, the lids following".into()
                    },
                    displacement: field.clone(),
                }),
        );
        let order = |label: &str| names.iter().position(|n| *n == label).unwrap_or(usize::MAX);
        cells.sort_by_key(|c| order(&c.label));
    }
    cells
}
