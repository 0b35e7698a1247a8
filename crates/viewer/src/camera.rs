//! Orbit camera of the 3D viewport: orbit, pan, zoom, reset, and picking rays.

use glam::{Mat4, Vec2, Vec3};

/// A camera orbiting a target point. Angles in radians; the home pose looks along −z
/// (from +z toward the face, which is how the bundled faces are oriented).
///
/// ```
/// use viewer::camera::OrbitCamera;
/// use glam::Vec3;
/// let mut cam = OrbitCamera::framing(Vec3::ZERO, 1.0);
/// cam.orbit(0.3, 0.1);
/// cam.reset();
/// assert!((cam.eye() - Vec3::new(0.0, 0.0, cam.distance)).length() < 1e-5);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitCamera {
    /// Point the camera looks at (world space).
    pub target: Vec3,
    /// Distance from the target to the eye.
    pub distance: f32,
    /// Rotation about the world y axis (0 = eye on +z).
    pub yaw: f32,
    /// Elevation above the x-z plane, clamped to ±[`OrbitCamera::MAX_PITCH`].
    pub pitch: f32,
    /// Vertical field of view.
    pub fov_y: f32,
    home: (Vec3, f32),
}

impl OrbitCamera {
    /// Largest pitch magnitude (just under 90°, so the up vector stays defined).
    pub const MAX_PITCH: f32 = 1.55;

    /// A camera framing a sphere of `radius` around `center`, looking along −z.
    pub fn framing(center: Vec3, radius: f32) -> Self {
        let fov_y = 35f32.to_radians();
        let radius = if radius.is_finite() && radius > 0.0 {
            radius
        } else {
            1.0
        };
        let distance = radius / (fov_y * 0.5).sin() * 1.05;
        OrbitCamera {
            target: center,
            distance,
            yaw: 0.0,
            pitch: 0.0,
            fov_y,
            home: (center, distance),
        }
    }

    /// Back to the home pose given to [`OrbitCamera::framing`].
    pub fn reset(&mut self) {
        self.target = self.home.0;
        self.distance = self.home.1;
        self.yaw = 0.0;
        self.pitch = 0.0;
    }

    /// Unit vector from the target to the eye.
    pub fn back(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(cp * sy, sp, cp * cy)
    }

    /// Eye position (world space).
    pub fn eye(&self) -> Vec3 {
        self.target + self.distance * self.back()
    }

    /// Rotates around the target by `d_yaw`, `d_pitch` radians.
    pub fn orbit(&mut self, d_yaw: f32, d_pitch: f32) {
        self.yaw = (self.yaw + d_yaw).rem_euclid(std::f32::consts::TAU);
        self.pitch = (self.pitch + d_pitch).clamp(-Self::MAX_PITCH, Self::MAX_PITCH);
    }

    /// Moves the target in the view plane by a drag of `delta_px` pixels in a viewport
    /// `viewport_height_px` pixels high, so the point under the cursor follows it.
    pub fn pan(&mut self, delta_px: Vec2, viewport_height_px: f32) {
        if viewport_height_px <= 0.0 {
            return;
        }
        let world_per_px = 2.0 * self.distance * (self.fov_y * 0.5).tan() / viewport_height_px;
        let back = self.back();
        let right = Vec3::Y.cross(back).normalize_or_zero();
        let up = back.cross(right);
        self.target += (-delta_px.x * right + delta_px.y * up) * world_per_px;
    }

    /// Multiplies the distance by `factor` (< 1 zooms in), kept within 1e-3…1e3 × home.
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(self.home.1 * 1e-3, self.home.1 * 1e3);
        }
    }

    /// View matrix: `view_from_world`.
    pub fn view_from_world(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye(), self.target, Vec3::Y)
    }

    /// Projection matrix (wgpu depth range 0…1): `clip_from_view`.
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        // wgpu clip space: y up, depth 0…1 (the D3D convention).
        glam::camera::rh::proj::directx::perspective(
            self.fov_y,
            aspect,
            self.distance * 0.01,
            self.distance * 20.0,
        )
    }

    /// `clip_from_world = clip_from_view · view_from_world`.
    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        self.clip_from_view(aspect) * self.view_from_world()
    }

    /// World-space ray (origin, unit direction) through a point given in normalised device
    /// coordinates (x right, y up, both in −1…1).
    pub fn ray_through(&self, ndc: Vec2, aspect: f32) -> (Vec3, Vec3) {
        let world_from_clip = self.clip_from_world(aspect).inverse();
        let near = world_from_clip.project_point3(ndc.extend(0.0));
        let far = world_from_clip.project_point3(ndc.extend(1.0));
        (near, (far - near).normalize_or_zero())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn target_projects_to_screen_centre_and_ray_hits_it() {
        let mut cam = OrbitCamera::framing(Vec3::new(1.0, 2.0, 3.0), 2.0);
        cam.orbit(0.7, -0.4);
        let c = cam.clip_from_world(1.5).project_point3(cam.target);
        assert!(c.x.abs() < 1e-5 && c.y.abs() < 1e-5, "{c}");
        let (o, d) = cam.ray_through(Vec2::ZERO, 1.5);
        let along = (cam.target - o).dot(d);
        assert!((o + along * d - cam.target).length() < 1e-4);
    }

    #[test]
    fn pan_moves_target_perpendicular_to_view_and_zoom_scales_distance() {
        let mut cam = OrbitCamera::framing(Vec3::ZERO, 1.0);
        let d0 = cam.distance;
        cam.pan(Vec2::new(100.0, 0.0), 500.0);
        // Dragging right moves the target left (−x) when looking along −z.
        assert!(cam.target.x < 0.0 && cam.target.y.abs() < 1e-6 && cam.target.z.abs() < 1e-6);
        cam.zoom(0.5);
        assert!((cam.distance - 0.5 * d0).abs() < 1e-6);
        cam.zoom(0.0);
        assert!(
            (cam.distance - 0.5 * d0).abs() < 1e-6,
            "non-positive factor ignored"
        );
        cam.orbit(0.0, 10.0);
        assert_eq!(cam.pitch, OrbitCamera::MAX_PITCH);
        cam.reset();
        assert_eq!(cam.target, Vec3::ZERO);
        assert_eq!(cam.distance, d0);
    }
}
