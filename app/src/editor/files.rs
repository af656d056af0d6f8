//! Files: the native dialogs behind [`Dialogs`] (tests script them instead), and every
//! read and write on a thread of its own, its result coming back as an [`IoResult`] that
//! the UI thread applies. The UI never waits on a dialog or a disk.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex};

use agesim_core::defaults;
use agesim_core::layers::wrinkles::wrinkle_file::{self, WrinkleFile};
use agesim_core::project::Project;
use agesim_core::scene::WrinkleSource;

/// What a dialog was opened for.
#[derive(Clone, Debug, PartialEq)]
pub enum Purpose {
    OpenProject,
    SaveProject,
    ImportMesh,
    /// Replace the wrinkle files with one (`add: false`) or add one to them.
    LoadWrinkles {
        add: bool,
    },
    /// Save the wrinkle file at this index of the edited files.
    SaveWrinkles(usize),
    /// A grey-scale image for this project field (`large.mask`, `hair.outer_mask`, …).
    Image(&'static str),
    /// The folder the Export window writes into.
    ExportFolder,
}

impl Purpose {
    /// The dialog's title, filters and mode.
    pub fn request(&self, file_name: Option<String>) -> DialogRequest {
        const PROJECT: (&str, &[&str]) = ("agesim project", &["json"]);
        const IMAGES: (&str, &[&str]) = ("Images", IMAGE_EXTENSIONS);
        let (title, filters, mode): (String, Vec<(&str, &[&str])>, Mode) = match self {
            Self::OpenProject => ("Open project".into(), vec![PROJECT], Mode::Open),
            Self::SaveProject => ("Save project as".into(), vec![PROJECT], Mode::Save),
            Self::ImportMesh => (
                "Import head mesh".into(),
                vec![("Meshes", &["obj", "gltf", "glb"])],
                Mode::Open,
            ),
            Self::LoadWrinkles { add: false } => (
                "Load wrinkle file".into(),
                vec![("Wrinkle files", &["wrk", "txt"])],
                Mode::Open,
            ),
            Self::LoadWrinkles { add: true } => (
                "Add wrinkle file".into(),
                vec![("Wrinkle files", &["wrk", "txt"])],
                Mode::Open,
            ),
            Self::SaveWrinkles(_) => (
                "Save wrinkle file as".into(),
                vec![("Wrinkle files", &["wrk"])],
                Mode::Save,
            ),
            Self::Image(field) => (format!("Load image for {field}"), vec![IMAGES], Mode::Open),
            Self::ExportFolder => ("Export into folder".into(), Vec::new(), Mode::Folder),
        };
        DialogRequest {
            title,
            filters: filters
                .into_iter()
                .map(|(n, e)| (n.to_owned(), e.iter().map(|s| (*s).to_owned()).collect()))
                .collect(),
            mode,
            file_name,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Open,
    Save,
    Folder,
}

/// One dialog to show.
#[derive(Clone, Debug)]
pub struct DialogRequest {
    pub title: String,
    /// (name, extensions without the dot).
    pub filters: Vec<(String, Vec<String>)>,
    pub mode: Mode,
    /// Suggested file name for a save dialog.
    pub file_name: Option<String>,
}

/// Shows a file dialog and blocks until the user picks a path (or cancels: `None`).
/// Called on a thread of its own, never on the UI thread.
pub trait Dialogs: Send + Sync + std::fmt::Debug {
    fn pick(&self, request: &DialogRequest) -> Option<PathBuf>;

    /// Whether a dialog can open at all; `Err` says what would make it possible (the
    /// editor then shows its own file browser).
    fn available(&self) -> Result<(), String> {
        Ok(())
    }
}

/// The platform's dialogs through `rfd` (the XDG portal on Linux, zenity without one).
#[derive(Debug, Default)]
pub struct NativeDialogs;

impl Dialogs for NativeDialogs {
    /// On Linux rfd needs the XDG desktop portal (over the D-Bus session bus) or
    /// zenity; without either its dialogs return at once, as if cancelled.
    fn available(&self) -> Result<(), String> {
        if !cfg!(target_os = "linux") {
            return Ok(());
        }
        let bus = std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some_and(|v| !v.is_empty());
        let zenity = std::env::var_os("PATH").is_some_and(|paths| {
            std::env::split_paths(&paths).any(|dir| dir.join("zenity").is_file())
        });
        if bus || zenity {
            Ok(())
        } else {
            Err(
                "no native file dialog here (no D-Bus session for the XDG desktop portal, no \
                 zenity): install xdg-desktop-portal-gtk or zenity to get it; meanwhile \
                 agesim's own file browser opens"
                    .into(),
            )
        }
    }

    fn pick(&self, r: &DialogRequest) -> Option<PathBuf> {
        let mut d = rfd::FileDialog::new().set_title(&r.title);
        for (name, ext) in &r.filters {
            d = d.add_filter(name, ext);
        }
        if let Some(name) = &r.file_name {
            d = d.set_file_name(name);
        }
        match r.mode {
            Mode::Open => d.pick_file(),
            Mode::Save => d.save_file(),
            Mode::Folder => d.pick_folder(),
        }
    }
}

/// Dialogs answered from a queue, for tests: each `pick` takes the next answer (`None`
/// when the queue is empty, like a cancelled dialog) and records the title it was asked.
#[derive(Debug, Default)]
pub struct ScriptedDialogs {
    answers: Mutex<VecDeque<Option<PathBuf>>>,
    asked: Mutex<Vec<String>>,
    /// Behave as a desktop without any native dialog ([`Dialogs::available`]).
    unavailable: bool,
}

impl ScriptedDialogs {
    /// Dialogs of a desktop that has none: the editor must use its own file browser.
    pub fn unavailable() -> Self {
        Self {
            unavailable: true,
            ..Self::default()
        }
    }

    pub fn answer(&self, path: Option<PathBuf>) {
        lock(&self.answers).push_back(path);
    }

    /// The titles of the dialogs shown so far.
    pub fn asked(&self) -> Vec<String> {
        lock(&self.asked).clone()
    }
}

impl Dialogs for ScriptedDialogs {
    fn pick(&self, request: &DialogRequest) -> Option<PathBuf> {
        lock(&self.asked).push(request.title.clone());
        lock(&self.answers).pop_front().flatten()
    }

    fn available(&self) -> Result<(), String> {
        if self.unavailable {
            Err("no native file dialog (scripted)".into())
        } else {
            Ok(())
        }
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// What a file thread brings back.
#[derive(Debug)]
pub enum IoResult {
    /// A dialog ended with a path; the UI decides (the worker loads meshes and images).
    Picked(Purpose, PathBuf),
    /// A dialog was cancelled.
    Cancelled,
    ProjectLoaded {
        path: PathBuf,
        result: Result<Project, String>,
    },
    WrinklesLoaded {
        path: PathBuf,
        add: bool,
        result: Result<WrinkleFile, String>,
    },
    /// A wrinkle file of the document changed on disk and was read again.
    WrinklesReloaded {
        path: PathBuf,
        result: Result<WrinkleFile, String>,
    },
    /// A project was saved; `project` is what the file now says (its wrinkle files may
    /// have been written beside it), `wrinkles` the edited files with their new paths.
    ProjectSaved {
        path: PathBuf,
        result: Result<(Project, Option<Vec<WrinkleSource>>), String>,
    },
    Saved {
        what: String,
        result: Result<PathBuf, String>,
    },
    /// The user's presets folder listed.
    UserPresets(Vec<PathBuf>),
    PresetSaved {
        path: PathBuf,
        result: Result<(), String>,
    },
    PresetLoaded {
        name: String,
        result: Result<Project, String>,
    },
    /// The session was written to the recovery folder (at this revision), or why not.
    Autosaved {
        revision: u64,
        result: Result<(), String>,
    },
    /// The landmark mode's file was written (its path), or why not.
    LandmarksSaved { result: Result<PathBuf, String> },
}

/// The file threads' mailbox.
pub struct Io {
    tx: Sender<IoResult>,
    rx: Receiver<IoResult>,
    wake: Arc<dyn Fn() + Send + Sync>,
    /// Tasks started and not yet polled back.
    pending: usize,
}

impl Io {
    pub fn new(wake: impl Fn() + Send + Sync + 'static) -> Self {
        let (tx, rx) = channel();
        Self {
            tx,
            rx,
            wake: Arc::new(wake),
            pending: 0,
        }
    }

    /// Whether a dialog or file task is still running.
    pub fn busy(&self) -> bool {
        self.pending > 0
    }

    /// Runs `task` on a thread of its own.
    pub fn spawn(&mut self, task: impl FnOnce() -> IoResult + Send + 'static) {
        let tx = self.tx.clone();
        let wake = self.wake.clone();
        self.pending += 1;
        std::thread::spawn(move || {
            let _ = tx.send(task());
            wake();
        });
    }

    /// Shows the dialog for `purpose`, then loads what it picked when that is a file the
    /// UI applies directly (a project, a wrinkle file).
    pub fn ask(&mut self, dialogs: &Arc<dyn Dialogs>, purpose: Purpose, file_name: Option<String>) {
        let dialogs = dialogs.clone();
        self.spawn(move || match dialogs.pick(&purpose.request(file_name)) {
            Some(path) => after_pick(purpose, path),
            None => IoResult::Cancelled,
        });
    }

    /// What [`Io::ask`] does once a path is picked, for a path picked elsewhere (the
    /// editor's own file browser).
    pub fn picked(&mut self, purpose: Purpose, path: PathBuf) {
        self.spawn(move || after_pick(purpose, path));
    }

    pub fn poll(&mut self) -> Vec<IoResult> {
        let results: Vec<IoResult> = self.rx.try_iter().collect();
        self.pending = self.pending.saturating_sub(results.len());
        results
    }

    /// Waits (at most `timeout`) for the first result `wanted` picks, and returns it with
    /// the results that came before it. Only for the exit, where a write still running
    /// must finish before the folder it writes is removed: the other results are
    /// dropped (a failed save's error is not shown), and a task that panicked sends
    /// nothing, so the wait runs its full time.
    pub fn wait_for(
        &mut self,
        timeout: std::time::Duration,
        wanted: impl Fn(&IoResult) -> bool,
    ) -> Vec<IoResult> {
        let until = std::time::Instant::now() + timeout;
        let mut results = Vec::new();
        while let Some(left) = until.checked_duration_since(std::time::Instant::now()) {
            let Ok(r) = self.rx.recv_timeout(left) else {
                break;
            };
            self.pending = self.pending.saturating_sub(1);
            let done = wanted(&r);
            results.push(r);
            if done {
                break;
            }
        }
        results
    }
}

/// A picked path: the files the UI applies directly are loaded here (a project, a wrinkle
/// file); the others go back as they are.
fn after_pick(purpose: Purpose, path: PathBuf) -> IoResult {
    match purpose {
        Purpose::OpenProject => load_project(path),
        Purpose::LoadWrinkles { add } => load_wrinkles(path, add),
        other => IoResult::Picked(other, path),
    }
}

pub fn load_project(path: PathBuf) -> IoResult {
    let result = Project::load(&path).map_err(|e| e.to_string());
    IoResult::ProjectLoaded { path, result }
}

pub fn load_wrinkles(path: PathBuf, add: bool) -> IoResult {
    let result = wrinkle_file::load(&path).map_err(|e| e.to_string());
    IoResult::WrinklesLoaded { path, add, result }
}

/// What a dropped or opened path is, by its name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    Project,
    Mesh,
    Wrinkles,
    Image,
}

/// The pictures the editor opens (colour and normal maps, masks): what the `image`
/// crate's decoders read (`agesim_core::maps::mask::decode_image`).
pub const IMAGE_EXTENSIONS: &[&str] = &["png", "jpg", "jpeg", "tif", "tiff", "bmp", "tga", "exr"];

pub fn kind_of(path: &Path) -> Option<FileKind> {
    let name = path.file_name()?.to_string_lossy().to_lowercase();
    let ext = name.rsplit('.').next().unwrap_or_default();
    Some(match ext {
        "json" => FileKind::Project,
        "obj" | "gltf" | "glb" => FileKind::Mesh,
        "wrk" | "txt" => FileKind::Wrinkles,
        e if IMAGE_EXTENSIONS.contains(&e) => FileKind::Image,
        _ => return None,
    })
}

/// Saves `project` to `path`. Edited wrinkle files are written beside it as
/// `STEM-NAME.wrk` (never over the files they were loaded from) and the project points
/// at them; when those were the built-in files, the built-in mask that goes with them is
/// written beside too, so the saved project bakes exactly what the editor shows. The
/// landmarks `found` automatically for its head (the mesh file's coordinates) are written
/// beside it as `STEM-landmarks.json` and named by the project: reopening it fits from
/// them, without searching again.
pub fn save_project(
    path: &Path,
    project: &Project,
    wrinkles: Option<&[WrinkleSource]>,
    found: Option<&agesim_core::head::landmarks::Landmarks>,
) -> Result<(Project, Option<Vec<WrinkleSource>>), String> {
    let mut project = project.clone();
    let dir = path.parent().unwrap_or(Path::new("")).to_owned();
    let stem = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = stem
        .strip_suffix(".agesim.json")
        .or_else(|| stem.strip_suffix(".json"))
        .unwrap_or(&stem)
        .to_owned();
    // One set: the wrinkle files, the mask and the project are staged, then put in place
    // all or none (a failure or a kill leaves the previous set whole).
    let set = agesim_core::output::export::OutputSet::new();
    let mut saved = None;
    if let Some(wrinkles) = wrinkles {
        let builtin = project.large.wrinkles.is_empty();
        let mut out = Vec::new();
        let mut paths = Vec::new();
        let mut used: Vec<String> = Vec::new();
        for w in wrinkles {
            let base = Path::new(&w.name)
                .file_stem()
                .map_or_else(|| "wrinkles".into(), |s| s.to_string_lossy().into_owned());
            // Two files of one name (from different folders) get their own copies.
            let mut name = base.clone();
            let mut k = 2;
            while used.contains(&name) {
                name = format!("{base}-{k}");
                k += 1;
            }
            used.push(name.clone());
            let target = dir.join(format!("{stem}-{name}.wrk"));
            let text = wrinkle_file::write(&w.file);
            set.stage(&target, |out| {
                std::io::Write::write_all(out, text.as_bytes())
            })
            .map_err(|e| e.to_string())?;
            paths.push(target.clone());
            out.push(WrinkleSource {
                name: target.display().to_string(),
                path: Some(target),
                file: w.file.clone(),
            });
        }
        if builtin && project.large.mask.is_none() {
            let (_, bytes) = defaults::WRINKLE_MASK;
            let target = dir.join(format!("{stem}-wrinkle-mask.png"));
            set.stage(&target, |w| std::io::Write::write_all(w, bytes))
                .map_err(|e| e.to_string())?;
            project.large.mask = Some(target);
        }
        project.large.wrinkles = paths;
        saved = Some(out);
    }
    if let Some(found) = found
        && project.mesh.path.is_some()
        && project.mesh.landmarks.is_none()
    {
        let target = dir.join(format!("{stem}-landmarks.json"));
        let text = found.to_json_pretty();
        set.stage(&target, |w| std::io::Write::write_all(w, text.as_bytes()))
            .map_err(|e| e.to_string())?;
        project.mesh.landmarks = Some(target.into());
    }
    let text = project.file_text(path);
    set.stage(path, |w| std::io::Write::write_all(w, text.as_bytes()))
        .map_err(|e| e.to_string())?;
    set.commit().map_err(|e| e.to_string())?;
    Ok((project, saved))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn two_wrinkle_files_of_one_name_get_two_copies() {
        let dir = tempfile::tempdir().unwrap();
        let file = |x: f32| {
            wrinkle_file::parse(
                &format!("!\nma={x};0.5\nmb={};0.6\nn=3\n", x + 0.05),
                Path::new("forehead.wrk"),
            )
            .unwrap()
        };
        let sources: Vec<WrinkleSource> = ["a/forehead.wrk", "b/forehead.wrk"]
            .iter()
            .zip([0.3, 0.6])
            .map(|(name, x)| WrinkleSource {
                name: (*name).to_owned(),
                path: Some(PathBuf::from(name)),
                file: file(x),
            })
            .collect();
        let path = dir.path().join("p.agesim.json");
        let (project, saved) =
            save_project(&path, &Project::default(), Some(&sources), None).unwrap();
        let paths = &project.large.wrinkles;
        assert_eq!(paths.len(), 2);
        assert_ne!(paths[0], paths[1]);
        for (p, s) in paths.iter().zip(&sources) {
            assert_eq!(&wrinkle_file::load(p).unwrap(), &s.file);
        }
        assert_eq!(saved.unwrap().len(), 2);
        // The built-in mask went beside it (the files were the built-in set's stand-ins).
        assert!(project.large.mask.unwrap().is_file());
    }

    /// Landmarks found automatically are saved beside a project with a head file and
    /// named by it (reopening fits from them); a project that names landmarks keeps them.
    #[test]
    fn found_landmarks_are_saved_beside_the_project() {
        let dir = tempfile::tempdir().unwrap();
        let mut found = agesim_core::head::landmarks::Landmarks::default();
        found
            .set("pronasale", glam::Vec3::new(0.0, 1.0, 2.0))
            .unwrap();
        let mut project = Project::default();
        project.mesh.path = Some(dir.path().join("head.obj"));
        let path = dir.path().join("p.agesim.json");
        let (saved, _) = save_project(&path, &project, None, Some(&found)).unwrap();
        let written = saved.mesh.landmark_file().unwrap().to_owned();
        assert_eq!(written, dir.path().join("p-landmarks.json"));
        assert_eq!(
            agesim_core::head::landmarks::Landmarks::load(&written).unwrap(),
            found
        );
        assert_eq!(
            Project::load(&path).unwrap().mesh.landmark_file(),
            Some(written.as_path())
        );
        // Named landmarks are the artist's: not replaced.
        project.mesh.landmarks = Some(dir.path().join("mine.json").into());
        let (saved, _) = save_project(&path, &project, None, Some(&found)).unwrap();
        assert_eq!(
            saved.mesh.landmark_file(),
            Some(dir.path().join("mine.json").as_path())
        );
    }

    /// A save is one set: when the project file cannot be put in place (here a folder
    /// stands where it goes), the wrinkle files and the mask beside it are not written
    /// either, and the files of an earlier save stay as they were.
    #[test]
    fn a_save_that_fails_writes_none_of_its_files() {
        let dir = tempfile::tempdir().unwrap();
        let source = WrinkleSource {
            name: "forehead.wrk".into(),
            path: None,
            file: wrinkle_file::parse("!\nma=0.3;0.5\nmb=0.35;0.6\nn=3\n", Path::new("f.wrk"))
                .unwrap(),
        };
        let good = dir.path().join("p.agesim.json");
        save_project(
            &good,
            &Project::default(),
            Some(std::slice::from_ref(&source)),
            None,
        )
        .unwrap();
        let before: Vec<(PathBuf, Vec<u8>)> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| {
                let p = e.unwrap().path();
                let bytes = std::fs::read(&p).unwrap();
                (p, bytes)
            })
            .collect();
        // The same names, a changed fibre, and a folder where the project file goes.
        let bad = dir.path().join("q.agesim.json");
        std::fs::create_dir(&bad).unwrap();
        let e = save_project(&bad, &Project::default(), Some(&[source]), None).unwrap_err();
        assert!(e.contains("q.agesim.json"), "{e}");
        for (p, bytes) in &before {
            assert_eq!(&std::fs::read(p).unwrap(), bytes, "{}", p.display());
        }
        let names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert!(
            !names.iter().any(|n| n.starts_with("q-")),
            "files of the failed save: {names:?}"
        );
    }
}
