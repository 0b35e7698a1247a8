//! Lists the triangles that turn over (their normal reverses) at each control's full
//! contraction and at each preset, per bundled face or given OBJ: how many there are, how many
//! lie within 12 mm of the lips or of the lids (where issues 10 and 11 allow skin to fold), and for every other one
//! (or every one with `--all`) where it is, its size, which of its corners were simulated (the
//! others are peeled or dropped by the simplification and carried over) and how far each
//! corner moves; with `--named`, every ARKit and VRM name too. This is how the known gaps of `tests/anatomical_muscles.rs` and `tests/jaw.rs`
//! were located.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin flip_report [-- face.obj ...] [-- --only id] [-- --all] [-- --named]
//! ```

use std::collections::HashSet;
use std::path::Path;

use facebem::report::measure::{FaceLandmarks, flipped_by};
use facebem::{Control, PipelineParams, build_face_model, expressions, expressions::presets};
use glam::{DVec2, DVec3};

/// Distance from the mouth loop, mm, within which a fold counts as "at the lips".
const LIPS_MM: f64 = 12.0;
/// The same for the eye loops (the lids and the folds at the canthi), as
/// `tests/expression_sets.rs` counts them.
const LIDS_MM: f64 = 12.0;

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let args: Vec<String> = std::env::args().skip(1).collect();
    let only = args
        .windows(2)
        .find(|w| w[0] == "--only")
        .map(|w| w[1].clone());
    let all = args.iter().any(|a| a == "--all");
    let named = args.iter().any(|a| a == "--named");
    let faces = facebem::input::faces_from_args(
        &args,
        &root.join("assets"),
        &facebem::input::BUNDLED_FACES,
    );
    for face in &faces {
        let mesh = face_prep::load_face(face)?;
        let m = build_face_model(&mesh, &PipelineParams::default(), &Control::new())?;
        let lm = FaceLandmarks::of(&m).ok_or_else(|| anyhow::anyhow!("no landmarks"))?;
        let mm = lm.mm_per_unit;
        let c = lm.canonical_points(&m.mesh.vertices);
        let front =
            |lp: &[u32]| -> Vec<DVec2> { lp.iter().map(|&v| c[v as usize].truncate()).collect() };
        let (mouth, eyes) = (
            front(&lm.loops.mouth),
            [front(&lm.loops.eye_l), front(&lm.loops.eye_r)],
        );
        let simulated: Option<HashSet<u32>> = m
            .simplified
            .as_ref()
            .map(|s| s.mesh.original_vertex.iter().copied().collect());
        let mut fields: Vec<(String, Vec<DVec3>)> = m
            .basis
            .muscle_ids
            .iter()
            .zip(&m.basis.displacements)
            .map(|(id, d)| (id.clone(), d.iter().map(|u| -*u).collect()))
            .collect();
        let mut recipes: Vec<(String, Vec<f64>)> = presets::ALL
            .iter()
            .map(|p| (p.name.to_owned(), p.sliders_for(m.muscle_ids())))
            .collect();
        if named {
            recipes.extend(named_recipes(m.muscle_ids()));
        }
        for (name, sliders) in recipes {
            let posed = m.pose(&sliders)?;
            let field = posed
                .iter()
                .zip(&m.mesh.vertices)
                .map(|(a, b)| *a - *b)
                .collect();
            fields.push((name, field));
        }
        println!("{} ({} triangles)", face.display(), m.mesh.triangles.len());
        for (name, field) in &fields {
            if only.as_ref().is_some_and(|o| o != name) {
                continue;
            }
            let flips = flipped_by(&m.mesh.vertices, field, &m.mesh.triangles);
            if flips.is_empty() {
                continue;
            }
            let mut lines = Vec::new();
            let (mut at_lips, mut at_lids) = (0, 0);
            for &t in &flips {
                let tri = m.mesh.triangles[t as usize];
                let centre = tri.iter().map(|&v| c[v as usize]).sum::<DVec3>() / 3.0;
                let to = |lp: &[DVec2]| {
                    face_prep::muscle_model::distance_to_loop(centre.truncate(), lp) * mm
                };
                let d_mm = to(&mouth);
                let lids_mm = to(&eyes[0]).min(to(&eyes[1]));
                if d_mm <= LIPS_MM || lids_mm <= LIDS_MM {
                    if d_mm <= LIPS_MM {
                        at_lips += 1;
                    } else {
                        at_lids += 1;
                    }
                    if !all {
                        continue;
                    }
                }
                let [a, b, q] = tri.map(|v| c[v as usize] * mm);
                let sim: String = tri
                    .iter()
                    .map(|v| match &simulated {
                        Some(s) if !s.contains(v) => 'c',
                        _ => 's',
                    })
                    .collect();
                let moved: Vec<String> = tri
                    .iter()
                    .map(|&v| format!("{:.1}", field[v as usize].length() * mm))
                    .collect();
                lines.push(format!(
                    "    t{t}: {d_mm:.1} mm from the lips, area {:.2} mm², corners {sim} (s simulated, c carried), moved {} mm",
                    0.5 * (b - a).cross(q - a).length(),
                    moved.join(" / ")
                ));
            }
            println!(
                "  {name:40} {} flipped ({:.2} %), {at_lips} within {LIPS_MM} mm of the lips, \
                 {at_lids} more within {LIDS_MM} mm of the lids",
                flips.len(),
                100.0 * flips.len() as f64 / m.mesh.triangles.len() as f64
            );
            for l in lines {
                println!("{l}");
            }
        }
    }
    Ok(())
}

/// Every ARKit and VRM name the rig makes, as its sliders; a corrective (`mouthClose`) on top of
/// its base (`jawOpen`), as ARKit defines it and as `tests/expression_sets.rs` judges it.
fn named_recipes(ids: &[String]) -> Vec<(String, Vec<f64>)> {
    let base = |name: &str| {
        expressions::sliders_for_name(name, ids)
            .ok()
            .map(|(s, _)| s)
    };
    expressions::arkit::EXPRESSIONS
        .iter()
        .chain(&expressions::vrm::EXPRESSIONS)
        .filter_map(|e| {
            let mut sliders = e.resolve(ids)?.sliders;
            if let Some(b) = expressions::corrective_base(e.name).and_then(base) {
                for (s, b) in sliders.iter_mut().zip(b) {
                    *s += b;
                }
            }
            Some((format!("{} {}", e.set.id(), e.name), sliders))
        })
        .collect()
}
