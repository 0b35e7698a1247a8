//! The passes that settle the responses after the transfer: where a response would turn
//! triangles of the user's mesh over, [`crate::settle::untangle`] relaxes it, region by region and
//! slider direction by slider direction, with the lid closure (`lid_closure`) in
//! between. The thesis model keeps its responses as solved (only the lid closure's passes run).

use face_prep::{FaceLoops, FaceMesh, FaceRig};
use glam::DVec3;

use crate::copy::Simplified;
use crate::frame::CanonicalFace;
use crate::transfer::SimplifiedFace;

pub mod injective;
mod lid_closure;
pub mod untangle;

/// What a face was simulated on: the copy of a large face (`simplified`, with `simulated` its
/// welded mesh; `None` when the face itself was simulated) and the input vertices peeled off for
/// the simulation (rolled-in lips, [`crate::copy::rolled_in`]).
#[derive(Clone, Copy)]
pub(crate) struct Simulation<'a> {
    pub(crate) simplified: Option<&'a SimplifiedFace>,
    pub(crate) simulated: &'a FaceMesh,
    pub(crate) peeled: &'a [u32],
}

/// Runs every settling pass on `displacements` (one field per control of `rig`, on `mesh`'s
/// vertices, named `muscle_ids`), in order: the lips relaxed, squints kept open and blinks
/// closed, the lids and lips relaxed again, the lips' orientation kept ([`injective`]), the
/// sphincter's sum, the mid and lower face, the forehead in both slider directions, the lids'
/// orientation kept ([`injective`]), and the brow lowerers in their combinations; last, the lip
/// seal made again from the settled jaw.
pub(crate) fn settle(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    sim: Simulation<'_>,
    muscle_ids: &[String],
    displacements: &mut [Vec<DVec3>],
) {
    let Simulation {
        simplified,
        simulated,
        peeled,
    } = sim;
    let anatomical = rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical;
    if anatomical {
        relax_each(mesh, rig, &untangle_fixed(mesh, rig, face), displacements);
    }
    lid_closure::keep_squints_open(rig, mesh, face, muscle_ids, displacements);
    lid_closure::close_blinks(
        rig,
        mesh,
        face,
        simplified.map(|s| (&s.mesh, simulated)),
        muscle_ids,
        displacements,
    );
    if !anatomical {
        return;
    }
    let lids_closed = closed_lids_fixed(mesh, rig, face, simplified.map(|s| &s.mesh));
    relax_each(mesh, rig, &lids_closed, displacements);
    project_at_the_lips(mesh, rig, face, displacements);
    relax_sphincter_sum(mesh, rig, muscle_ids, &lids_closed, displacements);
    let fixed = beyond_lips_and_lids_fixed(mesh, rig, face, Forehead::Fixed);
    relax_each(mesh, rig, &fixed, displacements);
    relax_each_guarded(mesh, rig, &fixed, Direction::Lengthened, displacements);
    let forehead_free = beyond_lips_and_lids_fixed(mesh, rig, face, Forehead::Free);
    relax_each_guarded(
        mesh,
        rig,
        &forehead_free,
        Direction::Contraction,
        displacements,
    );
    relax_each_guarded(
        mesh,
        rig,
        &forehead_free,
        Direction::HalfLengthened,
        displacements,
    );
    project_at_the_lids(mesh, rig, face, displacements);
    relax_brow_lowerers(mesh, rig, face, muscle_ids, displacements);
    seal_from_settled_jaw(mesh, rig, face, peeled, displacements);
}

/// The lip seal's field is a share of `jaw_open`'s ([`face_prep::lip_seal`]): made again here
/// from the settled `jaw_open`, so that the two stay in step where the passes relaxed the jaw
/// (the seal relaxed on its own would not take back the jaw's relaxed patches: a jagged seam
/// from the mouth corners across the cheeks on ICT 13k). The rolled-in lips peeled off for the
/// simulation (`peeled`) take their margins' shares, as their fields hang from the margins
/// ([`crate::copy::rolled_in::hang_from_margins`]): seen from the front, a lower lip rolled in
/// lies behind the upper one, where the share by position would leave it with the jaw. Nothing
/// for a rig without both.
fn seal_from_settled_jaw(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    peeled: &[u32],
    displacements: &mut [Vec<DVec3>],
) {
    let Some((seal, jaw)) = rig.lip_seal_controls() else {
        return;
    };
    let mut shares: Vec<DVec3> = rig
        .lip_seal_shares(&face.points)
        .into_iter()
        .map(DVec3::splat)
        .collect();
    crate::copy::rolled_in::hang_from_margins(&mut shares, &mesh.triangles, peeled);
    let shares: Vec<f64> = shares.iter().map(|w| w.x).collect();
    face_prep::lip_seal::take_back(displacements, seal, jaw, &shares);
}

/// Relaxes every response where it turns triangles over, moving only the vertices not in
/// `fixed` ([`untangle::relax_inversions`], patches of [`untangle::PATCH_MM`]).
fn relax_each(mesh: &FaceMesh, rig: &FaceRig, fixed: &[bool], displacements: &mut [Vec<DVec3>]) {
    use rayon::prelude::*;
    let patch_radius = untangle::PATCH_MM / rig.mm_per_unit();
    // Each response on its own: in parallel, the same result as in sequence.
    displacements.par_iter_mut().for_each(|field| {
        untangle::relax_inversions(&mesh.vertices, &mesh.triangles, field, fixed, patch_radius);
    });
}

/// Corrects every response within [`untangle::LIPS_MM`] of the mouth loop by
/// [`injective::project`]: the smoothest change, spread over [`injective::SCREENING_MM`], that
/// keeps the lips' triangles from turning over at full contraction and at full lengthening
/// (both slider directions; the jaw's sideways field is `jawLeft` one way and `jawRight` the
/// other). The outer contour, the eye loops and the mouth corners keep their values, and so
/// does everything farther from the lips. A response that folds nothing there is left exactly
/// as it is.
///
/// On the four bundled faces it takes every control's turned triangles at the lips to none
/// (ICT 13k's `jaw_forward` 40, `jaw_open` 24, the sphincter's lower half 38; ICT 2500's 7, 4
/// and 6), the lip seal's from 364 / 56 / 52 / 23 to 141 / 22 / 36 / 18 (ICT 13k / ICT 2500 /
/// Lee Perry-Smith / MediaPipe), and no preset's up (`cargo run --release -p facebem-tools
/// --bin flip_report`).
fn project_at_the_lips(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    displacements: &mut [Vec<DVec3>],
) {
    let fixed = untangle_fixed(mesh, rig, face);
    let params = injective::ProjectionParams::default();
    project_each(mesh, rig, &fixed, &params, displacements);
}

/// [`injective::project`] on every response (in parallel: each on its own), moving only the
/// vertices not in `fixed`.
fn project_each(
    mesh: &FaceMesh,
    rig: &FaceRig,
    fixed: &[bool],
    params: &injective::ProjectionParams,
    displacements: &mut [Vec<DVec3>],
) {
    use rayon::prelude::*;
    let screening = injective::SCREENING_MM / rig.mm_per_unit();
    let surface = injective::Surface::new(&mesh.vertices, &mesh.triangles, fixed, screening);
    displacements.par_iter_mut().for_each(|field| {
        injective::project(&surface, params, field);
    });
}

/// Corrects every response within [`untangle::LIDS_MM`] of an eye loop by [`injective::project`],
/// as [`project_at_the_lips`] does at the lips: the smoothest change that keeps the lids'
/// triangles from turning over at full contraction and at half lengthening. The eye loops
/// (closed exactly by the blink), the outer contour and the mouth corners keep their values, and
/// so does everything farther from the eyes. Half lengthening, not full: named expressions
/// lengthen a muscle by at most half (`browDownLeft`'s frontalis), and holding the lids at a
/// full lengthening that nothing uses moved ICT 2500's lateral frontalis 30 mm at the lid (the
/// penalty's smoothest correction of a fold no expression makes).
///
/// It replaced a relaxation pass over the lids and forehead at half lengthening. Every blink
/// then turns no triangle over on the four bundled faces (ICT 13k's `blink` 50, each
/// `eyeBlink*` 25; ICT 2500's 9 and 6 / 3; Lee Perry-Smith's 6 and 3 / 3; MediaPipe's 2 and
/// 1 / 1; `cargo run --release -p facebem-tools --bin flip_report -- --named`). It runs before
/// the brow lowerers' pass, which relaxes the corrugator in its combination with the fields
/// as corrected here (run after it, `browDownLeft` turned 1–2 triangles over beside the inner
/// canthus on ICT 13k and Lee Perry-Smith).
fn project_at_the_lids(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    displacements: &mut [Vec<DVec3>],
) {
    let fixed = lids_fixed(mesh, rig, face);
    let params = injective::ProjectionParams {
        slider_values: [-1.0, 0.5],
        ..Default::default()
    };
    project_each(mesh, rig, &fixed, &params, displacements);
}

/// Vertices [`project_at_the_lids`] leaves as they are: everything farther than
/// [`untangle::LIDS_MM`] from both eye loops, the outer contour, the eye loops and the mouth
/// corners.
fn lids_fixed(mesh: &FaceMesh, rig: &FaceRig, face: &CanonicalFace) -> Vec<bool> {
    let (loops, canonical) = (&face.loops, &face.points);
    let (_, eye_l, eye_r) = front_loops(loops, canonical);
    let reach = untangle::LIDS_MM / rig.mm_per_unit();
    let distance = face_prep::muscle_model::distance_to_loop;
    let mut fixed = vec![true; mesh.vertices.len()];
    for (f, p) in fixed.iter_mut().zip(canonical) {
        let p = p.truncate();
        *f = distance(p, &eye_l).min(distance(p, &eye_r)) > reach;
    }
    fix_contours_and_corners(&mut fixed, loops, canonical);
    fixed
}

/// Which way a response is relaxed by [`relax_each_guarded`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum Direction {
    /// The field as it is (full contraction).
    Contraction,
    /// The negated field (slider +1, the muscle lengthened past rest, which named expressions
    /// use: `mouthClose` lengthens the levator labii superioris by 0.4).
    Lengthened,
    /// The negated field at half value (`browDownLeft` lengthens the frontalis by 0.5): only
    /// what turns over at that value is relaxed.
    HalfLengthened,
}

/// Relaxes one direction of every response ([`untangle::relax_inversions`] of the field
/// or of its negation, moving only the vertices not in `fixed`), kept only if the other
/// direction then turns no more triangles over: one field serves both slider directions, and
/// smoothing where one turns triangles over can turn the other's over.
///
/// Regressions: ICT 2500's `mouthClose` turned 3 triangles over at the nostrils, 21–22 mm from
/// the lips, every one of them from the lengthened levator labii superioris (the lengthened
/// pass); its `surprised` turned 5 over on the brow line, 13–17 mm above the eye loops, at the
/// frontalis's one-vertex peaks (the contraction pass over the forehead); its `browDownLeft`
/// turned one over 9 mm above the eye loop, from the frontalis lengthened by half (the
/// half-lengthened pass over the forehead; relaxed at full value there instead, MediaPipe's
/// brow raise fell from 10.6 to 7.5 mm). ICT 13k's `disgust` (the frontalis lengthened by 0.3)
/// turned 16 upper-lid triangles over, 6–7 mm above the eye loops (a half-lengthened pass over
/// the lids and forehead, replaced since by [`project_at_the_lids`]: none there).
fn relax_each_guarded(
    mesh: &FaceMesh,
    rig: &FaceRig,
    fixed: &[bool],
    direction: Direction,
    displacements: &mut [Vec<DVec3>],
) {
    use rayon::prelude::*;
    let patch_radius = untangle::PATCH_MM / rig.mm_per_unit();
    let (sign, value) = match direction {
        Direction::Contraction => (1.0, 1.0),
        Direction::Lengthened => (-1.0, 1.0),
        Direction::HalfLengthened => (-1.0, 0.5),
    };
    // The other direction at full and at half value (named expressions use both).
    let turned_other = |f: &[DVec3]| -> [usize; 2] {
        [1.0, 0.5].map(|value| {
            let other: Vec<DVec3> = f.iter().map(|u| *u * (-sign * value)).collect();
            untangle::turned_over(&mesh.vertices, &mesh.triangles, &other).len()
        })
    };
    displacements.par_iter_mut().for_each(|field| {
        let mut relaxed: Vec<DVec3> = field.iter().map(|u| *u * (sign * value)).collect();
        let moved = untangle::relax_inversions(
            &mesh.vertices,
            &mesh.triangles,
            &mut relaxed,
            fixed,
            patch_radius,
        );
        if moved == 0 {
            return;
        }
        for u in &mut relaxed {
            *u /= sign * value;
        }
        let (after, before) = (turned_other(&relaxed), turned_other(field));
        if after[0] <= before[0] && after[1] <= before[1] {
            *field = relaxed;
        }
    });
}

/// `mouthPucker` contracts both halves of the mouth's sphincter at once: their sum is relaxed
/// as one field ([`untangle::relax_sum`]), moving only the vertices not in `fixed` (the
/// second pass's: lips and lids free; ICT 2500: 17 turned triangles → 11).
fn relax_sphincter_sum(
    mesh: &FaceMesh,
    rig: &FaceRig,
    muscle_ids: &[String],
    fixed: &[bool],
    displacements: &mut [Vec<DVec3>],
) {
    let find = |kind: face_prep::MuscleKind| muscle_ids.iter().position(|id| id == kind.id());
    let (Some(upper), Some(lower)) = (
        find(face_prep::MuscleKind::OrbicularisOrisUpper),
        find(face_prep::MuscleKind::OrbicularisOrisLower),
    ) else {
        return;
    };
    let patch_radius = untangle::PATCH_MM / rig.mm_per_unit();
    let (first, second) = displacements.split_at_mut(upper.max(lower));
    let (a, b) = (&mut first[upper.min(lower)], &mut second[0]);
    untangle::relax_sum(&mesh.vertices, &mesh.triangles, a, b, fixed, patch_radius);
}

/// Vertices [`untangle::relax_inversions`] leaves as solved: everything farther than
/// [`untangle::LIPS_MM`] from the mouth loop (a turned triangle there is a defect to
/// see, not a lip folding), the outer contour, the eye loops and the mouth corners.
fn untangle_fixed(mesh: &FaceMesh, rig: &FaceRig, face: &CanonicalFace) -> Vec<bool> {
    let mut fixed = vec![true; mesh.vertices.len()];
    let (loops, canonical) = (&face.loops, &face.points);
    let mouth: Vec<glam::DVec2> = loops
        .mouth
        .iter()
        .filter_map(|&v| canonical.get(v as usize).map(|p| p.truncate()))
        .collect();
    let reach = untangle::LIPS_MM / rig.mm_per_unit();
    for (f, p) in fixed.iter_mut().zip(canonical) {
        *f = face_prep::muscle_model::distance_to_loop(p.truncate(), &mouth) > reach;
    }
    fix_contours_and_corners(&mut fixed, loops, canonical);
    fixed
}

/// Flags the outer contour, the eye loops and the mouth corners (`canonical`: the mesh's
/// vertices in the rig's canonical frame) as fixed for the relaxation passes.
fn fix_contours_and_corners(fixed: &mut [bool], loops: &FaceLoops, canonical: &[DVec3]) {
    let corners = crate::frame::mouth_corners(canonical, &loops.mouth)
        .map(|(l, r)| vec![l, r])
        .unwrap_or_default();
    for &v in loops
        .face
        .iter()
        .chain(&loops.eye_l)
        .chain(&loops.eye_r)
        .chain(&corners)
    {
        if let Some(f) = fixed.get_mut(v as usize) {
            *f = true;
        }
    }
}

/// The lowest canonical y of two polylines (the eye loops' lowest point).
fn lowest_y(a: &[glam::DVec2], b: &[glam::DVec2]) -> f64 {
    a.iter().chain(b).map(|p| p.y).fold(f64::INFINITY, f64::min)
}

/// The mouth and eye loops (left, right) as polylines in the canonical front plane.
fn front_loops(
    loops: &FaceLoops,
    canonical: &[DVec3],
) -> (Vec<glam::DVec2>, Vec<glam::DVec2>, Vec<glam::DVec2>) {
    let front = |lp: &[u32]| -> Vec<glam::DVec2> {
        lp.iter()
            .filter_map(|&v| canonical.get(v as usize).map(|p| p.truncate()))
            .collect()
    };
    (
        front(&loops.mouth),
        front(&loops.eye_l),
        front(&loops.eye_r),
    )
}

/// Whether [`beyond_lips_and_lids_fixed`] leaves the upper face (above the eyes' lowest
/// point) as it is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Forehead {
    /// Relaxed with the mid and lower face.
    Free,
    /// Left as solved.
    Fixed,
}

/// Vertices the last [`untangle::relax_inversions`] passes leave alone. They relax the
/// face beyond the lips and lids, where the lip elevators fold the skin at the nasolabial fold
/// and the nose's wing (Lee Perry-Smith's noseSneer and mouthUpperUp: 6 / 11 and 5 / 7 turned
/// triangles 13–30 mm from the lips, none after) and, with [`Forehead::Free`], where the
/// frontalis's brow raise turns the brow line over (ICT 2500's `surprised`: 5 turned triangles
/// 13–17 mm above the eye loops, none after; its brow points rise 10.0 / 9.2 mm at full
/// frontalis). Fixed: the lips and lids (within [`untangle::LIPS_MM`] of the mouth
/// loop or [`untangle::LIDS_MM`] of an eye loop; the earlier passes relaxed them), the
/// outer contour, the mouth corners and, with [`Forehead::Fixed`], every vertex above
/// `LIDS_MM` below the eye loops' lowest point.
fn beyond_lips_and_lids_fixed(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    forehead: Forehead,
) -> Vec<bool> {
    let mut fixed = vec![true; mesh.vertices.len()];
    let (loops, canonical) = (&face.loops, &face.points);
    let (mouth, eye_l, eye_r) = front_loops(loops, canonical);
    let lips = untangle::LIPS_MM / rig.mm_per_unit();
    let lids = untangle::LIDS_MM / rig.mm_per_unit();
    let eyes_bottom = lowest_y(&eye_l, &eye_r);
    let distance = face_prep::muscle_model::distance_to_loop;
    for (f, p) in fixed.iter_mut().zip(canonical) {
        let p = p.truncate();
        *f = (forehead == Forehead::Fixed && p.y > eyes_bottom - lids)
            || distance(p, &mouth) <= lips
            || distance(p, &eye_l).min(distance(p, &eye_r)) <= lids;
    }
    fix_contours_and_corners(&mut fixed, loops, canonical);
    fixed
}

/// The ARKit expressions whose brow lowerer [`relax_brow_lowerers`] relaxes in their
/// combination, with the control that takes the change (the expression's corrugator).
const BROW_LOWERING: [(&str, face_prep::MuscleKind); 2] = [
    ("browDownLeft", face_prep::MuscleKind::CorrugatorSuperciliiL),
    (
        "browDownRight",
        face_prep::MuscleKind::CorrugatorSuperciliiR,
    ),
];

/// A last pass over the brow lowerers. The corrugator pulls the skin over the frontal bone,
/// a thin layer on the skull whose motion stays where its traction is: it gathers beside the
/// inner canthus, and `browDownLeft`'s relaxed frontalis pushes the brow down onto it, turning
/// triangles over 12–21 mm from the eye (ICT 13k: 28 turned, 6 of them there; Lee Perry-Smith
/// 10 / 12; MediaPipe 4, the largest motion a 21 mm spike). Each corrugator is relaxed in its
/// `browDown*` combination ([`untangle::relax_in_combination`]; `angry` uses the same
/// ratio of the two), then alone, over the upper face ([`above_the_eyes_fixed`]); the
/// frontalis stays as solved (its brow raise is calibrated).
fn relax_brow_lowerers(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    muscle_ids: &[String],
    displacements: &mut [Vec<DVec3>],
) {
    let fixed = above_the_eyes_fixed(rig, face);
    let patch_radius = untangle::PATCH_MM / rig.mm_per_unit();
    for (name, carrier) in BROW_LOWERING {
        let Some(k) = muscle_ids.iter().position(|id| id == carrier.id()) else {
            continue;
        };
        let Some(resolved) = crate::expressions::find(name).and_then(|e| e.resolve(muscle_ids))
        else {
            continue;
        };
        let s_k = resolved.sliders[k];
        if s_k == 0.0 {
            continue;
        }
        let others: Vec<(usize, f64)> = resolved
            .sliders
            .iter()
            .enumerate()
            .filter(|&(i, &s)| i != k && s != 0.0)
            .map(|(i, &s)| (i, s / s_k))
            .collect();
        let mut field = std::mem::take(&mut displacements[k]);
        let views: Vec<(&[DVec3], f64)> = others
            .iter()
            .map(|&(i, w)| (displacements[i].as_slice(), w))
            .collect();
        untangle::relax_in_combination(
            &mesh.vertices,
            &mesh.triangles,
            &mut field,
            &views,
            &fixed,
            patch_radius,
        );
        untangle::relax_inversions(
            &mesh.vertices,
            &mesh.triangles,
            &mut field,
            &fixed,
            patch_radius,
        );
        displacements[k] = field;
    }
}

/// Vertices [`relax_brow_lowerers`] leaves alone: the mid and lower face (more than
/// [`untangle::LIDS_MM`] below the eye loops' lowest point), the outer contour, the eye
/// loops and the mouth corners.
fn above_the_eyes_fixed(rig: &FaceRig, face: &CanonicalFace) -> Vec<bool> {
    let (loops, canonical) = (&face.loops, &face.points);
    let (_, eye_l, eye_r) = front_loops(loops, canonical);
    let lids = untangle::LIDS_MM / rig.mm_per_unit();
    let eyes_bottom = lowest_y(&eye_l, &eye_r);
    let mut fixed: Vec<bool> = canonical
        .iter()
        .map(|p| p.y <= eyes_bottom - lids)
        .collect();
    fix_contours_and_corners(&mut fixed, loops, canonical);
    fixed
}

/// Vertices the second [`untangle::relax_inversions`] pass, after the lid closure,
/// leaves alone. It relaxes the lids (within [`untangle::LIDS_MM`] of the eye loops),
/// which the closure changed after the first pass, and, on a face simulated on a reduced
/// `copy`, the vertices the copy does not hold within [`untangle::LIPS_MM`] of the
/// mouth loop: their motion is interpolated from the copy, whose coarser triangles fold
/// differently from the input's at a commissure, and relaxing them changes no simulated value.
/// The outer contour, the eye loops (closed exactly) and the mouth corners stay. Relaxing the
/// carried-over vertices of the whole face instead moved ICT 2500's left brow point 1.9 mm less
/// than its right one under the frontalis.
fn closed_lids_fixed(
    mesh: &FaceMesh,
    rig: &FaceRig,
    face: &CanonicalFace,
    copy: Option<&Simplified>,
) -> Vec<bool> {
    let (loops, canonical) = (&face.loops, &face.points);
    let (mouth, eye_l, eye_r) = front_loops(loops, canonical);
    let lips = untangle::LIPS_MM / rig.mm_per_unit();
    let lids = untangle::LIDS_MM / rig.mm_per_unit();
    let mut simulated = vec![copy.is_none(); mesh.vertices.len()];
    for &v in copy.map_or(&[][..], |c| &c.original_vertex) {
        if let Some(s) = simulated.get_mut(v as usize) {
            *s = true;
        }
    }
    let mut fixed: Vec<bool> = canonical
        .iter()
        .zip(&simulated)
        .map(|(p, &simulated)| {
            use face_prep::muscle_model::distance_to_loop;
            let p = p.truncate();
            let at_lids =
                distance_to_loop(p, &eye_l) <= lids || distance_to_loop(p, &eye_r) <= lids;
            let at_lips = !simulated && distance_to_loop(p, &mouth) <= lips;
            !(at_lids || at_lips)
        })
        .collect();
    fix_contours_and_corners(&mut fixed, loops, canonical);
    fixed
}
