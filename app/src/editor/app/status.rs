//! The status line: adapter, frame time, bake progress, hairs, the deepest wrinkle. It shows
//! a [`Status`] the app gathers each frame.

use super::EditorApp;

/// What the status line shows.
pub(super) struct Status<'a> {
    pub adapter: &'a str,
    pub frame_ms: f32,
    /// `Some(seconds)` while a bake runs (egui's clock, for the dots), else the last bake.
    pub baking: Option<f64>,
    pub last_bake: (&'a str, f64),
    /// Hairs present at the age, of all.
    pub hairs: Option<(usize, usize)>,
    /// The 3D view's encode time and its hair thinning while moving (1: every hair).
    pub view: Option<(f64, u32)>,
    /// The 3D view's quality in words (the governor's).
    pub quality: String,
    /// The deepest large wrinkle shown, height units.
    pub deepest: Option<f32>,
}

/// The status line of `s`.
pub(super) fn status_line(ui: &mut egui::Ui, s: &Status<'_>) {
    ui.horizontal_wrapped(|ui| {
        ui.label(format!("adapter: {}", s.adapter));
        ui.separator();
        ui.label(format!("frame {:.1} ms", s.frame_ms));
        ui.separator();
        match s.baking {
            Some(now) => {
                // Not egui's spinner: it repaints every frame, and on a CPU adapter each
                // frame takes cores from the bake. Four frames a second show it is alive.
                let dots = (now * 4.0) as usize % 4;
                ui.label(format!("baking{:<3}", ".".repeat(dots)));
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_millis(250));
            }
            None => {
                ui.label(format!(
                    "last bake: {} in {:.0} ms",
                    s.last_bake.0, s.last_bake.1
                ));
            }
        }
        ui.separator();
        if let Some((present, all)) = s.hairs {
            ui.label(format!("hairs: {present} of {all}"));
        }
        if let Some((encode_ms, sparse)) = s.view {
            // One short item: the line must not wrap when the view starts moving (the
            // panels below would jump).
            let hair = if sparse > 1 {
                format!(", 1 hair in {sparse}")
            } else {
                String::new()
            };
            ui.label(format!("3D: {}{hair} · {encode_ms:.1} ms", s.quality));
        }
        if let Some(deepest) = s.deepest {
            ui.label(format!("deepest large wrinkle: {deepest:.2}"));
        }
    });
}

impl EditorApp {
    pub(super) fn status_ui(&mut self, ui: &mut egui::Ui, frame_ms: f32) {
        let t = self.doc.project.age.t;
        // The map is normalised; its depth applies where it is shown. Its deepest value is
        // computed once per map, not once per frame.
        let deepest = self.session.snapshot.large.as_ref().map(|l| {
            if !std::ptr::eq(self.deepest.0.as_ptr(), std::sync::Arc::as_ptr(l)) {
                self.deepest = (std::sync::Arc::downgrade(l), l.height.min_max().1);
            }
            let p = &self.doc.project;
            self.deepest.1 * p.large_depth_at(p.age.mapping().years(p.age.t))
        });
        let status = Status {
            adapter: &self.adapter,
            frame_ms,
            baking: self.session.busy().then_some(self.now),
            last_bake: (&self.session.last_what, self.session.last_bake_ms),
            hairs: self
                .session
                .snapshot
                .hair
                .as_ref()
                .map(|h| (h.count(t), h.len())),
            view: self.viewport.as_ref().map(|v| (v.encode_ms, v.sparse_hair)),
            quality: self.governor.describe(),
            deepest,
        };
        status_line(ui, &status);
    }
}
