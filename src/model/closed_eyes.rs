//! Eyes closed in the neutral: lids that meet along a line the reader cut open
//! ([`face_prep::frame::contact`]) or that touch at separate vertices. Such an eye's loop has
//! no area in the front plane; an open eye's loop has an area of 3 % of its width squared or
//! more.

use crate::frame::CanonicalFace;
use face_prep::FaceMesh;
use glam::DAffine3;

/// An eye counts as closed when its loop's area in the front plane (the rig's canonical x-y) is
/// below this fraction of the square of the loop's width (its x extent). Measured on the
/// bundled faces' open eyes (`tests/closed_mouths_and_eyes.rs`): 0.033 (Lee Perry-Smith's
/// right eye, the least open), 0.080 (its left), 0.17 (MediaPipe), 0.40–0.41 (ICT); lids that
/// touch or a cut lid line measure below 10⁻⁴.
pub const CLOSED_EYE_AREA_FRACTION: f64 = 0.005;

/// Each eye's opening: its loop's area in the front plane (the canonical frame's x-y, reached
/// by `canonical_from_input`, the rig's) over its width squared, for the face's left eye (+x)
/// and right eye. `None` when the mesh has no four loops (a loaded face mesh always has).
///
/// ```no_run
/// let mesh = face_prep::load_face("assets/mediapipe_canonical_4loop.obj".as_ref()).unwrap();
/// let params = facebem::PipelineParams::default();
/// let model = facebem::build_face_model(&mesh, &params, &facebem::Control::new()).unwrap();
/// let [left, right] =
///     facebem::model::eye_openings(&model.mesh, model.rig.canonical_from_input).unwrap();
/// assert!(left > facebem::model::CLOSED_EYE_AREA_FRACTION && (left - right).abs() < 1e-9);
/// ```
pub fn eye_openings(mesh: &FaceMesh, canonical_from_input: DAffine3) -> Option<[f64; 2]> {
    let CanonicalFace {
        loops,
        points: canonical,
    } = CanonicalFace::of_mesh(mesh, canonical_from_input)?;
    let opening = |lp: &[u32]| {
        let area = 0.5
            * (0..lp.len())
                .map(|i| {
                    let a = canonical[lp[i] as usize];
                    let b = canonical[lp[(i + 1) % lp.len()] as usize];
                    a.x * b.y - b.x * a.y
                })
                .sum::<f64>()
                .abs();
        let (lo, hi) = lp
            .iter()
            .map(|&v| canonical[v as usize].x)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
        let width = hi - lo;
        if width > 0.0 {
            area / (width * width)
        } else {
            0.0
        }
    };
    Some([opening(&loops.eye_l), opening(&loops.eye_r)])
}

/// Whether the face's left and right eye are closed in the neutral
/// ([`CLOSED_EYE_AREA_FRACTION`]).
pub fn closed_eyes(mesh: &FaceMesh, canonical_from_input: DAffine3) -> [bool; 2] {
    eye_openings(mesh, canonical_from_input)
        .map_or([false; 2], |o| o.map(|f| f < CLOSED_EYE_AREA_FRACTION))
}
