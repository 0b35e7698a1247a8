//! Posing the displayed face: sliders and presets, the CPU blend of the basis, and the overlay
//! lines, which follow the pose and the selection.

use std::sync::Arc;

use glam::DVec3;

use super::{SELECTION, ViewerApp};
use crate::overlay::{muscle_path, overlay_lines};
use crate::renderer::LineVertex;

impl ViewerApp {
    /// Sets every slider at once (clamped to −1…1; extra or missing values are ignored) and
    /// re-blends the pose, as moving the sliders would.
    pub fn set_sliders(&mut self, values: &[f64]) {
        self.active_preset = None;
        self.mix.clear();
        for (s, v) in self.sliders.iter_mut().zip(values) {
            *s = if v.is_finite() {
                v.clamp(-1.0, 1.0)
            } else {
                0.0
            };
        }
        self.repose();
        self.record_pose();
    }

    /// Applies the preset called `name`: a facebem preset ([`facebem::expressions::presets::find`]) or an
    /// ARKit / VRM 1.0 name ([`facebem::expressions::find`], from the controls the rig has);
    /// false if unknown or the rig has none of its controls.
    pub fn apply_preset(&mut self, name: &str) -> bool {
        let Some(face) = &self.face else { return false };
        let ids = &face.basis.muscle_ids;
        let (sliders, name) = if let Some(p) = facebem::expressions::presets::find(name) {
            (p.sliders_for(ids), p.name)
        } else if let Some(e) = facebem::expressions::find(name) {
            let Some(r) = e.resolve(ids) else {
                return false;
            };
            (r.sliders, e.name)
        } else {
            return false;
        };
        self.sliders = sliders;
        self.active_preset = Some(name);
        self.mix.clear();
        self.repose();
        self.record_pose();
        true
    }

    /// The preset the sliders are set to, until a slider moves (highlighted in the UI).
    pub fn active_preset(&self) -> Option<&'static str> {
        self.active_preset
    }

    pub(super) fn set_lines(&mut self, lines: Vec<LineVertex>) {
        self.lines = Arc::new(lines);
        self.lines_generation += 1;
    }

    pub(super) fn refresh_overlays(&mut self) {
        let mut lines = Vec::new();
        let selected_element = self.selection.as_ref().and_then(|s| s.element);
        if let Some(face) = &self.face {
            if let (Some(model), Some(geo)) = (&face.model, &face.rig_geometry) {
                let edited = self.edited_boxes().and_then(Result::ok);
                // Overlays follow the pose: every shell vertex moves by its own response
                // (the simulated surface's, also on a reduced copy), in the user's frame.
                let response = &model.shell_vertex_response;
                // A head's sliders go on past the controls (its gaze and tongue targets).
                let posed_geo = (response.len() <= self.sliders.len()
                    && response.iter().all(|r| r.len() == geo.vertices.len()))
                .then(|| {
                    let linear = geo.input_from_canonical.matrix3;
                    let mut g = (**geo).clone();
                    for (&s, field) in self.sliders.iter().zip(response) {
                        if s != 0.0 {
                            for (p, u) in g.vertices.iter_mut().zip(field) {
                                *p += linear * (s * *u);
                            }
                        }
                    }
                    g
                });
                let shown_geo = posed_geo.as_ref().unwrap_or(geo);
                self.muscle_paths = if self.overlays.muscles {
                    let muscles = self.params.muscles.as_deref().unwrap_or(&model.rig.muscles);
                    (muscles.iter())
                        .map(|m| {
                            let path = muscle_path(&model.rig, shown_geo, &m.front_chain);
                            (super::muscle_label(m), path)
                        })
                        .collect()
                } else {
                    Vec::new()
                };
                lines = overlay_lines(
                    &model.rig,
                    shown_geo,
                    &self.overlays,
                    selected_element,
                    self.params.muscles.as_deref(),
                    edited.as_ref(),
                );
            }
            // Without a rig element, outline the picked triangle of the displayed mesh.
            if let Some(sel) = &self.selection
                && sel.element.is_none()
                && let Some(t) = face.basis.triangles.get(sel.hit.triangle)
            {
                let p: Vec<DVec3> = t
                    .iter()
                    .filter_map(|&i| self.posed.positions_f64().get(i as usize).copied())
                    .collect();
                for k in 0..p.len() {
                    for q in [p[k], p[(k + 1) % p.len()]] {
                        lines.push(LineVertex {
                            position: q.as_vec3().to_array(),
                            color: SELECTION,
                        });
                    }
                }
            }
        }
        self.set_lines(lines);
    }

    pub(super) fn repose(&mut self) {
        let Some(face) = &self.face else { return };
        // A head's lids stay on its eyeballs in any mix of sliders.
        let contact = (face.head.as_ref())
            .and_then(|h| h.basis.as_ref())
            .map(|b| &b.contact);
        if let Err(e) = (self.posed).update_with_contact(&face.basis, &self.sliders, contact) {
            let text = format!("Cannot pose {}: {e}", face.name);
            self.error(text);
        }
        if self.face.as_ref().is_some_and(|f| f.model.is_some()) {
            self.refresh_overlays();
        }
    }
}

/// Button label of a preset: its name with a capital first letter ("smile" → "Smile").
pub fn preset_label(name: &str) -> String {
    let mut c = name.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}
