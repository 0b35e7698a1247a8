//! `pose` and `export`.

use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use facebem::expressions::{self, NameSet, NameSets, presets};
use facebem::input::Opened;

use crate::args::SolverArgs;
use crate::open;
use crate::rig::{check_trust, model_from, model_from_opened, pipeline_params};

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
    let opened = open(rig)?;
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
    let model = model_from_opened(rig, opened, &params)?;
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
    println!(
        "{}: posed {} vertices",
        output.display(),
        model.mesh.vertices.len()
    );
    Ok(())
}

pub(crate) fn export(
    rig: &Path,
    gltf: &Path,
    animation: bool,
    names: NameSets,
    arkit_naming: facebem::export::ArkitNaming,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let params = pipeline_params(solver)?;
    facebem::check_output(gltf, &[rig], &["glb", "gltf"], "a glTF export")?;
    let model = model_from(rig, &params)?;
    check_trust(&model, force)?;
    let params = facebem::export::GltfParams {
        animation,
        names,
        arkit_naming,
        ..Default::default()
    };
    model.write_gltf(gltf, &params)?;
    let (made, left_out) = expressions::for_rig(names, model.muscle_ids());
    let own = if names.facebem {
        2 * model.basis.muscle_count() + presets::ALL.len() - 1
    } else {
        0
    };
    println!("{}: {} morph targets", gltf.display(), made.len() + own);
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
        println!(
            "  {}: {count} of {} names ({} not modelled: no eyeballs/tongue)",
            set.display_name(),
            set.standard_size(),
            set.standard_size() - expressions::of_set(set).len()
        );
        if !partial.is_empty() {
            println!(
                "    from only some of their controls: {}",
                partial.join(" ")
            );
        }
        if !missing.is_empty() {
            println!(
                "    left out, their controls are not in this rig: {}",
                missing.join(" ")
            );
        }
    }
    Ok(())
}
