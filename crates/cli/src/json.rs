//! `--json` reports of `rig`, `info` and `export`: one JSON object on stdout, the text report
//! left out ([`crate::write_stdout`] drops it while [`set_mode`] is on).

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use face_prep::{FaceMesh, FaceRig};
use facebem::FaceModel;
use facebem::expressions::{self, NameSets};
use serde_json::{Value, json};

static JSON_MODE: AtomicBool = AtomicBool::new(false);

/// Turns the JSON mode on: the text report is left out of stdout.
pub(crate) fn set_mode(on: bool) {
    JSON_MODE.store(on, Ordering::Relaxed);
}

/// Whether a `--json` report is being written instead of text.
pub(crate) fn mode() -> bool {
    JSON_MODE.load(Ordering::Relaxed)
}

/// Prints `report` as one line of JSON (even in JSON mode).
pub(crate) fn print(report: &Value) {
    set_mode(false);
    outln!("{report}");
}

/// The model's numbers: what was simulated, sizes, times, warnings and trust.
pub(crate) fn model_report(model: &FaceModel) -> Value {
    let r = &model.report;
    json!({
        "frontTriangles": r.input_triangles,
        "simulatedTriangles": r.simulated_triangles,
        "simplified": r.simplify_path.map(|p| p.describe()),
        "shellElements": r.shell_elements,
        "controls": model.muscle_ids(),
        "unit": model.rig.unit.to_string(),
        "metresPerUnit": model.metres_per_unit(),
        "seconds": { "prep": r.prep_seconds, "solve": r.solve_seconds },
        "warnings": r.warnings().iter().map(ToString::to_string).collect::<Vec<_>>(),
        "untrustworthy": facebem::model::distrust(model),
    })
}

/// The report of a command that wrote `output` from `input` with `model`: [`model_report`],
/// where the rig came from, and the command's whole time since `started`.
pub(crate) fn command_report(
    command: &str,
    model: &FaceModel,
    input: &Path,
    output: &Path,
    rig_source: Value,
    started: std::time::Instant,
) -> Value {
    let mut report = model_report(model);
    report["command"] = command.into();
    report["input"] = json!(input);
    report["output"] = json!(output);
    report["rigSource"] = rig_source;
    report["seconds"]["total"] = started.elapsed().as_secs_f64().into();
    report
}

/// `info --json`: the file, its mesh, unit, loops, muscles, the ARKit and VRM names its
/// controls make, and (for a rig file) [`model_report`].
pub(crate) fn info_report(
    path: &Path,
    mesh: &FaceMesh,
    rig: &FaceRig,
    model: Option<&FaceModel>,
) -> Value {
    let muscles: Vec<&str> = rig.muscles.iter().map(|m| m.id()).collect();
    let ids: Vec<String> = match model {
        Some(m) => m.muscle_ids().to_vec(),
        None => muscles.iter().map(|s| s.to_string()).collect(),
    };
    let (made, left_out) = expressions::for_rig(NameSets::USERS, &ids);
    let choice = rig.unit_choice();
    let mut report = json!({
        "command": "info",
        "file": path,
        "kind": if model.is_some() { "rig file" } else { "face mesh" },
        "vertices": mesh.vertices.len(),
        "triangles": mesh.triangles.len(),
        "simulatedCopy": { "vertices": rig.face_vertex_count, "triangles": rig.face_triangle_count },
        "unit": rig.unit.to_string(),
        "unitDetected": rig.unit_detected,
        "unitChoice": choice.describe(),
        "shellElements": rig.shell.triangles.len(),
        "muscles": muscles,
        "names": made.iter().map(|m| m.expression.name).collect::<Vec<_>>(),
        "namesLeftOut": left_out.iter().map(|(e, _)| e.name).collect::<Vec<_>>(),
        "notModelled": expressions::NOT_MODELLED
            .iter()
            .map(|(name, why)| json!([name, why]))
            .collect::<Vec<_>>(),
    });
    if let Some(m) = model {
        report["rig"] = model_report(m);
    }
    report
}

/// `info --json` of a head or an avatar: each component's part, size and names.
pub(crate) fn parts_report(
    path: &Path,
    scene: &face_prep::parts::Scene,
    parts: &face_prep::parts::HeadParts,
    refusal: &str,
) -> Value {
    let components: Vec<Value> = parts
        .components
        .iter()
        .zip(&parts.kinds)
        .map(|(c, kind)| {
            let mut labels: Vec<&str> = c
                .triangles
                .iter()
                .map(|&t| scene.labels[scene.triangle_label[t as usize] as usize].as_str())
                .collect();
            labels.sort_unstable();
            labels.dedup();
            json!({
                "part": kind.describe(),
                "vertices": c.vertices.len(),
                "triangles": c.triangles.len(),
                "names": labels,
            })
        })
        .collect();
    json!({
        "command": "info",
        "file": path,
        "kind": "head or avatar",
        "vertices": scene.positions.len(),
        "triangles": scene.triangles.len(),
        "components": components,
        "refused": refusal,
    })
}
