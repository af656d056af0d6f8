//! The inputs a project names, changed from the editor: importing a mesh, loading masks
//! and wrinkle files (by dialog, by a path field's button, by drag-and-drop), and the
//! results of the file threads.

use std::path::{Path, PathBuf};

use agesim_core::scene::WrinkleSource;
use serde_json::Value;

use super::{EditorApp, Pending};
use crate::editor::fields_ui::Pick;
use crate::editor::files::{self, FileKind, IoResult, Purpose};

impl EditorApp {
    /// The head mesh from `path` (OBJ, glTF, GLB); the worker loads it, and an error
    /// puts the previous mesh back.
    pub fn import_mesh(&mut self, path: PathBuf) {
        self.record("import mesh", "import mesh", false);
        self.doc.project.mesh.path = Some(path.clone());
        // Its units are measured from the mesh (centimetres, millimetres, …); the bake
        // says how.
        self.doc.project.mesh.metres_per_unit = None;
        self.session.measure_mesh = true;
        self.submit(false, &format!("import {}", path.display()));
    }

    /// A grey-scale image into a project path field.
    pub(super) fn load_image(&mut self, field: &'static str, path: PathBuf) {
        self.apply(field, Value::from(path.display().to_string()), false);
    }

    /// A parsed wrinkle file replaces the current ones (or is added to them).
    pub(super) fn wrinkles_loaded(
        &mut self,
        path: PathBuf,
        add: bool,
        file: agesim_core::layers::wrinkles::wrinkle_file::WrinkleFile,
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
            if !self.doc.project.large.wrinkles.is_empty() {
                self.doc.project.large.wrinkles.push(path.clone());
            }
            // With the built-in files the list stays empty (they have no path), so the
            // edited set carries them and the new one.
            self.doc.wrinkles = Some(all);
        } else {
            self.doc.project.large.wrinkles = vec![path.clone()];
            self.doc.wrinkles = Some(vec![source]);
        }
        self.doc.project.large.enabled = true;
        self.persisted.map_view.selected = None;
        self.submit(false, "wrinkle file");
        self.info(format!("Loaded {} ({fibres} fibres)", path.display()));
    }

    /// Watches the files the document names. A wrinkle file that changed on disk is read
    /// again on a file thread ([`IoResult::WrinklesReloaded`]); another input (the mesh,
    /// a mask, the tile, the landmarks, the colour and normal maps) gets a new version
    /// (one undo step) and is read again by the next bake.
    pub(super) fn watch_files(&mut self) {
        let wrinkles: Vec<PathBuf> = self
            .wrinkles()
            .iter()
            .filter_map(|w| w.path.clone())
            .collect();
        let p = &self.doc.project;
        let landmark_file = p.mesh.landmark_file().map(Path::to_path_buf);
        let inputs = [
            &p.mesh.path,
            &landmark_file,
            &p.mesh.colour_map,
            &p.mesh.normal_map,
            &p.large.mask,
            &p.hair.outer_mask,
            &p.hair.inner_mask,
            &p.fine.tile,
        ];
        let mut paths = wrinkles.clone();
        paths.extend(inputs.into_iter().flatten().cloned());
        // The pictures the mesh file names are read with it: a change to one is a change
        // to the mesh.
        let textures = self.session.snapshot.mesh_texture_files.clone();
        paths.extend(textures.iter().cloned());
        self.watcher.set(&paths);
        let mut rebake = false;
        let mesh = self.doc.project.mesh.path.clone();
        for path in self.watcher.poll() {
            if let Some(mesh) = mesh.as_ref().filter(|_| textures.contains(&path)) {
                self.file_changed(mesh.clone(), &path);
                rebake = true;
            } else if wrinkles.contains(&path) {
                self.io.spawn(move || IoResult::WrinklesReloaded {
                    result: agesim_core::layers::wrinkles::wrinkle_file::load(&path)
                        .map_err(|e| e.to_string()),
                    path,
                });
            } else {
                self.file_changed(path.clone(), &path);
                rebake = true;
            }
        }
        if rebake {
            self.submit(false, "reload");
        }
    }

    /// An input file changed on disk (or was written here): one undo step that gives the
    /// input `path` a new version, read by the next bake (`changed`: the file that did;
    /// for a picture the mesh file's material names, the input is the mesh).
    pub(super) fn file_changed(&mut self, path: PathBuf, changed: &Path) {
        let name = changed.file_name().map_or_else(
            || changed.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        self.record(&format!("reload {name}"), "reload file", false);
        self.doc.next_file_version += 1;
        self.doc
            .files
            .insert(path.clone(), self.doc.next_file_version);
        if !self.session.reload.contains(&path) {
            self.session.reload.push(path);
        }
    }

    /// A wrinkle file read again after a change on disk: its fibres replace the old ones
    /// (one undo step); unchanged content (our own save) changes nothing.
    pub(super) fn wrinkles_reloaded(
        &mut self,
        path: PathBuf,
        file: agesim_core::layers::wrinkles::wrinkle_file::WrinkleFile,
    ) {
        let name = path.display().to_string();
        self.notices.close_errors_about(&name);
        let mut all = self.wrinkles().to_vec();
        let mut changed = false;
        for w in all
            .iter_mut()
            .filter(|w| w.path.as_deref() == Some(path.as_path()))
        {
            if w.file != file {
                w.file = file.clone();
                changed = true;
            }
        }
        if !changed {
            return;
        }
        self.record("reload wrinkle file", "reload wrinkle file", false);
        self.doc.wrinkles = Some(all);
        self.persisted.map_view.selected = None;
        self.submit(false, "reload");
        self.info(format!("Reloaded {name} ({} fibres)", file.groups.len()));
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
                            result: agesim_core::layers::wrinkles::wrinkle_file::save(&source.file, &path)
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
                IoResult::WrinklesReloaded { path, result } => match result {
                    Ok(file) => self.wrinkles_reloaded(path, file),
                    Err(e) => self.error(format!(
                        "{e}\n(the fibres as they were are kept; the file is read again when it changes)"
                    )),
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
                        let unchanged = self.doc.saving_revision == Some(self.doc.revision);
                        if unchanged {
                            self.doc.project.large.wrinkles = project.large.wrinkles;
                            self.doc.project.large.mask = project.large.mask;
                            self.doc.project.mesh.landmarks = project.mesh.landmarks;
                            if wrinkles.is_some() {
                                self.doc.wrinkles = wrinkles;
                            }
                            self.doc.saved_revision = self.doc.revision;
                            self.clear_recovery();
                        }
                        self.doc.path = Some(path.clone());
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
                IoResult::Autosaved { revision, result } => self.autosaved(revision, result),
                IoResult::LandmarksSaved { result } => match result {
                    Ok(path) => self.landmarks_saved(path),
                    Err(e) => self.error(format!("The landmarks were not saved: {e}")),
                },
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
}
