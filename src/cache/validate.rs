//! Checks of a decoded rig file beyond its checksum: anyone can recompute a checksum, so a
//! crafted file must not reach posing, exports or the viewer with indices out of range,
//! non-finite or absurd numbers, or fields whose lengths disagree.

use face_prep::error::sig6;
use face_prep::limits::MAX_COORDINATE;
use glam::DVec3;

use crate::export::layout::ExportLayout;
use crate::model::{FaceModel, SimplifiedFace};

fn check_points(what: &str, points: &[DVec3]) -> Result<(), String> {
    for (i, p) in points.iter().enumerate() {
        if !p.is_finite() || p.abs().max_element() > MAX_COORDINATE {
            return Err(format!(
                "{what} {i} is not finite or absurdly large: ({}, {}, {})",
                sig6(p.x),
                sig6(p.y),
                sig6(p.z)
            ));
        }
    }
    Ok(())
}

fn check_len(what: &str, len: usize, expected: usize) -> Result<(), String> {
    if len != expected {
        return Err(format!("{what} has {len} entries, expected {expected}"));
    }
    Ok(())
}

fn check_indices<'a>(
    what: &str,
    indices: impl IntoIterator<Item = &'a u32>,
    count: usize,
) -> Result<(), String> {
    for (i, &v) in indices.into_iter().enumerate() {
        if v as usize >= count {
            return Err(format!(
                "{what}: entry {i} refers to {v}, but there are only {count}"
            ));
        }
    }
    Ok(())
}

fn check_fields(
    what: &str,
    fields: &[Vec<DVec3>],
    muscles: usize,
    len: usize,
) -> Result<(), String> {
    check_len(what, fields.len(), muscles)?;
    for (k, f) in fields.iter().enumerate() {
        check_len(&format!("{what} of muscle {k}"), f.len(), len)?;
        check_points(&format!("{what} of muscle {k}, value"), f)?;
    }
    Ok(())
}

/// Checks that every index of `model` is in range, every number finite and within
/// [`MAX_COORDINATE`], every per-vertex, per-element and per-muscle field as long as what it
/// describes, the muscle ids unique and the kept OBJ text readable by the exports (what is
/// accepted always exports). Returns what is wrong.
pub fn validate_model(model: &FaceModel) -> Result<(), String> {
    check_mesh(model)?;
    let muscles = check_basis(model)?;
    check_rig(model, muscles)?;
    check_fields(
        "shell element response",
        &model.shell_element_response,
        muscles,
        model.rig.shell.triangles.len(),
    )?;
    check_fields(
        "shell vertex response",
        &model.shell_vertex_response,
        muscles,
        model.rig.shell.vertices.len(),
    )?;
    if let Some(s) = &model.simplified {
        check_simplified(s, model.mesh.vertices.len())?;
    }
    if let Some(text) = &model.obj_source {
        check_obj_source(text, &model.mesh)?;
    }
    check_numbers(model)?;
    let nu = model.params.poisson;
    if !(0.0..0.5).contains(&nu) {
        return Err(format!("Poisson ratio {} is outside [0, 0.5)", sig6(nu)));
    }
    Ok(())
}

/// The user's OBJ text kept for exports: read by the exports' own rules (those of the face
/// reader, [`face_prep::obj_text`]: finite numbers, faces referring to lines above them), with
/// one `v` line per input position, every position within [`MAX_COORDINATE`].
fn check_obj_source(text: &str, mesh: &face_prep::FaceMesh) -> Result<(), String> {
    let layout =
        ExportLayout::from_obj_for(text, mesh).map_err(|e| format!("its OBJ text: {e}"))?;
    check_points("OBJ source position", &layout.positions)
}

/// The numbers beside the geometry: the length unit, the feature boxes, the rig parameters,
/// and unique muscle ids (morph targets and sliders are named by them).
fn check_numbers(model: &FaceModel) -> Result<(), String> {
    // Up to 1e12 m per unit, positions within MAX_COORDINATE stay far inside glTF's f32.
    let metres = model.rig.unit.metres();
    if !(metres > 0.0 && metres <= 1e12) {
        return Err(format!(
            "length unit of {} m per unit is not in (0, 1e12]",
            sig6(metres)
        ));
    }
    let b = &model.rig.boxes;
    for (name, bx) in [
        ("face", &b.face),
        ("left eye", &b.eye_l),
        ("right eye", &b.eye_r),
        ("mouth", &b.mouth),
        ("nose", &b.nose),
        ("skull", &b.skull),
    ] {
        if !(bx.min.is_finite() && bx.max.is_finite()) {
            return Err(format!("feature box {name} is not finite"));
        }
    }
    let p = &model.rig.params;
    for (name, x) in [
        ("offset", p.offset),
        ("thickness", p.thickness),
        ("offset clamp", p.offset_clamp),
        ("ray spacing", p.ray_spacing),
        ("taper", p.taper),
    ] {
        if !x.is_finite() {
            return Err(format!("rig parameter {name} = {} is not finite", sig6(x)));
        }
    }
    let mut ids = std::collections::HashSet::new();
    if let Some(id) = model.basis.muscle_ids.iter().find(|id| !ids.insert(*id)) {
        return Err(format!("two muscles are named {id:?}"));
    }
    Ok(())
}

/// The user's face mesh: not empty, finite vertices, triangle and input-map indices in range.
fn check_mesh(model: &FaceModel) -> Result<(), String> {
    let mesh = &model.mesh;
    let nv = mesh.vertices.len();
    if nv == 0 || mesh.triangles.is_empty() {
        return Err("the face mesh is empty".into());
    }
    check_points("face vertex", &mesh.vertices)?;
    check_indices("face triangles", mesh.triangles.iter().flatten(), nv)?;
    check_indices(
        "input vertex map",
        mesh.input_to_vertex.iter().flatten(),
        nv,
    )
}

/// The muscle basis against the face mesh; returns the muscle count.
fn check_basis(model: &FaceModel) -> Result<usize, String> {
    let nv = model.mesh.vertices.len();
    let basis = &model.basis;
    let muscles = basis.muscle_ids.len();
    if muscles == 0 {
        return Err("the rig has no muscles".into());
    }
    check_len("muscle displacements", basis.displacements.len(), muscles)?;
    check_len("basis neutral vertices", basis.neutral.len(), nv)?;
    check_points("basis neutral vertex", &basis.neutral)?;
    check_indices("basis triangles", basis.triangles.iter().flatten(), nv)?;
    check_fields("displacement", &basis.displacements, muscles, nv)?;
    Ok(muscles)
}

/// The rig: its shell, loops, muscle chains, skull, face size and canonical frame.
fn check_rig(model: &FaceModel, muscles: usize) -> Result<(), String> {
    let rig = &model.rig;
    let shell = &rig.shell;
    let ne = shell.triangles.len();
    let nsv = shell.vertices.len();
    check_len("rig muscles", rig.muscles.len(), muscles)?;
    check_points("shell vertex", &shell.vertices)?;
    check_indices("shell elements", shell.triangles.iter().flatten(), nsv)?;
    check_len("shell element tags", shell.tags.len(), ne)?;
    check_len("shell element sources", shell.source_triangle.len(), ne)?;
    check_indices(
        "shell element sources",
        &shell.source_triangle,
        rig.face_triangle_count,
    )?;
    if rig.face_vertex_count > nsv {
        return Err(format!(
            "the rig's face has {} vertices but its shell only {nsv}",
            rig.face_vertex_count
        ));
    }
    let l = &rig.loops;
    for (name, lp) in [
        ("face loop", &l.face),
        ("left eye loop", &l.eye_l),
        ("right eye loop", &l.eye_r),
        ("mouth loop", &l.mouth),
    ] {
        check_indices(name, lp, rig.face_vertex_count)?;
    }
    for m in &rig.muscles {
        let chains = m.front_chain.iter().chain(&m.back_chain);
        check_indices(&format!("muscle {:?}", m.name), chains, ne)?;
    }
    check_indices("skull", &rig.skull, ne)?;
    if !(rig.face_size.is_finite() && rig.face_size > 0.0) {
        return Err(format!("face size {} is not positive", sig6(rig.face_size)));
    }
    let a = rig.canonical_from_input;
    if !(a.matrix3.is_finite() && a.translation.is_finite()) {
        return Err("the canonical frame is not finite".into());
    }
    Ok(())
}

/// The simplified copy a large face was simulated on, against the face's `nv` vertices.
fn check_simplified(s: &SimplifiedFace, nv: usize) -> Result<(), String> {
    let m = &s.mesh;
    check_points("simulated vertex", &m.vertices)?;
    check_indices(
        "simulated triangles",
        m.triangles.iter().flatten(),
        m.vertices.len(),
    )?;
    check_len(
        "simulated vertex map",
        m.original_vertex.len(),
        m.vertices.len(),
    )?;
    check_indices("simulated vertex map", &m.original_vertex, nv)?;
    check_len("transfer samples", s.transfer.samples.len(), nv)?;
    check_indices(
        "transfer samples",
        s.transfer.samples.iter().map(|(t, _)| t),
        m.triangles.len(),
    )?;
    if let Some(i) = s
        .transfer
        .samples
        .iter()
        .position(|(_, w)| !w.iter().all(|x| x.is_finite()))
    {
        return Err(format!("transfer sample {i} has non-finite weights"));
    }
    Ok(())
}
