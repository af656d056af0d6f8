//! agesim's own file browser, for desktops where the native dialog cannot open (on
//! Linux: no XDG desktop portal and no zenity, e.g. a tiling window manager or Xvfb).
//! An egui window: the folder's subfolders and the files its filters accept, a file name,
//! and Open / Save / Choose folder. It reads folders on the UI thread, one listing per
//! folder change (a folder, not a file's contents).

use std::path::{Path, PathBuf};

use super::files::{DialogRequest, Mode, Purpose};

/// One listing entry.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Entry {
    /// Folders first, then by name.
    is_file: bool,
    name: String,
}

/// An open browser: what it was opened for and where it is.
pub struct FileBrowser {
    pub purpose: Purpose,
    request: DialogRequest,
    dir: PathBuf,
    entries: Vec<Entry>,
    name: String,
    error: Option<String>,
    /// A save onto this existing file was asked once: the next Save replaces it.
    confirm_replace: Option<PathBuf>,
}

/// What the typed name leads to.
#[derive(Debug, PartialEq)]
enum Choice {
    Pick(PathBuf),
    /// A folder: go into it.
    Enter(PathBuf),
    /// Not yet (the message says why).
    Refused(String),
}

/// How a frame of the browser ended.
pub enum Outcome {
    /// Still open.
    Open,
    Picked(PathBuf),
    Cancelled,
}

impl FileBrowser {
    /// A browser for `purpose`, starting in `dir` (else the current folder, else the
    /// home folder, else the root: the first of them that can be read).
    pub fn new(purpose: Purpose, file_name: Option<String>, dir: PathBuf) -> Self {
        let request = purpose.request(file_name.clone());
        let mut b = Self {
            purpose,
            request,
            dir: PathBuf::new(),
            entries: Vec::new(),
            name: file_name.unwrap_or_default(),
            error: None,
            confirm_replace: None,
        };
        let candidates = [
            Some(dir),
            std::env::current_dir().ok(),
            std::env::var_os("HOME").map(PathBuf::from),
            Some(PathBuf::from("/")),
        ];
        for dir in candidates.into_iter().flatten() {
            if !dir.as_os_str().is_empty() && b.enter(dir) {
                break;
            }
        }
        b
    }

    /// Lists `dir` (kept only if it can be read); whether it could.
    fn enter(&mut self, dir: PathBuf) -> bool {
        let dir = std::path::absolute(&dir).unwrap_or(dir);
        match std::fs::read_dir(&dir) {
            Ok(read) => {
                let mut entries: Vec<Entry> = read
                    .filter_map(Result::ok)
                    .filter_map(|e| {
                        let name = e.file_name().to_string_lossy().into_owned();
                        let is_file = !e.path().is_dir();
                        (!name.starts_with('.') && (!is_file || self.accepts(&name)))
                            .then_some(Entry { is_file, name })
                    })
                    .collect();
                entries.sort();
                self.entries = entries;
                self.dir = dir;
                self.error = None;
                self.confirm_replace = None;
                true
            }
            Err(e) => {
                self.error = Some(format!("{}: {e}", dir.display()));
                false
            }
        }
    }

    /// Whether a file of this name passes the request's filters (all files without any).
    fn accepts(&self, name: &str) -> bool {
        if self.request.mode == Mode::Folder {
            return false;
        }
        let lower = name.to_lowercase();
        self.request.filters.is_empty()
            || self
                .request
                .filters
                .iter()
                .flat_map(|(_, exts)| exts)
                .any(|e| lower.ends_with(&format!(".{e}")))
    }

    /// What the typed name (relative to the folder, or absolute) leads to in this mode.
    fn chosen(&self) -> Choice {
        let typed = self.name.trim();
        let path = if typed.is_empty() {
            self.dir.clone()
        } else {
            self.dir.join(typed)
        };
        match self.request.mode {
            Mode::Folder if path.is_dir() => Choice::Pick(path),
            Mode::Folder => Choice::Refused(format!("{} is not a folder", path.display())),
            _ if !typed.is_empty() && path.is_dir() => Choice::Enter(path),
            Mode::Open if path.is_file() => Choice::Pick(path),
            Mode::Open => Choice::Refused(format!("{} is not a file", path.display())),
            Mode::Save if typed.is_empty() => Choice::Refused("type a file name".into()),
            Mode::Save if !path.parent().is_some_and(Path::is_dir) => {
                Choice::Refused(format!("{}: no such folder", path.display()))
            }
            Mode::Save if path.exists() && self.confirm_replace.as_ref() != Some(&path) => {
                Choice::Refused(format!(
                    "{} exists: Save again to replace it",
                    path.display()
                ))
            }
            Mode::Save => Choice::Pick(path),
        }
    }

    /// Draws the browser; returns how it ended this frame.
    pub fn ui(&mut self, ctx: &egui::Context) -> Outcome {
        let mut outcome = Outcome::Open;
        let mut enter = None;
        let mut open = true;
        egui::Window::new(&self.request.title)
            .id(egui::Id::unique("agesim file browser"))
            .open(&mut open)
            .collapsible(false)
            .default_size([520.0, 420.0])
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    if ui.button("Up").clicked()
                        && let Some(parent) = self.dir.parent()
                    {
                        enter = Some(parent.to_owned());
                    }
                    ui.label(egui::RichText::new(self.dir.display().to_string()).monospace());
                });
                ui.separator();
                egui::ScrollArea::vertical()
                    .max_height(260.0)
                    .auto_shrink([false, true])
                    .show(ui, |ui| {
                        for e in &self.entries {
                            let label = if e.is_file {
                                e.name.clone()
                            } else {
                                format!("{}/", e.name)
                            };
                            // A click selects, a double-click opens (a folder: goes in).
                            let r = ui.selectable_label(self.name == e.name, label);
                            if r.clicked() {
                                self.name = e.name.clone();
                            }
                            if r.double_clicked() {
                                if e.is_file {
                                    outcome = Outcome::Picked(self.dir.join(&e.name));
                                } else {
                                    enter = Some(self.dir.join(&e.name));
                                    // The folder's name was selected by the first click.
                                    if self.name == e.name {
                                        self.name.clear();
                                    }
                                }
                            }
                        }
                        if self.entries.is_empty() {
                            ui.weak("(nothing here for this dialog)");
                        }
                    });
                ui.separator();
                // Enter in the name field does what the button does (a full path typed
                // and entered opens that file, as in any file dialog).
                let mut submit = false;
                if self.request.mode != Mode::Folder {
                    ui.horizontal(|ui| {
                        let label = ui.label("file name");
                        let field = ui
                            .text_edit_singleline(&mut self.name)
                            .labelled_by(label.id);
                        submit =
                            field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                    });
                }
                let filters: Vec<String> = self
                    .request
                    .filters
                    .iter()
                    .map(|(n, e)| format!("{n} (.{})", e.join(", .")))
                    .collect();
                if !filters.is_empty() {
                    ui.weak(filters.join("; "));
                }
                ui.horizontal(|ui| {
                    let verb = match self.request.mode {
                        Mode::Open => "Open",
                        Mode::Save => "Save",
                        Mode::Folder => "Choose this folder",
                    };
                    if ui.button(verb).clicked() || submit {
                        match self.chosen() {
                            Choice::Pick(path) => outcome = Outcome::Picked(path),
                            Choice::Enter(dir) => {
                                enter = Some(dir);
                                self.name.clear();
                            }
                            Choice::Refused(e) => {
                                // Refused once for an existing file: Save again replaces it.
                                let path = self.dir.join(self.name.trim());
                                if self.request.mode == Mode::Save && path.is_file() {
                                    self.confirm_replace = Some(path);
                                }
                                self.error = Some(e);
                            }
                        }
                    }
                    if ui.button("Cancel").clicked() {
                        outcome = Outcome::Cancelled;
                    }
                });
                if let Some(e) = &self.error {
                    ui.colored_label(egui::Color32::from_rgb(255, 110, 90), e);
                }
            });
        if let Some(dir) = enter {
            self.enter(dir);
        }
        if !open {
            outcome = Outcome::Cancelled;
        }
        outcome
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_folders_and_the_files_its_filters_accept() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("heads")).unwrap();
        for f in ["a.obj", "b.GLB", "notes.txt", ".hidden.obj"] {
            std::fs::write(dir.path().join(f), "").unwrap();
        }
        let b = FileBrowser::new(Purpose::ImportMesh, None, dir.path().to_owned());
        let names: Vec<&str> = b.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["heads", "a.obj", "b.GLB"]);
        let mut b = b;
        b.name = "a.obj".into();
        assert_eq!(b.chosen(), Choice::Pick(dir.path().join("a.obj")));
        b.name = "heads".into();
        assert_eq!(b.chosen(), Choice::Enter(dir.path().join("heads")));
        b.name = "missing.obj".into();
        assert!(matches!(b.chosen(), Choice::Refused(e) if e.contains("missing.obj")));
        // A full path typed opens that file, wherever the browser stands.
        let elsewhere = tempfile::tempdir().unwrap();
        let map = elsewhere.path().join("head_diffuse.tga");
        std::fs::write(&map, "").unwrap();
        let mut b = FileBrowser::new(Purpose::ImportMesh, None, dir.path().to_owned());
        b.name = map.display().to_string();
        assert_eq!(b.chosen(), Choice::Pick(map));
    }

    #[test]
    fn saving_over_a_file_asks_first_and_an_unreadable_start_falls_back() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("p.agesim.json"), "{}").unwrap();
        let mut b = FileBrowser::new(Purpose::SaveProject, None, dir.path().to_owned());
        b.name = "p.agesim.json".into();
        assert!(matches!(b.chosen(), Choice::Refused(e) if e.contains("Save again")));
        b.confirm_replace = Some(dir.path().join("p.agesim.json"));
        assert_eq!(b.chosen(), Choice::Pick(dir.path().join("p.agesim.json")));
        b.name = "new.agesim.json".into();
        assert_eq!(b.chosen(), Choice::Pick(dir.path().join("new.agesim.json")));
        // An empty or missing start folder: the current folder instead, never nothing.
        let b = FileBrowser::new(Purpose::ImportMesh, None, PathBuf::new());
        assert!(!b.dir.as_os_str().is_empty());
        let b = FileBrowser::new(Purpose::ImportMesh, None, dir.path().join("gone"));
        assert!(b.dir.is_dir());
    }
}
