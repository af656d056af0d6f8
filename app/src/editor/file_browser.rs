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
}

/// How a frame of the browser ended.
pub enum Outcome {
    /// Still open.
    Open,
    Picked(PathBuf),
    Cancelled,
}

impl FileBrowser {
    /// A browser for `purpose`, starting in `dir`.
    pub fn new(purpose: Purpose, file_name: Option<String>, dir: PathBuf) -> Self {
        let request = purpose.request(file_name.clone());
        let mut b = Self {
            purpose,
            request,
            dir: PathBuf::new(),
            entries: Vec::new(),
            name: file_name.unwrap_or_default(),
            error: None,
        };
        b.enter(dir);
        b
    }

    /// Lists `dir` (kept only if it can be read).
    fn enter(&mut self, dir: PathBuf) {
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
            }
            Err(e) => self.error = Some(format!("{}: {e}", dir.display())),
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

    /// The path the typed name stands for, checked for the mode.
    fn chosen(&self) -> Result<PathBuf, String> {
        let typed = self.name.trim();
        let path = if typed.is_empty() {
            self.dir.clone()
        } else {
            self.dir.join(typed)
        };
        match self.request.mode {
            Mode::Open if path.is_file() => Ok(path),
            Mode::Open => Err(format!("{} is not a file", path.display())),
            Mode::Save if typed.is_empty() => Err("type a file name".into()),
            Mode::Save if path.parent().is_some_and(Path::is_dir) => Ok(path),
            Mode::Save => Err(format!("{}: no such folder", path.display())),
            Mode::Folder if path.is_dir() => Ok(path),
            Mode::Folder => Err(format!("{} is not a folder", path.display())),
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
                            let r = ui.selectable_label(e.is_file && self.name == e.name, label);
                            if r.clicked() {
                                if e.is_file {
                                    self.name = e.name.clone();
                                } else {
                                    enter = Some(self.dir.join(&e.name));
                                }
                            }
                            if r.double_clicked() && e.is_file {
                                outcome = Outcome::Picked(self.dir.join(&e.name));
                            }
                        }
                        if self.entries.is_empty() {
                            ui.weak("(nothing here for this dialog)");
                        }
                    });
                ui.separator();
                if self.request.mode != Mode::Folder {
                    ui.horizontal(|ui| {
                        let label = ui.label("file name");
                        ui.text_edit_singleline(&mut self.name)
                            .labelled_by(label.id);
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
                    if ui.button(verb).clicked() {
                        match self.chosen() {
                            Ok(path) => outcome = Outcome::Picked(path),
                            Err(e) => self.error = Some(e),
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
        assert_eq!(b.chosen().unwrap(), dir.path().join("a.obj"));
        b.name = "missing.obj".into();
        assert!(b.chosen().unwrap_err().contains("missing.obj"));
    }
}
