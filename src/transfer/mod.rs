//! The transfer stage: the responses simulated on a reduced copy of the face (rolled-in parts
//! peeled off, or a large face simplified or remeshed, [`crate::copy`]) carried to every vertex
//! of the user's mesh. Each input vertex takes the displacement of the closest point on the
//! copy's front surface, interpolated with that point's barycentric coordinates ([`Transfer`]);
//! peeled eyelids and lips start from the margin they hang from and are then extended
//! harmonically ([`crate::copy::rolled_in::hang_from_margins`]); the input's mouth corners that
//! the copy does not hold follow the commissure.

pub mod along_surface;
mod carry;
pub mod eye_contact;
pub mod gaze;
pub mod head;
pub mod lid_riders;
pub mod nearest;
pub mod tongue;

use glam::DVec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::copy::Simplified;

pub(crate) use carry::carry_to_input;

/// The reduced copy of a face that was simulated (simplified, or with rolled-in parts
/// peeled off, or both) and the map that carries its fields to the full mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimplifiedFace {
    /// The simulated front mesh (its vertices are a subset of the full mesh's).
    pub mesh: Simplified,
    /// Closest-point barycentric transfer to every full-mesh vertex.
    pub transfer: Transfer,
}

/// Errors of the transfer stage.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TransferError {
    /// The simulated copy has no triangle to carry its responses from.
    #[error("the simulated copy of the face has no triangles to carry its responses from")]
    EmptyCopy,
}

/// For every vertex of a full mesh: the simplified triangle holding its closest point and that
/// point's barycentric coordinates, so fields on the simplified mesh can be carried over.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Transfer {
    /// Per full vertex: (simplified triangle index, barycentric weights).
    pub samples: Vec<(u32, [f64; 3])>,
}

impl Transfer {
    /// Finds, for every point of `full`, the closest point on the triangles of `coarse`
    /// (brute force over the triangles, parallel over the points). `None` if `coarse` has no
    /// triangles.
    pub fn build(full: &[DVec3], coarse: &Simplified) -> Option<Transfer> {
        if coarse.triangles.is_empty() {
            return None;
        }
        let tris: Vec<[DVec3; 3]> = coarse
            .triangles
            .iter()
            .map(|t| t.map(|i| coarse.vertices[i as usize]))
            .collect();
        let samples = full
            .par_iter()
            .map(|&p| {
                let mut best = (f64::INFINITY, 0u32, [1.0, 0.0, 0.0]);
                for (t, &[a, b, c]) in tris.iter().enumerate() {
                    let w = face_prep::closest_point::closest_point_barycentric(p, a, b, c);
                    let q = a * w[0] + b * w[1] + c * w[2];
                    let d = q.distance_squared(p);
                    if d < best.0 {
                        best = (d, t as u32, w);
                    }
                }
                (best.1, best.2)
            })
            .collect();
        Some(Transfer { samples })
    }

    /// Re-targets the full-mesh vertices `hanging` (e.g. eyelids and lips peeled off the
    /// simulated copy, [`crate::copy::rolled_in`]) to the closest point of the copy's inner boundary
    /// loops (its eye and mouth margins: every boundary loop but the longest, the outer
    /// contour). A peeled flap hangs from that margin; the closest point of the whole surface
    /// can lie on the other lip (seen on the ICT faces: the two mouth corners, mirror images,
    /// followed points moving 4.8 and 10.8 mm). Vertices stay as they are when the copy has
    /// no inner loop.
    pub fn snap_to_margins(&mut self, full: &[DVec3], coarse: &Simplified, hanging: &[u32]) {
        let Ok(loops) = face_prep::topology::validate(&coarse.vertices, &coarse.triangles) else {
            return;
        };
        let Some(outer) = (0..loops.len()).max_by(|&a, &b| {
            let pa = face_prep::orient::loop_perimeter(&coarse.vertices, &loops[a]);
            let pb = face_prep::orient::loop_perimeter(&coarse.vertices, &loops[b]);
            pa.total_cmp(&pb)
        }) else {
            return;
        };
        // Each margin edge with the triangle that holds it and the edge's corner slots in it.
        let mut edge_owner = std::collections::HashMap::new();
        for (t, tri) in coarse.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                edge_owner.insert((a.min(b), a.max(b)), (t as u32, k, (k + 1) % 3));
            }
        }
        let mut edges = Vec::new();
        for (i, lp) in loops.iter().enumerate() {
            if i == outer {
                continue;
            }
            for j in 0..lp.len() {
                let (a, b) = (lp[j], lp[(j + 1) % lp.len()]);
                if let Some(&(t, ka, kb)) = edge_owner.get(&(a.min(b), a.max(b))) {
                    let tri = coarse.triangles[t as usize];
                    let (ka, kb) = if tri[ka] == a { (ka, kb) } else { (kb, ka) };
                    edges.push((a, b, t, ka, kb));
                }
            }
        }
        if edges.is_empty() {
            return;
        }
        for &v in hanging {
            let Some(&p) = full.get(v as usize) else {
                continue;
            };
            let mut best = (f64::INFINITY, self.samples[v as usize]);
            for &(a, b, t, ka, kb) in &edges {
                let (pa, pb) = (coarse.vertices[a as usize], coarse.vertices[b as usize]);
                let d = pb - pa;
                let f = if d.length_squared() > 0.0 {
                    ((p - pa).dot(d) / d.length_squared()).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let dist = (pa + d * f).distance_squared(p);
                if dist < best.0 {
                    let mut w = [0.0; 3];
                    w[ka] = 1.0 - f;
                    w[kb] = f;
                    best = (dist, (t, w));
                }
            }
            self.samples[v as usize] = best.1;
        }
    }

    /// Interpolates a per-vertex field of the simplified mesh onto the full mesh's vertices.
    /// `coarse_field` must have one value per simplified vertex.
    pub fn apply(&self, coarse: &Simplified, coarse_field: &[DVec3]) -> Vec<DVec3> {
        self.samples
            .iter()
            .map(|(t, w)| {
                let tri = coarse.triangles[*t as usize];
                (0..3)
                    .map(|k| coarse_field[tri[k] as usize] * w[k])
                    .sum::<DVec3>()
            })
            .collect()
    }
}
