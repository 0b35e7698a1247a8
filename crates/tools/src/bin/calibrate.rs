//! Measures every muscle and preset of the bundled faces in millimetres against human motion
//! and the captured ICT expressions.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin calibrate [-- --thesis] [-- face.obj ...]
//! ```

use std::path::Path;

use face_prep::muscle_model::MuscleModel;
use facebem::report::measure::{
    FaceLandmarks, SurfacePoint, cosine, elevation_deg, flipped_by, max_length,
};
use facebem::{Control, FaceModel, PipelineParams, build_face_model, expressions::presets};
use glam::DVec3;

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let args: Vec<String> = std::env::args().skip(1).collect();
    let thesis = args.iter().any(|a| a == "--thesis");
    let faces = facebem::input::faces_from_args(
        &args,
        &root.join("assets"),
        &facebem::input::BUNDLED_FACES,
    );
    let mut params = PipelineParams::default();
    if thesis {
        params.rig.muscle_model = MuscleModel::Thesis;
    }
    for face in &faces {
        let mesh = face_prep::load_face(face)?;
        let t0 = std::time::Instant::now();
        let model = build_face_model(&mesh, &params, &Control::new())?;
        println!(
            "\n== {} ({:.1} s, {})",
            face.file_name().and_then(|n| n.to_str()).unwrap_or("?"),
            t0.elapsed().as_secs_f64(),
            model.rig.unit_choice().describe()
        );
        println!(
            "response amplification {:.2}, shell self-intersections {}",
            model.report.response_amplification, model.report.shell_self_intersections
        );
        report(&model)?;
        if face.ends_with("ict_narrow_face_4loop.obj") {
            calibration(&model, &root.join("tests/data/calibration"))?;
        }
    }
    Ok(())
}

fn report(model: &FaceModel) -> anyhow::Result<()> {
    let lm = FaceLandmarks::of(model).ok_or_else(|| anyhow::anyhow!("no landmarks"))?;
    let n_tris = model.mesh.triangles.len();
    let mm = lm.mm_per_unit;
    let c = |i: u32| {
        lm.canonical_from_input
            .transform_point3(model.mesh.vertices[i as usize])
            * mm
    };
    println!(
        "corner L at {:.1?}, R at {:.1?}; rig mouth box {:.1?}..{:.1?}; brow L at {:.1?}",
        c(lm.mouth_corner_l),
        c(lm.mouth_corner_r),
        model.rig.boxes.mouth.min * mm,
        model.rig.boxes.mouth.max * mm,
        c(lm.brow_l)
    );
    for m in &model.rig.muscles {
        if let Some((k, a)) = m
            .kind
            .and_then(|k| Some((k, face_prep::muscle_kind::attachment(k, &model.rig.boxes)?)))
        {
            println!(
                "  {:<30} origin {:>6.1?} insertion {:>6.1?} front {:>3} back {:>3}",
                k.id(),
                a.origin * mm,
                a.insertion * mm,
                m.front_chain.len(),
                m.back_chain.len()
            );
        }
    }
    println!(
        "{:<30} {:>7} {:>22} {:>7} {:>14} {:>14} {:>8} {:>6}",
        "muscle (full contraction)",
        "max mm",
        "max at (canon mm)",
        "cornL",
        "cornL ∠",
        "cornR/∠",
        "contour",
        "flips"
    );
    for (k, id) in model.muscle_ids().iter().enumerate() {
        let field: Vec<DVec3> = model.basis.displacements[k].iter().map(|d| -*d).collect();
        row(model, &lm, id, &field, n_tris);
    }
    for p in presets::ALL.iter().skip(1) {
        let sliders = p.sliders_for(model.muscle_ids());
        let posed = model.pose(&sliders)?;
        let field: Vec<DVec3> = posed
            .iter()
            .zip(&model.mesh.vertices)
            .map(|(a, b)| *a - *b)
            .collect();
        row(model, &lm, &format!("preset {}", p.name), &field, n_tris);
    }
    // Symmetry: left response vs mirrored right response at the landmarks.
    let mirror = |d: DVec3| DVec3::new(-d.x, d.y, d.z);
    let pairs = [
        (
            "zygomaticus_major",
            SurfacePoint::vertex(lm.mouth_corner_l),
            SurfacePoint::vertex(lm.mouth_corner_r),
        ),
        ("frontalis", lm.brow_point_l, lm.brow_point_r),
    ];
    for (name, vl, vr) in pairs {
        let (Some(kl), Some(kr)) = (
            model
                .muscle_ids()
                .iter()
                .position(|m| m == &format!("{name}_l")),
            model
                .muscle_ids()
                .iter()
                .position(|m| m == &format!("{name}_r")),
        ) else {
            continue;
        };
        let dl = lm.canonical_mm(vl.sample(&model.basis.displacements[kl]));
        let dr = lm.canonical_mm(vr.sample(&model.basis.displacements[kr]));
        println!(
            "symmetry {name}: |L − mirror(R)| = {:.2} mm",
            (dl - mirror(dr)).length()
        );
    }
    Ok(())
}

fn row(model: &FaceModel, lm: &FaceLandmarks, label: &str, field: &[DVec3], n_tris: usize) {
    let (imax, max) = field
        .iter()
        .enumerate()
        .map(|(i, d)| (i, d.length()))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    let at = lm
        .canonical_from_input
        .transform_point3(model.mesh.vertices[imax])
        * lm.mm_per_unit;
    let cl = lm.canonical_mm(field[lm.mouth_corner_l as usize]);
    let cr = lm.canonical_mm(field[lm.mouth_corner_r as usize]);
    let bl = lm.canonical_mm(lm.brow_point_l.sample(field));
    let flipped = flipped_by(&model.mesh.vertices, field, &model.mesh.triangles);
    let flips = flipped.len();
    if std::env::var_os("FLIPS").is_some() {
        for &t in flipped.iter().take(6) {
            let c = model.mesh.triangles[t as usize]
                .iter()
                .map(|&v| {
                    lm.canonical_from_input
                        .transform_point3(model.mesh.vertices[v as usize])
                        * lm.mm_per_unit
                })
                .sum::<DVec3>()
                / 3.0;
            println!("    flipped triangle {t} at {c:.1?}");
        }
    }
    println!(
        "{label:<30} {:>7.2} ({:>6.1},{:>6.1},{:>6.1}) {:>7.2} {:>6.1}° {:>5.2}/{:>5.1}° {:>8.3} {:>6}  browL up {:.2}",
        max * lm.mm_per_unit,
        at.x,
        at.y,
        at.z,
        cl.length(),
        elevation_deg(cl, 1.0),
        cr.length(),
        elevation_deg(cr, -1.0),
        lm.contour_motion_mm(field),
        flips,
        bl.y
    );
    let _ = (n_tris, max_length(field));
}

fn calibration(model: &FaceModel, dir: &Path) -> anyhow::Result<()> {
    let captured = |name: &str| -> anyhow::Result<Vec<DVec3>> {
        let m = face_prep::load_face(&dir.join(format!("ict_narrow_face_{name}.obj")))?;
        Ok(m.vertices
            .iter()
            .zip(&model.mesh.vertices)
            .map(|(a, b)| *a - *b)
            .collect())
    };
    let response = |id: &str| -> Option<Vec<DVec3>> {
        let k = model.muscle_ids().iter().position(|m| m == id)?;
        Some(model.basis.displacements[k].iter().map(|d| -*d).collect())
    };
    let sum =
        |a: Vec<DVec3>, b: Vec<DVec3>| a.iter().zip(&b).map(|(x, y)| *x + *y).collect::<Vec<_>>();
    let lm = FaceLandmarks::of(model).ok_or_else(|| anyhow::anyhow!("no landmarks"))?;
    let pairs: [(&str, Vec<DVec3>); 5] = [
        ("mouthSmile_L", captured("mouthSmile_L")?),
        ("mouthSmile_R", captured("mouthSmile_R")?),
        (
            "browUp_L (inner+outer)",
            sum(captured("browInnerUp_L")?, captured("browOuterUp_L")?),
        ),
        (
            "browUp_R (inner+outer)",
            sum(captured("browInnerUp_R")?, captured("browOuterUp_R")?),
        ),
        ("jawOpen", captured("jawOpen")?),
    ];
    println!("calibration against captured ICT shapes (cosine of whole fields):");
    for (name, c) in &pairs {
        let mut line = format!("  {name:<24}");
        for id in model.muscle_ids() {
            if let Some(r) = response(id) {
                line.push_str(&format!(" {}={:+.2}", short(id), cosine(&r, c)));
            }
        }
        println!("{line}");
    }
    for (id, name, v) in [
        (
            "zygomaticus_major_l",
            "mouthSmile_L",
            SurfacePoint::vertex(lm.mouth_corner_l),
        ),
        (
            "zygomaticus_major_r",
            "mouthSmile_R",
            SurfacePoint::vertex(lm.mouth_corner_r),
        ),
        ("frontalis_l", "browUp_L (inner+outer)", lm.brow_point_l),
        ("frontalis_r", "browUp_R (inner+outer)", lm.brow_point_r),
    ] {
        let (Some(r), Some((_, c))) = (response(id), pairs.iter().find(|p| p.0 == name)) else {
            continue;
        };
        let (rv, cv) = (v.sample(&r), v.sample(c));
        let ratio = rv.length() / cv.length().max(1e-12);
        let side = if id.ends_with("_l") { 1.0 } else { -1.0 };
        println!(
            "  captured {name} at the landmark: {:.2} mm at {:.1}° (rig: {:.1}°)",
            cv.length() * lm.mm_per_unit,
            elevation_deg(lm.canonical_mm(cv), side),
            elevation_deg(lm.canonical_mm(rv), side)
        );
        println!(
            "  {id} vs {name}: cosine {:.3}, landmark magnitude ratio {:.2} ({:.2} vs {:.2} mm)",
            cosine(&r, c),
            ratio,
            rv.length() * lm.mm_per_unit,
            cv.length() * lm.mm_per_unit
        );
    }
    Ok(())
}

fn short(id: &str) -> String {
    id.split('_')
        .map(|w| w.chars().next().unwrap_or('?'))
        .collect()
}
