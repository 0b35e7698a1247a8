//! The 3D viewport: camera interaction, picking, and the paint callback of the frame.

use std::sync::Arc;

use eframe::egui;
use glam::Vec2;

use super::{BACKGROUND, SKIN, Selection, ViewerApp};
use crate::overlay::muscles_of_element;
use crate::picking::pick_triangle;
use crate::renderer::{SceneFrame, SceneUniforms, SurfaceFrame, ViewportCallback};

impl ViewerApp {
    pub(super) fn viewport(&mut self, ui: &mut egui::Ui) {
        let size = ui.available_size();
        let (full, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        self.viewport_rect = Some(full);
        // Compare mode: the posed face in the right half (picking and boxes work there), the
        // neutral one in the left, one camera.
        let rect = self.scene_rect(full);
        let aspect = rect.width() / rect.height().max(1.0);
        let delta = response.drag_delta();
        // Box editing: a drag that starts on a box edge (or Alt + inside a box) moves it.
        if response.drag_started_by(egui::PointerButton::Primary) {
            self.box_drag = None;
            if self.overlays.boxes
                && let Some(press) = ui.input(|i| i.pointer.press_origin())
            {
                let alt = ui.input(|i| i.modifiers.alt);
                self.box_drag = self.grab_box(rect, press, alt);
            }
        }
        if !response.dragged_by(egui::PointerButton::Primary) && !response.drag_started() {
            self.box_drag = None;
        }
        if let (Some(grab), true) = (
            self.box_drag,
            response.dragged_by(egui::PointerButton::Primary),
        ) && let Some(to) = response.interact_pointer_pos()
        {
            self.drag_box(rect, grab, to - delta, to);
        }
        let pan = response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Primary)
                && ui.input(|i| i.modifiers.shift));
        if pan {
            self.camera.pan(Vec2::new(delta.x, delta.y), rect.height());
        } else if response.dragged_by(egui::PointerButton::Primary) && self.box_drag.is_none() {
            self.camera.orbit(-delta.x * 0.01, delta.y * 0.01);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.camera.zoom((-scroll * 0.002).exp());
            }
        }
        if response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
            && rect.contains(pos)
        {
            let ndc = Vec2::new(
                (pos.x - rect.left()) / rect.width() * 2.0 - 1.0,
                1.0 - (pos.y - rect.top()) / rect.height() * 2.0,
            );
            self.pick(ndc, aspect);
        }
        if self.face.is_none() {
            return;
        }
        if self.uploaded_generation != self.posed.generation() {
            self.uploaded_vertices = Arc::new(self.posed.vertices().to_vec());
            self.uploaded_generation = self.posed.generation();
        }
        self.refresh_surface();
        let hovered_muscle = response
            .hover_pos()
            .and_then(|p| self.muscle_at(p))
            .filter(|_| self.overlays.muscles);
        let Some(face) = &self.face else { return };
        if !self.has_wgpu {
            self.legend_in(ui, full);
            return;
        }
        let ppp = ui.ctx().pixels_per_point();
        let size_px = [
            (full.width() * ppp).round().max(1.0) as u32,
            (full.height() * ppp).round().max(1.0) as u32,
        ];
        let wire_color = if self.shaded {
            [0.15, 0.1, 0.08, 0.55]
        } else {
            [0.85, 0.85, 0.9, 1.0]
        };
        let frame = SceneFrame {
            topology_id: face.topology_id,
            edges: Arc::clone(&face.edges),
            pose_generation: self.uploaded_generation,
            vertices: Arc::clone(&self.uploaded_vertices),
            lines_generation: self.lines_generation,
            lines: Arc::clone(&self.lines),
            surface: Some(SurfaceFrame {
                id: face.topology_id,
                surface: Arc::clone(&face.surface),
                generation: self.uploaded_generation * 2 + u64::from(self.heat),
                vertices: Arc::clone(&self.surface_vertices),
                neutral: self.compare.then(|| Arc::clone(&face.neutral_surface)),
            }),
            uniforms: SceneUniforms {
                clip_from_world: self.camera.clip_from_world(aspect).to_cols_array_2d(),
                eye: self.camera.eye().extend(1.0).to_array(),
                base_color: SKIN,
                wire_color,
            },
            shaded: self.shaded,
            wireframe: self.wireframe || !self.shaded,
            background: egui_wgpu::wgpu::Color {
                r: BACKGROUND[0] as f64,
                g: BACKGROUND[1] as f64,
                b: BACKGROUND[2] as f64,
                a: 1.0,
            },
        };
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(
            full,
            ViewportCallback { frame, size_px },
        ));
        self.frames_with_face += 1;
        if self.compare {
            let font = egui::FontId::proportional(14.0);
            let color = egui::Color32::from_gray(220);
            for (r, text) in [(full.with_max_x(rect.left()), "Neutral"), (rect, "Posed")] {
                let at = r.center_bottom() - egui::vec2(0.0, 10.0);
                ui.painter()
                    .text(at, egui::Align2::CENTER_BOTTOM, text, font.clone(), color);
            }
        }
        if let (Some(name), Some(pos)) = (hovered_muscle, response.hover_pos()) {
            self.muscle_label_at(ui, pos, &name);
        }
        self.legend_in(ui, full);
    }

    /// The muscle whose drawn line passes within 8 points of `pos` (nearest first), while the
    /// muscle overlay is on.
    pub fn muscle_at(&self, pos: egui::Pos2) -> Option<String> {
        let screen = self.screen_projection()?;
        let mut best: Option<(f32, &str)> = None;
        for (name, path) in &self.muscle_paths {
            let points: Vec<Option<egui::Pos2>> = path.iter().map(|p| screen(*p)).collect();
            for w in points.windows(2) {
                let (Some(a), Some(b)) = (w[0], w[1]) else {
                    continue;
                };
                let d = distance_to_segment(pos, a, b);
                if d <= 8.0 && best.is_none_or(|(bd, _)| d < bd) {
                    best = Some((d, name));
                }
            }
        }
        best.map(|(_, n)| n.to_owned())
    }

    /// The screen position (egui points) of the middle point of muscle `index`'s drawn line,
    /// while the muscle overlay is on (tests hover there).
    pub fn muscle_line_point(&self, index: usize) -> Option<egui::Pos2> {
        let (_, path) = self.muscle_paths.get(index)?;
        self.screen_projection()?(*path.get(path.len() / 2)?)
    }

    /// World (user frame) → egui points of the posed view, as last drawn; `None` for a point
    /// behind the eye.
    fn screen_projection(&self) -> Option<impl Fn(glam::DVec3) -> Option<egui::Pos2>> {
        let rect = self.scene_rect(self.viewport_rect?);
        let aspect = rect.width() / rect.height().max(1.0);
        let clip_from_world = self.camera.clip_from_world(aspect);
        Some(move |p: glam::DVec3| {
            let c = clip_from_world * p.as_vec3().extend(1.0);
            (c.w > 0.0).then(|| {
                egui::pos2(
                    rect.left() + (c.x / c.w + 1.0) * 0.5 * rect.width(),
                    rect.top() + (1.0 - c.y / c.w) * 0.5 * rect.height(),
                )
            })
        })
    }

    /// The part of the viewport showing the posed face (its right half in compare mode).
    pub(super) fn scene_rect(&self, full: egui::Rect) -> egui::Rect {
        if self.compare {
            full.with_min_x(full.left() + (full.width() / 2.0).floor())
        } else {
            full
        }
    }

    /// Re-makes the drawn surface's vertices when the pose or the heat map changed.
    fn refresh_surface(&mut self) {
        let key = (self.posed.generation(), self.heat);
        let Some(face) = &self.face else { return };
        if self.surface_key == Some(key) {
            return;
        }
        let mm_per_unit = face.model.as_ref().map(|m| m.rig.mm_per_unit());
        let heat = match (self.heat, mm_per_unit) {
            (true, Some(mm)) => Some((
                face.basis.neutral.as_slice(),
                self.posed.positions_f64(),
                mm,
            )),
            _ => None,
        };
        let mut out = Vec::with_capacity(face.surface.welded.len());
        face.surface.fill(self.posed.vertices(), heat, &mut out);
        self.surface_vertices = Arc::new(out);
        self.surface_key = Some(key);
    }

    /// The name of a hovered muscle, in a small box by the pointer.
    fn muscle_label_at(&self, ui: &egui::Ui, pos: egui::Pos2, name: &str) {
        let painter = ui.painter();
        let galley = painter.layout_no_wrap(
            name.to_owned(),
            egui::FontId::proportional(13.0),
            egui::Color32::WHITE,
        );
        let at = pos + egui::vec2(14.0, -8.0 - galley.size().y);
        let frame = egui::Rect::from_min_size(at, galley.size()).expand(4.0);
        painter.rect_filled(frame, 3.0, egui::Color32::from_black_alpha(200));
        painter.galley(at, galley, egui::Color32::WHITE);
    }

    /// The muscle colour legend in the viewport's top-left corner (drawn over the 3D view),
    /// while the muscle overlay is on.
    fn legend_in(&mut self, ui: &mut egui::Ui, rect: egui::Rect) {
        if self.overlays.muscles {
            let mut corner = ui.new_child(egui::UiBuilder::new().max_rect(rect.shrink(8.0)));
            self.legend_ui(&mut corner);
        }
    }

    pub(super) fn pick(&mut self, ndc: Vec2, aspect: f32) {
        let Some(face) = &self.face else { return };
        let (o, d) = self.camera.ray_through(ndc, aspect);
        let (o, d) = (o.as_dvec3(), d.as_dvec3());
        let hit = pick_triangle(self.posed.positions_f64(), &face.basis.triangles, o, d);
        self.selection = hit.map(|hit| {
            // The rig's front elements (user frame, neutral): on a simplified large face they
            // are not the user's triangles, so they are picked separately.
            let element = match (&face.model, &face.rig_geometry) {
                (Some(m), Some(geo)) => {
                    let n = m.rig.face_triangle_count.min(m.rig.shell.triangles.len());
                    pick_triangle(&geo.vertices, &m.rig.shell.triangles[..n], o, d)
                        .map(|h| h.triangle as u32)
                }
                _ => None,
            };
            let muscles = match (&face.model, element) {
                (Some(m), Some(e)) => {
                    muscles_of_element(self.params.muscles.as_deref().unwrap_or(&m.rig.muscles), e)
                }
                _ => Vec::new(),
            };
            Selection {
                hit,
                element,
                muscles,
            }
        });
        self.refresh_overlays();
    }
}

/// Distance from `p` to the segment `a`–`b` (points).
fn distance_to_segment(p: egui::Pos2, a: egui::Pos2, b: egui::Pos2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_sq().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
    p.distance(a + t * ab)
}
