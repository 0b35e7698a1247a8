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

/// Cosine of the largest angle between two adjacent elements' normals at a vertex that
/// [`element_to_vertex_linear`] fits (60°); beyond it the vertex is on a sharp edge.
const SMOOTH_SIDE_COS: f64 = 0.5;

/// Smallest determinant, relative to the cube of the total weight, of the normalised fit
/// matrix that [`element_to_vertex_linear`] accepts (below it the centroids are nearly
/// collinear and the fit falls back to the area-weighted average).
const MIN_FIT_DETERMINANT: f64 = 1e-4;

/// Vertex values recovered from element values by a linear fit over each vertex's adjacent
/// elements (patch recovery): at every vertex, the affine function of the position in its
/// tangent plane that fits the adjacent elements' centroid values best (least squares,
/// weighted by area) is evaluated at the vertex, each component limited to the range of the
/// values it was fitted to. A field that varies linearly over the patch is recovered exactly,
/// whatever the elements' sizes and shapes; the plain area-weighted average
/// ([`element_to_vertex`]) leans toward the values of the largest adjacent elements, whose
/// centroids lie farthest away. Where the field is not one smooth function over the patch,
/// the vertex takes the area-weighted average instead: on a sharp edge (two adjacent elements'
/// normals more than 60° apart), beside an element whose value was
/// prescribed (`prescribed[e]`: e.g. skin held at zero next to skin that moves, a jump the
/// fit would extrapolate into a peak), where fewer than three elements meet, or where their
/// centroids are nearly collinear.
///
/// ```
/// use bem_core::{element_to_vertex, element_to_vertex_linear, SurfaceMesh};
/// use glam::DVec3;
/// // A closed double cone: a fan of unequal triangles around vertex 0 in the plane z = 0 on
/// // top, an apex below; and a field u = x.
/// let vertices = vec![
///     DVec3::ZERO,
///     DVec3::new(1.0, 0.0, 0.0),
///     DVec3::new(0.0, 1.0, 0.0),
///     DVec3::new(-4.0, 0.0, 0.0),
///     DVec3::new(0.0, -1.0, 0.0),
///     DVec3::new(0.0, 0.0, -1.0),
/// ];
/// let triangles = vec![
///     [0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1],
///     [5, 2, 1], [5, 3, 2], [5, 4, 3], [5, 1, 4],
/// ];
/// let flat = SurfaceMesh::new(vertices, triangles).unwrap();
/// let u: Vec<DVec3> = flat.centroids().iter().map(|c| DVec3::new(c.x, 0.0, 0.0)).collect();
/// let linear = element_to_vertex_linear(&flat, &u, &[false; 8]).unwrap();
/// let average = element_to_vertex(&flat, &u).unwrap();
/// assert!(linear[0].length() < 1e-12); // u(0) = 0 exactly
/// assert!(average[0].x < -0.5); // pulled toward the two large triangles
/// assert_eq!(linear[5], average[5]); // the apex is a sharp point: averaged
/// ```
pub fn element_to_vertex_linear(
    mesh: &SurfaceMesh,
    values: &[DVec3],
    prescribed: &[bool],
) -> Result<Vec<DVec3>, BemError> {
    let average = element_to_vertex(mesh, values)?;
    if prescribed.len() != mesh.element_count() {
        return Err(BemError::WrongLength {
            what: "prescribed-element flags",
            expected: mesh.element_count(),
            got: prescribed.len(),
        });
    }
    let vertex_count = mesh.vertices().len();
    let mut adjacent: Vec<Vec<u32>> = vec![Vec::new(); vertex_count];
    for (e, tri) in mesh.triangles().iter().enumerate() {
        for &v in tri {
            adjacent[v as usize].push(e as u32);
        }
    }
    Ok(adjacent
        .iter()
        .enumerate()
        .map(|(v, elements)| {
            if elements.iter().any(|&e| prescribed[e as usize]) {
                return average[v];
            }
            fit_at_vertex(mesh, values, mesh.vertices()[v], elements).unwrap_or(average[v])
        })
        .collect())
}

/// [`element_to_vertex_linear`] at one vertex `x`; `None` where it falls back to the average.
fn fit_at_vertex(
    mesh: &SurfaceMesh,
    values: &[DVec3],
    x: DVec3,
    elements: &[u32],
) -> Option<DVec3> {
    let normal = elements
        .iter()
        .map(|&e| mesh.area(e as usize) * mesh.normal(e as usize))
        .sum::<DVec3>()
        .try_normalize()?;
    let patch: Vec<usize> = elements.iter().map(|&e| e as usize).collect();
    let sharp = patch.iter().enumerate().any(|(i, &a)| {
        patch[i + 1..]
            .iter()
            .any(|&b| mesh.normal(a).dot(mesh.normal(b)) < SMOOTH_SIDE_COS)
    });
    if patch.len() < 3 || sharp {
        return None;
    }
    let (t1, t2) = normal.any_orthonormal_pair();
    let scale = patch
        .iter()
        .map(|&e| (mesh.centroid(e) - x).length())
        .sum::<f64>()
        / patch.len() as f64;
    if scale <= 0.0 || !scale.is_finite() {
        return None;
    }
    let mut m = glam::DMat3::ZERO;
    let mut rhs = [DVec3::ZERO; 3];
    let mut total = 0.0;
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &e in &patch {
        let d = (mesh.centroid(e) - x) / scale;
        let basis = DVec3::new(1.0, d.dot(t1), d.dot(t2));
        let w = mesh.area(e);
        m += glam::DMat3::from_cols(basis * basis.x, basis * basis.y, basis * basis.z) * w;
        for (r, b) in rhs.iter_mut().zip(basis.to_array()) {
            *r += values[e] * (w * b);
        }
        total += w;
        lo = lo.min(values[e]);
        hi = hi.max(values[e]);
    }
    if total <= 0.0 || m.determinant() < MIN_FIT_DETERMINANT * total.powi(3) {
        return None;
    }
    // The value at the vertex is the constant term: the first row of M⁻¹ applied to the
    // right-hand sides (M is symmetric, so its first column).
    let first = m.inverse().x_axis;
    let fitted = rhs[0] * first.x + rhs[1] * first.y + rhs[2] * first.z;
    fitted.is_finite().then(|| fitted.clamp(lo, hi))
}
