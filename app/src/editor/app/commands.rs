//! The document's commands: its history (undo / redo, one step per drag), its file
//! (new, open, save, save as, recent files), the unsaved-changes prompt and the messages.

use std::path::{Path, PathBuf};

use agesim_core::project::Project;

use super::EditorApp;
use crate::editor::file_browser::{FileBrowser, Outcome as BrowserOutcome};
use crate::editor::files::{self, IoResult, Purpose};
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
    pub(super) fn verb(&self) -> &'static str {
        match self {
            Self::New => "starting a new project",
            Self::Open | Self::OpenPath(_) => "opening another project",
            Self::Quit => "quitting",
        }
    }
}

impl EditorApp {
    pub(super) fn doc(&self) -> Doc {
        Doc {
            project: self.doc.project.clone(),
            wrinkles: self.doc.wrinkles.clone(),
            files: self.doc.files.clone(),
            revision: self.doc.revision,
        }
    }

    /// Records the document before a change named `name` (one step per drag of `key`)
    /// and gives the changed document a new revision.
    pub(super) fn record(&mut self, name: &str, key: &str, dragging: bool) {
        // Field paths read as words in the Edit menu: "large gamma", "hair density per cm2".
        let name = name.replace(['.', '_'], " ");
        let name = name.as_str();
        let before = self.doc();
        self.doc.history.record(name, key, &before, dragging);
        self.doc.next_revision += 1;
        self.doc.revision = self.doc.next_revision;
    }

    pub(super) fn restore(&mut self, doc: Doc, what: &str) {
        self.doc.project = doc.project;
        self.doc.wrinkles = doc.wrinkles;
        self.doc.files = doc.files;
        self.doc.revision = doc.revision;
        self.submit(false, what);
    }

    pub fn undo(&mut self) {
        if let Some((name, doc)) = self.doc.history.undo(self.doc()) {
            self.restore(doc, &format!("undo {name}"));
            self.info(format!("Undid {name}"));
        }
    }

    pub fn redo(&mut self) {
        if let Some((name, doc)) = self.doc.history.redo(self.doc()) {
            self.restore(doc, &format!("redo {name}"));
            self.info(format!("Redid {name}"));
        }
    }

    /// Whether the document differs from the file it was opened from or saved to.
    pub fn modified(&self) -> bool {
        self.doc.revision != self.doc.saved_revision
    }

    /// The project file of the document, if it has one.
    pub fn path(&self) -> Option<&Path> {
        self.doc.path.as_deref()
    }

    /// The window title: file name and a `*` when modified.
    pub fn title(&self) -> String {
        let name = self.doc.file_name("untitled");
        format!("{name}{} — agesim", if self.modified() { " *" } else { "" })
    }

    /// A new document: no undo across it, not modified.
    pub(super) fn replace_document(&mut self, project: Project, path: Option<PathBuf>, what: &str) {
        self.doc.project = project;
        self.doc.wrinkles = None;
        self.persisted.map_view.selected = None;
        self.doc.path = path;
        self.doc.history.clear();
        self.doc.next_revision += 1;
        self.doc.revision = self.doc.next_revision;
        self.doc.saved_revision = self.doc.revision;
        self.submit(false, what);
    }

    pub(super) fn info(&mut self, text: impl Into<String>) {
        let now = self.now;
        let text = text.into();
        self.harness.shown(&text, false);
        self.notices.post(text, false, now);
    }

    pub(super) fn error(&mut self, text: impl Into<String>) {
        let now = self.now;
        let text = text.into();
        self.harness.shown(&text, true);
        self.notices.post(text, true, now);
    }

    /// The error toasts still open, for tests.
    pub fn open_errors(&self) -> Vec<String> {
        self.notices.open_errors().map(|n| n.text.clone()).collect()
    }

    /// Runs `action` now, or asks first when the document has unsaved changes.
    pub fn guard(&mut self, action: Pending) {
        if self.modified() {
            self.prompt = Some(action);
        } else {
            self.run_pending(action);
        }
    }

    pub(super) fn run_pending(&mut self, action: Pending) {
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
        if self.io.busy() || self.browser.is_some() {
            self.info("A file dialog or file task is still open");
            return;
        }
        if let Err(why) = self.dialogs.available() {
            if !self.told_no_native_dialog {
                self.told_no_native_dialog = true;
                self.info(why);
            }
            let start = self
                .doc
                .path
                .as_ref()
                .and_then(|p| p.parent())
                .filter(|p| !p.as_os_str().is_empty())
                .map(Path::to_owned)
                .or_else(|| std::env::current_dir().ok())
                .unwrap_or_default();
            self.browser = Some(FileBrowser::new(purpose, file_name, start));
            return;
        }
        self.io.ask(&self.dialogs, purpose, file_name);
    }

    /// agesim's own file browser, while one is open.
    pub(super) fn browser_ui(&mut self, ctx: &egui::Context) {
        let Some(browser) = &mut self.browser else {
            return;
        };
        match browser.ui(ctx) {
            BrowserOutcome::Open => {}
            BrowserOutcome::Cancelled => self.browser = None,
            BrowserOutcome::Picked(path) => {
                let purpose = browser.purpose.clone();
                self.browser = None;
                self.io.picked(purpose, path);
            }
        }
    }

    /// Saves to the document's file, or asks where when it has none.
    pub fn save(&mut self) {
        match self.doc.path.clone() {
            Some(path) => self.save_to(path),
            None => self.save_as(),
        }
    }

    pub fn save_as(&mut self) {
        let name = self.doc.file_name("head.agesim.json");
        self.ask(Purpose::SaveProject, Some(name));
    }

    pub(super) fn save_to(&mut self, path: PathBuf) {
        let (project, wrinkles) = (self.doc.project.clone(), self.doc.wrinkles.clone());
        self.doc.saving_revision = Some(self.doc.revision);
        // Landmarks found automatically are saved with the project (in the mesh file's
        // coordinates), so reopening it does not search again.
        let snapshot = &self.session.snapshot;
        let found = snapshot
            .landmarks
            .as_deref()
            .filter(|_| snapshot.landmarks_found && project.mesh.path.is_some())
            .map(|l| {
                let mut file = agesim_core::head::landmarks::Landmarks::default();
                for name in agesim_core::head::landmarks::NAMES {
                    if let Some(p) = l.get(name) {
                        let _ = file.set(name, snapshot.file_from_scene * p);
                    }
                }
                file
            });
        self.io.spawn(move || IoResult::ProjectSaved {
            result: files::save_project(&path, &project, wrinkles.as_deref(), found.as_ref()),
            path,
        });
    }

    pub(super) fn remember_recent(&mut self, path: &Path) {
        let recent = &mut self.persisted.recent;
        recent.retain(|p| p != path);
        recent.insert(0, path.to_owned());
        recent.truncate(RECENT);
    }
}
