//! `facebem export` and `pose` of a whole head (issue 32): its front face is cut from the skin
//! and rigged like a face mesh, the rig is carried to every vertex of every part
//! ([`facebem::transfer::head::carry_to_head`]); `export` writes the user's file back with the
//! morph targets on all of it ([`facebem::export::head::head_gltf`]), `pose` one pose of it.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use face_prep::parts::front_face;
use facebem::input::heads::WholeFile;

use crate::args::SolverArgs;
use crate::rig::{check_trust, compute};

/// Exports the head read as `whole` from `path` to `out`: an OBJ head as a glTF with one mesh
/// per part, a GLB or VRM head as the user's own file with the targets added
/// ([`facebem::export::head::head_gltf`]).
pub(crate) fn export_head(
    path: &Path,
    out: &Path,
    whole: WholeFile,
    gltf_params: facebem::export::GltfParams,
    params: &facebem::PipelineParams,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let limits = face_prep::InputLimits::default();
    let mut inputs: Vec<PathBuf> = vec![path.to_path_buf()];
    if facebem::export::head::is_obj(path) {
        // The material libraries and textures are inputs too: checked before the long rig.
        let bytes = face_prep::limits::read_input_file(path, &limits)?;
        let text = String::from_utf8_lossy(&bytes);
        let folder = match path.parent() {
            Some(f) if !f.as_os_str().is_empty() => f,
            _ => Path::new("."),
        };
        let materials = facebem::export::material::ObjMaterials::load(&text, folder)?;
        inputs.extend(materials.files_read);
        let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
        facebem::check_output(out, &inputs, &["glb", "gltf"], "an OBJ head's glTF export")?;
    } else {
        // A .gltf's buffers and images are inputs too (it comes back packed into one GLB).
        inputs.extend(face_prep::input::files_read_by(path));
        let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
        facebem::check_output(out, &inputs, &["glb", "vrm"], "a glTF, GLB or VRM head")?;
    }
    let (model, head) = rig_head(path, &whole, params, solver, force)?;
    let built = facebem::export::head::head_gltf(path, out, &whole, &model, &head, &gltf_params)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    facebem::write_atomic(out, &built.bytes)?;
    for w in &built.warnings {
        eprintln!("warning: {w}");
    }
    outln!("{}: {}", out.display(), built.line);
    Ok(())
}

/// Cuts the front face of the head `whole` (read from `path`), rigs it and carries the rig to
/// every vertex of the head.
pub(crate) fn rig_head(
    path: &Path,
    whole: &WholeFile,
    params: &facebem::PipelineParams,
    solver: &SolverArgs,
    force: bool,
) -> Result<(facebem::FaceModel, facebem::transfer::head::HeadBasis)> {
    let front = front_face(&whole.scene, &whole.parts)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mesh = face_prep::FaceMesh::from_triangles(&front.positions, &front.triangles)
        .with_context(|| format!("{}: its front face", path.display()))?;
    outln!(
        "{} is a head ({}): rigging its front face ({} triangles) first",
        path.display(),
        whole.summary(),
        mesh.triangles.len()
    );
    let params = facebem::PipelineParams {
        outline_is_cut: true,
        ..params.clone()
    };
    let (model, _) = compute(&mesh, None, &params, solver.no_cache)?;
    check_trust(&model, force)?;
    let head = facebem::transfer::head::carry_to_head(
        &whole.scene,
        &whole.parts,
        &front,
        &model.mesh,
        &model.rig,
        &model.basis,
    );
    Ok((model, head))
}

/// `facebem pose` of a head read as `whole` from `path`: the whole head posed (every part) by
/// `preset` — an ARKit or VRM name as the head's export makes it (gaze and `tongueOut`
/// included), or a facebem preset — and the sliders `sets` on top, the lids kept on the
/// eyeballs; written in the OBJ's own layout (an OBJ head) or as a plain OBJ.
#[allow(clippy::too_many_arguments)]
pub(crate) fn pose_head(
    path: &Path,
    output: &Path,
    whole: WholeFile,
    preset: Option<&str>,
    sets: &[(String, f64)],
    params: &facebem::PipelineParams,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    use facebem::expressions::{arkit, presets, vrm};
    let mut inputs: Vec<PathBuf> = vec![path.to_path_buf()];
    inputs.extend(face_prep::input::files_read_by(path));
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    facebem::check_output(output, &inputs, &["obj"], "a pose (OBJ)")?;
    // A standard name as the standard spells it (the head makes all of them).
    let standard = preset.and_then(|name| {
        (arkit::NAMES.iter().chain(vrm::NAMES.iter()))
            .find(|n| n.eq_ignore_ascii_case(name.trim()))
            .copied()
    });
    if let Some(name) = preset
        && presets::find(name).is_none()
        && standard.is_none()
    {
        bail!(
            "unknown preset {name:?} (known: {}, or an ARKit or VRM 1.0 name, see --help)",
            presets::names().join(", ")
        );
    }
    let (model, head) = rig_head(path, &whole, params, solver, force)?;
    let basis = &head.basis;
    let mut sliders = vec![0.0; basis.muscle_ids.len()];
    for (id, value) in sets {
        let k = basis
            .muscle_index(id)
            .ok_or_else(|| anyhow::anyhow!("unknown muscle {id:?} (`facebem info` lists them)"))?;
        sliders[k] = *value;
    }
    let mut field: Vec<glam::DVec3> = match (preset.and_then(presets::find), standard) {
        // A facebem preset first, as for a face.
        (Some(p), _) => {
            for (s, v) in sliders.iter_mut().zip(p.sliders_for(&basis.muscle_ids)) {
                if *s == 0.0 {
                    *s = v;
                }
            }
            vec![glam::DVec3::ZERO; basis.neutral.len()]
        }
        (None, Some(name)) => {
            let names = model
                .gltf_params(&facebem::export::GltfParams::default())
                .names;
            head.named_fields_for(names)
                .into_iter()
                .find(|(n, _)| n == name)
                .map(|(_, f)| f)
                .ok_or_else(|| anyhow::anyhow!("{name}: this head cannot make it"))?
        }
        (None, None) => vec![glam::DVec3::ZERO; basis.neutral.len()],
    };
    let posed_by_sliders = basis.pose(&sliders)?;
    for ((d, p), n) in field.iter_mut().zip(&posed_by_sliders).zip(&basis.neutral) {
        *d += *p - *n;
    }
    head.contact.apply(&basis.neutral, &mut field);
    let posed: Vec<glam::DVec3> = (basis.neutral.iter().zip(&field))
        .map(|(n, d)| *n + *d)
        .collect();
    let text = if facebem::export::head::is_obj(path) {
        let limits = face_prep::InputLimits::default();
        let bytes = face_prep::limits::read_input_file(path, &limits)?;
        let template = String::from_utf8_lossy(&bytes);
        let identity: Vec<Option<u32>> = (0..posed.len() as u32).map(Some).collect();
        facebem::export::obj::pose_from_template(&template, &identity, &posed)?
    } else {
        facebem::export::obj::plain_obj(&posed, &basis.triangles)?
    };
    facebem::write_atomic(output, text.as_bytes())?;
    outln!(
        "{}: posed all {} vertices of the head",
        output.display(),
        posed.len()
    );
    Ok(())
}
