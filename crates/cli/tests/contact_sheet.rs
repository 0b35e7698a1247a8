//! The contact sheet of the bundled default face (MediaPipe): grid, coverage, heat where the
//! muscles are, none at neutral, orientation (not upside down, not mirrored), determinism, PNG
//! round trip.

#[path = "../../../tests/support/mod.rs"]
mod support;

use std::sync::OnceLock;

use facebem::report::contact_sheet::{
    self, RgbImage, Selection, SheetCell, SheetError, SheetLayout, SheetOptions, heat,
};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

static MODEL: OnceLock<FaceModel> = OnceLock::new();
static SHEET: OnceLock<(Vec<SheetCell>, RgbImage)> = OnceLock::new();

fn model() -> &'static FaceModel {
    MODEL.get_or_init(|| {
        let path = support::asset(support::FACES[0]);
        let (mesh, _) = facebem::input::read_face(&path).expect("bundled face loads");
        build_face_model(&mesh, &PipelineParams::default(), &Control::new())
            .expect("default face rigs")
    })
}

/// The standard sheet of the default face with default options.
fn sheet() -> &'static (Vec<SheetCell>, RgbImage) {
    SHEET.get_or_init(|| {
        let cells = contact_sheet::standard_cells(model(), Selection::All);
        let img = contact_sheet::render(model(), &cells, &SheetOptions::default())
            .expect("sheet renders");
        (cells, img)
    })
}

fn layout() -> SheetLayout {
    contact_sheet::layout(sheet().0.len(), &SheetOptions::default())
}

fn cell_index(label: &str) -> usize {
    sheet()
        .0
        .iter()
        .position(|c| c.label == label)
        .unwrap_or_else(|| panic!("no cell {label}"))
}

/// Pixels of a panel, with panel-local coordinates, leaving out the view caption's rows.
fn panel_pixels(cell: usize, view: usize) -> Vec<(u32, u32, [u8; 3])> {
    let r = layout().panel(cell, view);
    let img = &sheet().1;
    let mut out = Vec::new();
    for y in 14..r.h {
        for x in 0..r.w {
            out.push((x, y, img.get(r.x + x, r.y + y)));
        }
    }
    out
}

/// Canonical positions of the rig's mouth corners (extreme-x vertices of the mouth loop): the
/// face's left (+x) first.
fn mouth_corners(m: &FaceModel) -> (DVec3, DVec3) {
    let mouth: Vec<DVec3> = m
        .rig
        .loops
        .mouth
        .iter()
        .map(|&v| m.rig.shell.vertices[v as usize])
        .collect();
    let left = mouth.iter().copied().max_by(|a, b| a.x.total_cmp(&b.x));
    let right = mouth.iter().copied().min_by(|a, b| a.x.total_cmp(&b.x));
    (left.unwrap(), right.unwrap())
}

fn loop_centre(m: &FaceModel, lp: &[u32]) -> DVec3 {
    lp.iter()
        .map(|&v| m.rig.shell.vertices[v as usize])
        .sum::<DVec3>()
        / lp.len() as f64
}

/// Heat weight of the front-view pixels within `radius_px` of `centre_px`: the sum over
/// pixels of (bin + 1), grey counting 0.
fn heat_near(cell: usize, centre_px: (f64, f64), radius_px: f64) -> usize {
    panel_pixels(cell, 0)
        .into_iter()
        .filter(|&(x, y, _)| {
            let (dx, dy) = (
                f64::from(x) + 0.5 - centre_px.0,
                f64::from(y) + 0.5 - centre_px.1,
            );
            dx * dx + dy * dy <= radius_px * radius_px
        })
        .filter_map(|(_, _, c)| heat::classify(c).map(|b| b + 1))
        .sum()
}

/// Heat-weighted centroid (panel pixels) of a panel's coloured pixels, and their count.
fn heat_centroid(cell: usize, view: usize) -> ((f64, f64), usize) {
    let (mut sx, mut sy, mut sw, mut n) = (0.0, 0.0, 0.0, 0);
    for (x, y, c) in panel_pixels(cell, view) {
        if let Some(b) = heat::classify(c) {
            let w = (b + 1) as f64;
            sx += w * f64::from(x);
            sy += w * f64::from(y);
            sw += w;
            n += 1;
        }
    }
    ((sx / sw.max(1e-12), sy / sw.max(1e-12)), n)
}

#[test]
fn default_sheet_has_one_cell_per_pose_in_a_four_column_grid() {
    let (cells, img) = sheet();
    let m = model();
    // neutral + each muscle + each preset other than neutral.
    assert_eq!(
        cells.len(),
        1 + m.muscle_ids().len() + facebem::expressions::presets::ALL.len() - 1
    );
    // Every standard control of the table is on the default face.
    assert_eq!(m.muscle_ids().len(), face_prep::MuscleKind::ALL.len());
    assert_eq!(cells[0].label, "neutral");
    let l = layout();
    assert_eq!(
        (l.columns, l.rows, l.views),
        (4, cells.len().div_ceil(4) as u32, 2)
    );
    assert_eq!((img.width, img.height), (l.width, l.height));
    // Cells do not overlap and lie inside the image.
    for i in 0..cells.len() {
        let r = l.cell(i);
        assert!(
            r.x + r.w <= img.width && r.y + r.h <= img.height,
            "cell {i}: {r:?}"
        );
        for j in 0..i {
            let q = l.cell(j);
            let apart =
                r.x >= q.x + q.w || q.x >= r.x + r.w || r.y >= q.y + q.h || q.y >= r.y + r.h;
            assert!(apart, "cells {i} and {j} overlap");
        }
    }
}

/// The face fills a plausible part of every panel: measured 59 % (front) and 52–53 % (3/4) on
/// the default face; an empty, tiny or overflowing face falls outside 30–85 %.
#[test]
fn face_covers_a_plausible_fraction_of_every_panel() {
    let background = SheetOptions::default().lighting.background;
    let mut range = [(1.0f64, 0.0f64); 2];
    for cell in 0..sheet().0.len() {
        for (view, r) in range.iter_mut().enumerate() {
            let px = panel_pixels(cell, view);
            let face = px.iter().filter(|p| p.2 != background).count();
            let frac = face as f64 / px.len() as f64;
            *r = (r.0.min(frac), r.1.max(frac));
            assert!(
                (0.30..0.85).contains(&frac),
                "cell {} view {view}: face covers {:.1} %",
                sheet().0[cell].label,
                100.0 * frac
            );
        }
    }
    eprintln!("face coverage (front, 3/4): {range:.3?}");
}

#[test]
fn neutral_cell_has_no_heat_and_every_muscle_cell_has_some() {
    for view in 0..2 {
        let hot = panel_pixels(0, view)
            .into_iter()
            .filter(|p| heat::classify(p.2).is_some())
            .count();
        assert_eq!(hot, 0, "neutral view {view}: {hot} heat-coloured pixels");
    }
    for id in model().muscle_ids() {
        let (_, n) = heat_centroid(cell_index(id), 0);
        assert!(n > 50, "{id}: only {n} heat-coloured pixels");
    }
}

/// The face is upright and seen as a person is seen: the eyes above the mouth, the face's left
/// eye on the image's right; frontalis heat lies above the eyes' line.
#[test]
fn faces_are_upright_and_not_mirrored() {
    let m = model();
    let cam = contact_sheet::cameras(m, &SheetOptions::default())[0];
    let (el, er, mouth) = (
        cam.project(loop_centre(m, &m.rig.loops.eye_l)),
        cam.project(loop_centre(m, &m.rig.loops.eye_r)),
        cam.project(loop_centre(m, &m.rig.loops.mouth)),
    );
    assert!(
        el.1 < mouth.1 && er.1 < mouth.1,
        "eyes {el:?} {er:?} mouth {mouth:?}"
    );
    assert!(
        el.0 > er.0,
        "left eye {el:?} should be right of right eye {er:?}"
    );
    for id in ["frontalis_l", "frontalis_r"] {
        let ((_, y), _) = heat_centroid(cell_index(id), 0);
        assert!(
            y < 0.5 * (el.1 + er.1),
            "{id} heat centroid y {y} below the eyes"
        );
    }
}

/// Zygomaticus major pulls its own mouth corner: in the front view the heat around the face's
/// left mouth corner (image right) is far stronger for zygomaticus_major_l than around the right
/// corner, and the other way round for _r; the heat centroid lies on the muscle's side.
#[test]
fn zygomaticus_heat_is_at_its_own_mouth_corner() {
    let m = model();
    let opts = SheetOptions::default();
    let cam = contact_sheet::cameras(m, &opts)[0];
    let (left, right) = mouth_corners(m);
    let (pl, pr) = (cam.project(left), cam.project(right));
    assert!(
        pl.0 > pr.0,
        "face-left corner {pl:?} must be image-right of {pr:?}"
    );
    let radius = 0.06 * f64::from(opts.panel_px);
    let centre_x = 0.5 * (pl.0 + pr.0);
    for (id, own, other, sign) in [
        ("zygomaticus_major_l", pl, pr, 1.0),
        ("zygomaticus_major_r", pr, pl, -1.0),
    ] {
        let c = cell_index(id);
        let (h_own, h_other) = (
            heat_near(c, (own.0, own.1), radius),
            heat_near(c, (other.0, other.1), radius),
        );
        eprintln!("{id}: heat near own corner {h_own}, near the other {h_other}");
        assert!(
            h_own > 0 && h_own >= 3 * h_other,
            "{id}: own {h_own} other {h_other}"
        );
        let ((x, _), _) = heat_centroid(c, 0);
        assert!(
            sign * (x - centre_x) > 0.0,
            "{id}: heat centroid x {x}, face centre {centre_x}"
        );
    }
}

#[test]
fn rendering_is_deterministic_and_png_round_trips() {
    let cells = contact_sheet::standard_cells(model(), Selection::Muscles);
    let opts = SheetOptions {
        title: "determinism".into(),
        panel_px: 96,
        columns: 3,
        ..SheetOptions::default()
    };
    let a = contact_sheet::render(model(), &cells, &opts).unwrap();
    let b = contact_sheet::render(model(), &cells, &opts).unwrap();
    assert!(a == b, "two renders differ");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sheet.png");
    contact_sheet::write_png(&path, &a).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(
        bytes,
        a.to_png().unwrap(),
        "PNG encoding is not deterministic"
    );
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (a.width, a.height));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(&buf[..info.buffer_size()], &a.pixels[..]);
}

#[test]
fn bad_cells_and_options_are_errors() {
    let m = model();
    let cells = [SheetCell::new("short", "", vec![0.0; 3])];
    let err = contact_sheet::render(m, &cells, &SheetOptions::default()).unwrap_err();
    assert!(matches!(err, SheetError::Pose { .. }), "{err}");
    assert!(err.to_string().contains("short"), "{err}");
    let cells = [contact_sheet::neutral_cell(m)];
    let opts = SheetOptions {
        views: vec![],
        ..SheetOptions::default()
    };
    assert!(matches!(
        contact_sheet::render(m, &cells, &opts),
        Err(SheetError::Options(_))
    ));
    let opts = SheetOptions {
        mm_per_unit: Some(f64::NAN),
        ..SheetOptions::default()
    };
    assert!(matches!(
        contact_sheet::render(m, &cells, &opts),
        Err(SheetError::Options(_))
    ));
}

/// `facebem sheet FACE -o PNG --only muscles` writes a PNG of neutral + the ten muscles; a bad
/// `--only` is a usage error.
#[test]
fn cli_sheet_writes_the_png() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("muscles.png");
    let bin = env!("CARGO_BIN_EXE_facebem");
    let face = support::asset(support::FACES[0]);
    let run = std::process::Command::new(bin)
        .args([
            "sheet".as_ref(),
            face.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
        .args(["--only", "muscles"])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    // Neutral and one cell per control of the default face.
    let cells = face_prep::MuscleKind::ALL.len() + 1;
    assert!(stdout.contains(&format!("{cells} cells")), "{stdout}");
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
    let info = decoder.read_info().unwrap().info().clone();
    let l = contact_sheet::layout(cells, &SheetOptions::default());
    assert_eq!((info.width, info.height), (l.width, l.height));

    let bad = std::process::Command::new(bin)
        .args([
            "sheet".as_ref(),
            face.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
        .args(["--only", "eyes"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
}

/// The heat scale is in millimetres through the rig's unit: the default face is detected in
/// centimetres, and the hottest pixel of frontalis_l (a broad raise over the brow) is in the bin
/// of its largest vertex displacement in mm (or the one below: the peak vertex need not fall on
/// a pixel); drawn as if in millimetres it falls to the bin of a tenth of that. (It used the
/// zygomaticus, whose peak is the mouth-corner vertex alone since the lips around it are
/// relaxed where they would turn over, `facebem::settle::untangle`; a one-vertex peak at the mouth's
/// edge covers no pixel of its own bin.)
#[test]
fn heat_scale_follows_the_rigs_unit() {
    let m = model();
    assert_eq!(contact_sheet::mm_per_unit(m), 10.0);
    let cells = [contact_sheet::muscle_cells(m)
        .into_iter()
        .find(|c| c.label == "frontalis_l")
        .unwrap()];
    let k = m.basis.muscle_index("frontalis_l").unwrap();
    let max_mm = 10.0
        * m.basis.displacements[k]
            .iter()
            .map(|d| d.length())
            .fold(0.0, f64::max);
    let top = heat::bin(max_mm).unwrap();
    assert!(top >= 4, "frontalis moves only {max_mm} mm");
    let hottest = |mm_per_unit: Option<f64>| {
        let opts = SheetOptions {
            mm_per_unit,
            panel_px: 128,
            ..SheetOptions::default()
        };
        let img = contact_sheet::render(m, &cells, &opts).unwrap();
        let l = contact_sheet::layout(1, &opts);
        // Panels only (the header holds the colour bar).
        let (front, side) = (l.panel(0, 0), l.panel(0, 1));
        (0..img.height)
            .flat_map(|y| (0..img.width).map(move |x| (x, y)))
            .filter(|&(x, y)| front.contains(x, y) || side.contains(x, y))
            .filter_map(|(x, y)| heat::classify(img.get(x, y)))
            .max()
    };
    let as_cm = hottest(None).unwrap();
    assert!(
        as_cm == top || as_cm + 1 == top,
        "hottest bin {as_cm}, max {max_mm} mm"
    );
    let as_mm = hottest(Some(1.0));
    assert!(
        as_mm <= heat::bin(0.1 * max_mm),
        "as mm: {as_mm:?}, max {max_mm} mm"
    );
}
