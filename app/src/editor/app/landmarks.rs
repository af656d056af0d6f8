//! The guided landmark mode (docs/models.md §7a): the head's landmarks as labelled dots
//! on the 3D view, a list of every landmark, drag a dot over the surface to correct it,
//! pick a missing one and click on the head to place it, "Fit" writes the landmark file
//! beside the mesh and fits the template again.

use std::path::PathBuf;

use agesim_core::head::landmarks::{Landmarks, NAMES};
use agesim_core::project::LandmarkSource;
use serde_json::Value;

use super::EditorApp;
use crate::editor::files::IoResult;
use crate::editor::viewport::LandmarkOverlay;

/// The landmarks being edited, in the scene's coordinates (the mesh as shown: +Y up, +Z
/// forward), and the one a click places.
#[derive(Clone, Debug, Default)]
pub struct LandmarkMode {
    pub points: Landmarks,
    pub selected: Option<&'static str>,
    /// Whether a point moved since the mode opened or the last fit.
    pub edited: bool,
}

impl LandmarkMode {
    /// The dots the view draws.
    pub fn overlay(&self) -> LandmarkOverlay {
        LandmarkOverlay {
            points: NAMES
                .iter()
                .filter_map(|n| Some((*n, self.points.get(n)?)))
                .collect(),
            selected: self.selected,
        }
    }

    /// Takes a point dragged or placed on the head; a placed missing landmark selects
    /// the next missing one, so the list can be walked by clicking on the head.
    pub fn place(&mut self, name: &'static str, p: glam::Vec3) {
        let was_missing = self.points.get(name).is_none();
        if self.points.set(name, p).is_ok() {
            self.edited = true;
        }
        if was_missing {
            self.selected = NAMES
                .iter()
                .copied()
                .find(|n| self.points.get(n).is_none())
                .or(Some(name));
        }
    }
}

impl EditorApp {
    /// Opens the mode on the landmarks the last bake fitted with (the project's file or
    /// those found automatically), or closes it.
    pub fn toggle_landmark_mode(&mut self) {
        if self.landmark_mode.take().is_some() {
            return;
        }
        let snapshot = &self.session.snapshot;
        let points = snapshot.landmarks.as_deref().cloned().unwrap_or_default();
        let selected = NAMES.iter().copied().find(|n| points.get(n).is_none());
        self.landmark_mode = Some(LandmarkMode {
            points,
            selected,
            edited: false,
        });
        if self.doc.project.mesh.path.is_none() {
            self.info("The default head is the template: its landmarks are shown, not fitted");
        }
    }

    /// The landmark list: each name placed or missing, select one to place it; "Fit".
    pub(super) fn landmark_window(&mut self, ctx: &egui::Context) {
        let Some(mode) = &mut self.landmark_mode else {
            return;
        };
        let found = self.session.snapshot.landmarks_found;
        let (open, fit) = landmark_window(ctx, mode, found);
        if fit {
            self.fit_landmarks();
        }
        if !open {
            self.landmark_mode = None;
        }
    }

    /// Writes the edited landmarks (in the mesh file's coordinates) to
    /// `<mesh>.landmarks.json` beside the mesh (or the file the project names), on a file
    /// thread; the project then names it and the template is fitted again. A project that
    /// holds its landmarks itself (`mesh.landmarks` as points) gets the new points instead
    /// (one undo step), no file.
    fn fit_landmarks(&mut self) {
        let (Some(mode), Some(mesh)) = (&mut self.landmark_mode, &self.doc.project.mesh.path)
        else {
            self.error("Fitting needs a head of your own: import a head mesh first");
            return;
        };
        mode.edited = false;
        // Back from the scene's axes to the file's.
        let back = self.session.snapshot.file_from_scene;
        let mut file = Landmarks::default();
        for name in NAMES {
            if let Some(p) = mode.points.get(name) {
                let _ = file.set(name, back * p);
            }
        }
        let path = match &self.doc.project.mesh.landmarks {
            Some(LandmarkSource::Points(_)) => {
                let points: serde_json::Map<String, Value> = NAMES
                    .iter()
                    .filter_map(|n| {
                        let p = file.get(n)?;
                        Some(((*n).to_owned(), Value::from(p.to_array().to_vec())))
                    })
                    .collect();
                self.apply("mesh.landmarks", Value::Object(points), false);
                self.info("Fitting to the landmarks (kept in the project)");
                return;
            }
            Some(LandmarkSource::File(path)) => path.clone(),
            None => landmark_path_for(mesh),
        };
        self.io.spawn(move || IoResult::LandmarksSaved {
            result: write_landmarks(&path, &file).map(|()| path.clone()),
        });
    }

    /// The landmark file is written: the project names it (one undo step) and the next
    /// bake fits with it (read again if the project named it already).
    pub(super) fn landmarks_saved(&mut self, path: PathBuf) {
        if self.doc.project.mesh.landmark_file() == Some(path.as_path()) {
            self.file_changed(path.clone(), &path);
            self.submit(false, "fit to the landmarks");
        } else {
            self.apply(
                "mesh.landmarks",
                Value::from(path.display().to_string()),
                false,
            );
        }
        self.info(format!("Fitting to the landmarks of {}", path.display()));
    }

    /// Each frame: the view draws the dots and reports a dot moved or placed.
    pub(super) fn landmark_view_sync(&mut self) {
        let Some(viewport) = &mut self.viewport else {
            return;
        };
        if let (Some(mode), Some((name, p))) =
            (&mut self.landmark_mode, viewport.landmark_edit.take())
        {
            mode.place(name, p);
        }
        viewport.landmarks = self.landmark_mode.as_ref().map(LandmarkMode::overlay);
    }
}

/// `head.obj` → `head.landmarks.json` beside it.
fn landmark_path_for(mesh: &std::path::Path) -> PathBuf {
    let stem = mesh
        .file_stem()
        .map_or("head".into(), |s| s.to_string_lossy().into_owned());
    mesh.with_file_name(format!("{stem}.landmarks.json"))
}

fn write_landmarks(path: &std::path::Path, landmarks: &Landmarks) -> Result<(), String> {
    let text = landmarks.to_json_pretty();
    let set = agesim_core::output::export::OutputSet::new();
    set.stage(path, |w| std::io::Write::write_all(w, text.as_bytes()))
        .and_then(|()| set.commit())
        .map_err(|e| e.to_string())
}

/// The Landmarks window over the guided `mode` it edits (the landmark selected); `found`:
/// the landmarks were found automatically. Returns whether it stays open and whether Fit
/// was pressed.
fn landmark_window(ctx: &egui::Context, mode: &mut LandmarkMode, found: bool) -> (bool, bool) {
    let mut open = true;
    let mut fit = false;
    egui::Window::new("Landmarks")
        .open(&mut open)
        // Over the inspector, clear of the 3D view where the dots are.
        .anchor(egui::Align2::RIGHT_TOP, egui::vec2(-12.0, 60.0))
        .resizable(false)
        .show(ctx, |ui| {
            ui.label(if found && !mode.edited {
                "Found automatically: drag a dot to correct it."
            } else {
                "Drag a dot over the head to move it."
            });
            ui.label("Select a landmark, then click on the head to place it.");
            egui::Grid::new("landmark list")
                .striped(true)
                .show(ui, |ui| {
                    for name in NAMES {
                        let placed = mode.points.get(name).is_some();
                        let chosen = mode.selected == Some(name);
                        if ui.selectable_label(chosen, name).clicked() {
                            mode.selected = Some(name);
                        }
                        ui.label(if placed { "placed" } else { "missing" });
                        ui.end_row();
                    }
                });
            let placed = mode.points.len();
            ui.horizontal(|ui| {
                let enough = placed >= agesim_core::head::fit::MIN_LANDMARKS;
                fit = ui
                    .add_enabled(enough, egui::Button::new("Fit"))
                    .on_hover_text(
                        "write the landmark file beside the mesh and fit the template again",
                    )
                    .clicked();
                ui.label(format!("{placed} of {} placed", NAMES.len()));
            });
        });
    (open, fit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placing_a_missing_landmark_selects_the_next_missing_one() {
        let mut mode = LandmarkMode::default();
        mode.place("glabella", glam::Vec3::ONE);
        assert_eq!(mode.selected, Some("nasion"));
        assert!(mode.edited);
        // Moving a placed one keeps the selection.
        mode.selected = Some("pronasale");
        mode.place("glabella", glam::Vec3::ZERO);
        assert_eq!(mode.selected, Some("pronasale"));
        assert_eq!(
            landmark_path_for(std::path::Path::new("/a/head.obj")),
            PathBuf::from("/a/head.landmarks.json")
        );
    }
}
