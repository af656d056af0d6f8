//! Messages for the artist: toasts in the corner of the window (errors stay until closed,
//! the rest fade after a few seconds) and the Messages window with all of them.

use egui::Color32;

/// How long an information toast stays, seconds.
const INFO_SECONDS: f64 = 6.0;
/// Messages kept in the log.
const LOG_LIMIT: usize = 200;

#[derive(Clone, Debug)]
pub struct Notice {
    pub text: String,
    pub error: bool,
    /// egui time when it was posted, seconds.
    pub at: f64,
    /// Still shown as a toast.
    pub toast: bool,
}

#[derive(Debug, Default)]
pub struct Notices {
    log: Vec<Notice>,
}

const ERROR: Color32 = Color32::from_rgb(255, 120, 100);

impl Notices {
    pub fn post(&mut self, text: impl Into<String>, error: bool, now: f64) {
        self.log.push(Notice {
            text: text.into(),
            error,
            at: now,
            toast: true,
        });
        if self.log.len() > LOG_LIMIT {
            self.log.remove(0);
        }
    }

    /// Takes down the error toasts that mention `what` (a file that was fixed); they stay
    /// in the log.
    pub fn close_errors_about(&mut self, what: &str) {
        for n in self
            .log
            .iter_mut()
            .filter(|n| n.error && n.text.contains(what))
        {
            n.toast = false;
        }
    }

    /// The errors still shown as toasts.
    pub fn open_errors(&self) -> impl Iterator<Item = &Notice> {
        self.log.iter().filter(|n| n.toast && n.error)
    }

    /// Draws the toasts at the bottom right, above `bottom_margin` px.
    pub fn toasts_ui(&mut self, ctx: &egui::Context, bottom_margin: f32) {
        let now = ctx.input(|i| i.time);
        for n in &mut self.log {
            if !n.error && now - n.at > INFO_SECONDS {
                n.toast = false;
            }
        }
        if !self.log.iter().any(|n| n.toast) {
            return;
        }
        if self.log.iter().any(|n| n.toast && !n.error) {
            ctx.request_repaint_after(std::time::Duration::from_millis(500));
        }
        egui::Area::new(egui::Id::unique("toasts"))
            .anchor(egui::Align2::RIGHT_BOTTOM, [-12.0, -bottom_margin])
            .order(egui::Order::Foreground)
            .show(ctx, |ui| {
                ui.set_max_width(460.0);
                // Newest at the bottom, at most five.
                let shown: Vec<usize> =
                    (0..self.log.len()).filter(|&i| self.log[i].toast).collect();
                for &i in shown.iter().rev().take(5).rev() {
                    let n = &mut self.log[i];
                    egui::Frame::popup(ui.style()).show(ui, |ui| {
                        ui.horizontal(|ui| {
                            if ui.small_button("x").on_hover_text("close").clicked() {
                                n.toast = false;
                            }
                            let text = egui::RichText::new(&n.text);
                            if n.error {
                                ui.label(text.color(ERROR));
                            } else {
                                ui.label(text);
                            }
                        });
                    });
                }
            });
    }

    /// The Messages window's contents.
    pub fn log_ui(&mut self, ui: &mut egui::Ui) {
        if ui.button("Clear").clicked() {
            self.log.clear();
        }
        egui::ScrollArea::vertical()
            .stick_to_bottom(true)
            .show(ui, |ui| {
                for n in &self.log {
                    let text = egui::RichText::new(&n.text).monospace();
                    ui.label(if n.error { text.color(ERROR) } else { text });
                }
            });
    }
}
