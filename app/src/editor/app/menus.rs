//! The menu bar: File, Edit, View, Presets, Help.

use std::path::Path;

use super::{EditorApp, Layout, MapKind, Pending};
use crate::editor::files::Purpose;

impl EditorApp {
    pub(super) fn file_menu(&mut self, ui: &mut egui::Ui) {
        let item = |ui: &mut egui::Ui, text: &str, shortcut: &str| {
            ui.add(egui::Button::new(text).shortcut_text(shortcut))
                .clicked()
        };
        if item(ui, "New (default head)", "Ctrl+N") {
            self.guard(Pending::New);
        }
        if item(ui, "Open project…", "Ctrl+O") {
            self.guard(Pending::Open);
        }
        ui.menu_button("Open recent", |ui| {
            if self.persisted.recent.is_empty() {
                ui.label("(none yet)");
            }
            for path in self.persisted.recent.clone() {
                if ui.button(path.display().to_string()).clicked() {
                    self.guard(Pending::OpenPath(path));
                }
            }
        });
        if item(ui, "Save project", "Ctrl+S") {
            self.save();
        }
        if item(ui, "Save project as…", "Ctrl+Shift+S") {
            self.save_as();
        }
        ui.separator();
        if item(ui, "Import head mesh…", "Ctrl+I") {
            self.ask(Purpose::ImportMesh, None);
        }
        if ui.button("Load wrinkle file…").clicked() {
            self.ask(Purpose::LoadWrinkles { add: false }, None);
        }
        if ui.button("Add wrinkle file…").clicked() {
            self.ask(Purpose::LoadWrinkles { add: true }, None);
        }
        let selected_file = self.persisted.map_view.selected.map_or(0, |(f, _)| f);
        let file_name = self.wrinkles().get(selected_file).map(|w| {
            Path::new(&w.name).file_name().map_or_else(
                || "wrinkles.wrk".into(),
                |n| n.to_string_lossy().into_owned(),
            )
        });
        if ui
            .add_enabled(
                file_name.is_some(),
                egui::Button::new(format!(
                    "Save wrinkle file {} as…",
                    file_name.as_deref().unwrap_or("")
                )),
            )
            .clicked()
        {
            self.ask(Purpose::SaveWrinkles(selected_file), file_name);
        }
        ui.menu_button("Load image", |ui| {
            for (field, text) in [
                ("mesh.colour_map", "Head colour map…"),
                ("large.mask", "Large-wrinkle mask…"),
                ("fine.tile", "Fine-wrinkle tile…"),
                ("hair.outer_mask", "Hair mask, young (outer)…"),
                ("hair.inner_mask", "Hair mask, old (inner)…"),
            ] {
                if ui.button(text).clicked() {
                    self.ask(Purpose::Image(field), None);
                }
            }
        });
        ui.separator();
        if item(ui, "Export…", "Ctrl+E") {
            self.windows.export = true;
        }
        ui.separator();
        if ui.button("Quit").clicked() {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    pub(super) fn edit_menu(&mut self, ui: &mut egui::Ui) {
        let undo = self.doc.history.undo_name().map(|n| format!("Undo {n}"));
        if ui
            .add_enabled(
                undo.is_some(),
                egui::Button::new(undo.as_deref().unwrap_or("Undo")).shortcut_text("Ctrl+Z"),
            )
            .clicked()
        {
            self.undo();
        }
        let redo = self.doc.history.redo_name().map(|n| format!("Redo {n}"));
        if ui
            .add_enabled(
                redo.is_some(),
                egui::Button::new(redo.as_deref().unwrap_or("Redo")).shortcut_text("Ctrl+Shift+Z"),
            )
            .clicked()
        {
            self.redo();
        }
        ui.separator();
        if ui.button("Add fibre").clicked() {
            self.add_fibre();
        }
        if ui
            .add_enabled(
                self.persisted.map_view.selected.is_some(),
                egui::Button::new("Delete fibre").shortcut_text("Delete"),
            )
            .clicked()
        {
            self.delete_fibre();
        }
    }

    pub(super) fn help_menu(&mut self, ui: &mut egui::Ui) {
        if ui
            .add(egui::Button::new("Keyboard shortcuts").shortcut_text("F1"))
            .clicked()
        {
            self.windows.help = true;
        }
        if ui.button("Messages").clicked() {
            self.windows.messages = true;
        }
        if ui.button("About agesim").clicked() {
            self.windows.about = true;
        }
    }

    pub(super) fn menu_ui(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| self.file_menu(ui));
            ui.menu_button("Edit", |ui| self.edit_menu(ui));
            ui.menu_button("View", |ui| {
                for kind in MapKind::ALL {
                    ui.radio_value(&mut self.persisted.map_view.kind, kind, kind.name());
                }
                ui.separator();
                ui.checkbox(&mut self.persisted.map_view.show_fibres, "show fibres");
                ui.checkbox(&mut self.persisted.map_view.show_layout, "show UV layout");
                if ui.button("Reset map view").clicked() {
                    self.persisted.map_view.zoom = 1.0;
                    self.persisted.map_view.offset = [0.0, 0.0];
                }
                if ui.button("Frame the head").clicked()
                    && let Some(v) = &mut self.viewport
                {
                    v.reset(&mut self.doc.project);
                }
                ui.separator();
                for (layout, name) in [
                    (Layout::Both, "Head and map"),
                    (Layout::Head, "Head only"),
                    (Layout::Map, "Map only"),
                ] {
                    ui.radio_value(&mut self.persisted.layout, layout, name);
                }
            });
            ui.menu_button("Presets", |ui| self.presets_menu(ui));
            ui.menu_button("Help", |ui| self.help_menu(ui));
        });
    }
}
