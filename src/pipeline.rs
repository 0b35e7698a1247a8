//! The orchestration, stage by stage: input mesh → frame ([`crate::frame`]) → copy
//! ([`crate::copy`]) → rig (face-prep: shell and controls) → solve ([`crate::solve`]) →
//! transfer ([`crate::transfer`]) → settle ([`crate::settle`]) → [`FaceModel`]. The data it
//! passes between the stages lives in [`crate::model`].

use std::time::Instant;

use face_prep::{FaceMesh, FaceRig};
use glam::DVec3;

use crate::control::{Control, Stage};
use crate::copy::simplify::SimplifyPath;
use crate::frame::InputFrame;
use crate::model::{
    FaceModel, MuscleBasis, PipelineError, PipelineParams, PrecomputeReport, PreparedRig,
};
use crate::solve::Solved;
use crate::transfer::Transfer;

/// The prep step alone (fast, no BEM): the input's frame, rolled-in parts peeled off,
/// simplification of a large face, rig, muscle override. A face symmetric in shape but not in
/// its triangles is prepared as its mirror-meshed stand-in ([`crate::copy::symmetrize`]).
pub fn prepare(mesh: &FaceMesh, params: &PipelineParams) -> Result<PreparedRig, PipelineError> {
    params.validate()?;
    face_prep::check_not_scrambled(&mesh.vertices, &mesh.triangles)?;
    let Some(stand_in) = crate::copy::symmetrize::stand_in(mesh, params.outline_is_cut) else {
        return prepare_as_written(mesh, params);
    };
    let inner = prepare_as_written(&stand_in.mesh, params)?;
    let transfer = stand_in_transfer(mesh, &stand_in)?;
    // A vertex of the face is peeled when its closest stand-in point is mostly on peeled
    // stand-in vertices.
    let mut peeled = vec![false; stand_in.mesh.vertices.len()];
    for &v in &inner.peeled_vertices {
        peeled[v as usize] = true;
    }
    let peeled_vertices = (0..mesh.vertices.len() as u32)
        .filter(|&v| {
            let (t, w) = transfer.samples[v as usize];
            let tri = stand_in.surface.triangles[t as usize];
            (0..3)
                .filter(|&k| peeled[tri[k] as usize])
                .map(|k| w[k])
                .sum::<f64>()
                > 0.5
        })
        .collect();
    Ok(PreparedRig {
        simplified: Some(onto_face(inner.simplified.as_ref(), &stand_in)),
        peeled_vertices,
        simplify_path: Some(SimplifyPath::of_stand_in(inner.simplify_path)),
        frame: InputFrame::find(mesh)?,
        ..inner
    })
}

/// The closest-point transfer from a face's stand-in to the face's own vertices.
fn stand_in_transfer(
    mesh: &FaceMesh,
    stand_in: &crate::copy::symmetrize::StandIn,
) -> Result<Transfer, PipelineError> {
    crate::copy::symmetrize::transfer_to_face(mesh, stand_in).ok_or(PipelineError::Transfer(
        crate::transfer::TransferError::EmptyCopy,
    ))
}

/// The simulated copy of a stand-in (`copy`, `None` for the whole stand-in) with its vertices
/// mapped to the face's own.
fn onto_face(
    copy: Option<&crate::copy::Simplified>,
    stand_in: &crate::copy::symmetrize::StandIn,
) -> crate::copy::Simplified {
    match copy {
        Some(c) => crate::copy::Simplified {
            original_vertex: c
                .original_vertex
                .iter()
                .map(|&v| stand_in.surface.original_vertex[v as usize])
                .collect(),
            ..c.clone()
        },
        None => stand_in.surface.clone(),
    }
}

/// [`prepare`] of the mesh as it is.
fn prepare_as_written(
    mesh: &FaceMesh,
    params: &PipelineParams,
) -> Result<PreparedRig, PipelineError> {
    let frame = InputFrame::find(mesh)?;
    let reduced =
        crate::copy::reduce::reduce(mesh, &frame, params.peel_rolled_in, &params.large_face)?;
    let (simulated, simplified) = match reduced.simplified {
        Some(s) => (
            FaceMesh::from_triangles(&s.vertices, &s.triangles)?,
            Some(s),
        ),
        None => (mesh.clone(), None),
    };
    let mut rig = FaceRig::build(&simulated, &params.rig)?;
    if let Some(boxes) = params.boxes {
        rig = rig.with_boxes(boxes)?;
    }
    if let Some(muscles) = &params.muscles {
        rig = rig.with_muscles(muscles.clone())?;
    }
    Ok(PreparedRig {
        simulated,
        simplified,
        rig,
        peeled_vertices: reduced.peeled_vertices,
        simplify_path: reduced.simplify_path,
        copy_fallback: reduced.copy_fallback,
        frame,
    })
}

/// The rig of `mesh` as [`build_face_model`] would simulate it (for `info`, muscle files,
/// editing). No BEM solve.
pub fn prep_rig(mesh: &FaceMesh, params: &PipelineParams) -> Result<FaceRig, PipelineError> {
    Ok(prepare(mesh, params)?.rig)
}

/// Builds the rig and the muscle basis of `mesh`.
///
/// Eyelids and lips rolled in behind their contours are peeled off the simulated surface
/// (`params.peel_rolled_in`), and large faces (more than `params.large_face.max_triangles`
/// front triangles) are simulated on a simplified copy; the displacements of such a reduced
/// copy are then carried to every vertex.
/// Progress of every stage goes to `control`; cancelling it stops the work at the next check
/// (the LU factorisation itself runs to completion once started).
///
/// A face that is mirror-symmetric in shape but not in its triangles is built as its
/// mirror-meshed stand-in ([`crate::copy::symmetrize`]), settled there, and its fields carried
/// to the face's own vertices (closest point, barycentric), so that left and right agree
/// whatever the triangulation.
pub fn build_face_model(
    mesh: &FaceMesh,
    params: &PipelineParams,
    control: &Control,
) -> Result<FaceModel, PipelineError> {
    let mut model = build_shape(mesh, params, control)?;
    keep_closed_lids(&mut model);
    Ok(model)
}

/// The lid controls of an eye that is closed in the neutral ([`crate::model::closed_eyes`]:
/// lids cut open along their contact line, [`FaceMesh::lid_lines`], or touching) leave it as it
/// is: blinking a closed eye would push its upper lid through the lower one, and raising the
/// lid of a closed eye pulls it open; the palpebral orbicularis and the levator of that side get
/// no response. (The squint's lower lid rises by a fraction of the opening,
/// [`face_prep::controls::eyelid::SQUINT_RISE_FRACTION`], so it leaves a closed eye alone by
/// itself. The rig still has the controls, so every named expression keeps its sliders.)
fn keep_closed_lids(model: &mut FaceModel) {
    use face_prep::MuscleKind;
    let [left, right] = crate::model::closed_eyes(&model.mesh, model.rig.canonical_from_input);
    let kinds = [
        (left, MuscleKind::OrbicularisOculiPalpebralL),
        (left, MuscleKind::LevatorPalpebraeL),
        (right, MuscleKind::OrbicularisOculiPalpebralR),
        (right, MuscleKind::LevatorPalpebraeR),
    ];
    for (closed, kind) in kinds {
        if closed && let Some(k) = model.basis.muscle_ids.iter().position(|id| id == kind.id()) {
            model.basis.displacements[k].fill(DVec3::ZERO);
        }
    }
}

/// [`build_face_model`] before the closed lids are kept still.
fn build_shape(
    mesh: &FaceMesh,
    params: &PipelineParams,
    control: &Control,
) -> Result<FaceModel, PipelineError> {
    params.validate()?;
    face_prep::check_not_scrambled(&mesh.vertices, &mesh.triangles)?;
    let Some(stand_in) = crate::copy::symmetrize::stand_in(mesh, params.outline_is_cut) else {
        return build_as_written(mesh, params, control);
    };
    let inner = build_as_written(&stand_in.mesh, params, control)?;
    let t = Instant::now();
    let transfer = stand_in_transfer(mesh, &stand_in)?;
    let displacements = inner
        .basis
        .displacements
        .iter()
        .map(|field| transfer.apply(&stand_in.surface, field))
        .collect();
    let copy = onto_face(inner.simplified.as_ref().map(|s| &s.mesh), &stand_in);
    let copy_transfer = Transfer::build(&mesh.vertices, &copy).ok_or(PipelineError::Transfer(
        crate::transfer::TransferError::EmptyCopy,
    ))?;
    let report = PrecomputeReport {
        input_triangles: mesh.triangles.len(),
        simplify_path: Some(SimplifyPath::of_stand_in(inner.report.simplify_path)),
        transfer_seconds: inner.report.transfer_seconds + t.elapsed().as_secs_f64(),
        ..inner.report
    };
    Ok(FaceModel {
        mesh: mesh.clone(),
        simplified: Some(crate::transfer::SimplifiedFace {
            mesh: copy,
            transfer: copy_transfer,
        }),
        basis: MuscleBasis {
            muscle_ids: inner.basis.muscle_ids,
            neutral: mesh.vertices.clone(),
            triangles: mesh.triangles.clone(),
            displacements,
        },
        report,
        ..inner
    })
}

/// [`build_face_model`] of the mesh as it is. A large face whose edge-collapse copy gives a
/// rig that is not trustworthy ([`crate::model::distrust`]) is built again on its remeshed
/// copy ([`crate::copy::CopyMethod::Remesh`]), and that rig is kept when it is trustworthy,
/// with the reason in [`PrecomputeReport::copy_fallback`] (a warning; [`FaceModel::params`]
/// stay the ones asked for, so the cache finds the model again): the two copies are two
/// discretisations of the same surface, and where the simplifier leaves a long triangle under
/// a thin shelf of tissue (the flipped ICT face's lower lids, `docs/journal.md`) the remesher's
/// near-equilateral triangles do not.
fn build_as_written(
    mesh: &FaceMesh,
    params: &PipelineParams,
    control: &Control,
) -> Result<FaceModel, PipelineError> {
    let model = build_one_copy(mesh, params, control)?;
    let copied = model.report.simplify_path.is_some_and(|p| p.is_collapse());
    if !copied || params.large_face.method != crate::copy::CopyMethod::Collapse {
        return Ok(model);
    }
    let causes = crate::model::distrust(&model);
    if causes.is_empty() {
        return Ok(model);
    }
    let mut remesh = params.clone();
    remesh.large_face.method = crate::copy::CopyMethod::Remesh;
    let other = build_one_copy(mesh, &remesh, control)?;
    if !crate::model::distrust(&other).is_empty() {
        return Ok(model);
    }
    let reason = format!(
        "the rig on the edge-collapse copy was not trustworthy ({})",
        causes.join("; ")
    );
    Ok(FaceModel {
        params: params.clone(),
        report: PrecomputeReport {
            copy_fallback: Some(reason),
            ..other.report
        },
        ..other
    })
}

/// One build of the mesh as it is, on the copy `params` ask for.
fn build_one_copy(
    mesh: &FaceMesh,
    params: &PipelineParams,
    control: &Control,
) -> Result<FaceModel, PipelineError> {
    let t0 = Instant::now();
    control.report(Stage::Prep, 0, 1);
    let PreparedRig {
        simulated,
        simplified,
        rig,
        peeled_vertices,
        simplify_path,
        copy_fallback,
        frame,
    } = prepare_as_written(mesh, params)?;
    if rig.muscles.is_empty() {
        return Err(PipelineError::NoMuscles);
    }
    let shell_self_intersections = rig.shell.self_intersections().len();
    control.report(Stage::Prep, 1, 1);
    check_cancel(control)?;
    let prep_seconds = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let solved = crate::solve::solve_rig(&rig, params.poisson, params.quadrature, control)?;
    let solve_seconds = t1.elapsed().as_secs_f64();
    check_cancel(control)?;

    let t2 = Instant::now();
    control.report(Stage::Transfer, 0, 1);
    let face = frame.in_rig(&rig, mesh);
    let (mut displacements, simplified) = crate::transfer::carry_to_input(
        mesh,
        &rig,
        &face,
        &simulated,
        simplified,
        &peeled_vertices,
        &solved.vertex,
    )?;
    control.report(Stage::Transfer, 1, 1);
    control.report(Stage::Settle, 0, 1);
    let muscle_ids: Vec<String> = rig.muscles.iter().map(muscle_id).collect();
    crate::settle::settle(
        mesh,
        &rig,
        &face,
        crate::settle::Simulation {
            simplified: simplified.as_ref(),
            simulated: &simulated,
            peeled: &peeled_vertices,
        },
        &muscle_ids,
        &mut displacements,
    );
    control.report(Stage::Settle, 1, 1);
    let basis = MuscleBasis {
        muscle_ids,
        neutral: mesh.vertices.clone(),
        triangles: mesh.triangles.clone(),
        displacements,
    };
    let (force_peak_control, force_peak_ratio) = solved
        .force_peak_ratio
        .iter()
        .zip(&basis.muscle_ids)
        .filter_map(|(r, id)| r.map(|r| (id.clone(), r)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or_default();
    let report = PrecomputeReport {
        input_triangles: mesh.triangles.len(),
        force_peak_ratio,
        force_peak_control,
        simulated_triangles: simulated.triangles.len(),
        simplify_path,
        copy_fallback,
        shell_elements: rig.shell.triangles.len(),
        dofs: 3 * rig.shell.triangles.len(),
        shell_self_intersections,
        response_amplification: response_amplification(&rig, &solved),
        condition_estimate: solved.report.condition_estimate,
        quadrature_unconverged: solved.report.quadrature.unconverged_blocks,
        quadrature_worst_error: solved
            .report
            .quadrature
            .worst
            .map_or(0.0, |w| w.estimated_error),
        prep_seconds,
        solve_seconds,
        transfer_seconds: t2.elapsed().as_secs_f64(),
    };
    Ok(FaceModel {
        mesh: mesh.clone(),
        obj_source: None,
        rig,
        simplified,
        basis,
        shell_element_response: solved.element,
        shell_vertex_response: solved.vertex,
        params: params.clone(),
        report,
    })
}

/// [`PrecomputeReport::response_amplification`]: the largest ratio, over the controls, of a
/// response's largest element motion to the motion its pattern prescribes.
fn response_amplification(rig: &FaceRig, solved: &Solved) -> f64 {
    (0..rig.muscles.len())
        .map(|k| {
            // A force-driven control's pattern is a traction: its response is compared with
            // the front displacement it was scaled to (a near-singular shell answers with far
            // larger motion inside the shell than on the face).
            let prescribed = rig.force_target(k).unwrap_or_else(|| {
                rig.muscle_pattern(k)
                    .iter()
                    .map(|(_, d)| d.length())
                    .fold(0.0, f64::max)
            });
            let response = solved.element[k]
                .iter()
                .map(|u: &DVec3| u.length())
                .fold(0.0, f64::max);
            if prescribed > 0.0 {
                response / prescribed
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

/// Identifier of a muscle ([`face_prep::Muscle::id`]): its standard id, else its name.
fn muscle_id(m: &face_prep::Muscle) -> String {
    m.id().to_owned()
}

fn check_cancel(control: &Control) -> Result<(), PipelineError> {
    if control.is_cancelled() {
        Err(PipelineError::Cancelled)
    } else {
        Ok(())
    }
}
