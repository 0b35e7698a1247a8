//! `facebem export` of a whole head (issue 32, first method): its front face is cut from the
//! skin and rigged like a face mesh, the rig is carried to every vertex of every part
//! ([`facebem::transfer::head::carry_to_head`]), and the user's OBJ comes back as a glTF with
//! its own vertices, texture coordinates and materials and the morph targets on all of it.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use face_prep::parts::front_face;
use facebem::input::heads::WholeFile;

use crate::args::SolverArgs;
use crate::rig::{check_trust, compute};

/// Exports the head read as `whole` from `path` to `gltf`.
pub(crate) fn export_head(
    path: &Path,
    gltf: &Path,
    whole: WholeFile,
    gltf_params: facebem::export::GltfParams,
    params: &facebem::PipelineParams,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let is_obj = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if !is_obj {
        return export_glb_head(path, gltf, whole, gltf_params, params, solver, force);
    }
    let limits = face_prep::InputLimits::default();
    let bytes = face_prep::limits::read_input_file(path, &limits)?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let folder = match path.parent() {
        Some(f) if !f.as_os_str().is_empty() => f,
        _ => Path::new("."),
    };
    let materials = facebem::export::material::ObjMaterials::load(&text, folder)?;
    let mut inputs: Vec<&Path> = vec![path];
    inputs.extend(materials.files_read.iter().map(PathBuf::as_path));
    facebem::check_output(gltf, &inputs, &["glb", "gltf"], "an OBJ head's glTF export")?;
    let (model, head) = rig_head(path, &whole, params, solver, force)?;
    let identity: Vec<Option<u32>> = (0..whole.scene.positions.len() as u32).map(Some).collect();
    let layout = facebem::export::ExportLayout::from_obj(&text, &identity)?;
    let named_fields = head.named_fields_for(model.gltf_params(&gltf_params).names);
    let basis = head.basis;
    let warnings = materials.warnings.clone();
    let params = facebem::export::GltfParams {
        format: facebem::export::GltfFormat::from_path(gltf),
        materials: Some(materials),
        named_fields,
        mesh_split: Some(mesh_per_part(&whole)),
        ..model.gltf_params(&gltf_params)
    };
    let (bytes, summary) = facebem::export::build_gltf(&basis, &layout, &params)?;
    facebem::write_atomic(gltf, &bytes)?;
    for w in warnings.iter().chain(&summary.warnings) {
        eprintln!("warning: {w}");
    }
    outln!(
        "{}: {} morph targets on all {} vertices of the head, {:.0} KB",
        gltf.display(),
        summary.target_names.len(),
        basis.neutral.len(),
        summary.bytes as f64 / 1000.0
    );
    Ok(())
}

/// Exports the GLB or VRM head read as `whole` from `path` to `out`: the user's own file with
/// the targets added to every mesh that moves ([`facebem::export::user_gltf::add_targets`]).
fn export_glb_head(
    path: &Path,
    out: &Path,
    whole: WholeFile,
    gltf_params: facebem::export::GltfParams,
    params: &facebem::PipelineParams,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let limits = face_prep::InputLimits::default();
    let bytes = face_prep::limits::read_input_file(path, &limits)?;
    if bytes.get(0..4) != Some(b"glTF".as_slice()) {
        bail!(
            "{}: a .gltf head is not written back (a .glb or .vrm is): save it as .glb first",
            path.display()
        );
    }
    facebem::check_output(out, &[path], &["glb", "vrm"], "a GLB or VRM head")?;
    let (model, head) = rig_head(path, &whole, params, solver, force)?;
    let params = facebem::export::GltfParams {
        named_fields: head.named_fields_for(model.gltf_params(&gltf_params).names),
        ..model.gltf_params(&gltf_params)
    };
    let named = facebem::export::gltf::named_targets(&head.basis, &params)?;
    let (glb, added) = facebem::export::user_gltf::add_targets(
        &bytes,
        &whole.scene,
        &named.targets,
        &named.same_as,
    )
    .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    facebem::write_atomic(out, &glb)?;
    outln!(
        "{}: {} morph targets added to {} of its meshes{}, {:.0} KB",
        out.display(),
        named.targets.len(),
        added.meshes.len(),
        if added.vrm_expressions.is_empty() {
            String::new()
        } else {
            format!(", {} VRM expressions bound", added.vrm_expressions.len())
        },
        glb.len() as f64 / 1000.0
    );
    Ok(())
}

/// Cuts the front face of the head `whole` (read from `path`), rigs it and carries the rig to
/// every vertex of the head.
fn rig_head(
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

/// One mesh per part of the head (skin, each eyeball, each row of teeth, gums and tongue, lid
/// parts, other), by the scene's triangles (an OBJ's export layout has the same triangles in
/// the same order).
fn mesh_per_part(whole: &WholeFile) -> facebem::export::gltf::MeshSplit {
    use face_prep::parts::{PartKind, Side};
    const NAMES: [&str; 8] = [
        "skin",
        "eyeball_left",
        "eyeball_right",
        "upper_teeth",
        "lower_teeth",
        "gums_and_tongue",
        "lid_parts",
        "other",
    ];
    let mut triangle_mesh = vec![7u32; whole.scene.triangles.len()];
    for (c, kind) in whole.parts.components.iter().zip(&whole.parts.kinds) {
        let mesh = match kind {
            PartKind::Skin => 0,
            PartKind::Eyeball(Side::Left) => 1,
            PartKind::Eyeball(Side::Right) => 2,
            PartKind::UpperTooth => 3,
            PartKind::LowerTooth => 4,
            PartKind::GumsAndTongue => 5,
            PartKind::LidPart => 6,
            _ => 7,
        };
        for &t in &c.triangles {
            if let Some(slot) = triangle_mesh.get_mut(t as usize) {
                *slot = mesh;
            }
        }
    }
    facebem::export::gltf::MeshSplit {
        names: NAMES.iter().map(|n| n.to_string()).collect(),
        triangle_mesh,
    }
}
