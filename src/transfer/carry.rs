//! The simulated copy's vertex fields → the input mesh's vertices, in the input frame.

use face_prep::{FaceMesh, FaceRig};
use glam::{DMat3, DVec3};

use super::{SimplifiedFace, Transfer, TransferError};
use crate::copy::Simplified;
use crate::frame::CanonicalFace;

/// Carries the solved shell-vertex fields (`shell_fields[k][v]`, canonical frame; the shell's
/// first vertices are `simulated`'s, in order) to every vertex of the input `mesh`, input
/// frame. With a reduced copy `simplified`, each input vertex takes the closest copy point's
/// field ([`Transfer`]); in the anatomical model the `peeled_vertices` and the input's mouth
/// corners the copy does not hold start from the closest margin point, and the peeled ones are
/// then hung harmonically from the margins. Returns the fields and the copy with its map.
pub(crate) fn carry_to_input(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    simulated: &FaceMesh,
    simplified: Option<Simplified>,
    peeled_vertices: &[u32],
    shell_fields: &[Vec<DVec3>],
) -> Result<(Vec<Vec<DVec3>>, Option<SimplifiedFace>), TransferError> {
    // Canonical → input: displacements are vectors, so only the linear part applies.
    let linear: DMat3 = rig.input_from_canonical().matrix3;
    // Shell vertices 0..n are the simulated face's vertices, in order.
    let n_front = simulated.vertices.len();
    let sim_fields: Vec<Vec<DVec3>> = shell_fields
        .iter()
        .map(|field| field[..n_front].iter().map(|d| linear * *d).collect())
        .collect();
    let Some(s) = simplified else {
        return Ok((sim_fields, None));
    };
    // Fields on the reduced copy's vertices (through its own welding map).
    let on_copy: Vec<Vec<DVec3>> = sim_fields
        .iter()
        .map(|f| {
            simulated
                .input_to_vertex
                .iter()
                .map(|v| v.map_or(DVec3::ZERO, |v| f[v as usize]))
                .collect()
        })
        .collect();
    let mut transfer = Transfer::build(&mesh.vertices, &s).ok_or(TransferError::EmptyCopy)?;
    let anatomical = rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical;
    // The mouth loop's corners that the copy does not hold (a rolled-in lip's inner corner, or
    // one the simplification dropped) follow the copy's margin at their closest point, the
    // commissure, instead of hanging between the two lips.
    let corners = if anatomical {
        missing_mouth_corners(face, &s)
    } else {
        Vec::new()
    };
    let hanging: Vec<u32> = peeled_vertices
        .iter()
        .copied()
        .filter(|v| !corners.contains(v))
        .collect();
    if anatomical {
        // Peeled vertices and dropped corners alike start from the closest margin point.
        let snapped: Vec<u32> = hanging.iter().chain(&corners).copied().collect();
        transfer.snap_to_margins(&mesh.vertices, &s, &snapped);
    }
    let mut fields: Vec<Vec<DVec3>> = on_copy.iter().map(|f| transfer.apply(&s, f)).collect();
    if anatomical {
        for f in &mut fields {
            crate::copy::rolled_in::hang_from_margins(f, &mesh.triangles, &hanging);
        }
    }
    Ok((fields, Some(SimplifiedFace { mesh: s, transfer })))
}

/// The input mouth loop's corners (its extreme vertices in the rig's canonical ±x, the
/// landmarks [`crate::report::measure::FaceLandmarks`] measures) that the simulated copy `copy`
/// does not hold. Regression: ICT 13k's rolled-in corners, hung harmonically between the two
/// lips' flaps, moved 12.8 mm at full zygomaticus while the commissure beside them moved 13.8.
fn missing_mouth_corners(face: &CanonicalFace, copy: &Simplified) -> Vec<u32> {
    let Some((left, right)) = face.mouth_corners() else {
        return Vec::new();
    };
    let mut missing: Vec<u32> = [left, right]
        .into_iter()
        .filter(|v| !copy.original_vertex.contains(v))
        .collect();
    missing.dedup();
    missing
}
