//! Which copy of the face is simulated: the whole input, the input with its rolled-in eyelids
//! and lips peeled off, or (above [`LargeFaceParams::max_triangles`]) a simplified or remeshed
//! copy of that.

use face_prep::FaceMesh;

use super::simplify::SimplifyPath;
use super::{CopyMethod, LargeFaceParams, Simplified, SimplifyError};
use crate::frame::{InputFrame, mouth_corners};

/// The copy [`reduce`] chose.
pub(crate) struct Reduced {
    /// The reduced copy; `None` when the whole input is simulated.
    pub simplified: Option<Simplified>,
    /// Input vertices peeled off with the rolled-in eyelids and lips.
    pub peeled_vertices: Vec<u32>,
    /// How a large face was simplified; `None` when it was not.
    pub simplify_path: Option<SimplifyPath>,
    /// Why the edge-collapse copy was replaced by a remeshed one ([`copy_large_face`]).
    pub copy_fallback: Option<String>,
}

/// Peels the rolled-in parts off `mesh` (when `peel_rolled_in`) and simplifies what is left
/// when it is larger than `params.max_triangles`, keeping the input's mouth corners.
pub(crate) fn reduce(
    mesh: &FaceMesh,
    frame: &InputFrame,
    peel_rolled_in: bool,
    params: &LargeFaceParams,
) -> Result<Reduced, SimplifyError> {
    let whole = Simplified::whole(&mesh.vertices, &mesh.triangles);
    let peeled = if peel_rolled_in {
        super::rolled_in::peel_rolled_in(&whole)
    } else {
        None
    };
    let peeled_vertices: Vec<u32> = match &peeled {
        Some(p) => {
            let mut kept = vec![false; whole.vertices.len()];
            for &v in &p.original_vertex {
                kept[v as usize] = true;
            }
            (0..kept.len() as u32)
                .filter(|&v| !kept[v as usize])
                .collect()
        }
        None => Vec::new(),
    };
    let base = peeled.as_ref().unwrap_or(&whole);
    let mut simplify_path = None;
    let mut copy_fallback = None;
    // A target at or above the face's own size leaves it whole, whatever the method: a remesh
    // would only add triangles to a dense solve (`--max-triangles 835 --target-triangles 1499
    // --copy remesh` took 10 s on an 836-triangle face; found by the fuzzer, issue 36).
    let large = base.triangles.len() > params.max_triangles;
    let simplified = if large && params.target_triangles < base.triangles.len() {
        let keep = kept_mouth_corners(mesh, frame, base);
        let (s, path, fallback) = copy_large_face(base, params, &keep)?;
        simplify_path = Some(path);
        copy_fallback = fallback;
        Some(Simplified {
            original_vertex: s
                .original_vertex
                .iter()
                .map(|&v| base.original_vertex[v as usize])
                .collect(),
            ..s
        })
    } else {
        peeled
    };
    Ok(Reduced {
        simplified,
        peeled_vertices,
        simplify_path,
        copy_fallback,
    })
}

/// The simulated copy of a large face by `params.method`. An edge-collapse copy that is not a
/// valid surface (meshoptimizer collapses exactly collinear vertices, as in a midpoint-
/// subdivided face, into zero-area triangles; issue 36, regression
/// `a_midpoint_subdivided_face_is_simulated_on_a_remeshed_copy`) is replaced by the remeshed
/// copy, whose vertices are new points of the surface; the reason is returned third.
fn copy_large_face(
    base: &Simplified,
    params: &LargeFaceParams,
    keep: &[u32],
) -> Result<(Simplified, SimplifyPath, Option<String>), SimplifyError> {
    let remesh = super::remesh_face::remesh_face;
    if params.method == CopyMethod::Remesh {
        let (s, path) = remesh(&base.vertices, &base.triangles, params, keep)?;
        return Ok((s, path, None));
    }
    let (mut s, path) =
        super::simplify::simplify_face(&base.vertices, &base.triangles, params, keep)?;
    if face_prep::topology::validate(&s.vertices, &s.triangles).is_err() {
        // Caps (a corner on the opposite edge) are flipped out first ([`super::flips`]).
        let (lo, hi) = face_prep::topology::bounding_box(s.vertices.iter().copied());
        let degenerate = face_prep::topology::DEGENERATE_REL_AREA * (hi - lo).length_squared();
        super::flips::flip_out_caps(&s.vertices, &mut s.triangles, degenerate);
    }
    match face_prep::topology::validate(&s.vertices, &s.triangles) {
        Ok(_) => Ok((s, path, None)),
        Err(e) => {
            let (s, path) = remesh(&base.vertices, &base.triangles, params, keep)?;
            Ok((
                s,
                path,
                Some(format!(
                    "the edge-collapse copy was not a valid surface ({e})"
                )),
            ))
        }
    }
}

/// The input mouth loop's corners (its extreme vertices in the canonical ±x, the landmarks
/// [`crate::report::measure::FaceLandmarks`] measures) that the reduced copy `base` holds, as
/// indices into `base`: a large face's simplification keeps them. Regression: Lee Perry-Smith's
/// copy collapsed its corners along the mouth loop, and they moved 9.8 / 9.0 mm at full
/// zygomaticus against 12.6 mm beside them (now 12.6 / 12.6 mm; `tests/face_simplify.rs`).
fn kept_mouth_corners(mesh: &FaceMesh, frame: &InputFrame, base: &Simplified) -> Vec<u32> {
    let canonical = frame.canonical_points(mesh);
    let Some((left, right)) = mouth_corners(&canonical, &frame.loops.mouth) else {
        return Vec::new();
    };
    [left, right]
        .into_iter()
        .filter_map(|v| base.original_vertex.iter().position(|&o| o == v))
        .map(|b| b as u32)
        .collect()
}
