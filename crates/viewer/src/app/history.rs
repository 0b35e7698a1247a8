//! Undo and redo (issue 35) of the pose and of the rig edits: each change of the sliders — a
//! drag (one step however long), a typed value, a preset, a reset, an API call — and each edit
//! of the feature boxes (a drag, a typed corner, Reset) or of the muscles (an element added or
//! removed, a muscle file loaded) is one step. Ctrl+Z undoes it,
//! Ctrl+Shift+Z or Ctrl+Y redoes it (⌘ on macOS), unless a text field has the keyboard.
//! Loading or rigging a face starts a new history.

use eframe::egui;

use super::ViewerApp;

/// Steps kept; older ones are forgotten.
pub const UNDO_DEPTH: usize = 256;

/// The sliders and the preset they were set to, and the rig edits not solved yet.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PoseState {
    sliders: Vec<f64>,
    preset: Option<&'static str>,
    mix: Vec<(&'static str, f64)>,
    boxes: Option<[face_prep::Box2; 4]>,
    muscles: Option<Vec<face_prep::Muscle>>,
}

/// The states before (undo) and after (redo) the committed one.
#[derive(Default)]
pub(super) struct PoseHistory {
    committed: Option<PoseState>,
    undo: Vec<PoseState>,
    redo: Vec<PoseState>,
}

impl ViewerApp {
    /// The pose as a history state.
    fn pose_state(&self) -> PoseState {
        PoseState {
            sliders: self.sliders.clone(),
            preset: self.active_preset,
            mix: self.mix.clone(),
            boxes: self.box_edit,
            muscles: self.params.muscles.clone(),
        }
    }

    /// Makes the current pose a step of the history when it differs from the last one (the UI
    /// calls it once no pointer button is down, so a drag is one step).
    pub(super) fn record_pose(&mut self) {
        let now = self.pose_state();
        let h = &mut self.history;
        match &h.committed {
            Some(c) if *c == now => {}
            Some(c) if c.sliders.len() == now.sliders.len() => {
                h.undo.push(c.clone());
                if h.undo.len() > UNDO_DEPTH {
                    h.undo.remove(0);
                }
                h.redo.clear();
                h.committed = Some(now);
            }
            // Another face (other controls): a new history.
            _ => {
                *h = PoseHistory {
                    committed: Some(now),
                    ..PoseHistory::default()
                }
            }
        }
    }

    /// Undoes the last pose change; false when there is none.
    pub fn undo(&mut self) -> bool {
        self.step(true)
    }

    /// Redoes the last undone pose change; false when there is none.
    pub fn redo(&mut self) -> bool {
        self.step(false)
    }

    /// One step back (from the undo stack to the redo stack) or forward.
    fn step(&mut self, back: bool) -> bool {
        self.record_pose();
        let h = &mut self.history;
        let (from, to) = if back {
            (&mut h.undo, &mut h.redo)
        } else {
            (&mut h.redo, &mut h.undo)
        };
        let Some(state) = from.pop() else {
            return false;
        };
        if let Some(c) = h.committed.replace(state.clone()) {
            to.push(c);
        }
        self.restore(state);
        true
    }

    /// Steps that can be undone and redone.
    pub fn history_depth(&self) -> (usize, usize) {
        (self.history.undo.len(), self.history.redo.len())
    }

    fn restore(&mut self, state: PoseState) {
        self.sliders = state.sliders;
        self.active_preset = state.preset;
        self.mix = state.mix;
        let edits_changed = self.box_edit != state.boxes || self.params.muscles != state.muscles;
        self.box_edit = state.boxes;
        self.params.muscles = state.muscles;
        if edits_changed {
            let element = self.selection.as_ref().and_then(|s| s.element);
            let names = element
                .zip(self.pending_muscles())
                .map(|(e, muscles)| crate::overlay::muscles_of_element(muscles, e));
            if let (Some(sel), Some(names)) = (&mut self.selection, names) {
                sel.muscles = names;
            }
            self.refresh_overlays();
        }
        self.repose();
    }

    /// Ctrl+Z, Ctrl+Shift+Z and Ctrl+Y, when no text field has the keyboard.
    pub(super) fn history_shortcuts(&mut self, ctx: &egui::Context) {
        if ctx.memory(|m| m.focused().is_some()) {
            return;
        }
        let shift = egui::Modifiers::COMMAND | egui::Modifiers::SHIFT;
        let redo = ctx.input_mut(|i| {
            i.consume_shortcut(&egui::KeyboardShortcut::new(shift, egui::Key::Z))
                || i.consume_shortcut(&egui::KeyboardShortcut::new(
                    egui::Modifiers::COMMAND,
                    egui::Key::Y,
                ))
        });
        let undo = !redo
            && ctx.input_mut(|i| {
                i.consume_shortcut(&egui::KeyboardShortcut::new(
                    egui::Modifiers::COMMAND,
                    egui::Key::Z,
                ))
            });
        if redo {
            self.redo();
        } else if undo {
            self.undo();
        }
    }
}
