//! Geometry of a sheet: header (title + colour-bar legend), then a grid of cells, each a label
//! strip over one panel per view.

use super::heat;
use super::image::RgbImage;
use super::raster::Arrows;
use super::text::{GLYPH_PX, draw_text, fit, text_width};

/// Space around and between cells, in pixels.
pub const PAD_PX: u32 = 12;
/// Space between the panels of one cell, in pixels.
pub const GAP_PX: u32 = 4;
/// Height of a cell's label strip: a 2× label line and a 1× caption line.
pub const LABEL_PX: u32 = 4 + 2 * GLYPH_PX + 4 + GLYPH_PX + 4;
/// Width of one colour box of the legend.
const LEGEND_BOX_PX: u32 = 44;
/// Height of one colour box of the legend.
const LEGEND_BOX_H_PX: u32 = 16;
/// Text left of the legend's colour bar.
const LEGEND_TEXT: &str = "|displacement|, mm:";
/// Height of the header: title (2×), gap, colour bar, edge labels.
pub const HEADER_PX: u32 = PAD_PX + 2 * GLYPH_PX + 8 + LEGEND_BOX_H_PX + 4 + GLYPH_PX + 4;

/// Text colour.
pub const INK: [u8; 3] = [20, 20, 20];
/// Colour of secondary text (captions, view names).
pub const INK_LIGHT: [u8; 3] = [95, 95, 95];
/// Sheet background (behind the white panels).
pub const PAPER: [u8; 3] = [236, 236, 236];

/// A rectangle in sheet pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    /// Left edge.
    pub x: u32,
    /// Top edge.
    pub y: u32,
    /// Width.
    pub w: u32,
    /// Height.
    pub h: u32,
}

impl Rect {
    /// Whether the pixel (`x`, `y`) lies inside.
    pub fn contains(&self, x: u32, y: u32) -> bool {
        x >= self.x && y >= self.y && x < self.x + self.w && y < self.y + self.h
    }
}

/// Where everything goes on a sheet of `cells` cells.
///
/// ```
/// use facebem::report::contact_sheet::SheetLayout;
/// let l = SheetLayout::new(19, 2, 256, 4);
/// assert_eq!((l.columns, l.rows), (4, 5));
/// let p = l.panel(5, 1); // cell 5 (row 1, column 1), second view
/// assert_eq!(p.w, 256);
/// assert!(p.x + p.w <= l.width && p.y + p.h <= l.height);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SheetLayout {
    /// Number of cells.
    pub cells: usize,
    /// Panels (views) per cell.
    pub views: usize,
    /// Side of a square panel in pixels.
    pub panel_px: u32,
    /// Cells per row.
    pub columns: u32,
    /// Rows of cells.
    pub rows: u32,
    /// Sheet width in pixels.
    pub width: u32,
    /// Sheet height in pixels.
    pub height: u32,
}

impl SheetLayout {
    /// The layout of `cells` cells of `views` square panels of `panel_px`, `columns` per row
    /// (fewer if there are fewer cells).
    pub fn new(cells: usize, views: usize, panel_px: u32, columns: u32) -> SheetLayout {
        let columns = columns.clamp(1, cells.max(1) as u32);
        let rows = (cells as u32).div_ceil(columns).max(1);
        let views_n = views.max(1) as u32;
        let cell_w = views_n * panel_px + (views_n - 1) * GAP_PX;
        let grid_w = PAD_PX + columns * (cell_w + PAD_PX);
        let legend_w = 2 * PAD_PX
            + text_width(LEGEND_TEXT, 1)
            + 8
            + (heat::COLOURS.len() as u32 + 1) * LEGEND_BOX_PX
            + 4 * GLYPH_PX;
        SheetLayout {
            cells,
            views,
            panel_px,
            columns,
            rows,
            width: grid_w.max(legend_w),
            height: HEADER_PX + rows * (LABEL_PX + panel_px + PAD_PX),
        }
    }

    /// Width of one cell (all its panels).
    pub fn cell_width(&self) -> u32 {
        let v = self.views.max(1) as u32;
        v * self.panel_px + (v - 1) * GAP_PX
    }

    /// The whole cell `i` (label strip and panels).
    pub fn cell(&self, i: usize) -> Rect {
        let (col, row) = (i as u32 % self.columns, i as u32 / self.columns);
        Rect {
            x: PAD_PX + col * (self.cell_width() + PAD_PX),
            y: HEADER_PX + row * (LABEL_PX + self.panel_px + PAD_PX),
            w: self.cell_width(),
            h: LABEL_PX + self.panel_px,
        }
    }

    /// Panel of view `v` of cell `i`.
    pub fn panel(&self, i: usize, v: usize) -> Rect {
        let c = self.cell(i);
        Rect {
            x: c.x + v as u32 * (self.panel_px + GAP_PX),
            y: c.y + LABEL_PX,
            w: self.panel_px,
            h: self.panel_px,
        }
    }

    /// Draws the title and the colour-bar legend of the fixed heat scale.
    /// With `arrows`, a note on the arrows' exaggeration follows the colour bar.
    pub fn draw_header(&self, img: &mut RgbImage, title: &str, arrows: Option<&Arrows>) {
        let title = fit(title, 2, self.width.saturating_sub(2 * PAD_PX));
        draw_text(img, PAD_PX, PAD_PX, &title, 2, INK);
        let bar_y = PAD_PX + 2 * GLYPH_PX + 8;
        draw_text(
            img,
            PAD_PX,
            bar_y + (LEGEND_BOX_H_PX - GLYPH_PX) / 2,
            LEGEND_TEXT,
            1,
            INK,
        );
        let x0 = PAD_PX + text_width(LEGEND_TEXT, 1) + 8;
        let boxes = std::iter::once(heat::SKIN).chain(heat::COLOURS);
        for (i, c) in boxes.enumerate() {
            img.fill_rect(
                x0 + i as u32 * LEGEND_BOX_PX,
                bar_y,
                LEGEND_BOX_PX,
                LEGEND_BOX_H_PX,
                c,
            );
        }
        // Each bin's lower edge under the left end of its box; "mm" after the last one.
        let label_y = bar_y + LEGEND_BOX_H_PX + 4;
        draw_text(img, x0 + 2, label_y, "0", 1, INK);
        for i in 0..heat::EDGES_MM.len() {
            let x = x0 + (i as u32 + 1) * LEGEND_BOX_PX;
            img.fill_rect(x, bar_y + LEGEND_BOX_H_PX, 1, 3, INK);
            draw_text(img, x + 2, label_y, &heat::edge_label(i), 1, INK);
        }
        if let Some(a) = arrows {
            let x = x0 + (heat::COLOURS.len() as u32 + 1) * LEGEND_BOX_PX + 3 * GLYPH_PX;
            let note = format!(
                "arrows: direction of motion, length x{} (>= {} mm)",
                a.exaggeration, a.min_mm
            );
            let note = fit(&note, 1, self.width.saturating_sub(x + PAD_PX));
            draw_text(
                img,
                x,
                bar_y + (LEGEND_BOX_H_PX - GLYPH_PX) / 2,
                &note,
                1,
                INK,
            );
        }
    }

    /// Draws cell `i`'s label (2×) and caption (1×), shortened to the cell width.
    pub fn draw_label(&self, img: &mut RgbImage, i: usize, label: &str, caption: &str) {
        let c = self.cell(i);
        let label = fit(label, 2, c.w);
        draw_text(img, c.x, c.y + 4, &label, 2, INK);
        let caption = fit(caption, 1, c.w);
        draw_text(img, c.x, c.y + 4 + 2 * GLYPH_PX + 4, &caption, 1, INK_LIGHT);
    }
}
