//! Measures the eyelid controls of faces in millimetres and draws a contact sheet of them
//! (neutral, blink, half blink, squint and wide of the face's left eye, blink of the right),
//! shaded without the heat map so the lids' shape can be judged.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin eyelids -- out.png [face.obj ...]
//! ```
//! (default face: `assets/ict_narrow_face_4loop.obj`; with several faces, one sheet each,
//! `out.png` getting the face's name as a suffix).

use std::path::{Path, PathBuf};

use face_prep::Side;
use face_prep::eyelid::EyeMargins;
use facebem::report::contact_sheet::{SheetCell, SheetOptions, render, write_png};
use facebem::report::measure::{FaceLandmarks, flipped_triangles};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "eyelids.png".into()));
    let mut faces: Vec<PathBuf> = args.map(PathBuf::from).collect();
    if faces.is_empty() {
        faces.push(root.join("assets/ict_narrow_face_4loop.obj"));
    }
    let several = faces.len() > 1;
    for face in &faces {
        let name = face
            .file_stem()
            .and_then(|n| n.to_str())
            .unwrap_or("face")
            .to_string();
        let mesh = face_prep::load_face(face)?;
        let model = build_face_model(&mesh, &PipelineParams::default(), &Control::new())?;
        println!("== {name}");
        report(&model)?;
        let cells = [
            ("neutral", "", 0.0),
            ("blink L", "orbicularis_oculi_palpebral_l", -1.0),
            ("half blink L", "orbicularis_oculi_palpebral_l", -0.5),
            ("squint L", "orbicularis_oculi_orbital_l", -1.0),
            ("wide L", "levator_palpebrae_l", -1.0),
            ("blink R", "orbicularis_oculi_palpebral_r", -1.0),
        ]
        .iter()
        .map(|&(label, id, v)| {
            let mut s = vec![0.0; model.muscle_ids().len()];
            if let Some(k) = model.basis.muscle_index(id) {
                s[k] = v;
            }
            SheetCell::new(label, id, s)
        })
        .collect::<Vec<_>>();
        let opts = SheetOptions {
            title: format!("{name}: eyelids"),
            panel_px: 640,
            columns: 2,
            arrows: None,
            // A tiny mm scale keeps every displacement in the heat map's grey bin: shading only.
            mm_per_unit: Some(1e-9),
            ..SheetOptions::default()
        };
        let path = if several {
            out.with_file_name(format!(
                "{}_{name}.png",
                out.file_stem()
                    .and_then(|s| s.to_str())
                    .unwrap_or("eyelids")
            ))
        } else {
            out.clone()
        };
        write_png(&path, &render(&model, &cells, &opts)?)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Prints, per eyelid control at full activation: the margins' largest and smallest vertical
/// gap, the other eye's and the contour's largest motion, flipped triangles.
fn report(model: &FaceModel) -> anyhow::Result<()> {
    let lm = FaceLandmarks::of(model).ok_or_else(|| anyhow::anyhow!("no four loops"))?;
    let mm = lm.mm_per_unit;
    let c: Vec<DVec3> = lm.canonical_points(&model.mesh.vertices);
    for (id, side) in [
        ("orbicularis_oculi_palpebral_l", Side::Left),
        ("orbicularis_oculi_palpebral_r", Side::Right),
        ("orbicularis_oculi_orbital_l", Side::Left),
        ("levator_palpebrae_l", Side::Left),
    ] {
        let Some(k) = model.basis.muscle_index(id) else {
            continue;
        };
        let field: Vec<DVec3> = model.basis.displacements[k].iter().map(|d| -*d).collect();
        let posed: Vec<DVec3> = c
            .iter()
            .zip(&field)
            .map(|(p, d)| *p + lm.canonical_from_input.transform_vector3(*d))
            .collect();
        let (own, other) = match side {
            Side::Left => (&lm.loops.eye_l, &lm.loops.eye_r),
            _ => (&lm.loops.eye_r, &lm.loops.eye_l),
        };
        let m =
            EyeMargins::of_loop(&c, own, side).ok_or_else(|| anyhow::anyhow!("no eye margins"))?;
        let range = |g: Vec<Option<f64>>| {
            let g: Vec<f64> = g.into_iter().flatten().collect();
            (
                g.iter().copied().fold(f64::MIN, f64::max) * mm,
                g.iter().copied().fold(f64::MAX, f64::min) * mm,
            )
        };
        let (h0, _) = range(m.vertical_gaps(&c));
        let (largest, lowest) = range(m.vertical_gaps(&posed));
        let centre = face_prep::orient::loop_centroid(&c, other).truncate();
        let other_eye = (0..c.len())
            .filter(|&v| (c[v].truncate() - centre).length() * mm < 25.0)
            .map(|v| field[v].length() * mm)
            .fold(0.0, f64::max);
        let moved: Vec<DVec3> = model
            .mesh
            .vertices
            .iter()
            .zip(&field)
            .map(|(p, d)| *p + *d)
            .collect();
        let flipped = flipped_triangles(&model.mesh.vertices, &moved, &model.mesh.triangles);
        println!(
            "{id}: opening {h0:.2} mm -> vertical gap {largest:.3} .. {lowest:.3} mm, other eye \
             {other_eye:.3} mm, contour {:.3} mm, flipped {} of {}",
            lm.contour_motion_mm(&field),
            flipped.len(),
            model.mesh.triangles.len()
        );
    }
    Ok(())
}
