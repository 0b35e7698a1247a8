//! The remeshed copy of a large face ([`crate::copy::CopyMethod::Remesh`]): the face
//! remeshed in its canonical frame ([`crate::copy::remesh`]), finer at the mouth and the eyes, and
//! as a mirrored half when the face is mirror-symmetric.

use crate::copy::simplify::{
    Canonical, LeftHalf, MIRROR_TOLERANCE_IOD, SimplifyPath, left_half, mirror_map,
};
use crate::copy::{LargeFaceParams, Simplified, SimplifyError};
use glam::DVec3;

/// Edge length at the mouth loop, as a fraction of the remeshed copy's global target length
/// ([`remesh_face`]): the lips' knife edge and the commissures, where the responses
/// change fastest.
pub const MOUTH_REFINEMENT: f64 = 0.3;

/// Edge length at the eye loops, as a fraction of the global target length (the lids' knife
/// edges).
pub const EYE_REFINEMENT: f64 = 0.5;

/// Growth of the edge length per unit of distance from the mouth and eye loops.
pub const REFINEMENT_GRADE: f64 = 0.2;

/// [`crate::copy::simplify::simplify_face`] by isotropic remeshing ([`crate::copy::remesh`]) instead of edge
/// collapses: a copy of near-equilateral triangles about `params.target_triangles` strong,
/// smaller toward the mouth and the eyes ([`MOUTH_REFINEMENT`], [`EYE_REFINEMENT`]), on the
/// input surface. Built in the face's canonical frame and order, so it does not depend on how
/// the file is written; a mirror-symmetric face is remeshed as its left half and mirrored. The
/// vertices flagged in `keep` are kept where they are. The copy's other vertices are new
/// points of the surface: [`Simplified::original_vertex`] names the input vertex closest to
/// each. A face without a canonical frame is remeshed as written, without refinement.
///
/// ```
/// use facebem::copy::remesh_face::remesh_face;
/// use facebem::copy::simplify::SimplifyPath;
/// use facebem::copy::LargeFaceParams;
/// let mesh = facebem::input::default_face().unwrap();
/// let params = LargeFaceParams { target_triangles: 600, ..LargeFaceParams::default() };
/// let (copy, path) = remesh_face(&mesh.vertices, &mesh.triangles, &params, &[]).unwrap();
/// assert_eq!(path, SimplifyPath::RemeshedMirrored);
/// assert!((450..900).contains(&copy.triangles.len()));
/// ```
pub fn remesh_face(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    params: &LargeFaceParams,
    keep: &[u32],
) -> Result<(Simplified, SimplifyPath), SimplifyError> {
    let mut remesh_params = crate::copy::remesh::RemeshParams {
        target_triangles: params.target_triangles,
        ..crate::copy::remesh::RemeshParams::default()
    };
    let Some(canon) = Canonical::of(vertices, triangles) else {
        let mut flags = vec![false; vertices.len()];
        for &v in keep {
            if let Some(f) = flags.get_mut(v as usize) {
                *f = true;
            }
        }
        let r = crate::copy::remesh::remesh(vertices, triangles, &flags, &remesh_params)?;
        return Ok((
            Simplified {
                vertices: r.positions,
                triangles: r.triangles,
                original_vertex: r.nearest_input,
            },
            SimplifyPath::RemeshedAsWritten,
        ));
    };
    let mut kept = vec![false; canon.positions.len()];
    for (c, &v) in canon.input_vertex.iter().enumerate() {
        kept[c] = keep.contains(&v);
    }
    let polyline =
        |lp: &[u32]| -> Vec<DVec3> { lp.iter().map(|&v| canon.positions[v as usize]).collect() };
    remesh_params.refinements = std::iter::once((&canon.mouth, MOUTH_REFINEMENT))
        .chain(canon.eyes.iter().map(|e| (e, EYE_REFINEMENT)))
        .map(|(lp, fraction)| crate::copy::remesh::Refinement {
            polyline: polyline(lp),
            fraction,
            grade: REFINEMENT_GRADE,
        })
        .collect();
    let mirrored = mirror_map(&canon.positions, &canon.triangles)
        .and_then(|mirror| remesh_mirrored(&canon, &mirror, &remesh_params, &kept));
    let (r, path) = match mirrored {
        Some(r) => (r, SimplifyPath::RemeshedMirrored),
        None => (
            crate::copy::remesh::remesh(&canon.positions, &canon.triangles, &kept, &remesh_params)?,
            SimplifyPath::Remeshed,
        ),
    };
    Ok((
        Simplified {
            vertices: r
                .positions
                .iter()
                .map(|&p| canon.input_from_grid.transform_point3(p))
                .collect(),
            triangles: r.triangles,
            original_vertex: r
                .nearest_input
                .iter()
                .map(|&c| canon.input_vertex[c as usize])
                .collect(),
        },
        path,
    ))
}

/// Remeshes the left half of a mirror-symmetric canonical face and mirrors it (see
/// [`crate::copy::remesh`]). `None` when the half or the glued result is not a valid surface with the
/// face's loop count.
fn remesh_mirrored(
    canon: &Canonical,
    mirror: &[u32],
    params: &crate::copy::remesh::RemeshParams,
    kept: &[bool],
) -> Option<crate::copy::remesh::Remeshed> {
    let LeftHalf {
        half,
        anchors,
        locks,
    } = left_half(canon, mirror, kept)?;
    let keep: Vec<bool> = anchors.iter().zip(&locks).map(|(&a, &l)| a || l).collect();
    let half_params = crate::copy::remesh::RemeshParams {
        target_triangles: (params.target_triangles / 2).max(16),
        ..params.clone()
    };
    let r =
        crate::copy::remesh::remesh(&half.vertices, &half.triangles, &keep, &half_params).ok()?;
    let loops = face_prep::topology::validate(&r.positions, &r.triangles).ok()?;
    let mut positions = r.positions.clone();
    let n = positions.len();
    let mut midline = vec![false; n];
    for lp in &loops {
        for &v in lp {
            if positions[v as usize].x.abs() <= MIRROR_TOLERANCE_IOD {
                midline[v as usize] = true;
                positions[v as usize].x = 0.0;
            }
        }
    }
    let nearest_half: Vec<u32> = r
        .nearest_input
        .iter()
        .map(|&h| half.original_vertex[h as usize])
        .collect();
    let mut nearest_input = nearest_half.clone();
    let mut image = vec![0u32; n];
    for v in 0..n {
        if midline[v] {
            image[v] = v as u32;
        } else {
            image[v] = positions.len() as u32;
            let p = positions[v];
            positions.push(DVec3::new(-p.x, p.y, p.z));
            nearest_input.push(mirror[nearest_half[v] as usize]);
        }
    }
    let mut triangles = r.triangles.clone();
    triangles.extend(
        r.triangles
            .iter()
            .map(|t| [t[0], t[2], t[1]].map(|v| image[v as usize])),
    );
    let glued = face_prep::topology::validate(&positions, &triangles).ok()?;
    (glued.len() == canon.loop_count).then_some(crate::copy::remesh::Remeshed {
        positions,
        triangles,
        nearest_input,
    })
}
