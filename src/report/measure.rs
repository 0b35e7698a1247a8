//! Measuring expressions in millimetres: landmarks of the user's face (mouth corners, brows,
//! outer contour), displacements at them, flipped triangles and the similarity of two
//! displacement fields. Used by the tests that hold the muscle model to human motion, the
//! `calibrate` example and the contact sheet.

use face_prep::FaceMesh;
use face_prep::orient::{FaceLoops, loop_centroid};
use glam::{DAffine3, DVec2, DVec3};

use crate::FaceModel;

/// Landmarks of a face, as indices of its own (welded) vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceLandmarks {
    /// The input → canonical transform the landmarks were measured in (the rig's).
    pub canonical_from_input: DAffine3,
    /// The four loops of the input mesh.
    pub loops: FaceLoops,
    /// Mouth-loop vertex of largest canonical x (the face's left corner).
    pub mouth_corner_l: u32,
    /// Mouth-loop vertex of smallest canonical x.
    pub mouth_corner_r: u32,
    /// Brow point above the left eye: the front vertex nearest, in the front plane, to the eye
    /// loop's centre x at [`BROW_ABOVE_EYE_TOP_IOD`] interocular distances above the eye loop's top.
    pub brow_l: u32,
    /// The same above the right eye.
    pub brow_r: u32,
    /// The brow point above the left eye itself, on the surface (the point [`Self::brow_l`] is
    /// the nearest vertex to; [`SurfacePoint::vertex`] of it where no front triangle lies over
    /// the point). A vertex can sit millimetres off the point on a coarse mesh, where the brow
    /// raise falls off steeply toward the lid: ICT dec2500's right brow vertex rises 7.3 mm
    /// at full frontalis, the point 9.2 mm (the left 11.2 and 10.0; ICT 13k 10.5 on both).
    pub brow_point_l: SurfacePoint,
    /// The same above the right eye.
    pub brow_point_r: SurfacePoint,
    /// Inner brow above the left eye: the front vertex nearest, in the front plane, to the eye
    /// loop's medial end (its vertex nearest the face's midline) at [`BROW_ABOVE_EYE_TOP_IOD`]
    /// interocular distances above the eye loop's top (where the corrugator pulls: AU4).
    pub brow_inner_l: u32,
    /// The same above the right eye.
    pub brow_inner_r: u32,
    /// The inner brow point above the left eye itself, on the surface (as
    /// [`Self::brow_point_l`] is for [`Self::brow_l`]).
    pub brow_inner_point_l: SurfacePoint,
    /// The same above the right eye.
    pub brow_inner_point_r: SurfacePoint,
    /// Millimetres per mesh unit (the rig's unit).
    pub mm_per_unit: f64,
}

/// A point on a mesh's surface: the corners of the triangle holding it and its barycentric
/// weights there, so any per-vertex field can be read at the point itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// The triangle's vertices.
    pub corners: [u32; 3],
    /// Barycentric weights of the point (non-negative, summing to 1).
    pub weights: [f64; 3],
}

impl SurfacePoint {
    /// The point at vertex `v`.
    ///
    /// ```
    /// use facebem::report::measure::SurfacePoint;
    /// use glam::DVec3;
    /// let field = [DVec3::X, DVec3::Y];
    /// assert_eq!(SurfacePoint::vertex(1).sample(&field), DVec3::Y);
    /// ```
    pub fn vertex(v: u32) -> SurfacePoint {
        SurfacePoint {
            corners: [v; 3],
            weights: [1.0, 0.0, 0.0],
        }
    }

    /// The frontmost point of the surface (largest z) over `xy` in the front plane: of the
    /// triangles of `points` (canonical frame) whose x-y projection holds `xy`, the one that is
    /// highest there. `None` when no triangle lies over `xy` (or it is not finite).
    ///
    /// ```
    /// use facebem::report::measure::SurfacePoint;
    /// use glam::{DVec2, DVec3};
    /// // Two stacked triangles; the point is read on the upper one (z = 1).
    /// let p = [DVec3::ZERO, DVec3::X, DVec3::Y,
    ///          DVec3::new(0.0, 0.0, 1.0), DVec3::new(1.0, 0.0, 1.0), DVec3::new(0.0, 1.0, 1.0)];
    /// let s = SurfacePoint::over(&p, &[[0, 1, 2], [3, 4, 5]], DVec2::new(0.25, 0.5)).unwrap();
    /// assert_eq!(s.corners, [3, 4, 5]);
    /// let field = [DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::X * 4.0, DVec3::ZERO];
    /// assert!((s.sample(&field).x - 1.0).abs() < 1e-12);
    /// ```
    pub fn over(points: &[DVec3], triangles: &[[u32; 3]], xy: DVec2) -> Option<SurfacePoint> {
        if !xy.is_finite() {
            return None;
        }
        let mut best: Option<(f64, SurfacePoint)> = None;
        for t in triangles {
            if t.iter().any(|&i| i as usize >= points.len()) {
                continue;
            }
            let [a, b, c] = t.map(|i| points[i as usize]);
            let (a2, b2, c2) = (a.truncate(), b.truncate(), c.truncate());
            let det = (b2 - a2).perp_dot(c2 - a2);
            // Triangles seen edge-on (or degenerate, or not finite) hold no point of the plane.
            let scale = (b2 - a2).length_squared().max(f64::MIN_POSITIVE);
            if det.is_nan() || det.abs() <= f64::EPSILON * scale {
                continue;
            }
            let w1 = (xy - a2).perp_dot(c2 - a2) / det;
            let w2 = (b2 - a2).perp_dot(xy - a2) / det;
            let w0 = 1.0 - w1 - w2;
            let tol = -1e-9;
            let z = a.z * w0 + b.z * w1 + c.z * w2;
            let inside = w0 >= tol && w1 >= tol && w2 >= tol && z.is_finite();
            if !inside {
                continue;
            }
            if best.as_ref().is_none_or(|(bz, _)| z > *bz) {
                let w = [w0.max(0.0), w1.max(0.0), w2.max(0.0)];
                let sum = w[0] + w[1] + w[2];
                best = Some((
                    z,
                    SurfacePoint {
                        corners: *t,
                        weights: w.map(|x| x / sum),
                    },
                ));
            }
        }
        best.map(|(_, s)| s)
    }

    /// A per-vertex field at the point (vertices missing from `field` count as zero).
    pub fn sample(&self, field: &[DVec3]) -> DVec3 {
        self.corners
            .iter()
            .zip(self.weights)
            .map(|(&v, w)| field.get(v as usize).copied().unwrap_or(DVec3::ZERO) * w)
            .sum()
    }
}

/// Height of the brow landmark above the eye loop's top, in interocular distances (0.25 iod ≈
/// 16 mm on an adult: the middle of the eyebrow).
pub const BROW_ABOVE_EYE_TOP_IOD: f64 = 0.25;

impl FaceLandmarks {
    /// Landmarks of `model`'s input mesh, measured in its rig's canonical frame and unit.
    /// `None` when the mesh does not have four loops (it always has for a computed model).
    pub fn of(model: &FaceModel) -> Option<FaceLandmarks> {
        FaceLandmarks::of_mesh(
            &model.mesh,
            model.rig.canonical_from_input,
            model.rig.mm_per_unit(),
        )
    }

    /// Landmarks of a mesh in the given canonical frame.
    pub fn of_mesh(
        mesh: &FaceMesh,
        canonical_from_input: DAffine3,
        mm_per_unit: f64,
    ) -> Option<FaceLandmarks> {
        let crate::frame::CanonicalFace { loops, points: c } =
            crate::frame::CanonicalFace::of_mesh(mesh, canonical_from_input)?;
        let (mouth_corner_l, mouth_corner_r) = crate::frame::mouth_corners(&c, &loops.mouth)?;
        let eye_l = loop_centroid(&c, &loops.eye_l);
        let eye_r = loop_centroid(&c, &loops.eye_r);
        let iod = eye_l.truncate().distance(eye_r.truncate());
        let top = |lp: &[u32]| lp.iter().map(|&i| c[i as usize].y).fold(f64::MIN, f64::max);
        let nearest = |x: f64, y: f64| {
            (0..c.len() as u32).min_by(|&a, &b| {
                let d = |i: u32| (c[i as usize].x - x).powi(2) + (c[i as usize].y - y).powi(2);
                d(a).total_cmp(&d(b))
            })
        };
        let brow_xy_l = DVec2::new(eye_l.x, top(&loops.eye_l) + BROW_ABOVE_EYE_TOP_IOD * iod);
        let brow_xy_r = DVec2::new(eye_r.x, top(&loops.eye_r) + BROW_ABOVE_EYE_TOP_IOD * iod);
        let brow_l = nearest(brow_xy_l.x, brow_xy_l.y)?;
        let brow_r = nearest(brow_xy_r.x, brow_xy_r.y)?;
        let brow_point_l = SurfacePoint::over(&c, &mesh.triangles, brow_xy_l)
            .unwrap_or(SurfacePoint::vertex(brow_l));
        let brow_point_r = SurfacePoint::over(&c, &mesh.triangles, brow_xy_r)
            .unwrap_or(SurfacePoint::vertex(brow_r));
        let midline = 0.5 * (eye_l.x + eye_r.x);
        let medial_x = |lp: &[u32]| {
            lp.iter()
                .map(|&i| c[i as usize].x)
                .min_by(|a, b| (a - midline).abs().total_cmp(&(b - midline).abs()))
        };
        let inner_xy_l = DVec2::new(
            medial_x(&loops.eye_l)?,
            top(&loops.eye_l) + BROW_ABOVE_EYE_TOP_IOD * iod,
        );
        let inner_xy_r = DVec2::new(
            medial_x(&loops.eye_r)?,
            top(&loops.eye_r) + BROW_ABOVE_EYE_TOP_IOD * iod,
        );
        let brow_inner_l = nearest(inner_xy_l.x, inner_xy_l.y)?;
        let brow_inner_r = nearest(inner_xy_r.x, inner_xy_r.y)?;
        let brow_inner_point_l = SurfacePoint::over(&c, &mesh.triangles, inner_xy_l)
            .unwrap_or(SurfacePoint::vertex(brow_inner_l));
        let brow_inner_point_r = SurfacePoint::over(&c, &mesh.triangles, inner_xy_r)
            .unwrap_or(SurfacePoint::vertex(brow_inner_r));
        Some(FaceLandmarks {
            canonical_from_input,
            loops,
            mouth_corner_l,
            mouth_corner_r,
            brow_l,
            brow_r,
            brow_point_l,
            brow_point_r,
            brow_inner_point_l,
            brow_inner_point_r,
            brow_inner_l,
            brow_inner_r,
            mm_per_unit,
        })
    }

    /// Points of the input frame (a mesh's vertices) in the canonical frame, face units.
    ///
    /// ```
    /// let mesh = facebem::input::default_face().unwrap();
    /// let lm = facebem::report::measure::FaceLandmarks::of_mesh(
    ///     &mesh, glam::DAffine3::IDENTITY, 1.0).unwrap();
    /// assert_eq!(lm.canonical_points(&mesh.vertices), mesh.vertices);
    /// ```
    pub fn canonical_points(&self, points: &[DVec3]) -> Vec<DVec3> {
        points
            .iter()
            .map(|&p| self.canonical_from_input.transform_point3(p))
            .collect()
    }

    /// A displacement of the input frame, in the canonical frame and in mm.
    pub fn canonical_mm(&self, d: DVec3) -> DVec3 {
        self.canonical_from_input.transform_vector3(d) * self.mm_per_unit
    }

    /// Largest displacement, mm, of any vertex of the outer contour.
    pub fn contour_motion_mm(&self, field: &[DVec3]) -> f64 {
        self.loops
            .face
            .iter()
            .filter_map(|&i| field.get(i as usize))
            .map(|d| d.length() * self.mm_per_unit)
            .fold(0.0, f64::max)
    }
}

/// Elevation in degrees above the horizontal of a canonical displacement `d` in the front
/// plane (x-y), with `lateral_sign` = +1 for the face's left (+x): 90° straight up, 0° straight
/// out, negative downward.
///
/// ```
/// use glam::DVec3;
/// let up_and_out = facebem::report::measure::elevation_deg(DVec3::new(-1.0, 1.0, 0.3), -1.0);
/// assert!((up_and_out - 45.0).abs() < 1e-9);
/// ```
pub fn elevation_deg(d: DVec3, lateral_sign: f64) -> f64 {
    d.y.atan2(lateral_sign * d.x).to_degrees()
}

/// Largest vertex displacement of a field (in the field's units).
pub fn max_length(field: &[DVec3]) -> f64 {
    field.iter().map(|d| d.length()).fold(0.0, f64::max)
}

/// Cosine similarity of two displacement fields over the same vertices: `a·b / (|a| |b|)`
/// (1 = same shape, whatever the scale; 0 when either is zero).
///
/// ```
/// use glam::DVec3;
/// let a = [DVec3::X, DVec3::Y];
/// let b = [DVec3::X * 2.0, DVec3::Y * 2.0];
/// assert!((facebem::report::measure::cosine(&a, &b) - 1.0).abs() < 1e-12);
/// ```
pub fn cosine(a: &[DVec3], b: &[DVec3]) -> f64 {
    let dot: f64 = a.iter().zip(b).map(|(x, y)| x.dot(*y)).sum();
    let na: f64 = a.iter().map(|x| x.length_squared()).sum::<f64>().sqrt();
    let nb: f64 = b.iter().map(|x| x.length_squared()).sum::<f64>().sqrt();
    if na > 0.0 && nb > 0.0 {
        dot / (na * nb)
    } else {
        0.0
    }
}

/// Triangles that turn over when `neutral` is displaced by `field` (one displacement per
/// vertex): [`flipped_triangles`] of the displaced mesh.
///
/// ```
/// use glam::DVec3;
/// let v = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let fold = [DVec3::ZERO, DVec3::ZERO, DVec3::new(0.0, -2.0, 0.0)];
/// assert_eq!(facebem::report::measure::flipped_by(&v, &fold, &[[0, 1, 2]]), vec![0]);
/// ```
pub fn flipped_by(neutral: &[DVec3], field: &[DVec3], triangles: &[[u32; 3]]) -> Vec<u32> {
    let posed: Vec<DVec3> = neutral.iter().zip(field).map(|(a, b)| *a + *b).collect();
    flipped_triangles(neutral, &posed, triangles)
}

/// Triangles whose normal reverses between `neutral` and `posed` (the dot product of the two
/// normals is negative): folded skin or an inverted element.
pub fn flipped_triangles(neutral: &[DVec3], posed: &[DVec3], triangles: &[[u32; 3]]) -> Vec<u32> {
    let normal = |p: &[DVec3], t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| p[i as usize]);
        (b - a).cross(c - a)
    };
    triangles
        .iter()
        .enumerate()
        .filter(|(_, t)| normal(neutral, t).dot(normal(posed, t)) < 0.0)
        .map(|(i, _)| i as u32)
        .collect()
}
