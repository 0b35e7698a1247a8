//! Rolled-in eyelids and lips: the parts of the surface that curl behind the eye and mouth
//! contours are not simulated.
//!
//! Some scanned or artist-made faces (the ICT faces) continue the eyelids and lips past their
//! visible edge and roll them inward, facing away from the viewer; the lips even press
//! together. Offset into a shell, such a flap is tissue far thinner than an element, on which
//! the constant-element BEM is close to singular: responses of up to 1751 times the muscles' own
//! motion on the ICT 13k face, depending on details of its simplified copy. [`peel_rolled_in`]
//! removes those triangles from the simulated copy, so the knife edges sit at the visible lid
//! and lip margins; the peeled vertices take the displacement of the nearest simulated point
//! like every other vertex of a reduced copy ([`crate::transfer::Transfer`]).

use crate::copy::Simplified;
use glam::DVec3;
use std::collections::HashSet;

/// Removes, from the face `face`, the triangles that face away from the viewer (canonical
/// normal z < 0) and are connected to an eye or mouth contour through such triangles; then
/// puts back removed triangles around any vertex that was left with two boundary fans (so the
/// surface stays a manifold). Returns `None` when nothing is peeled or when the result would
/// not be a face with four boundary loops (the caller then simulates the surface as it is).
///
/// ```
/// use facebem::copy::Simplified;
/// use facebem::copy::rolled_in::peel_rolled_in;
/// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
///     .join("assets/ict_narrow_face_dec2500_4loop.obj");
/// let face = face_prep::load_face(&path).unwrap();
/// let whole = Simplified::whole(&face.vertices, &face.triangles);
/// let peeled = peel_rolled_in(&whole).unwrap();
/// assert!(peeled.triangles.len() < face.triangles.len());
/// ```
pub fn peel_rolled_in(face: &Simplified) -> Option<Simplified> {
    let loops = face_prep::topology::validate(&face.vertices, &face.triangles).ok()?;
    let (canonical_from_face, loops) =
        face_prep::orient::canonical_frame(&face.vertices, &face.triangles, &loops).ok()?;
    let canonical_z = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| canonical_from_face.transform_point3(face.vertices[i as usize]));
        (b - a).cross(c - a).z
    };
    let mut on_cut = vec![false; face.vertices.len()];
    for lp in [&loops.eye_l, &loops.eye_r, &loops.mouth] {
        for &v in lp.iter() {
            on_cut[v as usize] = true;
        }
    }
    let mut kept = vec![true; face.triangles.len()];
    loop {
        let mut changed = false;
        for (t, tri) in face.triangles.iter().enumerate() {
            if kept[t] && tri.iter().any(|&v| on_cut[v as usize]) && canonical_z(tri) < 0.0 {
                kept[t] = false;
                changed = true;
                for &v in tri {
                    on_cut[v as usize] = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    restore_bow_ties(&face.triangles, &mut kept, face.vertices.len());
    if kept.iter().all(|&k| k) {
        return None;
    }
    let triangles: Vec<[u32; 3]> = face
        .triangles
        .iter()
        .zip(&kept)
        .filter(|(_, k)| **k)
        .map(|(t, _)| *t)
        .collect();
    let peeled = face.subset(&triangles);
    let loops = face_prep::topology::validate(&peeled.vertices, &peeled.triangles).ok()?;
    (loops.len() == 4).then_some(peeled)
}

/// Puts removed triangles back around every vertex that has more than one outgoing boundary
/// edge among the kept triangles, until there is none.
fn restore_bow_ties(triangles: &[[u32; 3]], kept: &mut [bool], vertex_count: usize) {
    loop {
        let edges: HashSet<(u32, u32)> = triangles
            .iter()
            .zip(kept.iter())
            .filter(|(_, k)| **k)
            .flat_map(|(t, _)| (0..3).map(move |i| (t[i], t[(i + 1) % 3])))
            .collect();
        let mut boundary_out = vec![0u32; vertex_count];
        for &(a, b) in &edges {
            if !edges.contains(&(b, a)) {
                boundary_out[a as usize] += 1;
            }
        }
        let mut restored = false;
        for (t, tri) in triangles.iter().enumerate() {
            if !kept[t] && tri.iter().any(|&v| boundary_out[v as usize] > 1) {
                kept[t] = true;
                restored = true;
            }
        }
        if !restored {
            return;
        }
    }
}

/// Displacements of peeled (rolled-in) vertices as the harmonic extension of the simulated
/// surface's displacements over the peeled flaps: each peeled vertex ends at the mean of its
/// neighbours over the triangles' edges (an edge of two triangles counted twice), the simulated
/// vertices held, solved exactly ([`face_prep::harmonic::extend`]); a flap that touches no
/// simulated vertex keeps the field as given (e.g. the closest margin point's). A flap thus
/// hangs smoothly from its margin; taking each vertex's closest margin point alone folded the
/// triangles of the mouth corners, where the upper and lower lip margins meet and move
/// differently.
///
/// ```
/// use glam::DVec3;
/// // A strip 0-1-2-3: the middle vertices 1, 2 are peeled, the ends move by 0 and 3.
/// let tris = [[0, 1, 4], [1, 2, 4], [2, 3, 4]];
/// let mut field = vec![DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::X * 3.0, DVec3::X];
/// facebem::copy::rolled_in::hang_from_margins(&mut field, &tris, &[1, 2]);
/// assert!(field[1].x > 0.0 && field[1].x < field[2].x && field[2].x < 3.0);
/// ```
pub fn hang_from_margins(field: &mut [DVec3], triangles: &[[u32; 3]], peeled: &[u32]) {
    if peeled.is_empty() {
        return;
    }
    let n = field.len();
    let mut is_peeled = vec![false; n];
    for &v in peeled {
        if let Some(p) = is_peeled.get_mut(v as usize) {
            *p = true;
        }
    }
    let edges: Vec<(u32, u32, f64)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3], 1.0)))
        .filter(|&(a, b, _)| (a as usize) < n && (b as usize) < n && a != b)
        .collect();
    // In range by construction; a failed factorisation leaves the field as given.
    let _ = face_prep::harmonic::extend(&edges, &is_peeled, field);
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A square face, 12 x 12 quads, with three square holes (two eyes, a mouth); around the
    /// mouth, if `rolled`, the ring of triangles next to the hole is tilted to face −z (a lip
    /// rolled inward).
    fn face_with_lip(rolled: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let n = 13usize;
        let idx = |x: usize, y: usize| (y * n + x) as u32;
        let mut vertices: Vec<DVec3> = (0..n * n)
            .map(|i| DVec3::new((i % n) as f64, (i / n) as f64, 0.0))
            .collect();
        let hole =
            |x: usize, y: usize| ((x == 3 || x == 8) && y == 8) || ((4..=7).contains(&x) && y == 3);
        let mut triangles = vec![];
        for y in 0..n - 1 {
            for x in 0..n - 1 {
                if hole(x, y) {
                    continue;
                }
                triangles.push([idx(x, y), idx(x + 1, y), idx(x + 1, y + 1)]);
                triangles.push([idx(x, y), idx(x + 1, y + 1), idx(x, y + 1)]);
            }
        }
        if !rolled {
            return (vertices, triangles);
        }
        // Roll the mouth's inner vertex ring back: the vertices on the hole's border move
        // outward past their neighbours and down, so the ring's triangles face −z.
        for x in 4..=8 {
            for y in [3, 4] {
                let v = idx(x, y) as usize;
                let dy = if y == 3 { -1.5 } else { 1.5 };
                vertices[v] += DVec3::new(0.0, dy, -1.0);
            }
        }
        (vertices, triangles)
    }

    #[test]
    fn a_lip_rolled_behind_its_contour_is_peeled_and_the_face_keeps_four_loops() {
        let (vertices, triangles) = face_with_lip(true);
        let whole = Simplified::whole(&vertices, &triangles);
        let peeled = peel_rolled_in(&whole).expect("something to peel");
        let removed = triangles.len() - peeled.triangles.len();
        assert!(removed >= 8, "only {removed} triangles peeled");
        // Every kept triangle faces the viewer where it touches the (new) mouth contour, and
        // no triangle facing away is left next to a contour.
        let loops = face_prep::topology::validate(&peeled.vertices, &peeled.triangles).unwrap();
        assert_eq!(loops.len(), 4);
        let (frame, fl) =
            face_prep::orient::canonical_frame(&peeled.vertices, &peeled.triangles, &loops)
                .unwrap();
        let on_inner: HashSet<u32> = [&fl.eye_l, &fl.eye_r, &fl.mouth]
            .into_iter()
            .flatten()
            .copied()
            .collect();
        for t in &peeled.triangles {
            if t.iter().any(|v| on_inner.contains(v)) {
                let [a, b, c] = t.map(|i| frame.transform_point3(peeled.vertices[i as usize]));
                assert!((b - a).cross(c - a).z > 0.0, "rolled triangle {t:?} kept");
            }
        }
        // The kept vertices are the originals.
        for (k, &o) in peeled.original_vertex.iter().enumerate() {
            assert_eq!(peeled.vertices[k], vertices[o as usize]);
        }
    }

    #[test]
    fn a_face_without_rolled_parts_is_left_alone() {
        let (vertices, triangles) = face_with_lip(false);
        assert_eq!(
            peel_rolled_in(&Simplified::whole(&vertices, &triangles)),
            None
        );
    }
}
