//! The menu bar: File, Edit, View, Presets, Help. It shows [`MenuState`], edits only the
//! view settings ([`Persisted`]) and returns the [`Command`]s chosen.

use std::path::PathBuf;

use agesim_core::defaults;

use super::command::{Command, user_preset_name};
use super::{Layout, MapKind, Pending, Persisted};
use crate::editor::files::Purpose;

/// What the menus show of the document and the session.
pub(super) struct MenuState<'a> {
    /// The names of the steps undo and redo would take.
    pub undo: Option<String>,
    pub redo: Option<String>,
    /// The selected fibre's wrinkle file (its index and file name), else the first file.
    pub wrinkle_file: Option<(usize, String)>,
    pub user_presets: &'a [PathBuf],
}

/// The menu bar; returns the commands chosen.
pub(super) fn menu_bar(
    ui: &mut egui::Ui,
    state: &MenuState<'_>,
    view: &mut Persisted,
) -> Vec<Command> {
    let mut out = Vec::new();
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| file_menu(ui, state, view, &mut out));
        ui.menu_button("Edit", |ui| edit_menu(ui, state, view, &mut out));
        ui.menu_button("View", |ui| view_menu(ui, view, &mut out));
        ui.menu_button("Presets", |ui| presets_menu(ui, state, &mut out));
        ui.menu_button("Help", |ui| help_menu(ui, &mut out));
    });
    out
}

fn item(ui: &mut egui::Ui, text: &str, shortcut: &str) -> bool {
    ui.add(egui::Button::new(text).shortcut_text(shortcut))
        .clicked()
}

fn file_menu(ui: &mut egui::Ui, state: &MenuState<'_>, view: &Persisted, out: &mut Vec<Command>) {
    if item(ui, "New (default head)", "Ctrl+N") {
        out.push(Command::Guard(Pending::New));
    }
    if item(ui, "Open project…", "Ctrl+O") {
        out.push(Command::Guard(Pending::Open));
    }
    ui.menu_button("Open recent", |ui| {
        if view.recent.is_empty() {
            ui.label("(none yet)");
        }
        for path in &view.recent {
            if ui.button(path.display().to_string()).clicked() {
                out.push(Command::Guard(Pending::OpenPath(path.clone())));
            }
        }
    });
    if item(ui, "Save project", "Ctrl+S") {
        out.push(Command::Save);
    }
    if item(ui, "Save project as…", "Ctrl+Shift+S") {
        out.push(Command::SaveAs);
    }
    ui.separator();
    if item(ui, "Import head mesh…", "Ctrl+I") {
        out.push(Command::Ask(Purpose::ImportMesh, None));
    }
    if ui.button("Load wrinkle file…").clicked() {
        out.push(Command::Ask(Purpose::LoadWrinkles { add: false }, None));
    }
    if ui.button("Add wrinkle file…").clicked() {
        out.push(Command::Ask(Purpose::LoadWrinkles { add: true }, None));
    }
    let file_name = state.wrinkle_file.as_ref().map(|(_, n)| n.as_str());
    if ui
        .add_enabled(
            file_name.is_some(),
            egui::Button::new(format!("Save wrinkle file {} as…", file_name.unwrap_or(""))),
        )
        .clicked()
        && let Some((index, name)) = &state.wrinkle_file
    {
        out.push(Command::Ask(
            Purpose::SaveWrinkles(*index),
            Some(name.clone()),
        ));
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
                out.push(Command::Ask(Purpose::Image(field), None));
            }
        }
    });
    ui.separator();
    if item(ui, "Export…", "Ctrl+E") {
        out.push(Command::ShowExport);
    }
    ui.separator();
    if ui.button("Quit").clicked() {
        out.push(Command::Quit);
    }
}

fn edit_menu(ui: &mut egui::Ui, state: &MenuState<'_>, view: &Persisted, out: &mut Vec<Command>) {
    let undo = state.undo.as_ref().map(|n| format!("Undo {n}"));
    if ui
        .add_enabled(
            undo.is_some(),
            egui::Button::new(undo.as_deref().unwrap_or("Undo")).shortcut_text("Ctrl+Z"),
        )
        .clicked()
    {
        out.push(Command::Undo);
    }
    let redo = state.redo.as_ref().map(|n| format!("Redo {n}"));
    if ui
        .add_enabled(
            redo.is_some(),
            egui::Button::new(redo.as_deref().unwrap_or("Redo")).shortcut_text("Ctrl+Shift+Z"),
        )
        .clicked()
    {
        out.push(Command::Redo);
    }
    ui.separator();
    if ui.button("Add fibre").clicked() {
        out.push(Command::AddFibre);
    }
    if ui
        .add_enabled(
            view.map_view.selected.is_some(),
            egui::Button::new("Delete fibre").shortcut_text("Delete"),
        )
        .clicked()
    {
        out.push(Command::DeleteFibre);
    }
}

fn view_menu(ui: &mut egui::Ui, view: &mut Persisted, out: &mut Vec<Command>) {
    for kind in MapKind::ALL {
        ui.radio_value(&mut view.map_view.kind, kind, kind.name());
    }
    ui.separator();
    ui.checkbox(&mut view.map_view.show_fibres, "show fibres");
    ui.checkbox(&mut view.map_view.show_layout, "show UV layout");
    if ui.button("Reset map view").clicked() {
        view.map_view.zoom = 1.0;
        view.map_view.offset = [0.0, 0.0];
    }
    if ui.button("Frame the head").clicked() {
        out.push(Command::FrameHead);
    }
    ui.separator();
    for (layout, name) in [
        (Layout::Both, "Head and map"),
        (Layout::Head, "Head only"),
        (Layout::Map, "Map only"),
    ] {
        ui.radio_value(&mut view.layout, layout, name);
    }
}

fn presets_menu(ui: &mut egui::Ui, state: &MenuState<'_>, out: &mut Vec<Command>) {
    ui.label(egui::RichText::new("Skin micro-relief presets").weak());
    for name in defaults::preset_names() {
        if ui.button(name).clicked() {
            out.push(Command::ShippedPreset(name));
        }
    }
    ui.separator();
    ui.label(egui::RichText::new("Your presets").weak());
    if state.user_presets.is_empty() {
        ui.label("(none yet)");
    }
    for path in state.user_presets {
        if ui.button(user_preset_name(path)).clicked() {
            out.push(Command::UserPreset(path.clone()));
        }
    }
    ui.separator();
    if ui.button("Save as preset…").clicked() {
        out.push(Command::ShowSavePreset);
    }
}

fn help_menu(ui: &mut egui::Ui, out: &mut Vec<Command>) {
    if ui
        .add(egui::Button::new("Keyboard shortcuts").shortcut_text("F1"))
        .clicked()
    {
        out.push(Command::ShowHelp);
    }
    if ui.button("Messages").clicked() {
        out.push(Command::ShowMessages);
    }
    if ui.button("About agesim").clicked() {
        out.push(Command::ShowAbout);
    }
}
