//! The solve stage: the rig's shell, skull and muscle patterns → one response per control, by
//! bem-core's constant-element BEM (one dense LU, one right-hand side per control; the maths is in
//! `docs/design/solve.md`), with the modiolus pins (`modiolus_pin`) and the force-driven
//! controls scaled to their targets.

use std::sync::atomic::AtomicBool;

use bem_core::{ElementKind, Material, QuadratureParams, ResponseBasis, SolveParams, SurfaceMesh};
use face_prep::FaceRig;
use face_prep::muscle_kind::Generator;
use face_prep::muscle_model::MuscleModel;
use glam::DVec3;

use crate::control::{Control, Stage};
use modiolus_pin::ModiolusCases;

pub(crate) mod modiolus_pin;

/// Errors of the solve stage.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SolveError {
    /// The BEM solve failed.
    #[error("BEM solve: {0}")]
    Bem(#[from] bem_core::BemError),
    /// The shell is not a valid closed surface for the BEM.
    #[error("shell: {0}")]
    Shell(#[from] bem_core::MeshError),
    /// The caller cancelled the computation.
    #[error("cancelled")]
    Cancelled,
}

/// Responses of the shell to each muscle at slider = 1 (canonical frame).
pub(crate) struct Solved {
    /// `element[k][e]`: displacement of shell element `e` (at its centroid) for muscle `k`.
    pub element: Vec<Vec<DVec3>>,
    /// `vertex[k][v]`: per shell vertex, from the adjacent elements (a linear fit in the
    /// anatomical model, [`bem_core::element_to_vertex_linear`]; the area-weighted average in
    /// the thesis model).
    pub vertex: Vec<Vec<DVec3>>,
    /// What bem-core measured about the solve (condition estimate, quadrature accuracy).
    pub report: bem_core::SolveReport,
    /// Per control: for a force-driven band muscle, its largest front displacement (its target) over
    /// the traction-weighted mean displacement of the elements it loads
    /// ([`force_peak_ratio`]); `None` for the others.
    pub force_peak_ratio: Vec<Option<f64>>,
}

/// Solves the rig's BEM problem: skull elements fixed at zero, every element of a
/// displacement-driven muscle displacement-prescribed (zero, except in its own muscle's
/// right-hand side, where it follows the muscle's pattern), the deep layer on the teeth sliding
/// ([`face_prep::teeth`]), all other elements traction-type: free, except a force-driven
/// control's elements in its own right-hand side ([`face_prep::force_controls`]; that response
/// is scaled to its target). One LU, one right-hand side per control.
pub(crate) fn solve_rig(
    rig: &FaceRig,
    poisson: f64,
    quadrature: QuadratureParams,
    control: &Control,
) -> Result<Solved, SolveError> {
    let mesh = SurfaceMesh::new(rig.shell.vertices.clone(), rig.shell.triangles.clone())?;
    let material = Material::new(poisson, 1.0)?;
    let kinds = element_kinds(rig, mesh.element_count());
    // A muscle that pins a modiolus gets its response from the modiolus's unit load cases
    // (its own case stays empty; crate::solve::modiolus_pin).
    let modiolus = ModiolusCases::plan(rig, &kinds, rig.muscles.len());
    let mut groups = load_groups(rig, &mesh, &kinds, &modiolus);
    groups.extend(modiolus.load_cases());
    let basis = run_bem(rig, &mesh, &material, &kinds, &groups, quadrature, control)?;
    let report = basis.report;
    let element: Vec<Vec<DVec3>> = basis
        .responses
        .into_iter()
        .map(|s| s.displacement)
        .collect();
    let mut element = element;
    modiolus.apply(&mut element)?;
    groups.truncate(rig.muscles.len());
    let prescribed: Vec<bool> = kinds
        .iter()
        .map(|&k| k == ElementKind::Displacement)
        .collect();
    // Vertex values: the anatomical model fits them linearly over each smooth vertex's
    // adjacent elements, so a coarse copy's large elements do not bias them (a one-vertex peak
    // of the frontalis on ICT 2500's copy turned the brow line over); the thesis model keeps
    // the plain area-weighted average, reproducing its basis bit for bit.
    let to_vertex = |u: &[DVec3]| {
        if rig.params.muscle_model == MuscleModel::Anatomical {
            bem_core::element_to_vertex_linear(&mesh, u, &prescribed)
        } else {
            bem_core::element_to_vertex(&mesh, u)
        }
    };
    let mut vertex: Vec<Vec<DVec3>> = element
        .iter()
        .map(|u| to_vertex(u))
        .collect::<Result<_, _>>()?;
    let peak_ratio =
        scale_force_responses(rig, &mesh, &modiolus, &groups, &mut element, &mut vertex);
    if rig.params.muscle_model == MuscleModel::Anatomical {
        hold_bone_vertices(rig, &mut vertex);
    }
    lip_seal(rig, &mut element, &mut vertex);
    Ok(Solved {
        element,
        vertex,
        report,
        force_peak_ratio: peak_ratio,
    })
}

/// The boundary condition type of every shell element: skull and displacement-driven muscles
/// prescribed, the deep layer on the teeth sliding, the rest traction-type (force-driven
/// controls load traction-type elements, free in every other response).
fn element_kinds(rig: &FaceRig, n: usize) -> Vec<ElementKind> {
    let mut kinds = vec![ElementKind::Traction; n];
    for &e in &rig.skull {
        kinds[e as usize] = ElementKind::Displacement;
    }
    // Force-driven controls load traction-type elements (free in every other response).
    for (k, m) in rig.muscles.iter().enumerate() {
        if !rig.is_force_control(k) {
            for e in m.elements() {
                kinds[e as usize] = ElementKind::Displacement;
            }
        }
    }
    // The deep layer on the teeth slides ([`face_prep::teeth`]; disjoint from the above).
    for e in rig.sliding_elements() {
        kinds[e as usize] = ElementKind::Sliding;
    }
    kinds
}

/// One right-hand side per control: its pattern, with a sliding element's share projected
/// (a force along the teeth, a displacement along their normal); empty for a pinned control.
fn load_groups(
    rig: &FaceRig,
    mesh: &SurfaceMesh,
    kinds: &[ElementKind],
    modiolus: &ModiolusCases,
) -> Vec<Vec<(usize, DVec3)>> {
    (0..rig.muscles.len())
        .map(|k| {
            if modiolus.is_pinned(k) {
                return Vec::new();
            }
            let force = rig.is_force_control(k);
            rig.muscle_pattern(k)
                .into_iter()
                .map(|(e, d)| {
                    let e = e as usize;
                    if kinds[e] != ElementKind::Sliding {
                        return (e, d);
                    }
                    // On a sliding element a force pulls along the teeth (its tangential part);
                    // a displacement (the jaw's lower teeth) moves it along their normal.
                    let normal = mesh.normal(e);
                    let along_normal = normal * d.dot(normal);
                    (
                        e,
                        if force {
                            d - along_normal
                        } else {
                            along_normal
                        },
                    )
                })
                .collect()
        })
        .collect()
}

/// bem-core's solve of every right-hand side, with progress and cancellation through `control`.
fn run_bem(
    rig: &FaceRig,
    mesh: &SurfaceMesh,
    material: &Material,
    kinds: &[ElementKind],
    groups: &[Vec<(usize, DVec3)>],
    quadrature: QuadratureParams,
    control: &Control,
) -> Result<ResponseBasis, SolveError> {
    let progress = |p: bem_core::Progress| {
        let stage = match p.stage {
            bem_core::Stage::Assembly => Stage::Assembly,
            bem_core::Stage::Factorisation => Stage::Factorisation,
            // The solves, and any later stage bem-core adds.
            _ => Stage::Solves,
        };
        control.report(stage, p.done as u64, p.total as u64);
    };
    let flag: &AtomicBool = control.flag();
    let bem_control = bem_core::Control {
        cancel: Some(flag),
        progress: Some(&progress),
    };
    // The thesis model reproduces its basis bit for bit: f64 LU. The anatomical model solves
    // in mixed precision (the LU in f32, refined to f64 accuracy; bem_core::MixedLu).
    let precision = match rig.params.muscle_model {
        MuscleModel::Thesis => bem_core::Precision::Double,
        // The anatomical model, and any later one: the faster default.
        _ => bem_core::Precision::Mixed,
    };
    let params = SolveParams {
        quadrature,
        precision,
        ..SolveParams::default()
    };
    ResponseBasis::compute(mesh, material, kinds, groups, &params, &bem_control).map_err(
        |e| match e {
            bem_core::BemError::Cancelled => SolveError::Cancelled,
            e => SolveError::Bem(e),
        },
    )
}

/// A force has no unit: scales each force-driven response (element and vertex values) to its
/// target, the largest front-surface displacement of the muscle's full contraction. Returns the
/// band muscles' [`force_peak_ratio`] (`None` for the other controls).
fn scale_force_responses(
    rig: &FaceRig,
    mesh: &SurfaceMesh,
    modiolus: &ModiolusCases,
    groups: &[Vec<(usize, DVec3)>],
    element: &mut [Vec<DVec3>],
    vertex: &mut [Vec<DVec3>],
) -> Vec<Option<f64>> {
    let front_vertices = rig.face_vertex_count.min(rig.shell.vertices.len());
    // Both recoveries commute with a positive scale, so the vertex values are scaled with the
    // element values instead of being recovered again.
    let mut peak_ratio = vec![None; element.len()];
    for (k, (field, at_vertices)) in element.iter_mut().zip(vertex.iter_mut()).enumerate() {
        // A pinned response already moves by its pin (a length): nothing to scale.
        if modiolus.is_pinned(k) {
            continue;
        }
        if let Some(target) = rig.force_target(k) {
            let factor =
                face_prep::force_controls::scale_to_target(&at_vertices[..front_vertices], target);
            for u in field.iter_mut().chain(at_vertices.iter_mut()) {
                *u *= factor;
            }
            // Band muscles only: a sphincter's ring pulls toward the mouth's centre from every
            // side, so its tissue's mean motion along the pull is small by construction (2.2-4.3
            // times its largest motion on the bundled faces), and the cheek puff is a pressure.
            let band = rig.muscles[k]
                .kind
                .is_some_and(|kind| matches!(kind.generator(), Generator::Force(_)));
            if band {
                peak_ratio[k] = Some(force_peak_ratio(mesh, &groups[k], field, target));
            }
        }
    }
    peak_ratio
}

/// The lip seal's response ([`face_prep::lip_seal`]): at slider +1, `jaw_open`'s response
/// times minus the seal's share at each element centroid and shell vertex, so `jaw_open` +
/// `lip_seal` at full value takes the share of the jaw's motion back. Nothing for a rig without
/// both controls.
fn lip_seal(rig: &FaceRig, element: &mut [Vec<DVec3>], vertex: &mut [Vec<DVec3>]) {
    let Some((seal, jaw)) = rig.lip_seal_controls() else {
        return;
    };
    let centroids: Vec<DVec3> = (0..rig.shell.element_count())
        .map(|e| rig.shell.centroid(e))
        .collect();
    let take_back = face_prep::lip_seal::take_back;
    take_back(element, seal, jaw, &rig.lip_seal_shares(&centroids));
    take_back(vertex, seal, jaw, &rig.lip_seal_shares(&rig.shell.vertices));
}

/// Anatomical model: a vertex of a fixed (skull) element is on bone, the outer contour on the
/// fixed rim, so a face's cut line stays put (the thesis model keeps the plain element average,
/// reproducing its basis bit for bit) — except where a control moves the bone: the jaw
/// segment's vertices (its part of the contour included) move rigidly with the jaw in the jaw's
/// own responses.
fn hold_bone_vertices(rig: &FaceRig, vertex: &mut [Vec<DVec3>]) {
    for &e in &rig.skull {
        for &v in &rig.shell.triangles[e as usize] {
            for field in vertex.iter_mut() {
                field[v as usize] = DVec3::ZERO;
            }
        }
    }
    for (k, field) in vertex.iter_mut().enumerate() {
        for (v, d) in rig.prescribed_vertex_motion(k) {
            field[v as usize] = d;
        }
    }
}

/// How far a force-driven response's largest motion `peak` stands out from the motion of the
/// tissue the force pulls: `peak` over the traction-weighted mean displacement along the pull,
/// Σ aₑ tₑ·uₑ / Σ aₑ |tₑ| over the loaded elements (`loads`: element and traction; `field`:
/// element displacements; aₑ the element areas). About 1–2 when the muscle's own tissue moves
/// as far as anything; large when a few elements elsewhere (a sliver strip, a flap at the lips'
/// knife edge) move far more and, as the largest motion, set the response's scale. Infinite
/// when the loaded tissue moves against its pull on average.
pub(crate) fn force_peak_ratio(
    mesh: &SurfaceMesh,
    loads: &[(usize, DVec3)],
    field: &[DVec3],
    peak: f64,
) -> f64 {
    let (mut along, mut weight) = (0.0, 0.0);
    for &(e, t) in loads {
        let (Some(u), a) = (field.get(e), mesh.area(e)) else {
            continue;
        };
        along += a * t.dot(*u);
        weight += a * t.length();
    }
    if weight > 0.0 && along > 0.0 {
        peak / (along / weight)
    } else {
        f64::INFINITY
    }
}
