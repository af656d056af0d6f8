//! The windows (Export, Save preset, Help, Messages, About), the export run in the
//! background, and the unsaved-changes prompt when the window is closed.

use egui::Key;

use super::{EditorApp, Pending, SHORTCUTS};
use crate::editor::export_ui::{self, ExportAction, ExportRun};
use crate::editor::files::Purpose;

impl EditorApp {
    pub(super) fn start_export(&mut self) {
        let s = &self.persisted.export;
        let years = if s.at_current_age {
            self.doc.project.age.mapping().years(self.doc.project.age.t)
        } else {
            s.years
        };
        match s.request(years) {
            Ok(request) => {
                let ctx = self.ctx.clone();
                self.export_run = Some(ExportRun::start(
                    self.doc.project.clone(),
                    self.doc.wrinkles.clone(),
                    request,
                    move || ctx.request_repaint(),
                ));
            }
            Err(e) => self.error(e),
        }
    }

    /// Whether an export is running, for tests.
    pub fn exporting(&self) -> bool {
        self.export_run.is_some()
    }

    /// The Export window's settings.
    pub fn export_settings(&self) -> &export_ui::ExportSettings {
        &self.persisted.export
    }

    /// The Export window's settings, for tests.
    pub fn export_settings_mut(&mut self) -> &mut export_ui::ExportSettings {
        &mut self.persisted.export
    }

    pub(super) fn poll_export(&mut self) {
        let Some(run) = &self.export_run else {
            return;
        };
        let Some(result) = run.finished() else {
            return;
        };
        let cancelled = run.cancelled();
        self.export_run = None;
        match result {
            Ok(files) => {
                let folder = files
                    .first()
                    .and_then(|f| f.parent())
                    .map_or_else(String::new, |d| d.display().to_string());
                self.info(format!("Exported {} files into {folder}", files.len()));
            }
            Err(_) if cancelled => self.info("Export cancelled: no file was written or changed"),
            Err(e) => self.error(format!(
                "Export failed; no file was written or changed: {e}"
            )),
        }
    }

    /// The unsaved-changes prompt, the Export, Help, Messages and About windows.
    pub(super) fn windows_ui(&mut self, ctx: &egui::Context) {
        self.recovery_window(ctx);
        self.landmark_window(ctx);
        if let Some(action) = self.prompt.clone() {
            let modal = egui::Modal::new(egui::Id::unique("unsaved")).show(ctx, |ui| {
                ui.heading("Unsaved changes");
                let name = self.doc.file_name("the untitled project");
                ui.label(format!(
                    "Save the changes to {name} before {}?",
                    action.verb()
                ));
                ui.add_space(8.0);
                ui.horizontal(|ui| {
                    if ui.button("Save").clicked() {
                        self.prompt = None;
                        self.after_save = Some(action.clone());
                        self.save();
                    }
                    if ui.button("Don't save").clicked() {
                        self.prompt = None;
                        self.run_pending(action.clone());
                    }
                    if ui.button("Cancel").clicked() {
                        self.prompt = None;
                    }
                });
            });
            if modal.should_close() {
                self.prompt = None;
            }
        }
        let mut open = self.windows.export;
        let years = self.doc.project.age.mapping().years(self.doc.project.age.t);
        let running = self.export_run.as_ref().map(ExportRun::progress);
        let hairs = self.viewport.as_ref().map_or(0, |v| v.hairs_drawn);
        let mut action = ExportAction::None;
        egui::Window::new("Export")
            .default_pos(window_pos(ctx))
            .open(&mut open)
            .resizable(false)
            .show(ctx, |ui| {
                action =
                    export_ui::export_ui(ui, &mut self.persisted.export, years, running, hairs);
            });
        self.windows.export = open;
        match action {
            ExportAction::None => {}
            ExportAction::ChooseFolder => self.ask(Purpose::ExportFolder, None),
            ExportAction::Start => self.start_export(),
            ExportAction::Cancel => {
                if let Some(run) = &self.export_run {
                    run.cancel();
                }
            }
        }
        if save_preset_window(ctx, &mut self.windows.save_preset, &mut self.preset_name) {
            self.save_user_preset();
        }
        shortcuts_window(ctx, &mut self.windows.help);
        let mut open = self.windows.messages;
        egui::Window::new("Messages")
            .open(&mut open)
            .default_size([520.0, 300.0])
            .show(ctx, |ui| self.notices.log_ui(ui));
        self.windows.messages = open;
        about_window(ctx, &mut self.windows.about, &self.adapter);
    }

    /// Asks before the window closes with unsaved changes.
    pub(super) fn intercept_close(&mut self, ctx: &egui::Context) {
        // A scripted run (screenshot, benchmark, soak) closes itself: nobody to ask.
        let scripted = self.options.scripted();
        if ctx.input(|i| i.viewport().close_requested())
            && self.modified()
            && !self.quit_confirmed
            && !scripted
        {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.prompt = Some(Pending::Quit);
        }
    }
}

/// Where the windows first open.
fn window_pos(ctx: &egui::Context) -> egui::Pos2 {
    ctx.content_rect().center() - egui::vec2(240.0, 200.0)
}

/// The Save-as-preset window over the preset's `name`; `true` when Save was chosen (the
/// window then closes).
fn save_preset_window(ctx: &egui::Context, open: &mut bool, name: &mut String) -> bool {
    let mut save = false;
    egui::Window::new("Save as preset")
        .default_pos(window_pos(ctx))
        .open(open)
        .resizable(false)
        .collapsible(false)
        .show(ctx, |ui| {
            ui.label("The skin look (micro-relief, fine wrinkles, skin) under a name of yours:");
            ui.horizontal(|ui| {
                let label = ui.label("Name").id;
                let r = ui.text_edit_singleline(name).labelled_by(label);
                let enter = r.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
                save = ui.button("Save").clicked() || enter;
            });
        });
    if save {
        *open = false;
    }
    save
}

/// The keyboard shortcuts ([`SHORTCUTS`]).
fn shortcuts_window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Keyboard shortcuts")
        .default_pos(window_pos(ctx))
        .open(open)
        .show(ctx, |ui| {
            egui::Grid::new("shortcuts").striped(true).show(ui, |ui| {
                for (keys, what) in SHORTCUTS {
                    ui.label(egui::RichText::new(*keys).monospace());
                    ui.label(*what);
                    ui.end_row();
                }
            });
        });
}

/// About agesim: the version, the adapter in use, the licences of the heads.
fn about_window(ctx: &egui::Context, open: &mut bool, adapter: &str) {
    egui::Window::new("About agesim")
        .default_pos(window_pos(ctx))
        .open(open)
        .resizable(false)
        .show(ctx, |ui| {
            ui.heading(format!("agesim {}", env!("CARGO_PKG_VERSION")));
            ui.label("Age a human head: wrinkles, skin micro-relief, hair recession and graying.");
            ui.add_space(6.0);
            egui::Grid::new("about").show(ui, |ui| {
                for (k, v) in [
                    ("GPU adapter", adapter),
                    ("UI", "egui / eframe 0.37 (wgpu backend)"),
                    ("renderer", "wgpu 30"),
                    ("licence", env!("CARGO_PKG_LICENSE")),
                ] {
                    ui.label(k);
                    ui.label(v);
                    ui.end_row();
                }
            });
            ui.add_space(6.0);
            ui.label("The default head and template (assets/heads/lee-perry-smith):");
            ui.label(
                "Infinite, 3D Head Scan by Lee Perry-Smith, licensed under CC BY 3.0, based on a work at triplegangers.com.",
            );
            ui.label("Test heads: the MakeHuman head, CC0 1.0; agesim's mannequin.");
        });
}
