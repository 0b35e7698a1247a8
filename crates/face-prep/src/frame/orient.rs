//! Automatic orientation into the canonical frame (thesis 3.1.1 and the ch. 12 recipe) and
//! classification of the four boundary loops.

use crate::error::PrepError;
use crate::error::{fmt_p, sig6};
use glam::{DAffine3, DMat3, DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// The four boundary loops of a face, as vertex indices of the face mesh in the direction of the
/// boundary half-edges (the surface lies on the left when walking a loop seen from the front).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaceLoops {
    /// Outer face contour.
    pub face: Vec<u32>,
    /// The face's left eye (+x in the canonical frame).
    pub eye_l: Vec<u32>,
    /// The face's right eye (−x in the canonical frame).
    pub eye_r: Vec<u32>,
    /// Mouth.
    pub mouth: Vec<u32>,
}

/// Perimeter of a closed loop.
pub fn loop_perimeter(vertices: &[DVec3], lp: &[u32]) -> f64 {
    (0..lp.len())
        .map(|i| vertices[lp[i] as usize].distance(vertices[lp[(i + 1) % lp.len()] as usize]))
        .sum()
}

/// The loop `lp` in the front plane (the x-y of its `vertices`), in loop order.
pub(crate) fn loop_xy(vertices: &[DVec3], lp: &[u32]) -> Vec<DVec2> {
    lp.iter()
        .map(|&v| vertices[v as usize].truncate())
        .collect()
}

/// Length-weighted centroid of a closed polyline (insensitive to uneven vertex spacing).
pub fn loop_centroid(vertices: &[DVec3], lp: &[u32]) -> DVec3 {
    let mut sum = DVec3::ZERO;
    let mut total = 0.0;
    for i in 0..lp.len() {
        let a = vertices[lp[i] as usize];
        let b = vertices[lp[(i + 1) % lp.len()] as usize];
        let l = a.distance(b);
        sum += 0.5 * (a + b) * l;
        total += l;
    }
    if total > 0.0 {
        sum / total
    } else {
        vertices[lp[0] as usize]
    }
}

/// Finds the rigid transform from the input frame to the canonical frame and classifies the
/// loops. `loops` must hold exactly four loops.
///
/// Recipe (thesis ch. 12): the outer contour is the loop of largest perimeter; of the three
/// inner loops, the two of most similar perimeter are the eyes and the third is the mouth. The
/// front plane passes through the three inner-loop centroids; its normal, signed so that the
/// area-weighted normal of the (counter-clockwise wound) front surface points to +z, is the z
/// axis. y points from the mouth centroid toward the eyes' mid-point (projected into the plane),
/// x = y × z, so the face's left eye is at +x. The origin is the mean of the three inner-loop
/// centroids. The transform is rigid: units are kept.
pub fn canonical_frame(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Result<(DAffine3, FaceLoops), PrepError> {
    if loops.len() != 4 {
        return Err(PrepError::Orientation {
            reason: format!("{} loops instead of 4", loops.len()),
        });
    }
    let perim: Vec<f64> = loops.iter().map(|l| loop_perimeter(vertices, l)).collect();
    let (outer, e1, e2, m) = split_loops(&perim);
    let c1 = loop_centroid(vertices, &loops[e1]);
    let c2 = loop_centroid(vertices, &loops[e2]);
    let cm = loop_centroid(vertices, &loops[m]);
    let (canonical_from_input, x) = frame_from_centroids(vertices, triangles, [c1, c2, cm])?;
    let (left, right) = if x.dot(c1) > x.dot(c2) {
        (e1, e2)
    } else {
        (e2, e1)
    };
    check_outline(
        vertices,
        loops,
        &perim,
        &canonical_from_input,
        outer,
        [left, right, m],
    )?;
    Ok((
        canonical_from_input,
        FaceLoops {
            face: loops[outer].clone(),
            eye_l: loops[left].clone(),
            eye_r: loops[right].clone(),
            mouth: loops[m].clone(),
        },
    ))
}

/// Outer contour, the two eyes (in loop order) and the mouth among four loops of perimeters
/// `perim`: the outer contour is the longest loop, the eyes the two inner loops of most similar
/// perimeter.
fn split_loops(perim: &[f64]) -> (usize, usize, usize, usize) {
    let outer = (0..4)
        .max_by(|&a, &b| perim[a].total_cmp(&perim[b]))
        .unwrap_or(0);
    let inner: Vec<usize> = (0..4).filter(|&i| i != outer).collect();
    let dissimilarity = |a: usize, b: usize| (perim[a] - perim[b]).abs() / perim[a].max(perim[b]);
    let pairs = [
        (inner[0], inner[1], inner[2]),
        (inner[0], inner[2], inner[1]),
        (inner[1], inner[2], inner[0]),
    ];
    let (e1, e2, m) = pairs
        .into_iter()
        .min_by(|p, q| dissimilarity(p.0, p.1).total_cmp(&dissimilarity(q.0, q.1)))
        .unwrap_or(pairs[0]);
    (outer, e1, e2, m)
}

/// The canonical frame from the centroids of the two eyes and the mouth (`[c1, c2, cm]`) and
/// the front surface's area-weighted normal (see [`canonical_frame`]): the transform, and the x
/// axis in the input frame.
fn frame_from_centroids(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    centroids: [DVec3; 3],
) -> Result<(DAffine3, DVec3), PrepError> {
    let [c1, c2, cm] = centroids;
    let normal = (c2 - c1).cross(cm - c1);
    let scale = (c2 - c1).length().max((cm - c1).length());
    if normal.length().is_nan() || normal.length() <= 1e-6 * scale * scale {
        return Err(PrepError::Orientation {
            reason: format!(
                "eye and mouth centroids {}, {}, {} are collinear",
                fmt_p(&c1),
                fmt_p(&c2),
                fmt_p(&cm)
            ),
        });
    }
    let mut z = normal.normalize();
    let area_normal: DVec3 = triangles
        .iter()
        .map(|t| {
            let p = t.map(|i| vertices[i as usize]);
            (p[1] - p[0]).cross(p[2] - p[0])
        })
        .sum();
    let facing = area_normal.dot(z);
    if facing.abs() < 1e-9 * area_normal.length() || !facing.is_finite() {
        return Err(PrepError::Orientation {
            reason: "the surface's mean normal lies in the front plane".into(),
        });
    }
    if facing < 0.0 {
        z = -z;
    }
    let up = 0.5 * (c1 + c2) - cm;
    let y_raw = up - z * up.dot(z);
    if y_raw.length().is_nan() || y_raw.length() <= 1e-9 * scale {
        return Err(PrepError::Orientation {
            reason: "mouth lies on the eye line".into(),
        });
    }
    let y = y_raw.normalize();
    let x = y.cross(z);
    let origin = (c1 + c2 + cm) / 3.0;
    let rot = DMat3::from_cols(x, y, z).transpose();
    Ok((DAffine3::from_mat3_translation(rot, -(rot * origin)), x))
}

/// A front face's outer contour surrounds its eyes and mouth in the face plane; a whole head
/// cut at the neck has the neck cut as its longest loop, below the mouth. `inner` holds the
/// left eye, the right eye and the mouth.
fn check_outline(
    vertices: &[DVec3],
    loops: &[Vec<u32>],
    perim: &[f64],
    canonical_from_input: &DAffine3,
    outer: usize,
    inner: [usize; 3],
) -> Result<(), PrepError> {
    let [left, right, m] = inner;
    let outline: Vec<DVec2> = loops[outer]
        .iter()
        .map(|&v| {
            canonical_from_input
                .transform_point3(vertices[v as usize])
                .truncate()
        })
        .collect();
    let outside: Vec<&str> = [(left, "left eye"), (right, "right eye"), (m, "mouth")]
        .into_iter()
        .filter(|&(l, _)| {
            let c = canonical_from_input.transform_point3(loop_centroid(vertices, &loops[l]));
            !point_in_polygon(c.truncate(), &outline)
        })
        .map(|(_, name)| name)
        .collect();
    if !outside.is_empty() {
        let size = |l: usize| format!("{} edges, perimeter {}", loops[l].len(), sig6(perim[l]));
        return Err(PrepError::NotAFrontFace {
            reason: format!(
                "the longest loop ({}), taken as the face's outline, does not surround the {} in \
                 the face plane (the other loops: eyes {} and {}, mouth {}); a whole head cut at \
                 the neck looks like this",
                size(outer),
                outside.join(" and "),
                size(left),
                size(right),
                size(m)
            ),
        });
    }
    Ok(())
}

/// Whether `p` lies inside the closed polygon `poly` (even-odd rule).
fn point_in_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}
