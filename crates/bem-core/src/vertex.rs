//! Element values to vertex values.

use glam::DVec3;

use crate::{BemError, SurfaceMesh};

/// Area-weighted average, at every vertex, of the values of its adjacent elements
/// (vertices used by no element get zero).
///
/// ```
/// use bem_core::{element_to_vertex, shapes};
/// use glam::DVec3;
/// let mesh = shapes::sphere(1, 1.0).unwrap();
/// let v = element_to_vertex(&mesh, &vec![DVec3::X; mesh.element_count()]).unwrap();
/// assert!(v.iter().all(|d| (*d - DVec3::X).length() < 1e-15));
/// ```
pub fn element_to_vertex(mesh: &SurfaceMesh, values: &[DVec3]) -> Result<Vec<DVec3>, BemError> {
    if values.len() != mesh.element_count() {
        return Err(BemError::WrongLength {
            what: "element values",
            expected: mesh.element_count(),
            got: values.len(),
        });
    }
    let mut sum = vec![DVec3::ZERO; mesh.vertices().len()];
    let mut weight = vec![0.0; mesh.vertices().len()];
    for (e, tri) in mesh.triangles().iter().enumerate() {
        let a = mesh.area(e);
        for &v in tri {
            sum[v as usize] += a * values[e];
            weight[v as usize] += a;
        }
    }
    Ok(sum
        .into_iter()
        .zip(weight)
        .map(|(s, w)| if w > 0.0 { s / w } else { DVec3::ZERO })
        .collect())
}
