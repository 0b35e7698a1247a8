//! A timeline strip (issue 35): key two or more poses and play them, to judge expressions in
//! motion. Key `i` sits at `i × seconds_between_keys`; between two keys every slider moves from
//! one value to the other along a smoothstep (`3f² − 2f³`, zero speed at the keys, as an
//! animator's default ease), so the face passes through exactly the keyed poses. Playing loops.
//! A playing timeline is not an edit: it makes no undo steps, and stopping leaves the pose it
//! reached as one.

use std::time::Instant;

use eframe::egui;

use super::ViewerApp;

/// One key: the sliders and a label.
#[derive(Clone, Debug, PartialEq)]
pub struct TimelineKey {
    /// What was keyed (the preset or expression mix, or "pose N").
    pub label: String,
    /// Slider values, one per muscle.
    pub sliders: Vec<f64>,
}

/// The keys, the time and the playback state.
#[derive(Clone, Debug)]
pub struct Timeline {
    keys: Vec<TimelineKey>,
    seconds_between_keys: f64,
    time_s: f64,
    /// The instant playback's time 0 corresponds to.
    playing_since: Option<Instant>,
}

impl Default for Timeline {
    fn default() -> Self {
        Timeline {
            keys: Vec::new(),
            seconds_between_keys: 1.0,
            time_s: 0.0,
            playing_since: None,
        }
    }
}

impl Timeline {
    /// Whether it is playing.
    pub fn playing(&self) -> bool {
        self.playing_since.is_some()
    }

    /// Length in seconds (0 with fewer than two keys).
    pub fn duration_s(&self) -> f64 {
        self.keys.len().saturating_sub(1) as f64 * self.seconds_between_keys
    }

    /// The sliders at `time_s` (clamped to the timeline), `None` without keys.
    ///
    /// ```
    /// use viewer::app::timeline::Timeline;
    /// let mut t = Timeline::default();
    /// t.add_key("a".into(), vec![0.0, 1.0]);
    /// t.add_key("b".into(), vec![1.0, -1.0]);
    /// assert_eq!(t.sliders_at(0.5).unwrap(), [0.5, 0.0]);
    /// assert_eq!(t.sliders_at(0.25).unwrap()[0], 0.15625);
    /// assert_eq!(t.sliders_at(9.0).unwrap(), [1.0, -1.0]);
    /// ```
    pub fn sliders_at(&self, time_s: f64) -> Option<Vec<f64>> {
        let last = self.keys.len().checked_sub(1)?;
        let x = if self.seconds_between_keys > 0.0 && time_s.is_finite() {
            (time_s / self.seconds_between_keys).clamp(0.0, last as f64)
        } else {
            0.0
        };
        let i = (x.floor() as usize).min(last.saturating_sub(1));
        let (a, b) = (&self.keys[i], &self.keys[(i + 1).min(last)]);
        let f = (x - i as f64).clamp(0.0, 1.0);
        let ease = f * f * (3.0 - 2.0 * f);
        Some(
            a.sliders
                .iter()
                .zip(&b.sliders)
                .map(|(a, b)| a + (b - a) * ease)
                .collect(),
        )
    }

    /// Appends a key.
    pub fn add_key(&mut self, label: String, sliders: Vec<f64>) {
        self.keys.push(TimelineKey { label, sliders });
    }

    /// The keys in order.
    pub fn keys(&self) -> &[TimelineKey] {
        &self.keys
    }
}

impl ViewerApp {
    /// The timeline.
    pub fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// Keys the current pose at the end of the timeline.
    pub fn key_current_pose(&mut self) {
        let label = match (self.active_preset, self.mix.as_slice()) {
            (Some(p), _) => p.to_owned(),
            (None, []) => format!("pose {}", self.timeline.keys.len() + 1),
            (None, mix) => mix
                .iter()
                .map(|(n, w)| format!("{n} {w:.2}"))
                .collect::<Vec<_>>()
                .join(" + "),
        };
        self.timeline.add_key(label, self.sliders.clone());
    }

    /// Moves the timeline to `time_s` and poses the face there.
    pub fn set_timeline_time(&mut self, time_s: f64) {
        self.timeline.time_s = time_s.clamp(0.0, self.timeline.duration_s());
        let Some(sliders) = self.timeline.sliders_at(self.timeline.time_s) else {
            return;
        };
        if sliders.len() == self.sliders.len() {
            self.sliders = sliders;
            self.active_preset = None;
            self.mix.clear();
            self.repose();
        }
    }

    /// Starts or stops playback (playing needs two keys).
    pub fn set_timeline_playing(&mut self, play: bool) {
        let t = &mut self.timeline;
        t.playing_since = (play && t.keys.len() >= 2).then(|| {
            let back = std::time::Duration::from_secs_f64(t.time_s.max(0.0));
            Instant::now()
                .checked_sub(back)
                .unwrap_or_else(Instant::now)
        });
    }

    /// Advances a playing timeline to the present (looping) and asks for the next frame.
    pub(super) fn play_timeline(&mut self, ctx: &egui::Context) {
        let Some(since) = self.timeline.playing_since else {
            return;
        };
        let duration = self.timeline.duration_s();
        if duration <= 0.0 || self.face.is_none() {
            self.timeline.playing_since = None;
            return;
        }
        self.set_timeline_time(since.elapsed().as_secs_f64() % duration);
        ctx.request_repaint();
    }

    pub(super) fn timeline_ui(&mut self, ui: &mut egui::Ui) {
        let keys = self.timeline.keys.len();
        egui::CollapsingHeader::new(format!("Timeline ({keys} keys)"))
            .id_salt("timeline")
            .show(ui, |ui| {
                let has_face = self
                    .face
                    .as_ref()
                    .is_some_and(|f| f.basis.muscle_count() > 0);
                ui.horizontal(|ui| {
                    if ui
                        .add_enabled(has_face, egui::Button::new("Key pose"))
                        .on_hover_text("Add the current pose at the end of the timeline")
                        .clicked()
                    {
                        self.key_current_pose();
                    }
                    let playing = self.timeline.playing();
                    let label = if playing { "Stop" } else { "Play" };
                    if ui
                        .add_enabled(keys >= 2, egui::Button::new(label))
                        .clicked()
                    {
                        self.set_timeline_playing(!playing);
                    }
                    if ui
                        .add_enabled(keys > 0, egui::Button::new("Clear"))
                        .clicked()
                    {
                        self.timeline = Timeline::default();
                    }
                });
                let mut spk = self.timeline.seconds_between_keys;
                ui.add(
                    egui::Slider::new(&mut spk, 0.2..=5.0)
                        .text("s between keys")
                        .max_decimals(1),
                );
                self.timeline.seconds_between_keys = spk;
                if keys >= 2 {
                    let mut t = self.timeline.time_s;
                    let r = ui.add(
                        egui::Slider::new(&mut t, 0.0..=self.timeline.duration_s())
                            .text("Time (s)")
                            .max_decimals(2),
                    );
                    // While playing, the slider follows the time (and may round it): only a
                    // press on it scrubs.
                    let scrub = !self.timeline.playing() || r.is_pointer_button_down_on();
                    if r.changed() && scrub {
                        self.set_timeline_playing(false);
                        self.set_timeline_time(t);
                    }
                }
                let mut remove = None;
                for (i, k) in self.timeline.keys.iter().enumerate() {
                    ui.horizontal(|ui| {
                        if ui.small_button("Remove").clicked() {
                            remove = Some(i);
                        }
                        let at = i as f64 * self.timeline.seconds_between_keys;
                        ui.label(format!("{at:.1} s: {}", k.label));
                    });
                }
                if let Some(i) = remove {
                    self.timeline.keys.remove(i);
                    self.set_timeline_playing(false);
                }
            });
    }
}
