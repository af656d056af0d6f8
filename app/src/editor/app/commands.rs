//! The editor's commands: the document's history (undo / redo), files (new, open, save,
//! import, load, drag-and-drop, recent files, presets), the unsaved-changes prompt and
//! exports, with the menus, shortcuts and windows that call them.

use std::path::{Path, PathBuf};

use agesim_core::defaults;
use agesim_core::project::Project;
use agesim_core::scene::WrinkleSource;
use egui::{Key, KeyboardShortcut, Modifiers};
use serde_json::Value;

use super::EditorApp;
use crate::editor::export_ui::{self, ExportAction, ExportRun};
use crate::editor::fields_ui::Pick;
use crate::editor::files::{self, FileKind, IoResult, Purpose};
use crate::editor::history::Doc;

/// Recent projects kept in the File menu.
const RECENT: usize = 8;

/// What waits for an answer to "save the changes?".
#[derive(Clone, Debug, PartialEq)]
pub enum Pending {
    New,
    Open,
    OpenPath(PathBuf),
    Quit,
}

impl Pending {
    fn verb(&self) -> &'static str {
        match self {
            Self::New => "starting a new project",
            Self::Open | Self::OpenPath(_) => "opening another project",
            Self::Quit => "quitting",
        }
    }
}

/// The keyboard shortcuts, for the Help window and the README.
pub const SHORTCUTS: &[(&str, &str)] = &[
    ("Ctrl+N", "new project (the default head)"),
    ("Ctrl+O", "open a project"),
    ("Ctrl+S", "save the project"),
    ("Ctrl+Shift+S", "save the project as"),
    ("Ctrl+I", "import a head mesh (OBJ, glTF, GLB)"),
    ("Ctrl+E", "export maps, renders, GLB"),
    ("Ctrl+Z", "undo"),
    ("Ctrl+Shift+Z, Ctrl+Y", "redo"),
    ("Delete", "delete the selected fibre"),
    ("F1", "this help"),
    ("drag (head)", "orbit"),
    ("right-drag (head)", "pan"),
    ("scroll (head)", "zoom"),
    ("Shift+drag (head)", "move the light"),
    ("double-click (head)", "frame the head"),
    (
        "drag a handle (map)",
        "move a fibre's end or the whole fibre",
    ),
    ("scroll / right-drag (map)", "zoom / pan the map"),
    ("double-click a slider", "reset it to its default"),
    (
        "drop a file on the window",
        "open a project, import a mesh, add a wrinkle file, load a mask",
    ),
];

impl EditorApp {
    // ---- the document and its history ----

    pub(super) fn doc(&self) -> Doc {
        Doc {
            project: self.project.clone(),
            wrinkles: self.wrinkles.clone(),
            revision: self.revision,
        }
    }

    /// Records the document before a change named `name` (one step per drag of `key`)
    /// and gives the changed document a new revision.
    pub(super) fn record(&mut self, name: &str, key: &str, dragging: bool) {
        // Field paths read as words in the Edit menu: "large gamma", "hair density per cm2".
        let name = name.replace(['.', '_'], " ");
        let name = name.as_str();
        let before = self.doc();
        self.history.record(name, key, &before, dragging);
        self.next_revision += 1;
        self.revision = self.next_revision;
    }

    fn restore(&mut self, doc: Doc, what: &str) {
        self.project = doc.project;
        self.wrinkles = doc.wrinkles;
        self.revision = doc.revision;
        self.submit(false, what);
    }

    pub fn undo(&mut self) {
        if let Some((name, doc)) = self.history.undo(self.doc()) {
            self.restore(doc, &format!("undo {name}"));
            self.info(format!("Undid {name}"));
        }
    }

    pub fn redo(&mut self) {
        if let Some((name, doc)) = self.history.redo(self.doc()) {
            self.restore(doc, &format!("redo {name}"));
            self.info(format!("Redid {name}"));
        }
    }

    /// Whether the document differs from the file it was opened from or saved to.
    pub fn modified(&self) -> bool {
        self.revision != self.saved_revision
    }

    /// The project file of the document, if it has one.
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The window title: file name and a `*` when modified.
    pub fn title(&self) -> String {
        let name = self.path.as_ref().and_then(|p| p.file_name()).map_or_else(
            || "untitled".to_owned(),
            |n| n.to_string_lossy().into_owned(),
        );
        format!("{name}{} — agesim", if self.modified() { " *" } else { "" })
    }

    /// A new document: no undo across it, not modified.
    fn replace_document(&mut self, project: Project, path: Option<PathBuf>, what: &str) {
        self.project = project;
        self.wrinkles = None;
        self.persisted.map_view.selected = None;
        self.path = path;
        self.history.clear();
        self.next_revision += 1;
        self.revision = self.next_revision;
        self.saved_revision = self.revision;
        self.submit(false, what);
    }

    // ---- messages ----

    pub(super) fn info(&mut self, text: impl Into<String>) {
        let now = self.now;
        self.notices.post(text, false, now);
    }

    pub(super) fn error(&mut self, text: impl Into<String>) {
        let now = self.now;
        self.notices.post(text, true, now);
    }

    /// The error toasts still open, for tests.
    pub fn open_errors(&self) -> Vec<String> {
        self.notices.open_errors().map(|n| n.text.clone()).collect()
    }

    // ---- files ----

    /// Runs `action` now, or asks first when the document has unsaved changes.
    pub fn guard(&mut self, action: Pending) {
        if self.modified() {
            self.prompt = Some(action);
        } else {
            self.run_pending(action);
        }
    }

    fn run_pending(&mut self, action: Pending) {
        match action {
            Pending::New => self.replace_document(Project::default(), None, "new project"),
            Pending::Open => self.ask(Purpose::OpenProject, None),
            Pending::OpenPath(path) => {
                self.io.spawn(move || files::load_project(path));
            }
            Pending::Quit => {
                self.quit_confirmed = true;
                self.ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
    }

    /// Opens a dialog (one at a time) on its own thread.
    pub(super) fn ask(&mut self, purpose: Purpose, file_name: Option<String>) {
        if self.io.busy() {
            self.info("A file dialog or file task is still open");
            return;
        }
        self.io.ask(&self.dialogs, purpose, file_name);
    }

    /// Saves to the document's file, or asks where when it has none.
    pub fn save(&mut self) {
        match self.path.clone() {
            Some(path) => self.save_to(path),
            None => self.save_as(),
        }
    }

    pub fn save_as(&mut self) {
        let name = self.path.as_ref().and_then(|p| p.file_name()).map_or_else(
            || "head.agesim.json".to_owned(),
            |n| n.to_string_lossy().into_owned(),
        );
        self.ask(Purpose::SaveProject, Some(name));
    }

    fn save_to(&mut self, path: PathBuf) {
        let (project, wrinkles) = (self.project.clone(), self.wrinkles.clone());
        self.saving_revision = Some(self.revision);
        self.io.spawn(move || IoResult::ProjectSaved {
            result: files::save_project(&path, &project, wrinkles.as_deref()),
            path,
        });
    }

    fn remember_recent(&mut self, path: &Path) {
        let recent = &mut self.persisted.recent;
        recent.retain(|p| p != path);
        recent.insert(0, path.to_owned());
        recent.truncate(RECENT);
    }

    /// The head mesh from `path` (OBJ, glTF, GLB); the worker loads it, and an error
    /// puts the previous mesh back.
    pub fn import_mesh(&mut self, path: PathBuf) {
        self.record("import mesh", "import mesh", false);
        self.project.mesh.path = Some(path.clone());
        self.submit(false, &format!("import {}", path.display()));
    }

    /// A grey-scale image into a project path field.
    fn load_image(&mut self, field: &'static str, path: PathBuf) {
        self.apply(field, Value::from(path.display().to_string()), false);
    }

    /// A parsed wrinkle file replaces the current ones (or is added to them).
    fn wrinkles_loaded(
        &mut self,
        path: PathBuf,
        add: bool,
        file: agesim_core::wrinkle_file::WrinkleFile,
    ) {
        let fibres = file.groups.len();
        self.record(
            if add {
                "add wrinkle file"
            } else {
                "load wrinkle file"
            },
            "wrinkle file",
            false,
        );
        let source = WrinkleSource {
            name: path.display().to_string(),
            path: Some(path.clone()),
            file,
        };
        if add {
            let mut all = self.wrinkles().to_vec();
            all.push(source);
            if !self.project.large.wrinkles.is_empty() {
                self.project.large.wrinkles.push(path.clone());
            }
            // With the built-in files the list stays empty (they have no path), so the
            // edited set carries them and the new one.
            self.wrinkles = Some(all);
        } else {
            self.project.large.wrinkles = vec![path.clone()];
            self.wrinkles = Some(vec![source]);
        }
        self.project.large.enabled = true;
        self.persisted.map_view.selected = None;
        self.submit(false, "wrinkle file");
        self.info(format!("Loaded {} ({fibres} fibres)", path.display()));
    }

    /// Applies what the file threads brought back.
    pub(super) fn poll_io(&mut self) {
        for result in self.io.poll() {
            match result {
                // A cancelled dialog also cancels what was to follow it (the Save of the
                // unsaved-changes prompt: no New, Open or Quit after a save that did not
                // happen).
                IoResult::Cancelled => self.after_save = None,
                IoResult::Picked(purpose, path) => match purpose {
                    Purpose::SaveProject => self.save_to(path),
                    Purpose::ImportMesh => self.import_mesh(path),
                    Purpose::Image(field) => self.load_image(field, path),
                    Purpose::ExportFolder => self.persisted.export.folder = Some(path),
                    Purpose::SaveWrinkles(i) => {
                        let Some(source) = self.wrinkles().get(i).cloned() else {
                            continue;
                        };
                        self.io.spawn(move || IoResult::Saved {
                            what: "wrinkle file".into(),
                            result: agesim_core::wrinkle_file::save(&source.file, &path)
                                .map(|()| path)
                                .map_err(|e| e.to_string()),
                        });
                    }
                    Purpose::OpenProject | Purpose::LoadWrinkles { .. } => {}
                },
                IoResult::ProjectLoaded { path, result } => match result {
                    Ok(project) => {
                        self.remember_recent(&path);
                        self.info(format!("Opened {}", path.display()));
                        self.replace_document(project, Some(path), "open project");
                    }
                    Err(e) => self.error(format!("Could not open the project: {e}")),
                },
                IoResult::WrinklesLoaded { path, add, result } => match result {
                    Ok(file) => self.wrinkles_loaded(path, add, file),
                    Err(e) => self.error(format!(
                        "The wrinkle file was not loaded; the fibres are unchanged.\n{e}"
                    )),
                },
                IoResult::ProjectSaved { path, result } => match result {
                    Ok((project, wrinkles)) => {
                        // The saved document may point at wrinkle files written beside it.
                        let unchanged = self.saving_revision == Some(self.revision);
                        if unchanged {
                            self.project.large.wrinkles = project.large.wrinkles;
                            self.project.large.mask = project.large.mask;
                            if wrinkles.is_some() {
                                self.wrinkles = wrinkles;
                            }
                            self.saved_revision = self.revision;
                        }
                        self.path = Some(path.clone());
                        self.remember_recent(&path);
                        self.info(format!("Saved {}", path.display()));
                        if let Some(next) = self.after_save.take() {
                            self.run_pending(next);
                        }
                    }
                    Err(e) => {
                        self.after_save = None;
                        self.error(format!("The project was not saved: {e}"));
                    }
                },
                IoResult::Saved { what, result } => match result {
                    Ok(path) => self.info(format!("Saved the {what} {}", path.display())),
                    Err(e) => self.error(format!("The {what} was not saved: {e}")),
                },
                IoResult::UserPresets(list) => self.user_presets = list,
                IoResult::PresetSaved { path, result } => match result {
                    Ok(()) => {
                        self.info(format!("Saved the preset {}", path.display()));
                        self.refresh_user_presets();
                    }
                    Err(e) => self.error(format!("The preset was not saved: {e}")),
                },
                IoResult::PresetLoaded { name, result } => match result {
                    Ok(preset) => self.apply_preset(&name, &preset, true),
                    Err(e) => self.error(format!("The preset {name} was not loaded: {e}")),
                },
            }
        }
    }

    /// Files dropped on the window, by their kind.
    pub(super) fn handle_drops(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_owned())
                .filter(|p| !p.as_os_str().is_empty())
                .collect()
        });
        for path in dropped {
            match files::kind_of(&path) {
                Some(FileKind::Project) => self.guard(Pending::OpenPath(path)),
                Some(FileKind::Mesh) => self.import_mesh(path),
                Some(FileKind::Wrinkles) => {
                    self.io.spawn(move || files::load_wrinkles(path, true));
                }
                Some(FileKind::Image) => {
                    self.info(format!("{} is the large-wrinkle mask now", path.display()));
                    self.load_image("large.mask", path);
                }
                None => self.error(format!(
                    "{}: not a file the editor opens (projects *.json, meshes *.obj *.gltf *.glb, wrinkle files *.wrk, images)",
                    path.display()
                )),
            }
        }
        let hovering = ctx.input(|i| !i.raw.hovered_files.is_empty());
        if hovering {
            let rect = ctx.content_rect();
            let painter = ctx.layer_painter(egui::LayerId::new(
                egui::Order::Foreground,
                egui::Id::unique("drop"),
            ));
            painter.rect_filled(rect, 0.0, egui::Color32::from_black_alpha(160));
            painter.text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "Drop: project, mesh, wrinkle file or mask",
                egui::FontId::proportional(24.0),
                egui::Color32::WHITE,
            );
        }
    }

    /// A path field's Load… / Add… button.
    pub(super) fn pick_for_field(&mut self, field: &'static str, pick: Pick) {
        let purpose = match field {
            "mesh.path" => Purpose::ImportMesh,
            "large.wrinkles" => Purpose::LoadWrinkles {
                add: pick == Pick::Add,
            },
            other => Purpose::Image(other),
        };
        self.ask(purpose, None);
    }

    // ---- presets ----

    /// Where the user's presets live.
    fn presets_dir(&self) -> Option<PathBuf> {
        self.config_dir.as_ref().map(|d| d.join("presets"))
    }

    pub(super) fn refresh_user_presets(&mut self) {
        let Some(dir) = self.presets_dir() else {
            return;
        };
        self.io.spawn(move || {
            let mut list: Vec<PathBuf> = std::fs::read_dir(&dir)
                .map(|entries| {
                    entries
                        .filter_map(|e| e.ok().map(|e| e.path()))
                        .filter(|p| p.to_string_lossy().ends_with(".agesim.json"))
                        .collect()
                })
                .unwrap_or_default();
            list.sort();
            IoResult::UserPresets(list)
        });
    }

    /// Takes a preset's skin look: the micro-relief sections (and, from the user's own
    /// presets, the fine wrinkles and skin shading). Mesh, wrinkles, hair and age stay.
    pub(super) fn apply_preset(&mut self, name: &str, preset: &Project, with_skin: bool) {
        self.record(&format!("preset {name}"), "preset", false);
        let p = &mut self.project;
        p.pores = preset.pores.clone();
        p.furrows = preset.furrows.clone();
        p.noise = preset.noise.clone();
        p.warp = preset.warp.clone();
        p.overlap = preset.overlap.clone();
        p.normal = preset.normal.clone();
        p.map_size_mm = preset.map_size_mm;
        p.seed = preset.seed;
        if with_skin {
            p.fine = preset.fine.clone();
            p.skin = preset.skin.clone();
        }
        self.submit(false, &format!("preset {name}"));
        self.info(format!("Applied the preset {name}"));
    }

    fn apply_shipped_preset(&mut self, name: &str) {
        let Some((file, text)) = defaults::preset(name) else {
            return;
        };
        match Project::from_json_str(text, file) {
            Ok(preset) => self.apply_preset(name, &preset, false),
            Err(e) => self.error(e.to_string()),
        }
    }

    /// Saves the skin look as a preset of the user's: the whole project in the presets
    /// folder; applying it takes its micro-relief, fine wrinkles and skin.
    fn save_user_preset(&mut self) {
        let Some(dir) = self.presets_dir() else {
            self.error("There is no settings folder on this system to keep presets in");
            return;
        };
        let name = self.preset_name.trim().to_owned();
        if name.is_empty() || name.contains(['/', '\\', '.']) {
            self.error(format!(
                "`{name}` cannot be a preset name: use letters, digits, spaces, - and _"
            ));
            return;
        }
        let project = self.project.clone();
        let path = dir.join(format!("{name}.agesim.json"));
        self.io.spawn(move || {
            let result = std::fs::create_dir_all(&dir)
                .map_err(|e| format!("{}: {e}", dir.display()))
                .and_then(|()| project.save(&path).map_err(|e| e.to_string()));
            IoResult::PresetSaved { path, result }
        });
    }

    // ---- export ----

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

    fn start_export(&mut self) {
        let s = &self.persisted.export;
        let years = if s.at_current_age {
            self.project.age.mapping().years(self.project.age.t)
        } else {
            s.years
        };
        match s.request(years) {
            Ok(request) => {
                let ctx = self.ctx.clone();
                self.export_run = Some(ExportRun::start(
                    self.project.clone(),
                    self.wrinkles.clone(),
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

    // ---- menus, shortcuts, windows ----

    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) {
        let cmd = Modifiers::COMMAND;
        let shift = Modifiers::COMMAND | Modifiers::SHIFT;
        let pressed = |m: Modifiers, k: Key| {
            ctx.input_mut(|i| i.consume_shortcut(&KeyboardShortcut::new(m, k)))
        };
        // Shift variants first: a plain shortcut also matches with Shift held.
        if pressed(shift, Key::Z) || pressed(cmd, Key::Y) {
            self.redo();
        } else if pressed(cmd, Key::Z) {
            self.undo();
        }
        if pressed(shift, Key::S) {
            self.save_as();
        } else if pressed(cmd, Key::S) {
            self.save();
        }
        if pressed(cmd, Key::N) {
            self.guard(Pending::New);
        }
        if pressed(cmd, Key::O) {
            self.guard(Pending::Open);
        }
        if pressed(cmd, Key::I) {
            self.ask(Purpose::ImportMesh, None);
        }
        if pressed(cmd, Key::E) {
            self.windows.export = true;
        }
        if pressed(Modifiers::NONE, Key::F1) {
            self.windows.help = !self.windows.help;
        }
    }

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
        let undo = self.history.undo_name().map(|n| format!("Undo {n}"));
        if ui
            .add_enabled(
                undo.is_some(),
                egui::Button::new(undo.as_deref().unwrap_or("Undo")).shortcut_text("Ctrl+Z"),
            )
            .clicked()
        {
            self.undo();
        }
        let redo = self.history.redo_name().map(|n| format!("Redo {n}"));
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

    pub(super) fn presets_menu(&mut self, ui: &mut egui::Ui) {
        ui.label(egui::RichText::new("Skin micro-relief presets").weak());
        for name in defaults::preset_names() {
            if ui.button(name).clicked() {
                self.apply_shipped_preset(name);
            }
        }
        ui.separator();
        ui.label(egui::RichText::new("Your presets").weak());
        if self.user_presets.is_empty() {
            ui.label("(none yet)");
        }
        for path in self.user_presets.clone() {
            let name = path
                .file_name()
                .map(|n| {
                    n.to_string_lossy()
                        .trim_end_matches(".agesim.json")
                        .to_owned()
                })
                .unwrap_or_default();
            if ui.button(&name).clicked() {
                self.io.spawn(move || IoResult::PresetLoaded {
                    result: Project::load(&path).map_err(|e| e.to_string()),
                    name,
                });
            }
        }
        ui.separator();
        if ui.button("Save as preset…").clicked() {
            self.windows.save_preset = true;
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

    /// The unsaved-changes prompt, the Export, Help, Messages and About windows.
    pub(super) fn windows_ui(&mut self, ctx: &egui::Context) {
        if let Some(action) = self.prompt.clone() {
            let modal = egui::Modal::new(egui::Id::unique("unsaved")).show(ctx, |ui| {
                ui.heading("Unsaved changes");
                let name = self.path.as_ref().and_then(|p| p.file_name()).map_or_else(
                    || "the untitled project".to_owned(),
                    |n| n.to_string_lossy().into_owned(),
                );
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
        let years = self.project.age.mapping().years(self.project.age.t);
        let running = self.export_run.as_ref().map(ExportRun::progress);
        let mut action = ExportAction::None;
        egui::Window::new("Export")
            .default_pos(ctx.content_rect().center() - egui::vec2(240.0, 200.0))
            .open(&mut open)
            .resizable(false)
            .show(ctx, |ui| {
                action = export_ui::export_ui(ui, &mut self.persisted.export, years, running);
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
        let mut open = self.windows.save_preset;
        let mut save = false;
        egui::Window::new("Save as preset")
            .default_pos(ctx.content_rect().center() - egui::vec2(240.0, 200.0))
            .open(&mut open)
            .resizable(false)
            .collapsible(false)
            .show(ctx, |ui| {
                ui.label(
                    "The skin look (micro-relief, fine wrinkles, skin) under a name of yours:",
                );
                ui.horizontal(|ui| {
                    let label = ui.label("Name").id;
                    let r = ui
                        .text_edit_singleline(&mut self.preset_name)
                        .labelled_by(label);
                    let enter = r.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
                    save = ui.button("Save").clicked() || enter;
                });
            });
        if save {
            self.save_user_preset();
            open = false;
        }
        self.windows.save_preset = open;
        let mut open = self.windows.help;
        egui::Window::new("Keyboard shortcuts")
            .default_pos(ctx.content_rect().center() - egui::vec2(240.0, 200.0))
            .open(&mut open)
            .show(ctx, |ui| {
                egui::Grid::new("shortcuts").striped(true).show(ui, |ui| {
                    for (keys, what) in SHORTCUTS {
                        ui.label(egui::RichText::new(*keys).monospace());
                        ui.label(*what);
                        ui.end_row();
                    }
                });
            });
        self.windows.help = open;
        let mut open = self.windows.messages;
        egui::Window::new("Messages")
            .open(&mut open)
            .default_size([520.0, 300.0])
            .show(ctx, |ui| self.notices.log_ui(ui));
        self.windows.messages = open;
        let mut open = self.windows.about;
        egui::Window::new("About agesim")
            .default_pos(ctx.content_rect().center() - egui::vec2(240.0, 200.0))
            .open(&mut open)
            .resizable(false)
            .show(ctx, |ui| {
                ui.heading(format!("agesim {}", env!("CARGO_PKG_VERSION")));
                ui.label(
                    "Age a human head: wrinkles, skin micro-relief, hair recession and graying.",
                );
                ui.add_space(6.0);
                egui::Grid::new("about").show(ui, |ui| {
                    for (k, v) in [
                        ("GPU adapter", self.adapter.as_str()),
                        ("UI", "egui / eframe 0.37 (wgpu backend)"),
                        ("renderer", "wgpu 30"),
                        ("licence", env!("CARGO_PKG_LICENSE")),
                    ] {
                        ui.label(k);
                        ui.label(v);
                        ui.end_row();
                    }
                });
            });
        self.windows.about = open;
    }

    /// Asks before the window closes with unsaved changes.
    pub(super) fn intercept_close(&mut self, ctx: &egui::Context) {
        if ctx.input(|i| i.viewport().close_requested()) && self.modified() && !self.quit_confirmed
        {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.prompt = Some(Pending::Quit);
        }
    }
}
