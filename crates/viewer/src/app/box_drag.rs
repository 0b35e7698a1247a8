//! Dragging feature-box edges in the viewport (while the box editor is open and the box
//! overlay is shown): a drag starting within a few pixels of an edge moves that edge in the
//! canonical front plane; Alt + drag inside a box moves the whole box.

use eframe::egui;
use glam::{DVec2, DVec3, Vec2};

use super::ViewerApp;

/// Which part of a box a drag holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxHandle {
    /// The left edge (min x).
    MinX,
    /// The right edge (max x).
    MaxX,
    /// The bottom edge (min y).
    MinY,
    /// The top edge (max y).
    MaxY,
    /// The whole box.
    Move,
}

/// Largest distance (points) from an edge at which a drag grabs it.
const GRAB_POINTS: f32 = 8.0;

fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * ab)
}

impl ViewerApp {
    /// z of the front plane the boxes are drawn in (canonical frame).
    fn box_plane_z(&self) -> Option<f64> {
        let rig = &self.model()?.rig;
        let z = rig
            .shell
            .vertices
            .iter()
            .take(rig.face_vertex_count)
            .map(|p| p.z)
            .fold(f64::NEG_INFINITY, f64::max);
        z.is_finite().then_some(z)
    }

    /// Screen position (points) of canonical point `(x, y)` in the box plane.
    fn box_point_to_screen(&self, rect: egui::Rect, p: DVec2) -> Option<Vec2> {
        let rig = &self.model()?.rig;
        let z = self.box_plane_z()?;
        let input = rig
            .canonical_from_input
            .inverse()
            .transform_point3(DVec3::new(p.x, p.y, z));
        let aspect = rect.width() / rect.height().max(1.0);
        let ndc = self
            .camera
            .clip_from_world(aspect)
            .project_point3(input.as_vec3());
        Some(Vec2::new(
            rect.left() + (ndc.x + 1.0) * 0.5 * rect.width(),
            rect.top() + (1.0 - ndc.y) * 0.5 * rect.height(),
        ))
    }

    /// Canonical (x, y) where the ray through screen point `pos` meets the box plane.
    fn screen_to_box_plane(&self, rect: egui::Rect, pos: egui::Pos2) -> Option<DVec2> {
        let rig = &self.model()?.rig;
        let z = self.box_plane_z()?;
        let aspect = rect.width() / rect.height().max(1.0);
        let ndc = Vec2::new(
            (pos.x - rect.left()) / rect.width() * 2.0 - 1.0,
            1.0 - (pos.y - rect.top()) / rect.height() * 2.0,
        );
        let (o, d) = self.camera.ray_through(ndc, aspect);
        let o = rig.canonical_from_input.transform_point3(o.as_dvec3());
        let d = rig.canonical_from_input.transform_vector3(d.as_dvec3());
        if d.z.abs() < 1e-9 {
            return None;
        }
        let t = (z - o.z) / d.z;
        let hit = o + t * d;
        Some(DVec2::new(hit.x, hit.y))
    }

    /// The box handle under screen point `pos` (smallest boxes first), if any.
    pub(super) fn grab_box(
        &self,
        rect: egui::Rect,
        pos: egui::Pos2,
        whole: bool,
    ) -> Option<(usize, BoxHandle)> {
        let boxes = self.box_edit?;
        let p = Vec2::new(pos.x, pos.y);
        // Mouth, eyes, then the face box: small boxes win where they overlap.
        for i in [3, 1, 2, 0] {
            let b = boxes[i];
            let corner = |x: f64, y: f64| self.box_point_to_screen(rect, DVec2::new(x, y));
            let (c00, c10, c11, c01) = (
                corner(b.min.x, b.min.y)?,
                corner(b.max.x, b.min.y)?,
                corner(b.max.x, b.max.y)?,
                corner(b.min.x, b.max.y)?,
            );
            if whole {
                let inside = self
                    .screen_to_box_plane(rect, pos)
                    .is_some_and(|q| q.cmpge(b.min).all() && q.cmple(b.max).all());
                if inside {
                    return Some((i, BoxHandle::Move));
                }
                continue;
            }
            let edges = [
                (BoxHandle::MinX, segment_distance(p, c00, c01)),
                (BoxHandle::MaxX, segment_distance(p, c10, c11)),
                (BoxHandle::MinY, segment_distance(p, c00, c10)),
                (BoxHandle::MaxY, segment_distance(p, c01, c11)),
            ];
            if let Some((h, d)) = edges.into_iter().min_by(|a, b| a.1.total_cmp(&b.1))
                && d <= GRAB_POINTS
            {
                return Some((i, h));
            }
        }
        None
    }

    /// Moves the grabbed handle by the drag from `from` to `to` (screen points).
    pub(super) fn drag_box(
        &mut self,
        rect: egui::Rect,
        (index, handle): (usize, BoxHandle),
        from: egui::Pos2,
        to: egui::Pos2,
    ) {
        let (Some(a), Some(b)) = (
            self.screen_to_box_plane(rect, from),
            self.screen_to_box_plane(rect, to),
        ) else {
            return;
        };
        let d = b - a;
        let Some(boxes) = &mut self.box_edit else {
            return;
        };
        let Some(bx) = boxes.get_mut(index) else {
            return;
        };
        match handle {
            BoxHandle::MinX => bx.min.x += d.x,
            BoxHandle::MaxX => bx.max.x += d.x,
            BoxHandle::MinY => bx.min.y += d.y,
            BoxHandle::MaxY => bx.max.y += d.y,
            BoxHandle::Move => {
                bx.min += d;
                bx.max += d;
            }
        }
        self.refresh_overlays();
    }
}
