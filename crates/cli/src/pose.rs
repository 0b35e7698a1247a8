//! `pose` and `export`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use facebem::expressions::{self, NameSet, presets};
use facebem::input::Opened;

use crate::args::SolverArgs;
use crate::rig::{check_trust, model_from_opened, pipeline_params};

fn parse_set(s: &str) -> Result<(String, f64)> {
    let (id, value) = s
        .split_once('=')
        .ok_or_else(|| anyhow!("--set {s:?}: expected muscle_id=value"))?;
    let value: f64 = value
        .trim()
        .parse()
        .with_context(|| format!("--set {s:?}: {value:?} is not a number"))?;
    if !(-1.0..=1.0).contains(&value) {
        bail!("--set {s:?}: value {value} is outside [-1, 1]");
    }
    Ok((id.trim().to_string(), value))
}

pub(crate) fn pose(
    rig: &Path,
    sets: &[String],
    preset: Option<&str>,
    output: &Path,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let params = pipeline_params(solver)?;
    facebem::check_output(output, &[rig], &["obj"], "a pose (OBJ)")?;
    let parsed: Vec<(String, f64)> = sets.iter().map(|s| parse_set(s)).collect::<Result<_>>()?;
    // A whole head: posed whole (its own standard names included).
    let opened = match crate::open_face(rig) {
        Ok(opened) => opened,
        Err(e) => {
            if matches!(e, facebem::input::OpenError::Face { .. })
                && let Some(Ok(whole)) = facebem::input::heads::WholeFile::examine(rig)
            {
                return crate::head::pose_head(
                    rig, output, whole, preset, &parsed, &params, solver, force,
                );
            }
            return Err(crate::rig::whole_file_parts(rig, e, false));
        }
    };
    if let Some(name) = preset
        && presets::find(name).is_none()
        && expressions::find(name).is_none()
    {
        if let Some((name, reason)) = expressions::not_modelled(name) {
            bail!("{}", expressions::LookupError::NotModelled { name, reason });
        }
        bail!(
            "unknown preset {name:?} (known: {}, or an ARKit or VRM 1.0 name, see --help)",
            presets::names().join(", ")
        );
    }
    // Unknown muscle names are found before a face mesh's rig is computed.
    let known: Vec<String> = match &opened {
        Opened::Model(model) => model.muscle_ids().to_vec(),
        Opened::Face { .. } => face_prep::MuscleKind::ALL
            .iter()
            .map(|k| k.id().to_string())
            .collect(),
    };
    if let Some((id, _)) = parsed.iter().find(|(id, _)| !known.contains(id)) {
        // At most ten names in a one-line message (the anatomical rig has 27 controls).
        let shown: Vec<&str> = known.iter().take(10).map(String::as_str).collect();
        let more = match known.len().saturating_sub(shown.len()) {
            0 => String::new(),
            n => format!(", and {n} more: `facebem info` lists them"),
        };
        bail!("unknown muscle {id:?} (known: {}{more})", shown.join(", "));
    }
    let (model, _) = model_from_opened(rig, opened, &params, solver.no_cache)?;
    check_trust(&model, force)?;
    let ids = model.muscle_ids().to_vec();
    let mut sliders = vec![0.0; ids.len()];
    if let Some(name) = preset {
        let (values, missing) = expressions::sliders_for_name(name, &ids)?;
        if !missing.is_empty() {
            eprintln!(
                "warning: {name}: this rig has no {}; posed from its other controls",
                missing.join(", ")
            );
        }
        sliders = values;
    }
    for (id, value) in parsed {
        let k = model
            .basis
            .muscle_index(&id)
            .ok_or_else(|| anyhow!("unknown muscle {id:?} (known: {})", ids.join(", ")))?;
        sliders[k] = value;
    }
    model.write_obj(output, &sliders)?;
    outln!(
        "{}: posed {} vertices",
        output.display(),
        model.mesh.vertices.len()
    );
    Ok(())
}

pub(crate) fn export(
    rig: &Path,
    gltf: &Path,
    gltf_params: facebem::export::GltfParams,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let started = std::time::Instant::now();
    let params = pipeline_params(solver)?;
    // `.vrm` only for a head read whole (its own file written back, export_glb_head).
    let vrm = gltf
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vrm"));
    let allowed: &[&str] = if vrm { &["vrm"] } else { &["glb", "gltf"] };
    facebem::check_output(gltf, &[rig], allowed, "a glTF export")?;
    let opened = match crate::open_face(rig) {
        Ok(opened) => opened,
        // A whole head: its front face rigged, the rig carried to every part.
        Err(e @ facebem::input::OpenError::Face { .. }) => {
            return match facebem::input::heads::WholeFile::examine(rig) {
                Some(Ok(whole)) => {
                    crate::head::export_head(rig, gltf, whole, gltf_params, &params, solver, force)
                }
                Some(Err(refusal)) => Err(anyhow::anyhow!("{refusal}")),
                None => Err(e.into()),
            };
        }
        Err(e) => return Err(e.into()),
    };
    facebem::check_output(gltf, &[rig], &["glb", "gltf"], "a glTF export of a face")?;
    // The OBJ's own materials and textures, read from its folder (a rig file's: the folder it
    // is in) before any work; they are inputs the output must not overwrite.
    let obj_text = match &opened {
        facebem::input::Opened::Face { obj_source, .. } => obj_source.as_deref(),
        facebem::input::Opened::Model(model) => model.obj_source.as_deref(),
    };
    let folder = rig.parent().unwrap_or(Path::new("."));
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let materials = obj_text
        .map(|text| facebem::export::material::ObjMaterials::load(text, folder))
        .transpose()?;
    if let Some(m) = &materials {
        let mut inputs: Vec<&Path> = vec![rig];
        inputs.extend(m.files_read.iter().map(PathBuf::as_path));
        facebem::check_output(gltf, &inputs, &["glb", "gltf"], "a glTF export")?;
    }
    let mut warnings: Vec<String> = materials.iter().flat_map(|m| m.warnings.clone()).collect();
    let gltf_params = facebem::export::GltfParams {
        materials,
        ..gltf_params
    };
    let (model, source) = model_from_opened(rig, opened, &params, solver.no_cache)?;
    check_trust(&model, force)?;
    let (names, compress) = (gltf_params.names, gltf_params.compress);
    let summary = model.write_gltf(gltf, &gltf_params)?;
    warnings.extend(summary.warnings.iter().cloned());
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    if crate::json::mode() {
        let mut report =
            crate::json::command_report("export", &model, rig, gltf, source.json(), started);
        report["bytes"] = summary.bytes.into();
        report["compressed"] = compress.into();
        report["targets"] = serde_json::json!(summary.target_names);
        report["sameAs"] = serde_json::json!(summary.same_as);
        report["negativeOf"] = serde_json::json!(summary.negative_of);
        report["leftOut"] = serde_json::json!(summary.left_out);
        report["materialWarnings"] = serde_json::json!(warnings);
        crate::json::print(&report);
        return Ok(());
    }
    let (made, left_out) = expressions::for_rig(names, model.muscle_ids());
    outln!(
        "{}: {} morph targets, {:.0} KB{}",
        gltf.display(),
        summary.target_names.len(),
        summary.bytes as f64 / 1000.0,
        if compress {
            " (EXT_meshopt_compression)"
        } else {
            ""
        }
    );
    let repeats: Vec<String> = (summary.same_as.iter().map(|(a, b)| format!("{a} = {b}")))
        .chain(
            summary
                .negative_of
                .iter()
                .map(|(a, b)| format!("{a} = -{b}")),
        )
        .collect();
    if !repeats.is_empty() {
        outln!(
            "  left out as repeats (mesh.extras.sameAs, negativeOf): {}",
            repeats.join(", ")
        );
    }
    for set in [NameSet::Arkit, NameSet::Vrm] {
        if !names.contains(set) {
            continue;
        }
        let count = made.iter().filter(|m| m.expression.set == set).count();
        let partial: Vec<&str> = made
            .iter()
            .filter(|m| m.expression.set == set && !m.resolved.missing.is_empty())
            .map(|m| m.expression.name)
            .collect();
        let missing: Vec<&str> = left_out
            .iter()
            .filter(|(e, _)| e.set == set)
            .map(|(e, _)| e.name)
            .collect();
        outln!(
            "  {}: {count} of {} names ({} not modelled: no eyeballs/tongue)",
            set.display_name(),
            set.standard_size(),
            set.standard_size() - expressions::of_set(set).len()
        );
        if !partial.is_empty() {
            outln!(
                "    from only some of their controls: {}",
                partial.join(" ")
            );
        }
        if !missing.is_empty() {
            outln!(
                "    left out, their controls are not in this rig: {}",
                missing.join(" ")
            );
        }
    }
    Ok(())
}
