//! The status line: adapter, frame time, bake progress, hairs, the deepest wrinkle.

use super::EditorApp;

impl EditorApp {
    pub(super) fn status_ui(&mut self, ui: &mut egui::Ui, frame_ms: f32) {
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("adapter: {}", self.adapter));
            ui.separator();
            ui.label(format!("frame {frame_ms:.1} ms"));
            ui.separator();
            if self.session.busy() {
                // Not egui's spinner: it repaints every frame, and on a CPU adapter each
                // frame takes cores from the bake. Four frames a second show it is alive.
                let dots = (self.now * 4.0) as usize % 4;
                ui.label(format!("baking{:<3}", ".".repeat(dots)));
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_millis(250));
            } else {
                ui.label(format!(
                    "last bake: {} in {:.0} ms",
                    self.session.last_what, self.session.last_bake_ms
                ));
            }
            ui.separator();
            let t = self.doc.project.age.t;
            if let Some(h) = &self.session.snapshot.hair {
                ui.label(format!("hairs: {} of {}", h.count(t), h.len()));
            }
            if let Some(v) = &self.viewport {
                ui.label(format!("3D frame encode {:.1} ms", v.encode_ms));
                if v.sparse_hair > 1 {
                    ui.label(format!("(moving: 1 hair in {} drawn)", v.sparse_hair));
                }
            }
            if let Some(l) = &self.session.snapshot.large {
                if !std::ptr::eq(self.deepest.0.as_ptr(), std::sync::Arc::as_ptr(l)) {
                    self.deepest = (std::sync::Arc::downgrade(l), l.height.min_max().1);
                }
                // The map is normalised; its depth applies where it is shown.
                let deepest = self.deepest.1 * self.doc.project.large.depth;
                ui.label(format!("deepest large wrinkle: {deepest:.2}"));
            }
        });
    }
}
