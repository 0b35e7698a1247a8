//! Issue 33's recipe calibration: the slider weights of every ARKit target fitted once, on the
//! ICT narrow face, to ICT-FaceKit's captured shape by bounded linear least squares, then
//! printed as the table `src/expressions/arkit.rs` holds (and the cosines before and after).
//!
//! ```text
//! cargo run --release -p facebem-tools --bin fit_recipes
//! ```
//!
//! It prints the table (per target: the cosine before and after the fit, the cosine over the
//! vertices facing the viewer, the motion at the target's landmark — where the capture moves
//! at least 90 % of its peak — against the captured, the largest motion, and the share of the
//! motion where the capture moves under 10 % of its peak), then the block that is
//! `src/expressions/arkit_fitted.rs` (paste it there and run `cargo fmt`; the committed file
//! is exactly that).
//!
//! The method (so that the recipes are one calibration, not per-face tuning):
//!
//! - The unknowns are slider values of the rig's controls, each in [−1, +0.5] (−1 = full
//!   contraction; up to +0.5 = the resting tone released, as the hand-made recipes used).
//! - A `…Left` target may use the left controls and the unpaired ones (orbicularis oris,
//!   procerus); its weights are fitted to the captured left *and* (mirrored) right shapes at
//!   once, and the `…Right` recipe is their mirror. A target with no side (pucker, rolls,
//!   shrugs, browInnerUp, cheekPuff) gets one weight per muscle pair, the same on both sides.
//!   `mouthLeft` may use both sides, `mouthRight` is its mirror.
//! - The jaw's targets keep their kinematic recipes; the cheek-puff pressure is used only by
//!   `cheekPuff`; the jaw controls are not used by the other targets (a lip target that opens
//!   the jaw would double the jaw when added to `jawOpen`), nor the lip seal, whose size is the
//!   jaw's opening (it is `mouthClose`'s recipe); each lip's marginal orbicularis oris only
//!   that lip's roll (it curls the lip in: anywhere else it folds the lip margins over); the
//!   rolls (FACS's lip suck, AU28) not the muscles of the mouth corner (`MODIOLUS`).
//! - Minimised: Σ over the narrow face's vertices of |response − capture|² (mm²), solved by
//!   projected coordinate descent on the normal equations (a convex box-constrained quadratic,
//!   so the minimum is unique up to collinear controls), weights then rounded to 0.05 and those
//!   under 0.05 dropped, the rest re-fitted once.
//!
//! The captured fields are only compared with: no captured displacement enters a response.

use std::collections::HashMap;
use std::path::Path;

use facebem::expressions::{Definition, arkit};
use facebem::report::captures::{captured, on_input_vertices_mm};
use facebem::report::measure::cosine;
use facebem::{Control, PipelineParams, build_face_model};
use glam::DVec3;

const CONTRACT: f64 = -1.0;
/// How far an antagonist may be released (slider +0.5: the resting tone let go).
const RELAX: f64 = 0.5;

/// The antagonists a target may release (left versions; the right recipe mirrors): the brow
/// lowerer lets the frontalis go, a roll lets go the muscle that everts its lip, the mouth's
/// sideways move lets the other side's cheek go. Every other control only contracts.
const RELEASED: [(&str, &str); 7] = [
    ("browDownLeft", "frontalis_l"),
    ("angry", "frontalis_l"),
    ("mouthRollLower", "depressor_labii_inferioris"),
    ("mouthRollUpper", "levator_labii_superioris"),
    ("mouthLeft", "risorius_r"),
    ("mouthLeft", "buccinator_r"),
    ("mouthLeft", "zygomaticus_major_r"),
];

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let narrow = face_prep::load_face(&root.join("assets/ict_narrow_face_4loop.obj"))?;
    let model = build_face_model(&narrow, &PipelineParams::default(), &Control::new())?;
    let n = narrow.input_to_vertex.len();
    let ids = model.muscle_ids().to_vec();
    // Each control's response at slider +1, per input vertex, mm.
    let fields: HashMap<String, Vec<DVec3>> = ids
        .iter()
        .zip(&model.basis.displacements)
        .map(|(id, f)| (id.clone(), on_input_vertices_mm(&narrow.input_to_vertex, f)))
        .collect();
    let dir = root.join("tests/data/calibration/ict_head_deltas");
    let mut rows = Vec::new();
    for e in arkit::EXPRESSIONS.iter() {
        let (Definition::Terms(old) | Definition::Fitted { fallback: old, .. }) = e.definition
        else {
            continue;
        };
        let capture = captured(&dir, e.name, n)?
            .ok_or_else(|| anyhow::anyhow!("no capture of {}", e.name))?;
        let old_field = field_of(&fields, old.iter().map(|(i, v)| (i.to_string(), *v)));
        let recipe = if keeps_its_recipe(e.name) {
            // The recipe a rig with every control uses (mouthClose's is the lip seal).
            let (Definition::Terms(kept) | Definition::Fitted { terms: kept, .. }) = e.definition
            else {
                continue;
            };
            kept.iter().map(|(i, v)| (i.to_string(), *v)).collect()
        } else if let Some(left) = mirrored_of(e.name) {
            // The right (or mouthRight) recipe is the mirror of the left one's fit.
            let left_capture =
                captured(&dir, left, n)?.ok_or_else(|| anyhow::anyhow!("no capture of {left}"))?;
            let fit = fit(&fields, &ids, left, &left_capture, &capture)?;
            fit.into_iter().map(|(i, v)| mirror(&i, v)).collect()
        } else {
            let other = mirror_name(e.name).and_then(|m| captured(&dir, &m, n).ok().flatten());
            fit(
                &fields,
                &ids,
                e.name,
                &capture,
                other.as_deref().unwrap_or(&capture),
            )?
        };
        let new_field = field_of(&fields, recipe.iter().cloned());
        rows.push((e.name, old_field, new_field, capture, recipe));
    }
    // The vertices facing the viewer: the unit normal's forward (canonical +z) part above 0.3.
    let normals = face_prep::shell::vertex_normals(&narrow.vertices, &narrow.triangles);
    let forward = (model.rig.canonical_from_input.matrix3.inverse() * DVec3::Z).normalize_or_zero();
    let front: Vec<bool> = narrow
        .input_to_vertex
        .iter()
        .map(|v| v.is_some_and(|v| normals[v as usize].dot(forward) > 0.3))
        .collect();
    print_table(&rows, &front);
    print_emotions(&fields, &ids, &rows, &dir, n)?;
    print_recipes(&rows);
    Ok(())
}

/// The VRM emotions against the sums of ICT captures issue 33 names for them: facebem's preset,
/// and the sum of the fitted ARKit targets of the same names.
fn print_emotions(
    fields: &HashMap<String, Vec<DVec3>>,
    ids: &[String],
    rows: &[Row],
    dir: &Path,
    n: usize,
) -> anyhow::Result<()> {
    const SUMS: [(&str, &[&str]); 3] = [
        (
            "happy",
            &[
                "mouthSmileLeft",
                "mouthSmileRight",
                "cheekSquintLeft",
                "cheekSquintRight",
            ],
        ),
        (
            "angry",
            &[
                "browDownLeft",
                "browDownRight",
                "eyeSquintLeft",
                "eyeSquintRight",
                "mouthPressLeft",
                "mouthPressRight",
            ],
        ),
        ("sad", &["browInnerUp", "mouthFrownLeft", "mouthFrownRight"]),
    ];
    println!(
        "\n| VRM | ICT sum | preset cosine | sum of the fitted targets' cosine | fitted to the sum |"
    );
    println!("|---|---|---|---|---|");
    let mut joint_recipes = Vec::new();
    for (emotion, names) in SUMS {
        let mut capture = vec![DVec3::ZERO; n];
        let mut ours = vec![DVec3::ZERO; n];
        for name in names {
            let c = captured(dir, name, n)?.ok_or_else(|| anyhow::anyhow!("no {name}"))?;
            capture.iter_mut().zip(&c).for_each(|(a, b)| *a += *b);
            let row = rows
                .iter()
                .find(|r| r.0 == *name)
                .ok_or_else(|| anyhow::anyhow!("{name}"))?;
            ours.iter_mut().zip(&row.2).for_each(|(a, b)| *a += *b);
        }
        let preset = facebem::expressions::presets::find(emotion)
            .ok_or_else(|| anyhow::anyhow!("no preset {emotion}"))?
            .sliders_for(ids);
        let preset_field = field_of(fields, ids.iter().cloned().zip(preset));
        let joint = fit(fields, ids, emotion, &capture, &capture)?;
        let joint_field = field_of(fields, joint.iter().cloned());
        println!(
            "| {emotion} | {} | {:.2} | {:.2} | {:.2} |",
            names.join(" + "),
            cosine(&preset_field, &capture),
            cosine(&ours, &capture),
            cosine(&joint_field, &capture)
        );
        joint_recipes.push((emotion, joint));
    }
    for (emotion, joint) in joint_recipes {
        println!("\n// {emotion}, fitted to the ICT sum:");
        for (id, v) in joint {
            println!("(\"{id}\", {v:.2}),");
        }
    }
    Ok(())
}

/// Targets that keep their hand-made recipes: the jaw's kinematic ones; the blink, which must
/// close the lid (a weaker fit leaves it open); mouthClose, the lip seal over the open jaw (a
/// corrective no combination of muscles at the neutral makes: its captured lower lip rises
/// 38 mm; `face_prep::lip_seal`). And
/// those whose fit failed a standing check on another face (measured 2026-11-29, the gain
/// given up in brackets): browDown (0.52 → 0.82 with the orbicularis oculi's brow part) moves
/// ICT 2500's inner brow 2.86 mm down and in, under the 3 mm of `tests/face_muscles.rs` (ICT
/// 13k's 4.4 mm); mouthPucker (0.74 → 0.76) narrows Lee Perry-Smith's
/// mouth 19.4 %, under 20 %; mouthLeft / mouthRight (0.67 → 0.74) turn 13–28 triangles over
/// on ICT 2500 and Lee Perry-Smith, over the 0.5 % of `tests/expression_sets.rs`.
fn keeps_its_recipe(name: &str) -> bool {
    name.starts_with("jaw")
        || name.starts_with("eyeBlink")
        || name.starts_with("browDown")
        || matches!(
            name,
            "mouthClose" | "mouthPucker" | "mouthLeft" | "mouthRight"
        )
}

/// The upper bound of an unknown's slider value in `name`'s fit.
fn upper_bound(name: &str, unknown: &[String]) -> f64 {
    let released = RELEASED.iter().any(|(n, id)| {
        *n == name
            && unknown
                .iter()
                .any(|u| u == id || u.strip_suffix("_l") == Some(id))
    });
    if released { RELAX } else { 0.0 }
}

/// The left name whose fit this (right) name mirrors.
fn mirrored_of(name: &str) -> Option<&'static str> {
    if name == "mouthRight" {
        return Some("mouthLeft");
    }
    let stem = name.strip_suffix("Right")?;
    arkit::NAMES
        .iter()
        .copied()
        .find(|n| n.strip_suffix("Left") == Some(stem))
}

/// The capture name of the other side (`mouthSmileLeft` → `mouthSmileRight`).
fn mirror_name(name: &str) -> Option<String> {
    if name == "mouthLeft" {
        return Some("mouthRight".into());
    }
    name.strip_suffix("Left").map(|s| format!("{s}Right"))
}

/// The control of the other side with the value meaning the mirrored motion.
fn mirror(id: &str, v: f64) -> (String, f64) {
    facebem::expressions::mirrored_control(id, v)
}

fn field_of(
    fields: &HashMap<String, Vec<DVec3>>,
    terms: impl Iterator<Item = (String, f64)>,
) -> Vec<DVec3> {
    let n = fields.values().next().map_or(0, Vec::len);
    let mut out = vec![DVec3::ZERO; n];
    for (id, v) in terms {
        if let Some(f) = fields.get(&id) {
            out.iter_mut().zip(f).for_each(|(o, d)| *o += v * *d);
        }
    }
    out
}

/// The muscles that insert at the mouth corner (the modiolus), by id stem. The rolls do not use
/// them: FACS's lip suck (AU28), which ARKit's rolls are, is the orbicularis oris's own action
/// (Ekman, Friesen & Hager, *Facial Action Coding System*, 2002), and the corner muscles
/// pulling against the curled lip fold its inside over at the corners.
const MODIOLUS: [&str; 5] = [
    "levator_anguli_oris",
    "depressor_anguli_oris",
    "buccinator",
    "zygomaticus_major",
    "risorius",
];

/// The unknowns of a target: each a list of (control, sign) moved together.
fn unknowns(ids: &[String], name: &str) -> Vec<Vec<String>> {
    // The jaw and the lip seal (a corrective whose size is the jaw's opening) serve only their
    // own targets, which keep their recipes; the cheek puff only cheekPuff; each lip's marginal
    // part only that lip's roll (it curls the lip in; elsewhere it would fold the margins).
    let usable = |id: &str| {
        !id.starts_with("jaw_")
            && id != "lip_seal"
            && (id != "cheek_puff" || name == "cheekPuff")
            && (id != "orbicularis_oris_marginal_upper" || name == "mouthRollUpper")
            && (id != "orbicularis_oris_marginal_lower" || name == "mouthRollLower")
            && !(name.starts_with("mouthRoll") && MODIOLUS.iter().any(|m| id.starts_with(m)))
    };
    let sided = name.ends_with("Left");
    let both = name == "mouthLeft";
    let mut out: Vec<Vec<String>> = Vec::new();
    for id in ids.iter().filter(|i| usable(i)) {
        if let Some(stem) = id.strip_suffix("_l") {
            let right = format!("{stem}_r");
            if sided || both {
                out.push(vec![id.clone()]);
                if both && ids.contains(&right) {
                    out.push(vec![right]);
                }
            } else if ids.contains(&right) {
                out.push(vec![id.clone(), right]);
            } else {
                out.push(vec![id.clone()]);
            }
        } else if id.ends_with("_r") {
            // Paired with its left above; a right-only control stands alone.
            let left = format!("{}_l", &id[..id.len() - 2]);
            if !ids.contains(&left) && !sided {
                out.push(vec![id.clone()]);
            }
        } else {
            out.push(vec![id.clone()]);
        }
    }
    out
}

/// Bounded least-squares weights of `name`'s controls against its capture and, mirrored, the
/// other side's capture (the same capture again for a target with no side).
fn fit(
    fields: &HashMap<String, Vec<DVec3>>,
    ids: &[String],
    name: &str,
    capture: &[DVec3],
    other: &[DVec3],
) -> anyhow::Result<Vec<(String, f64)>> {
    let mut kept = unknowns(ids, name);
    let mut w = solve(fields, name, &kept, capture, other);
    // Drop what is under 0.1, fit the rest once more and round to 0.05.
    let (least, step) = (0.1, 0.05);
    let mut keep = Vec::new();
    for (u, x) in kept.iter().zip(&w) {
        if x.abs() >= least {
            keep.push(u.clone());
        }
    }
    kept = keep;
    w = solve(fields, name, &kept, capture, other);
    let mut out = Vec::new();
    for (u, x) in kept.iter().zip(&w) {
        let x = (x / step).round() * step;
        if x.abs() >= step - 1e-9 {
            for id in u {
                out.push((id.clone(), x));
            }
        }
    }
    if out.is_empty() {
        anyhow::bail!("{name}: no control moves toward the capture");
    }
    Ok(out)
}

/// Projected coordinate descent on the normal equations of the stacked problem.
fn solve(
    fields: &HashMap<String, Vec<DVec3>>,
    name: &str,
    unknowns: &[Vec<String>],
    capture: &[DVec3],
    other: &[DVec3],
) -> Vec<f64> {
    let col = |u: &[String], mirrored: bool| -> Vec<DVec3> {
        let terms = u.iter().map(|id| {
            if mirrored {
                mirror(id, 1.0)
            } else {
                (id.clone(), 1.0)
            }
        });
        field_of(fields, terms)
    };
    let a: Vec<Vec<DVec3>> = unknowns.iter().map(|u| col(u, false)).collect();
    let b: Vec<Vec<DVec3>> = unknowns.iter().map(|u| col(u, true)).collect();
    let m = unknowns.len();
    let dot = |x: &[DVec3], y: &[DVec3]| x.iter().zip(y).map(|(p, q)| p.dot(*q)).sum::<f64>();
    let mut gram = vec![vec![0.0; m]; m];
    let mut rhs = vec![0.0; m];
    for i in 0..m {
        for j in 0..m {
            gram[i][j] = dot(&a[i], &a[j]) + dot(&b[i], &b[j]);
        }
        rhs[i] = dot(&a[i], capture) + dot(&b[i], other);
    }
    let upper: Vec<f64> = unknowns.iter().map(|u| upper_bound(name, u)).collect();
    let mut w = vec![0.0; m];
    for _ in 0..20_000 {
        let mut change: f64 = 0.0;
        for i in 0..m {
            if gram[i][i] <= 0.0 {
                continue;
            }
            let g: f64 = (0..m).map(|j| gram[i][j] * w[j]).sum::<f64>() - rhs[i];
            let x = (w[i] - g / gram[i][i]).clamp(CONTRACT, upper[i]);
            change = change.max((x - w[i]).abs());
            w[i] = x;
        }
        if change < 1e-9 {
            break;
        }
    }
    w
}

type Row<'a> = (
    &'a str,
    Vec<DVec3>,
    Vec<DVec3>,
    Vec<DVec3>,
    Vec<(String, f64)>,
);

fn largest(f: &[DVec3]) -> f64 {
    f.iter().map(|d| d.length()).fold(0.0, f64::max)
}

/// Share of the response's squared motion where the capture moves under 10 % of its peak.
fn still_share(ours: &[DVec3], capture: &[DVec3]) -> f64 {
    let peak = largest(capture);
    let total: f64 = ours.iter().map(|d| d.length_squared()).sum();
    let still: f64 = ours
        .iter()
        .zip(capture)
        .filter(|(_, c)| c.length() < 0.1 * peak)
        .map(|(d, _)| d.length_squared())
        .sum();
    if total > 0.0 { still / total } else { 0.0 }
}

/// Mean motion of the response over the mean motion of the capture where the capture moves at
/// least 90 % of its peak (the target's landmark: the corner in a smile, the lid in a blink).
fn landmark_ratio(ours: &[DVec3], capture: &[DVec3]) -> f64 {
    let peak = largest(capture);
    let (mut o, mut c) = (0.0, 0.0);
    for (d, k) in ours.iter().zip(capture) {
        if k.length() >= 0.9 * peak {
            o += d.length();
            c += k.length();
        }
    }
    if c > 0.0 { o / c } else { 0.0 }
}

/// The cosine over the vertices flagged in `front` only.
fn front_cosine(ours: &[DVec3], capture: &[DVec3], front: &[bool]) -> f64 {
    let keep = |f: &[DVec3]| -> Vec<DVec3> {
        f.iter()
            .zip(front)
            .map(|(d, &on)| if on { *d } else { DVec3::ZERO })
            .collect()
    };
    cosine(&keep(ours), &keep(capture))
}

/// The table issue 33 asks for; `front` flags the vertices facing the viewer.
fn print_table(rows: &[Row], front: &[bool]) {
    println!(
        "| target | cosine before | cosine fitted | front-only cosine | at the landmark (× captured) | largest mm fitted (captured) | still share |"
    );
    println!("|---|---|---|---|---|---|---|");
    let (mut before, mut after) = (0.0, 0.0);
    for (name, old, new, cap, _) in rows {
        let (c0, c1) = (cosine(old, cap), cosine(new, cap));
        before += c0;
        after += c1;
        println!(
            "| {name} | {c0:.2} | {c1:.2} | {:.2} | {:.2} | {:.1} ({:.1}) | {:.2} |",
            front_cosine(new, cap, front),
            landmark_ratio(new, cap),
            largest(new),
            largest(cap),
            still_share(new, cap)
        );
    }
    let k = rows.len() as f64;
    println!(
        "\nmean cosine: before {:.3}, fitted {:.3}",
        before / k,
        after / k
    );
}

/// The recipes as the Rust source of `src/expressions/arkit_fitted.rs`, one constant per target
/// (`mouthSmileLeft` → `MOUTH_SMILE_LEFT`), terms by decreasing weight.
fn print_recipes(rows: &[Row]) {
    println!("\n// ---- src/expressions/arkit_fitted.rs ----");
    println!(
        "//! The ARKit recipes' slider weights, fitted once on the ICT narrow face to ICT-FaceKit's"
    );
    println!("//! captured shapes by bounded least squares. Generated by");
    println!(
        "//! `cargo run --release -p facebem-tools --bin fit_recipes` (the method is in that file's"
    );
    println!("//! documentation); edit there and regenerate, not here.\n");
    for (name, _, _, _, recipe) in rows.iter().filter(|r| !keeps_its_recipe(r.0)) {
        let mut recipe = recipe.clone();
        recipe.sort_by(|a, b| {
            a.1.abs()
                .total_cmp(&b.1.abs())
                .reverse()
                .then(a.0.cmp(&b.0))
        });
        let constant: String = name
            .chars()
            .flat_map(|c| {
                let sep = c.is_ascii_uppercase().then_some('_');
                sep.into_iter()
                    .chain(std::iter::once(c.to_ascii_uppercase()))
            })
            .collect();
        println!("/// `{name}`.");
        println!("pub(super) const {constant}: &[(&str, f64)] = &[");
        for (i, v) in recipe {
            println!("    (\"{i}\", {v:.2}),");
        }
        println!("];");
    }
}
