//! The side, top and bottom panels of the viewer: file, muscles, view, rig, export, status.

use std::path::PathBuf;

use eframe::egui;

use super::dialogs::DialogPurpose;
use super::{ExportKind, ViewerApp, muscle_label, preset_label};
use crate::muscle_edit::insert_into_chain;
use crate::overlay::{muscle_color, muscle_color_name};

impl ViewerApp {
    pub(super) fn toolbar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.label("File:");
            let edit = egui::TextEdit::singleline(&mut self.open_path)
                .hint_text("face.obj / face.glb / saved .rig")
                .desired_width(320.0);
            let r = ui.add(edit).labelled_by(ui.label("Path").id);
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.button("Open").clicked() || enter {
                let path = PathBuf::from(self.open_path.trim());
                self.open(ui.ctx(), path);
            }
            if ui
                .add_enabled(self.dialog.is_none(), egui::Button::new("Browse…"))
                .on_hover_text("Choose a face (.obj, .gltf, .glb) or a saved rig in a file dialog")
                .clicked()
            {
                self.show_dialog(ui.ctx(), DialogPurpose::Open);
            }
            if ui.button("Open default face").clicked() {
                self.open_default_face(ui.ctx());
            }
        });
        if let Some(m) = &self.message {
            let color = if m.is_error {
                egui::Color32::from_rgb(235, 90, 80)
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(color, &m.text);
        }
    }

    pub(super) fn sliders_ui(&mut self, ui: &mut egui::Ui) {
        let Some(face) = &self.face else {
            ui.label("No face loaded.");
            return;
        };
        ui.heading(&face.name);
        ui.label(format!(
            "{} vertices, {} triangles",
            face.basis.neutral.len(),
            face.basis.triangles.len()
        ));
        ui.separator();
        ui.strong("Muscles (−1 contracts … +1 relaxes)");
        let ids = face.basis.muscle_ids.clone();
        if ids.is_empty() {
            ui.label("The muscle rig is not computed yet.");
        }
        let mut changed = false;
        let mut preset_clicked = None;
        // The anatomical rig has 40 controls: their sliders scroll in a box about a dozen high,
        // so the presets and the panels below stay in reach.
        egui::ScrollArea::vertical()
            .id_salt("muscle_sliders")
            .max_height(MUSCLE_SLIDERS_HEIGHT)
            .show(ui, |ui| {
                for (id, value) in ids.iter().zip(self.sliders.iter_mut()) {
                    changed |= ui
                        .add(egui::Slider::new(value, -1.0..=1.0).text(slider_label(id)))
                        .changed();
                }
            });
        ui.horizontal_wrapped(|ui| {
            let enabled = !ids.is_empty();
            if ui
                .add_enabled(enabled, egui::Button::new("Reset muscles"))
                .clicked()
            {
                self.sliders.iter_mut().for_each(|s| *s = 0.0);
                changed = true;
            }
            for preset in facebem::expressions::presets::ALL
                .iter()
                .filter(|p| p.name != "neutral")
            {
                let active = self.active_preset == Some(preset.name);
                let button = egui::Button::new(preset_label(preset.name)).selected(active);
                let r = ui
                    .add_enabled(enabled, button)
                    .on_hover_text(format!("{} ({})", preset.description, preset.action_units));
                if r.clicked() {
                    self.sliders = preset.sliders_for(&ids);
                    preset_clicked = Some(preset.name);
                    changed = true;
                }
            }
        });
        if changed {
            self.active_preset = preset_clicked;
            // Muscles set by hand (or a preset) end the expression mix.
            self.mix.clear();
            self.repose();
        }
    }

    /// A colour swatch and the muscle's name with its colour's name, per muscle of the rig.
    pub(super) fn legend_ui(&mut self, ui: &mut egui::Ui) {
        let Some(muscles) = self.pending_muscles() else {
            return;
        };
        let rows: Vec<(egui::Color32, String)> = muscles
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let [r, g, b, _] = muscle_color(i).map(|x| (x * 255.0).round() as u8);
                let name = format!("{}: {}", muscle_label(m), muscle_color_name(i));
                (egui::Color32::from_rgb(r, g, b), name)
            })
            .collect();
        let frame = egui::Frame::popup(ui.style())
            .inner_margin(6.0)
            .multiply_with_opacity(0.8);
        frame.show(ui, |ui| {
            ui.spacing_mut().item_spacing = egui::vec2(4.0, 1.0);
            ui.spacing_mut().interact_size.y = 12.0;
            let small = |text: &str| egui::Label::new(egui::RichText::new(text).small());
            // Collapsed at first: hovering a line names its muscle.
            egui::CollapsingHeader::new(
                egui::RichText::new(format!("Muscle colours ({})", rows.len())).small(),
            )
            .id_salt("muscle legend")
            .default_open(false)
            .show(ui, |ui| {
                for (color, name) in &rows {
                    ui.horizontal(|ui| {
                        let (rect, _) =
                            ui.allocate_exact_size(egui::vec2(8.0, 8.0), egui::Sense::hover());
                        ui.painter().rect_filled(rect, 1.5, *color);
                        ui.add(small(name).selectable(false));
                    });
                }
            });
        });
    }

    /// The heat map's colour scale (the contact sheet's, in mm).
    fn heat_legend_ui(&self, ui: &mut egui::Ui) {
        use facebem::report::contact_sheet::heat;
        ui.horizontal_wrapped(|ui| {
            ui.spacing_mut().item_spacing.x = 2.0;
            for (i, c) in heat::COLOURS.iter().enumerate() {
                let (rect, _) =
                    ui.allocate_exact_size(egui::vec2(10.0, 10.0), egui::Sense::hover());
                ui.painter()
                    .rect_filled(rect, 1.0, egui::Color32::from_rgb(c[0], c[1], c[2]));
                if i == 0 || i + 1 == heat::COLOURS.len() {
                    ui.small(heat::edge_label(i));
                }
            }
            ui.small("mm");
        });
    }

    pub(super) fn view_ui(&mut self, ui: &mut egui::Ui) {
        ui.strong("View");
        ui.horizontal(|ui| {
            ui.checkbox(&mut self.shaded, "Shaded");
            ui.checkbox(&mut self.wireframe, "Wireframe");
            if ui.button("Reset view").clicked() {
                self.camera.reset();
            }
        });
        ui.horizontal(|ui| {
            ui.checkbox(&mut self.heat, "Heat map")
                .on_hover_text("Displacement from the neutral face in mm, over the texture");
            ui.checkbox(&mut self.compare, "Compare")
                .on_hover_text("The neutral face beside the posed one, same camera");
        });
        if self.heat {
            self.heat_legend_ui(ui);
        }
        let mut o = self.overlays;
        ui.horizontal_wrapped(|ui| {
            ui.checkbox(&mut o.muscles, "Muscles");
            ui.checkbox(&mut o.skull, "Skull");
            ui.checkbox(&mut o.boxes, "Feature boxes");
            ui.checkbox(&mut o.whole_shell, "Whole shell");
        });
        if o != self.overlays {
            self.set_overlays(o);
        }

        ui.label("Drag: orbit · right/middle or shift-drag: pan · wheel: zoom · click: pick");
        if let Some(sel) = &self.selection {
            ui.label(format!("Selected triangle {}", sel.hit.triangle));
            match sel.element {
                Some(e) if sel.muscles.is_empty() => {
                    ui.label(format!("Element {e}: in no muscle"));
                }
                Some(e) => {
                    ui.label(format!("Element {e}: {}", sel.muscles.join(", ")));
                }
                None => {}
            }
        }
        self.muscle_edit_ui(ui);
    }

    pub(super) fn muscle_edit_ui(&mut self, ui: &mut egui::Ui) {
        let Some(element) = self.selection.as_ref().and_then(|s| s.element) else {
            return;
        };
        let Some(model) = self.model() else { return };
        let names: Vec<String> = self
            .params
            .muscles
            .as_ref()
            .unwrap_or(&model.rig.muscles)
            .iter()
            .map(muscle_label)
            .collect();
        if names.is_empty() {
            return;
        }
        self.edit_target = self.edit_target.min(names.len() - 1);
        let mut add = false;
        let mut remove = false;
        ui.horizontal_wrapped(|ui| {
            egui::ComboBox::from_label("Target muscle")
                .selected_text(&names[self.edit_target])
                .show_ui(ui, |ui| {
                    for (i, n) in names.iter().enumerate() {
                        ui.selectable_value(&mut self.edit_target, i, n);
                    }
                });
            add = ui.button("Add element to muscle").clicked();
            remove = ui.button("Remove element from muscles").clicked();
        });
        if add {
            let target = self.edit_target;
            self.edit_muscles(|muscles, geo, rig| {
                if let Some(m) = muscles.get_mut(target) {
                    insert_into_chain(&mut m.front_chain, element, |e| geo.centroid(rig, e));
                }
            });
        }
        if remove {
            self.edit_muscles(|muscles, _, _| {
                for m in muscles.iter_mut() {
                    m.front_chain.retain(|&e| e != element);
                    m.back_chain.retain(|&e| e != element);
                }
            });
        }
    }

    pub(super) fn rig_ui(&mut self, ui: &mut egui::Ui) {
        ui.strong("Rig");
        let rig = &mut self.params.rig;
        let mut offset = rig.offset;
        let mut thickness = rig.thickness;
        ui.add(
            egui::Slider::new(&mut offset, 0.002..=0.1)
                .logarithmic(true)
                .text("Offset (× face size)"),
        );
        ui.add(
            egui::Slider::new(&mut thickness, 0.002..=0.1)
                .logarithmic(true)
                .text("Thickness (× face size)"),
        );
        rig.offset = offset;
        rig.thickness = thickness;
        let has_source =
            (self.face.as_ref()).is_some_and(|f| f.source.is_some() || f.head.is_some());
        ui.horizontal(|ui| {
            if ui
                .add_enabled(has_source, egui::Button::new("Rebuild rig"))
                .clicked()
            {
                self.rebuild_rig(ui.ctx());
            }
            let can_load = has_source && self.model().is_some() && self.dialog.is_none();
            if ui
                .add_enabled(can_load, egui::Button::new("Load muscle file…"))
                .on_hover_text("Choose a muscle file (thesis format) and rebuild the rig with it")
                .clicked()
            {
                self.show_dialog(ui.ctx(), DialogPurpose::MuscleFile);
            }
        });
        self.box_edit_ui(ui);
        if let Some(m) = self.model() {
            ui.label(format!(
                "{} shell elements, {} muscles, {} skull elements",
                m.rig.shell.triangles.len(),
                m.rig.muscles.len(),
                m.rig.skull.len()
            ));
        }
    }

    pub(super) fn box_edit_ui(&mut self, ui: &mut egui::Ui) {
        let Some(size) = self.model().map(|m| m.rig.face_size) else {
            return;
        };
        let mut changed = false;
        let mut apply = false;
        let mut revert = false;
        egui::CollapsingHeader::new("Edit feature boxes").show(ui, |ui| {
            if self.box_edit.is_none() {
                self.start_box_edit();
            }
            let Some(boxes) = &mut self.box_edit else {
                return;
            };
            ui.label("min x, min y, max x, max y (canonical frame, face units)");
            let speed = 0.002 * size;
            for (name, b) in ["Face", "Eye L", "Eye R", "Mouth"]
                .iter()
                .zip(boxes.iter_mut())
            {
                ui.horizontal(|ui| {
                    ui.label(*name);
                    let fields = [&mut b.min.x, &mut b.min.y, &mut b.max.x, &mut b.max.y];
                    for (v, what) in fields.into_iter().zip(["min x", "min y", "max x", "max y"]) {
                        let r = ui.add(egui::DragValue::new(v).speed(speed).max_decimals(3));
                        ui.ctx().accesskit_node_builder(r.id, |node| {
                            node.set_label(format!("{name} {what}"));
                        });
                        changed |= r.changed();
                    }
                });
            }
            ui.horizontal(|ui| {
                apply = ui.button("Apply boxes").clicked();
                revert = ui.button("Revert boxes").clicked();
            });
        });
        if let Some(Err(e)) = self.edited_boxes() {
            ui.colored_label(egui::Color32::from_rgb(235, 90, 80), e);
        }
        if revert {
            self.box_edit = None;
            self.start_box_edit();
        } else if changed {
            self.refresh_overlays();
        }
        if apply {
            self.apply_box_edit(ui.ctx());
        }
    }

    pub(super) fn export_ui(&mut self, ui: &mut egui::Ui) {
        ui.strong("Export");
        ui.horizontal(|ui| {
            let label = ui.label("Export folder");
            ui.add(egui::TextEdit::singleline(&mut self.export_dir).desired_width(180.0))
                .labelled_by(label.id)
                .on_hover_text("~ is your home folder. Existing files are never replaced: a second export is named “… (2)”.");
            if ui
                .add_enabled(self.dialog.is_none(), egui::Button::new("Choose…"))
                .on_hover_text("Choose the export folder in a file dialog")
                .clicked()
            {
                self.show_dialog(ui.ctx(), DialogPurpose::ExportFolder);
            }
        });
        ui.horizontal_wrapped(|ui| {
            let ready = self.exports_ready();
            let has_rig = self.model().is_some();
            for kind in [
                ExportKind::ObjPose,
                ExportKind::Gltf,
                ExportKind::MuscleFile,
            ] {
                let why = match ready {
                    Err(why) => Some(why),
                    Ok(()) if kind == ExportKind::MuscleFile && !has_rig => {
                        Some("This face has no computed rig, so no muscles to save")
                    }
                    Ok(()) => None,
                };
                let r = ui
                    .add_enabled(why.is_none(), egui::Button::new(kind.label()))
                    .on_disabled_hover_text(why.unwrap_or_default());
                if r.clicked() {
                    self.export(ui.ctx(), kind);
                }
            }
        });
    }

    pub(super) fn status_bar(&mut self, ui: &mut egui::Ui) {
        if let Some(job) = &self.exporting {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label(job.label());
            });
        }
        let job = match (&self.loading, &mut self.rigging) {
            (Some(j), _) => Some((
                j.label().to_owned(),
                j.control().fraction(),
                j.control().stage(),
            )),
            (None, Some(r)) => {
                // One bar over all stages (weighted by their typical share of the time), never
                // going back, with the stage and the elapsed time. No estimate of the time
                // left: the stages' weights are typical, not this face's, and a linear estimate
                // from them stalled (issue 35: "about 25 s left" at 31 s, 90 % for 40 s).
                r.shown_fraction = r.shown_fraction.max(r.job.control().fraction());
                let f = r.shown_fraction;
                let elapsed = r.started.elapsed().as_secs_f32();
                Some((
                    r.job.label().to_owned(),
                    f,
                    format!(
                        "{:.0} % · {} · {} elapsed",
                        100.0 * f,
                        r.job.control().stage(),
                        seconds_text(elapsed)
                    ),
                ))
            }
            (None, None) => None,
        };
        let Some((label, fraction, stage)) = job else {
            ui.label(if self.has_wgpu {
                "Ready"
            } else {
                "No wgpu device: 3D view disabled"
            });
            return;
        };
        if self.rigging.is_some() {
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(250));
        }
        let mut cancel = false;
        ui.horizontal(|ui| {
            ui.label(label);
            // Wide enough for its text (it was cut off).
            let text_width = ui
                .fonts_mut(|f| {
                    f.layout_no_wrap(
                        stage.clone(),
                        egui::TextStyle::Body.resolve(ui.style()),
                        egui::Color32::WHITE,
                    )
                })
                .size()
                .x;
            ui.add(
                egui::ProgressBar::new(fraction)
                    .text(stage)
                    .desired_width((text_width + 24.0).max(260.0)),
            );
            cancel = self.rigging.is_some() && ui.button("Cancel").clicked();
        });
        if cancel {
            self.cancel_rig();
        }
    }
}

/// Height, in points, of the scrolling box of muscle sliders (about a dozen sliders).
const MUSCLE_SLIDERS_HEIGHT: f32 = 280.0;

/// `3.2 s`, `42 s`, `2 min 05 s`.
fn seconds_text(seconds: f32) -> String {
    if seconds < 10.0 {
        format!("{seconds:.1} s")
    } else if seconds < 60.0 {
        format!("{seconds:.0} s")
    } else {
        let s = seconds.round() as u64;
        format!("{} min {:02} s", s / 60, s % 60)
    }
}

/// The label of a muscle slider: the thesis name of a standard muscle, else its id.
pub(super) fn slider_label(id: &str) -> String {
    face_prep::MuscleKind::from_id(id)
        .map_or_else(|| id.to_owned(), |m| m.display_name().to_owned())
}
