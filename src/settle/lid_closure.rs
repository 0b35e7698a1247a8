//! Exact blink closure on the displayed mesh ([`face_prep::eyelid::pin`]), and squints that
//! keep the lids from crossing ([`keep_squints_open`]).
//!
//! A blink's response comes out of the BEM as element values averaged to vertices, and for a
//! face simulated on a reduced copy it is then carried to the full mesh: neither lands the
//! upper lid margin exactly on the lower one. After the transfer, every blink field is
//! corrected on the displayed (input) mesh: the upper-margin vertices of the eye loop, and of
//! the simulated copy's eye loop (the visible lid margin of a face with rolled-in lids), are
//! pinned onto their lower-margin points at full blink, the correction fading over the upper
//! lid.

use face_prep::eyelid::pin::{close_margins, close_rolled_margins, pin_and_spread};
use face_prep::eyelid::{EyeMargins, LOWER_LID_BAND_MM, LidAction, UPPER_LID_BAND_MM};
use face_prep::muscle_kind::Generator;
use face_prep::{FaceMesh, FaceRig, MuscleKind, Side};
use glam::DVec3;

use crate::copy::Simplified;
use crate::frame::CanonicalFace;

/// Radius of the correction's fade, in multiples of [`UPPER_LID_BAND_MM`] (along the mesh's
/// edges from the upper margin).
pub const CLOSURE_RADIUS_BANDS: f64 = 1.5;

/// Pins every blink field of `fields` (one per control id of `ids`, input frame, per vertex of
/// `mesh`) so that at slider −1 the upper margins lie on the lower ones. `reduced` is the
/// simulated copy, if any, with the simulated mesh its rig was built on.
pub(crate) fn close_blinks(
    rig: &FaceRig,
    mesh: &FaceMesh,
    face: &CanonicalFace,
    reduced: Option<(&Simplified, &FaceMesh)>,
    ids: &[String],
    fields: &mut [Vec<DVec3>],
) {
    let blinks = lid_controls(ids, LidAction::Blink);
    if blinks.is_empty() {
        return;
    }
    let (loops, canonical) = (&face.loops, &face.points);
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
        let Some(shown_margins) = EyeMargins::of_loop(canonical, shown, side) else {
            continue;
        };
        let visible = sim_to_full.as_ref().and_then(|map| {
            let lp: Vec<u32> = simulated.iter().map(|&v| map[v as usize]).collect();
            let mut a = lp.clone();
            let mut b = shown.clone();
            a.sort_unstable();
            b.sort_unstable();
            (a != b && lp.iter().all(|&v| (v as usize) < canonical.len()))
                .then(|| EyeMargins::of_loop(canonical, &lp, side))
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

/// Rounds of [`keep_squints_open`] (each pins the lower-margin vertices still past the upper
/// margin and spreads the change over the lower lid).
pub const SQUINT_GUARD_ROUNDS: usize = 4;

/// Keeps every squint field (the orbicularis oculi's orbital part, which lifts the lower lid)
/// from lifting the lower margin of the displayed eye loop past the upper one at full squint:
/// wherever, seen from the front at an upper-margin vertex, the lower margin would end higher
/// than the upper one (or, where the neutral lids already overlap as on a slit scanned eye, any
/// higher than it is at rest), the lower-margin vertices under it are pinned that much lower
/// and the change is spread over the lower lid ([`pin_and_spread`], the upper margin and the
/// corners held). Regression: Lee Perry-Smith's right eye, open 2.5 mm with its lids
/// overlapping in the front view, had its lower margin lifted 0.13 mm past the upper one.
pub(crate) fn keep_squints_open(
    rig: &FaceRig,
    mesh: &FaceMesh,
    face: &CanonicalFace,
    ids: &[String],
    fields: &mut [Vec<DVec3>],
) {
    let squints = lid_controls(ids, LidAction::Squint);
    if squints.is_empty() {
        return;
    }
    let (loops, canonical) = (&face.loops, &face.points);
    // Up in the canonical frame, as an input-frame direction.
    let up = rig.input_from_canonical().transform_vector3(DVec3::Y);
    let radius = LOWER_LID_BAND_MM / rig.mm_per_unit();
    for (k, side) in squints {
        let shown = match side {
            Side::Left => &loops.eye_l,
            Side::Right => &loops.eye_r,
            Side::Center => continue,
        };
        let Some(margins) = EyeMargins::of_loop(canonical, shown, side) else {
            continue;
        };
        let Some(field) = fields.get_mut(k) else {
            continue;
        };
        if field.len() != canonical.len() {
            continue;
        }
        let neutral_gaps = margins.vertical_gaps(canonical);
        let tolerance = 1e-6 * margins.opening_height(canonical).max(f64::MIN_POSITIVE);
        let mut held: Vec<u32> = margins.upper.clone();
        held.extend([margins.medial, margins.lateral]);
        for _ in 0..SQUINT_GUARD_ROUNDS {
            // Full squint is slider −1: posed = neutral − field.
            let posed: Vec<DVec3> = canonical
                .iter()
                .zip(field.iter())
                .map(|(p, d)| *p - rig.canonical_from_input.transform_vector3(*d))
                .collect();
            let mut lower_by = vec![0.0f64; margins.lower.len()];
            let interior = &margins.upper[1..margins.upper.len().saturating_sub(1).max(1)];
            for (&u, g0) in interior.iter().zip(&neutral_gaps) {
                let Some(g0) = g0 else { continue };
                let Some((i, gap)) = margins.lower_under(&posed, posed[u as usize]) else {
                    continue;
                };
                let deficit = g0.min(0.0) - gap;
                if deficit > 0.0 {
                    for j in [i, i + 1] {
                        lower_by[j] = lower_by[j].max(deficit + tolerance);
                    }
                }
            }
            let pins: Vec<(u32, DVec3)> = margins
                .lower
                .iter()
                .zip(&lower_by)
                .filter(|&(v, &d)| d > 0.0 && !held.contains(v))
                .map(|(&v, &d)| (v, field[v as usize] + up * d))
                .collect();
            if pins.is_empty() {
                break;
            }
            pin_and_spread(&mesh.vertices, &mesh.triangles, field, &pins, &held, radius);
        }
    }
}

/// The controls of `ids` that are eyelid actions `action`, with their side.
fn lid_controls(ids: &[String], action: LidAction) -> Vec<(usize, Side)> {
    ids.iter()
        .enumerate()
        .filter_map(|(k, id)| {
            let kind = MuscleKind::from_id(id)?;
            matches!(kind.generator(), Generator::Lid(a) if a == action).then(|| (k, kind.side()))
        })
        .collect()
}
