//! The 3D viewport: camera interaction, picking, and the paint callback of the frame.

use std::sync::Arc;

use eframe::egui;
use glam::Vec2;

use super::{BACKGROUND, SKIN, Selection, ViewerApp};
use crate::overlay::muscles_of_element;
use crate::picking::pick_triangle;
use crate::renderer::{SceneFrame, SceneUniforms, ViewportCallback};

impl ViewerApp {
    pub(super) fn viewport(&mut self, ui: &mut egui::Ui) {
        let size = ui.available_size();
        let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        self.viewport_rect = Some(rect);
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
        {
            let ndc = Vec2::new(
                (pos.x - rect.left()) / rect.width() * 2.0 - 1.0,
                1.0 - (pos.y - rect.top()) / rect.height() * 2.0,
            );
            self.pick(ndc, aspect);
        }
        let Some(face) = &self.face else { return };
        if self.uploaded_generation != self.posed.generation() {
            self.uploaded_vertices = Arc::new(self.posed.vertices().to_vec());
            self.uploaded_generation = self.posed.generation();
        }
        if !self.has_wgpu {
            self.legend_in(ui, rect);
            return;
        }
        let ppp = ui.ctx().pixels_per_point();
        let size_px = [
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        ];
        let wire_color = if self.shaded {
            [0.15, 0.1, 0.08, 0.55]
        } else {
            [0.85, 0.85, 0.9, 1.0]
        };
        let frame = SceneFrame {
            topology_id: face.topology_id,
            triangles: Arc::clone(&face.triangles),
            edges: Arc::clone(&face.edges),
            pose_generation: self.uploaded_generation,
            vertices: Arc::clone(&self.uploaded_vertices),
            lines_generation: self.lines_generation,
            lines: Arc::clone(&self.lines),
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
            rect,
            ViewportCallback { frame, size_px },
        ));
        self.frames_with_face += 1;
        self.legend_in(ui, rect);
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
