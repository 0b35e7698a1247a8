//! The expression browser (issue 35): tabs for ARKit, VRM, facebem's presets and the muscles, a
//! search by name, and a 0…1 slider per expression (−1…1 per muscle). The sliders mix: the muscle sliders become the sum of
//! each expression's controls times its weight (clamped to −1…1), as glTF morph weights add.
//! Names the rig cannot make are listed greyed, with the reason on hover. Moving a muscle slider
//! by hand ends the mix.

use eframe::egui;
use facebem::expressions::{self, NameSet, presets};

use super::ViewerApp;

/// A tab of the browser.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BrowserTab {
    /// ARKit's 52 blendshapes.
    #[default]
    Arkit,
    /// VRM 1.0's expression presets.
    Vrm,
    /// facebem's FACS presets.
    Presets,
    /// The rig's muscles (−1 … 1 each, the sliders above, searchable).
    Muscles,
}

impl BrowserTab {
    /// Every tab, in order.
    pub const ALL: [BrowserTab; 4] = [
        BrowserTab::Arkit,
        BrowserTab::Vrm,
        BrowserTab::Presets,
        BrowserTab::Muscles,
    ];

    /// The tab's label.
    pub fn label(self) -> &'static str {
        match self {
            BrowserTab::Arkit => "ARKit",
            BrowserTab::Vrm => "VRM",
            BrowserTab::Presets => "Presets",
            BrowserTab::Muscles => "Muscles",
        }
    }
}

/// One entry of the browser: an expression's name and why the rig cannot make it, if so.
#[derive(Clone, Debug, PartialEq)]
pub struct BrowserEntry {
    /// The standard's name (`mouthSmileLeft`, `aa`, `happy`).
    pub name: &'static str,
    /// `None` when the rig makes it; otherwise the reason (shown greyed).
    pub unavailable: Option<String>,
}

/// The entries of `tab` whose name contains `query` (case-insensitive), for a rig with
/// `control_ids`.
///
/// ```
/// use viewer::app::browser::{BrowserTab, browser_entries};
/// let ids: Vec<String> = ["zygomaticus_major_l", "zygomaticus_major_r"].map(String::from).into();
/// let smile = browser_entries(BrowserTab::Arkit, "smile", &ids);
/// let names: Vec<&str> = smile.iter().map(|e| e.name).collect();
/// assert_eq!(names, ["mouthSmileLeft", "mouthSmileRight"]);
/// assert!(browser_entries(BrowserTab::Arkit, "eyeLookUp", &ids)[0].unavailable.is_some());
/// ```
pub fn browser_entries(tab: BrowserTab, query: &str, control_ids: &[String]) -> Vec<BrowserEntry> {
    let query = query.trim().to_lowercase();
    let matches = |name: &str| name.to_lowercase().contains(&query);
    let mut out = Vec::new();
    let set = match tab {
        BrowserTab::Arkit => Some(NameSet::Arkit),
        BrowserTab::Vrm => Some(NameSet::Vrm),
        BrowserTab::Presets | BrowserTab::Muscles => None,
    };
    if tab == BrowserTab::Muscles {
        // Not names of a standard: listed by the browser from the rig ([`muscle_entries`]).
        return out;
    }
    let Some(set) = set else {
        for p in presets::ALL.iter().filter(|p| p.name != "neutral") {
            if matches(p.name) {
                out.push(BrowserEntry {
                    name: p.name,
                    unavailable: None,
                });
            }
        }
        return out;
    };
    // The standard's full list, in its order: what the rig makes, then what it cannot.
    let standard: &[&'static str] = match set {
        NameSet::Arkit => &expressions::arkit::NAMES,
        _ => &expressions::vrm::NAMES,
    };
    for &name in standard.iter().filter(|n| matches(n)) {
        if own_target(name, control_ids).is_some() {
            // A head's own target (gaze, tongue): a slider of its own.
            out.push(BrowserEntry {
                name,
                unavailable: None,
            });
            continue;
        }
        let unavailable = match (expressions::not_modelled(name), expressions::find(name)) {
            (Some((_, why)), _) => Some(format!("not modelled: {why}")),
            (None, Some(e)) => match e.resolve(control_ids) {
                Some(r) if r.sliders.iter().any(|s| *s != 0.0) || name == "neutral" => None,
                _ => Some(format!(
                    "controls not in this rig: {}",
                    e.controls().join(", ")
                )),
            },
            (None, None) => Some("not defined".into()),
        };
        out.push(BrowserEntry { name, unavailable });
    }
    out
}

impl ViewerApp {
    /// The expressions mixed and their weights.
    pub fn expression_mix(&self) -> &[(&'static str, f64)] {
        &self.mix
    }

    /// Sets the weight (0…1) of the named expression (ARKit, VRM or a facebem preset) in the
    /// mix and poses the face with the mix; false if the rig cannot make it.
    pub fn set_expression_weight(&mut self, name: &str, weight: f64) -> bool {
        let Some(face) = &self.face else { return false };
        let ids = &face.basis.muscle_ids;
        let (sliders, name) = if let Some((k, name)) = own_target(name, ids) {
            let mut unit = vec![0.0; ids.len()];
            unit[k] = 1.0;
            (unit, name)
        } else if let Some(p) = presets::find(name) {
            (p.sliders_for(ids), p.name)
        } else if let Some(e) = expressions::find(name)
            && let Some(r) = e.resolve(ids)
        {
            (r.sliders, e.name)
        } else {
            return false;
        };
        let weight = if weight.is_finite() {
            weight.clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.mix.retain(|(n, _)| *n != name);
        if weight > 0.0 {
            self.mix.push((name, weight));
        }
        let mut mixed = vec![0.0; ids.len()];
        for &(n, w) in &self.mix {
            let s = if n == name {
                sliders.clone()
            } else if let Some((k, _)) = own_target(n, ids) {
                (0..ids.len())
                    .map(|j| if j == k { 1.0 } else { 0.0 })
                    .collect()
            } else if let Some(p) = presets::find(n) {
                p.sliders_for(ids)
            } else {
                expressions::find(n)
                    .and_then(|e| e.resolve(ids))
                    .map_or_else(|| vec![0.0; ids.len()], |r| r.sliders)
            };
            for (m, v) in mixed.iter_mut().zip(s) {
                *m += w * v;
            }
        }
        self.sliders = mixed.into_iter().map(|v| v.clamp(-1.0, 1.0)).collect();
        self.active_preset = None;
        self.repose();
        self.record_pose();
        true
    }

    /// The browser, a section that opens (so the panels below stay in reach): tabs, search,
    /// one slider per expression, the mix.
    pub(super) fn browser_ui(&mut self, ui: &mut egui::Ui) {
        if self.face.is_none() {
            return;
        }
        egui::CollapsingHeader::new("Expressions: ARKit, VRM, presets")
            .default_open(false)
            .show(ui, |ui| self.browser_body(ui));
    }

    fn browser_body(&mut self, ui: &mut egui::Ui) {
        let Some(face) = &self.face else { return };
        let ids = face.basis.muscle_ids.clone();
        ui.label("0 … 1 each; they add up.");
        ui.horizontal(|ui| {
            for tab in BrowserTab::ALL {
                ui.selectable_value(&mut self.browser_tab, tab, tab.label());
            }
        });
        ui.horizontal(|ui| {
            let label = ui.label("Search");
            ui.add(
                egui::TextEdit::singleline(&mut self.browser_query)
                    .hint_text("e.g. smile")
                    .desired_width(f32::INFINITY),
            )
            .labelled_by(label.id);
        });
        if self.browser_tab == BrowserTab::Muscles {
            self.muscle_tab(ui);
            return;
        }
        let mut set = None;
        egui::ScrollArea::vertical()
            .id_salt("expression_browser")
            .max_height(BROWSER_HEIGHT)
            .show(ui, |ui| {
                for entry in browser_entries(self.browser_tab, &self.browser_query, &ids) {
                    let mut w = self
                        .mix
                        .iter()
                        .find(|(n, _)| *n == entry.name)
                        .map_or(0.0, |m| m.1);
                    let enabled = entry.unavailable.is_none() && !ids.is_empty();
                    let r = ui.add_enabled(
                        enabled,
                        egui::Slider::new(&mut w, 0.0..=1.0).text(entry.name),
                    );
                    let r = match &entry.unavailable {
                        Some(why) => r.on_disabled_hover_text(why),
                        None => r,
                    };
                    if r.changed() {
                        set = Some((entry.name, w));
                    }
                }
            });
        if let Some((name, w)) = set {
            self.set_expression_weight(name, w);
        }
        if !self.mix.is_empty() {
            let listed: Vec<String> = self
                .mix
                .iter()
                .map(|(n, w)| format!("{n} {w:.2}"))
                .collect();
            ui.horizontal_wrapped(|ui| {
                ui.label(format!("Mix: {}", listed.join(" + ")));
                if ui.button("Clear mix").clicked() {
                    self.mix.clear();
                    self.sliders.iter_mut().for_each(|s| *s = 0.0);
                    self.active_preset = None;
                    self.repose();
                }
            });
        }
    }
}

impl ViewerApp {
    /// The Muscles tab: the muscle sliders (−1 … 1) whose name contains the search.
    fn muscle_tab(&mut self, ui: &mut egui::Ui) {
        let Some(face) = &self.face else { return };
        let query = self.browser_query.trim().to_lowercase();
        let names: Vec<(usize, String)> = (face.basis.muscle_ids.iter().enumerate())
            .map(|(k, id)| (k, super::panels::slider_label(id)))
            .filter(|(_, n)| n.to_lowercase().contains(&query))
            .collect();
        let mut changed = false;
        egui::ScrollArea::vertical()
            .id_salt("expression_browser_muscles")
            .max_height(BROWSER_HEIGHT)
            .show(ui, |ui| {
                for (k, name) in names {
                    if let Some(v) = self.sliders.get_mut(k) {
                        let r = ui.add(egui::Slider::new(v, -1.0..=1.0).text(name));
                        changed |= r.changed();
                    }
                }
            });
        if changed {
            self.active_preset = None;
            self.mix.clear();
            self.repose();
        }
    }
}

/// A standard name that is one of the rig's own sliders (a head's gaze and tongue targets,
/// [`crate::head::display_basis`]): its slider and the name as the standard spells it.
///
/// ```
/// use viewer::app::browser::own_target;
/// let ids: Vec<String> = ["jaw_open", "eyeLookUpLeft"].map(String::from).into();
/// assert_eq!(own_target("eyeLookUpLeft", &ids), Some((1, "eyeLookUpLeft")));
/// assert_eq!(own_target("eyeLookUpRight", &ids), None);
/// assert_eq!(own_target("jaw_open", &ids), None);
/// ```
pub fn own_target(name: &str, control_ids: &[String]) -> Option<(usize, &'static str)> {
    let name = (expressions::arkit::NAMES.iter())
        .chain(expressions::vrm::NAMES.iter())
        .find(|n| **n == name)?;
    let k = control_ids.iter().position(|c| c == name)?;
    Some((k, name))
}

/// Height of the browser's list, in points (about ten rows).
const BROWSER_HEIGHT: f32 = 230.0;
