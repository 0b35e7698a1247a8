//! Contact sheets: a face model drawn in many poses at once, from the front and at 3/4 view,
//! coloured by how far each point of the skin moved, in one PNG a person can judge.
//!
//! A sheet is a list of named slider vectors ([`SheetCell`]), so any set of poses can be put on
//! one page: the standard sheet ([`standard_cells`]) is neutral, each muscle at full contraction
//! and each preset. Every cell is drawn with the same cameras (fitted to the neutral face), the
//! same light and the same fixed heat scale in millimetres ([`heat`]), so cells and sheets of
//! different faces compare directly. The CPU software rasteriser ([`raster`]) needs no GPU and
//! gives byte-identical images on every run.
//!
//! ```no_run
//! use facebem::report::contact_sheet::{self, Selection, SheetOptions};
//! let (model, _) = facebem::input::default_model(None, &facebem::Control::new())?;
//! let cells = contact_sheet::standard_cells(&model, Selection::All);
//! let opts = SheetOptions { title: "default face".into(), ..SheetOptions::default() };
//! let image = contact_sheet::render(&model, &cells, &opts)?;
//! contact_sheet::write_png("sheet.png".as_ref(), &image)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A page per named expression set ([`Selection::Named`]): the ARKit blendshapes or the VRM 1.0
//! presets the rig can make ([`crate::expressions`]), each captioned with its FACS action
//! units.
//!
//! Command line: `facebem sheet face.rig -o sheet.png [--only muscles|presets|arkit|vrm]`.

mod camera;
pub mod head;
pub mod heat;
mod image;
mod layout;
pub mod raster;
mod text;

use std::path::Path;

use glam::DVec3;
use rayon::prelude::*;

use crate::expressions::{self, NameSet, NameSets};
use crate::{FaceModel, PoseError, WriteError, expressions::presets};

pub use camera::{Camera, View};
pub use image::RgbImage;
pub use layout::{Rect, SheetLayout};
pub use raster::{Arrows, Lighting};

/// Slider value of a muscle at full contraction (today's convention, `docs/design/controls.md`, "Muscles" and
/// [`crate::expressions::presets`]: negative contracts). The one place the sheet takes it from.
pub const FULL_CONTRACTION: f64 = -1.0;

/// One cell of a sheet: a pose and its name.
#[derive(Clone, Debug, PartialEq)]
pub struct SheetCell {
    /// Name drawn large above the cell (e.g. a muscle id or preset name).
    pub label: String,
    /// Small second line (e.g. the FACS action units); the cell's largest displacement in mm
    /// is drawn in front of it.
    pub caption: String,
    /// One slider value per muscle of the model ([`FaceModel::muscle_ids`]).
    pub sliders: Vec<f64>,
}

impl SheetCell {
    /// A cell from a label, a caption and a slider vector.
    pub fn new(label: impl Into<String>, caption: impl Into<String>, sliders: Vec<f64>) -> Self {
        SheetCell {
            label: label.into(),
            caption: caption.into(),
            sliders,
        }
    }
}

/// Which poses [`standard_cells`] puts on the sheet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Selection {
    /// Neutral, each muscle at full contraction, each other preset.
    #[default]
    All,
    /// Neutral (for reference) and each muscle at full contraction.
    Muscles,
    /// Every preset, neutral first.
    Presets,
    /// The named expressions of one standard (ARKit or VRM 1.0) the rig can make, in the
    /// standard's order ([`named_cells`]).
    Named(NameSet),
}

/// How a sheet is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct SheetOptions {
    /// Title line at the top (e.g. the face's file name).
    pub title: String,
    /// The views drawn for every cell, left to right (default: front, 3/4 left).
    pub views: Vec<View>,
    /// Side of one square view panel in pixels (16 to 2048).
    pub panel_px: u32,
    /// Cells per row.
    pub columns: u32,
    /// Supersampling factor per axis for anti-aliasing (1 to 4).
    pub supersample: u32,
    /// Free border around the neutral face in each panel, as a fraction of the panel (room for
    /// the face to move).
    pub margin: f64,
    /// Millimetres per model unit for the heat scale; `None`: [`mm_per_unit`] of the model.
    pub mm_per_unit: Option<f64>,
    /// Light and background.
    pub lighting: Lighting,
    /// Motion arrows over the heat map (which way the skin moved), `None` for none.
    pub arrows: Option<Arrows>,
}

impl Default for SheetOptions {
    fn default() -> Self {
        SheetOptions {
            title: String::new(),
            views: vec![View::front(), View::three_quarter()],
            panel_px: 256,
            columns: 4,
            supersample: 2,
            margin: 0.06,
            mm_per_unit: None,
            lighting: Lighting::default(),
            arrows: Some(Arrows::default()),
        }
    }
}

/// Errors drawing or writing a sheet.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SheetError {
    /// A cell's slider vector does not fit the model.
    #[error("sheet cell {label:?}: {source}")]
    Pose {
        /// The cell's label.
        label: String,
        /// What is wrong with its sliders.
        #[source]
        source: PoseError,
    },
    /// The options cannot be drawn (e.g. no view, panel size out of range).
    #[error("sheet options: {0}")]
    Options(String),
    /// PNG encoding failed.
    #[error("encoding the sheet as PNG: {0}")]
    Png(#[from] png::EncodingError),
    /// Writing the file failed.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Millimetres per model unit used for a model's heat map: the rig's length unit
/// ([`face_prep::FaceRig::unit`], given with `--units` or estimated from the eye distance).
pub fn mm_per_unit(model: &FaceModel) -> f64 {
    model.rig.unit.mm()
}

/// Neutral: every slider 0.
pub fn neutral_cell(model: &FaceModel) -> SheetCell {
    SheetCell::new(
        "neutral",
        "all sliders 0",
        vec![0.0; model.muscle_ids().len()],
    )
}

/// One cell per muscle of the model, each at [`FULL_CONTRACTION`] with every other slider 0.
pub fn muscle_cells(model: &FaceModel) -> Vec<SheetCell> {
    let n = model.muscle_ids().len();
    model
        .muscle_ids()
        .iter()
        .enumerate()
        .map(|(k, id)| {
            let mut sliders = vec![0.0; n];
            sliders[k] = FULL_CONTRACTION;
            SheetCell::new(
                id.clone(),
                format!("slider {FULL_CONTRACTION}: full contraction"),
                sliders,
            )
        })
        .collect()
}

/// One cell per preset of [`crate::expressions::presets::ALL`] (neutral first), captioned with its FACS
/// action units.
pub fn preset_cells(model: &FaceModel) -> Vec<SheetCell> {
    presets::ALL
        .iter()
        .map(|p| SheetCell::new(p.name, p.action_units, p.sliders_for(model.muscle_ids())))
        .collect()
}

/// One cell per named expression of `set` the rig can make ([`expressions::for_rig`]),
/// captioned with its FACS action units; one made from only some of its controls says
/// "partial"; a corrective is drawn over its base ([`expressions::corrective_base`]: mouthClose
/// over jawOpen). Names the rig cannot make at all are not drawn.
pub fn named_cells(model: &FaceModel, set: NameSet) -> Vec<SheetCell> {
    let sets = NameSets {
        facebem: false,
        arkit: set == NameSet::Arkit,
        vrm: set == NameSet::Vrm,
    };
    let (made, _) = expressions::for_rig(sets, model.muscle_ids());
    made.into_iter()
        .map(|m| {
            let e = m.expression;
            let mut caption = if m.resolved.missing.is_empty() {
                e.action_units().to_string()
            } else {
                format!("partial: {}", e.action_units())
            };
            let mut sliders = m.resolved.sliders;
            // A corrective is drawn on top of the expression it corrects.
            if let Some(base_name) = expressions::corrective_base(e.name)
                && let Ok((base, _)) = expressions::sliders_for_name(base_name, model.muscle_ids())
            {
                sliders.iter_mut().zip(base).for_each(|(s, b)| *s += b);
                caption = format!("{caption}, over {base_name}");
            }
            SheetCell::new(e.name, caption, sliders)
        })
        .collect()
}

/// The cells of the standard sheet: see [`Selection`].
pub fn standard_cells(model: &FaceModel, selection: Selection) -> Vec<SheetCell> {
    match selection {
        Selection::Named(set) => named_cells(model, set),
        Selection::Presets => preset_cells(model),
        Selection::Muscles => {
            let mut cells = vec![neutral_cell(model)];
            cells.extend(muscle_cells(model));
            cells
        }
        Selection::All => {
            let mut cells = vec![neutral_cell(model)];
            cells.extend(muscle_cells(model));
            cells.extend(
                preset_cells(model)
                    .into_iter()
                    .filter(|c| c.sliders.iter().any(|&s| s != 0.0)),
            );
            cells
        }
    }
}

/// The layout [`render`] uses for `cells` cells with `opts`.
pub fn layout(cells: usize, opts: &SheetOptions) -> SheetLayout {
    SheetLayout::new(cells, opts.views.len(), opts.panel_px, opts.columns)
}

/// The camera of each view in `opts` for `model` (panel pixels; canonical frame), as
/// [`render`] uses them: fitted to the neutral face.
pub fn cameras(model: &FaceModel, opts: &SheetOptions) -> Vec<Camera> {
    let t = model.rig.canonical_from_input;
    let neutral: Vec<DVec3> = model
        .basis
        .neutral
        .iter()
        .map(|&p| t.transform_point3(p))
        .collect();
    fitted_cameras(&neutral, opts)
}

/// The camera of each view in `opts` fitted to `neutral` (canonical frame).
fn fitted_cameras(neutral: &[DVec3], opts: &SheetOptions) -> Vec<Camera> {
    opts.views
        .iter()
        .map(|v| Camera::fit(v, neutral, opts.panel_px, opts.panel_px, opts.margin))
        .collect()
}

fn check_options(opts: &SheetOptions, mm: f64) -> Result<(), SheetError> {
    let bad = |m: String| Err(SheetError::Options(m));
    if opts.views.is_empty() {
        return bad("no views".into());
    }
    if !(16..=2048).contains(&opts.panel_px) {
        return bad(format!(
            "panel size {} px is outside 16..2048",
            opts.panel_px
        ));
    }
    if !(1..=4).contains(&opts.supersample) {
        return bad(format!(
            "supersampling {} is outside 1..4",
            opts.supersample
        ));
    }
    if !(0.0..0.45).contains(&opts.margin) {
        return bad(format!("margin {} is outside [0, 0.45)", opts.margin));
    }
    if !(mm.is_finite() && mm > 0.0) {
        return bad(format!("{mm} mm per unit is not a positive length"));
    }
    Ok(())
}

/// Draws `cells` of `model` into one sheet image (see the module docs).
pub fn render(
    model: &FaceModel,
    cells: &[SheetCell],
    opts: &SheetOptions,
) -> Result<RgbImage, SheetError> {
    let basis = &model.basis;
    for cell in cells {
        basis
            .check_sliders(&cell.sliders)
            .map_err(|source| SheetError::Pose {
                label: cell.label.clone(),
                source,
            })?;
    }
    let posed: Vec<FieldCell> = cells
        .par_iter()
        .map(|cell| {
            let mut posed = Vec::new();
            // Checked above.
            let _ = basis.pose_into(&cell.sliders, &mut posed);
            FieldCell {
                label: cell.label.clone(),
                caption: cell.caption.clone(),
                displacement: posed
                    .iter()
                    .zip(&basis.neutral)
                    .map(|(p, q)| *p - *q)
                    .collect(),
            }
        })
        .collect();
    render_fields(&SheetMesh::of(model), &posed, opts)
}

/// One cell of a sheet given as a displacement field, one per vertex of the [`SheetMesh`] (a
/// whole head's targets, [`head::head_cells`]).
#[derive(Clone, Debug, PartialEq)]
pub struct FieldCell {
    /// Name drawn large above the cell.
    pub label: String,
    /// Small second line; the cell's largest displacement in mm is drawn in front of it.
    pub caption: String,
    /// Displacement of every vertex, in the mesh's input frame and unit.
    pub displacement: Vec<DVec3>,
}

/// What a sheet is drawn on: a neutral mesh, its canonical frame and its unit.
#[derive(Clone, Copy, Debug)]
pub struct SheetMesh<'a> {
    /// Neutral positions (input frame).
    pub neutral: &'a [DVec3],
    /// Triangles indexing [`SheetMesh::neutral`].
    pub triangles: &'a [[u32; 3]],
    /// The face's canonical frame (upright, facing +z) from the input frame.
    pub canonical_from_input: glam::DAffine3,
    /// Millimetres per unit for the heat scale (when the options give none).
    pub mm_per_unit: f64,
}

impl<'a> SheetMesh<'a> {
    /// The model's own mesh.
    pub fn of(model: &'a FaceModel) -> SheetMesh<'a> {
        SheetMesh {
            neutral: &model.basis.neutral,
            triangles: &model.basis.triangles,
            canonical_from_input: model.rig.canonical_from_input,
            mm_per_unit: mm_per_unit(model),
        }
    }
}

/// Draws displacement fields of `mesh` into one sheet image, as [`render`] draws poses; a
/// cell whose field is not one vector per vertex is an error.
pub fn render_fields(
    mesh: &SheetMesh,
    cells: &[FieldCell],
    opts: &SheetOptions,
) -> Result<RgbImage, SheetError> {
    let mm = opts.mm_per_unit.unwrap_or(mesh.mm_per_unit);
    check_options(opts, mm)?;
    if let Some(c) = cells
        .iter()
        .find(|c| c.displacement.len() != mesh.neutral.len())
    {
        return Err(SheetError::Options(format!(
            "cell {:?} has {} displacements for {} vertices",
            c.label,
            c.displacement.len(),
            mesh.neutral.len()
        )));
    }
    let layout = layout(cells.len(), opts);
    let to_canonical = |points: &[DVec3]| -> Vec<DVec3> {
        let t = mesh.canonical_from_input;
        points.iter().map(|&p| t.transform_point3(p)).collect()
    };
    let cams = fitted_cameras(&to_canonical(mesh.neutral), opts);

    // Each cell's panels, rendered in parallel; each panel on its own, so the result does not
    // depend on the thread schedule.
    let drawn: Vec<(Vec<RgbImage>, f64)> = cells
        .par_iter()
        .map(|cell| {
            let posed: Vec<DVec3> = mesh
                .neutral
                .iter()
                .zip(&cell.displacement)
                .map(|(q, d)| *q + *d)
                .collect();
            let disp_mm: Vec<f64> = cell.displacement.iter().map(|d| d.length() * mm).collect();
            let max_mm = disp_mm.iter().copied().fold(0.0, f64::max);
            let positions = to_canonical(&posed);
            let rot = mesh.canonical_from_input.matrix3;
            let displacement: Vec<DVec3> = cell.displacement.iter().map(|d| rot * *d).collect();
            let mesh = raster::PanelMesh {
                positions: &positions,
                triangles: mesh.triangles,
                displacement_mm: &disp_mm,
                displacement: &displacement,
            };
            let panels = cams
                .par_iter()
                .map(|cam| {
                    raster::render_panel(
                        &mesh,
                        cam,
                        opts.panel_px,
                        opts.panel_px,
                        opts.supersample,
                        &opts.lighting,
                        opts.arrows.as_ref(),
                    )
                })
                .collect();
            (panels, max_mm)
        })
        .collect();

    let mut img = RgbImage::new(layout.width, layout.height, layout::PAPER);
    layout.draw_header(&mut img, &opts.title, opts.arrows.as_ref());
    for (i, (cell, (panels, max_mm))) in cells.iter().zip(&drawn).enumerate() {
        let caption = if cell.caption.is_empty() {
            format!("max {max_mm:.1} mm")
        } else {
            format!("max {max_mm:.1} mm | {}", cell.caption)
        };
        layout.draw_label(&mut img, i, &cell.label, &caption);
        for (v, (panel, view)) in panels.iter().zip(&opts.views).enumerate() {
            let r = layout.panel(i, v);
            img.blit(panel, r.x, r.y);
            text::draw_text(&mut img, r.x + 4, r.y + 4, &view.name, 1, layout::INK_LIGHT);
        }
    }
    Ok(img)
}

/// Writes `image` as a PNG at `path`, atomically ([`crate::write_atomic`]).
pub fn write_png(path: &Path, image: &RgbImage) -> Result<(), SheetError> {
    let bytes = image.to_png()?;
    crate::write_atomic(path, &bytes)?;
    Ok(())
}
