//! Views and the orthographic camera of a contact-sheet panel.
//!
//! Everything is drawn in the rig's canonical frame (`FaceRig::canonical_from_input`): the face
//! lies in x-y and looks toward +z, y is up, the face's own left is +x. A view turns the camera
//! about the vertical (y) axis by its yaw; at yaw 0 the camera looks down −z at the face, so the
//! face's left (+x) is on the image's right, as when facing a person. A positive yaw moves the
//! camera toward the face's left, showing its left cheek.

use glam::{DMat3, DVec3};

/// One viewing direction of every cell.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// Caption drawn in the panel (e.g. `"front"`).
    pub name: String,
    /// Camera yaw in degrees about the canonical y axis; positive toward the face's left.
    pub yaw_deg: f64,
}

impl View {
    /// The front view (yaw 0).
    pub fn front() -> View {
        View {
            name: "front".into(),
            yaw_deg: 0.0,
        }
    }

    /// The three-quarter view: camera 35° toward the face's left.
    pub fn three_quarter() -> View {
        View {
            name: "3/4 left".into(),
            yaw_deg: 35.0,
        }
    }

    /// Rotation from the canonical frame to view space (x right, y up, +z toward the camera).
    pub fn rotation(&self) -> DMat3 {
        DMat3::from_rotation_y(-self.yaw_deg.to_radians())
    }
}

/// Orthographic projection of canonical points into a panel's pixels: view-space x → pixel x,
/// view-space y → pixel y downward, view-space z is the depth (larger = nearer the camera).
///
/// ```
/// use facebem::report::contact_sheet::{Camera, View};
/// use glam::DVec3;
/// let pts = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
/// let cam = Camera::fit(&View::front(), &pts, 100, 100, 0.0);
/// let (x, y, _) = cam.project(DVec3::new(1.0, 1.0, 0.0));
/// assert!((x - 100.0).abs() < 1e-9 && y.abs() < 1e-9); // +x right, +y up
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Canonical → view-space rotation.
    pub rotation: DMat3,
    /// Pixels per model unit.
    pub pixels_per_unit: f64,
    /// Pixel position of the view-space origin.
    pub origin_px: (f64, f64),
}

impl Camera {
    /// The camera of `view` that fits `points` (canonical frame) into a `width` × `height` panel,
    /// leaving `margin` (a fraction of the panel) free on every side, centred. The same camera
    /// is used for every cell of a sheet (fitted to the neutral face), so the faces of all
    /// cells line up and motion is seen against a fixed frame.
    pub fn fit(view: &View, points: &[DVec3], width: u32, height: u32, margin: f64) -> Camera {
        let rotation = view.rotation();
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for &p in points {
            let q = rotation * p;
            lo = lo.min(q);
            hi = hi.max(q);
        }
        if !(lo.x.is_finite() && hi.x.is_finite() && lo.y.is_finite() && hi.y.is_finite()) {
            (lo, hi) = (DVec3::splat(-1.0), DVec3::splat(1.0));
        }
        let (w, h) = (f64::from(width), f64::from(height));
        let free = (1.0 - 2.0 * margin).max(0.05);
        let span_x = (hi.x - lo.x).max(1e-12);
        let span_y = (hi.y - lo.y).max(1e-12);
        let pixels_per_unit = (free * w / span_x).min(free * h / span_y);
        let centre = 0.5 * (lo + hi);
        Camera {
            rotation,
            pixels_per_unit,
            origin_px: (
                0.5 * w - pixels_per_unit * centre.x,
                0.5 * h + pixels_per_unit * centre.y,
            ),
        }
    }

    /// Pixel x, pixel y (downward) and depth (model units, larger = nearer) of a canonical point.
    pub fn project(&self, p: DVec3) -> (f64, f64, f64) {
        let q = self.rotation * p;
        (
            self.origin_px.0 + self.pixels_per_unit * q.x,
            self.origin_px.1 - self.pixels_per_unit * q.y,
            q.z,
        )
    }
}
