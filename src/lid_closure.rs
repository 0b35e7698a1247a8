//! Exact blink closure on the displayed mesh ([`face_prep::eyelid::pin`]).
//!
//! A blink's response comes out of the BEM as element values averaged to vertices, and for a
//! face simulated on a reduced copy it is then carried to the full mesh: neither lands the
//! upper lid margin exactly on the lower one. After the transfer, every blink field is
//! corrected on the displayed (input) mesh: the upper-margin vertices of the eye loop, and of
//! the simulated copy's eye loop (the visible lid margin of a face with rolled-in lids), are
//! pinned onto their lower-margin points at full blink, the correction fading over the upper
//! lid.

use face_prep::eyelid::pin::{close_margins, close_rolled_margins};
use face_prep::eyelid::{EyeMargins, LidAction, UPPER_LID_BAND_MM};
use face_prep::muscle_kind::Generator;
use face_prep::{FaceMesh, FaceRig, MuscleKind, Side};
use glam::DVec3;

use crate::large_face::Simplified;

/// Radius of the correction's fade, in multiples of [`UPPER_LID_BAND_MM`] (along the mesh's
/// edges from the upper margin).
pub const CLOSURE_RADIUS_BANDS: f64 = 1.5;

/// Pins every blink field of `fields` (one per control id of `ids`, input frame, per vertex of
/// `mesh`) so that at slider −1 the upper margins lie on the lower ones. `reduced` is the
/// simulated copy, if any, with the simulated mesh its rig was built on.
pub(crate) fn close_blinks(
    rig: &FaceRig,
    mesh: &FaceMesh,
    reduced: Option<(&Simplified, &FaceMesh)>,
    ids: &[String],
    fields: &mut [Vec<DVec3>],
) {
    let blinks: Vec<(usize, Side)> = ids
        .iter()
        .enumerate()
        .filter_map(|(k, id)| {
            let kind = MuscleKind::from_id(id)?;
            matches!(kind.generator(), Generator::Lid(LidAction::Blink)).then(|| (k, kind.side()))
        })
        .collect();
    if blinks.is_empty() {
        return;
    }
    let Ok(loops) = face_prep::topology::validate(&mesh.vertices, &mesh.triangles) else {
        return;
    };
    let Ok((_, loops)) =
        face_prep::orient::canonical_frame(&mesh.vertices, &mesh.triangles, &loops)
    else {
        return;
    };
    let canonical: Vec<DVec3> = mesh
        .vertices
        .iter()
        .map(|&p| rig.canonical_from_input.transform_point3(p))
        .collect();
    // Simulated vertex → full-mesh vertex.
    let sim_to_full: Option<Vec<u32>> = reduced.map(|(s, simulated)| {
        let mut map = vec![u32::MAX; simulated.vertices.len()];
        for (sv, v) in simulated.input_to_vertex.iter().enumerate() {
            if let Some(v) = v {
                map[*v as usize] = s.original_vertex[sv];
            }
        }
        map
    });
    // Into the head: canonical −z in the input frame.
    let back = rig.input_from_canonical().transform_vector3(DVec3::NEG_Z);
    let radius = CLOSURE_RADIUS_BANDS * UPPER_LID_BAND_MM / rig.mm_per_unit();
    for (k, side) in blinks {
        let (shown, simulated) = match side {
            Side::Left => (&loops.eye_l, &rig.loops.eye_l),
            Side::Right => (&loops.eye_r, &rig.loops.eye_r),
            Side::Center => continue,
        };
        let Some(shown_margins) = EyeMargins::of_loop(&canonical, shown, side) else {
            continue;
        };
        let visible = sim_to_full.as_ref().and_then(|map| {
            let lp: Vec<u32> = simulated.iter().map(|&v| map[v as usize]).collect();
            let mut a = lp.clone();
            let mut b = shown.clone();
            a.sort_unstable();
            b.sort_unstable();
            (a != b && lp.iter().all(|&v| (v as usize) < canonical.len()))
                .then(|| EyeMargins::of_loop(&canonical, &lp, side))
                .flatten()
        });
        let Some(field) = fields.get_mut(k) else {
            continue;
        };
        match visible {
            Some(visible) => close_rolled_margins(
                &mesh.vertices,
                &mesh.triangles,
                &visible,
                &shown_margins,
                back,
                field,
                -1.0,
                radius,
            ),
            None => close_margins(
                &mesh.vertices,
                &mesh.triangles,
                &[shown_margins],
                field,
                -1.0,
                radius,
            ),
        }
    }
}
