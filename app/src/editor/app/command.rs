//! The editor's commands: what a menu item, a shortcut or a panel's button asks for. The
//! panels return them and the app runs each in one place ([`EditorApp::run`]), so a panel
//! needs only the state it shows.

use std::path::PathBuf;

use agesim_core::project::Project;

use super::{EditorApp, Pending};
use crate::editor::files::{IoResult, Purpose};

/// One command.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Command {
    /// New, open, open a recent project: after "save the changes?" when modified.
    Guard(Pending),
    Save,
    SaveAs,
    Undo,
    Redo,
    /// A file dialog for `Purpose`, with a suggested file name.
    Ask(Purpose, Option<String>),
    AddFibre,
    DeleteFibre,
    /// A shipped preset by name, or the user's own from its file.
    ShippedPreset(&'static str),
    UserPreset(PathBuf),
    ShowExport,
    ShowSavePreset,
    ToggleHelp,
    ShowHelp,
    ShowMessages,
    ShowAbout,
    ToggleLandmarks,
    FrameHead,
    Quit,
}

impl EditorApp {
    /// Runs `command`.
    pub(super) fn run(&mut self, command: Command, ctx: &egui::Context) {
        match command {
            Command::Guard(pending) => self.guard(pending),
            Command::Save => self.save(),
            Command::SaveAs => self.save_as(),
            Command::Undo => self.undo(),
            Command::Redo => self.redo(),
            Command::Ask(purpose, name) => self.ask(purpose, name),
            Command::AddFibre => self.add_fibre(),
            Command::DeleteFibre => self.delete_fibre(),
            Command::ShippedPreset(name) => self.apply_shipped_preset(name),
            Command::UserPreset(path) => {
                let name = user_preset_name(&path);
                self.io.spawn(move || IoResult::PresetLoaded {
                    result: Project::load(&path).map_err(|e| e.to_string()),
                    name,
                });
            }
            Command::ShowExport => self.windows.export = true,
            Command::ShowSavePreset => self.windows.save_preset = true,
            Command::ToggleHelp => self.windows.help = !self.windows.help,
            Command::ShowHelp => self.windows.help = true,
            Command::ShowMessages => self.windows.messages = true,
            Command::ShowAbout => self.windows.about = true,
            Command::ToggleLandmarks => self.toggle_landmark_mode(),
            Command::FrameHead => {
                if let Some(v) = &mut self.viewport {
                    v.reset(&mut self.doc.project);
                }
            }
            Command::Quit => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
        }
    }
}

/// A user preset's name: its file name without `.agesim.json`.
pub(super) fn user_preset_name(path: &std::path::Path) -> String {
    path.file_name()
        .map(|n| {
            n.to_string_lossy()
                .trim_end_matches(".agesim.json")
                .to_owned()
        })
        .unwrap_or_default()
}
