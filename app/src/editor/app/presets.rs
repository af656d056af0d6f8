//! Presets: the shipped ones and the user's own (saved in the settings folder).

use std::path::PathBuf;

use agesim_core::defaults;
use agesim_core::project::Project;

use super::EditorApp;
use crate::editor::files::IoResult;

impl EditorApp {
    /// Where the user's presets live.
    pub(super) fn presets_dir(&self) -> Option<PathBuf> {
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
        let p = &mut self.doc.project;
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

    pub(super) fn apply_shipped_preset(&mut self, name: &str) {
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
    pub(super) fn save_user_preset(&mut self) {
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
        let project = self.doc.project.clone();
        let path = dir.join(format!("{name}.agesim.json"));
        self.io.spawn(move || {
            let result = std::fs::create_dir_all(&dir)
                .map_err(|e| format!("{}: {e}", dir.display()))
                .and_then(|()| project.save(&path).map_err(|e| e.to_string()));
            IoResult::PresetSaved { path, result }
        });
    }
}
