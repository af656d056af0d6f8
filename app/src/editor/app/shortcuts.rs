//! The keyboard shortcuts.

use egui::{Key, KeyboardShortcut, Modifiers};

use super::Pending;
use super::command::Command;
use crate::editor::files::Purpose;

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

/// The commands of the shortcuts pressed this frame (each consumed).
pub(super) fn shortcut_commands(ctx: &egui::Context) -> Vec<Command> {
    let cmd = Modifiers::COMMAND;
    let shift = Modifiers::COMMAND | Modifiers::SHIFT;
    let pressed =
        |m: Modifiers, k: Key| ctx.input_mut(|i| i.consume_shortcut(&KeyboardShortcut::new(m, k)));
    let mut out = Vec::new();
    // Shift variants first: a plain shortcut also matches with Shift held.
    if pressed(shift, Key::Z) || pressed(cmd, Key::Y) {
        out.push(Command::Redo);
    } else if pressed(cmd, Key::Z) {
        out.push(Command::Undo);
    }
    if pressed(shift, Key::S) {
        out.push(Command::SaveAs);
    } else if pressed(cmd, Key::S) {
        out.push(Command::Save);
    }
    if pressed(cmd, Key::N) {
        out.push(Command::Guard(Pending::New));
    }
    if pressed(cmd, Key::O) {
        out.push(Command::Guard(Pending::Open));
    }
    if pressed(cmd, Key::I) {
        out.push(Command::Ask(Purpose::ImportMesh, None));
    }
    if pressed(cmd, Key::E) {
        out.push(Command::ShowExport);
    }
    if pressed(Modifiers::NONE, Key::F1) {
        out.push(Command::ToggleHelp);
    }
    out
}
