//! CPU blend of the muscle basis into the vertex buffer the renderer uploads.

use facebem::{MuscleBasis, PoseError};
use glam::DVec3;

/// One GPU vertex: position and unit normal (f32, 24 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MeshVertex {
    /// Posed position (the basis' user frame).
    pub position: [f32; 3],
    /// Area-weighted vertex normal of the posed mesh.
    pub normal: [f32; 3],
}

/// The current pose of a [`MuscleBasis`]: `v = v0 + Σ s_k D_k`, evaluated in f64 with
/// [`MuscleBasis::pose_into`] and rounded once to f32. This is exactly the buffer the viewport
/// uploads, so tests can compare it with `basis.pose(..)`.
///
/// ```
/// use facebem::MuscleBasis;
/// use glam::DVec3;
/// use viewer::posed_mesh::PosedMesh;
/// let basis = MuscleBasis {
///     muscle_ids: vec!["m".into()],
///     neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     triangles: vec![[0, 1, 2]],
///     displacements: vec![vec![DVec3::Z; 3]],
/// };
/// let mut mesh = PosedMesh::default();
/// mesh.update(&basis, &[0.5]).unwrap();
/// assert_eq!(mesh.vertices()[1].position, [1.0, 0.0, 0.5]);
/// ```
#[derive(Clone, Debug, Default)]
pub struct PosedMesh {
    vertices: Vec<MeshVertex>,
    scratch: Vec<DVec3>,
    normals: Vec<DVec3>,
    generation: u64,
}

impl PosedMesh {
    /// Re-blends the vertices for `sliders` (one per muscle, each in −1…1).
    pub fn update(&mut self, basis: &MuscleBasis, sliders: &[f64]) -> Result<(), PoseError> {
        self.update_with_contact(basis, sliders, None)
    }

    /// [`PosedMesh::update`], then, for a head, the lids kept off the eyeballs in the mix
    /// ([`facebem::transfer::eye_contact::EyeContact::apply`] on the mixed displacement, as
    /// the exported targets are one by one).
    pub fn update_with_contact(
        &mut self,
        basis: &MuscleBasis,
        sliders: &[f64],
        contact: Option<&facebem::transfer::eye_contact::EyeContact>,
    ) -> Result<(), PoseError> {
        basis.pose_into(sliders, &mut self.scratch)?;
        if let Some(contact) = contact
            && self.scratch.len() == basis.neutral.len()
            && sliders.iter().any(|s| *s != 0.0)
        {
            let mut field: Vec<DVec3> = (self.scratch.iter().zip(&basis.neutral))
                .map(|(p, n)| *p - *n)
                .collect();
            if contact.apply(&basis.neutral, &mut field) > 0 {
                for ((p, n), d) in self.scratch.iter_mut().zip(&basis.neutral).zip(&field) {
                    *p = *n + *d;
                }
            }
        }
        self.normals.clear();
        self.normals.resize(self.scratch.len(), DVec3::ZERO);
        for t in &basis.triangles {
            let [a, b, c] = t.map(|i| i as usize);
            let (Some(pa), Some(pb), Some(pc)) = (
                self.scratch.get(a),
                self.scratch.get(b),
                self.scratch.get(c),
            ) else {
                continue;
            };
            // Cross product length = 2·area, so summing it area-weights the normals.
            let n = (*pb - *pa).cross(*pc - *pa);
            for i in [a, b, c] {
                self.normals[i] += n;
            }
        }
        self.vertices.clear();
        self.vertices.extend(
            self.scratch
                .iter()
                .zip(&self.normals)
                .map(|(p, n)| MeshVertex {
                    position: p.as_vec3().to_array(),
                    normal: n.normalize_or_zero().as_vec3().to_array(),
                }),
        );
        self.generation += 1;
        Ok(())
    }

    /// The blended vertices (what the renderer uploads).
    pub fn vertices(&self) -> &[MeshVertex] {
        &self.vertices
    }

    /// The blended positions in f64, before rounding to f32.
    pub fn positions_f64(&self) -> &[DVec3] {
        &self.scratch
    }

    /// Increases by one at every [`PosedMesh::update`]; the renderer re-uploads when it changes.
    pub fn generation(&self) -> u64 {
        self.generation
    }
}

/// Unique undirected edges of a triangle list, as a line-list index buffer (for wireframe).
pub fn edge_indices(triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut edges: Vec<(u32, u32)> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges.into_iter().flat_map(|(a, b)| [a, b]).collect()
}

/// Centre and radius of the bounding box of `points` (None when empty or not finite).
pub fn bounding_sphere(points: &[DVec3]) -> Option<(DVec3, f64)> {
    let first = *points.first()?;
    let (lo, hi) = points
        .iter()
        .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let centre = 0.5 * (lo + hi);
    let radius = 0.5 * (hi - lo).length();
    (centre.is_finite() && radius.is_finite()).then_some((centre, radius))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_point_along_triangle_winding_and_edges_are_unique() {
        let basis = MuscleBasis {
            muscle_ids: vec![],
            neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)],
            triangles: vec![[0, 1, 2], [1, 3, 2]],
            displacements: vec![],
        };
        let mut mesh = PosedMesh::default();
        mesh.update(&basis, &[]).unwrap();
        for v in mesh.vertices() {
            assert_eq!(v.normal, [0.0, 0.0, 1.0]);
        }
        assert_eq!(mesh.generation(), 1);
        // 5 unique edges (the diagonal 1-2 is shared).
        assert_eq!(
            edge_indices(&basis.triangles),
            vec![0, 1, 0, 2, 1, 2, 1, 3, 2, 3]
        );
        let (c, r) = bounding_sphere(&basis.neutral).unwrap();
        assert_eq!(c, DVec3::new(0.5, 0.5, 0.0));
        assert!((r - 0.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn wrong_slider_count_is_an_error_not_a_panic() {
        let basis = MuscleBasis {
            muscle_ids: vec!["a".into()],
            neutral: vec![DVec3::ZERO],
            triangles: vec![],
            displacements: vec![vec![DVec3::X]],
        };
        let mut mesh = PosedMesh::default();
        assert!(matches!(
            mesh.update(&basis, &[0.1, 0.2]),
            Err(PoseError::SliderCount {
                expected: 1,
                got: 2
            })
        ));
    }
}
