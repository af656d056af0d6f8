//! Autosave and recovery in the editor (see `editor::recovery`): the session written on a
//! file thread at most every `--autosave-seconds` while there are unsaved changes, the
//! offer to restore a session left by a crash, and its removal on a clean exit or a save.

use super::EditorApp;
use crate::editor::files::IoResult;
use crate::editor::recovery::{self, Left};

/// Autosave's state.
#[derive(Debug, Default)]
pub struct Autosave {
    /// The recovery folder (`None`: autosave off and nothing to recover).
    pub folder: Option<std::path::PathBuf>,
    /// egui time of the last write started.
    pub last: f64,
    pub in_flight: bool,
    /// The revision the folder holds.
    pub written: Option<u64>,
    /// A session left by an editor that did not exit cleanly, offered back.
    pub offer: Option<Left>,
    /// The folder of the session restored, removed with this editor's own.
    pub restored_from: Option<std::path::PathBuf>,
}

impl EditorApp {
    /// At start: finds a session left behind; `--recover` restores it at once, else it is
    /// offered.
    pub(super) fn start_recovery(&mut self) {
        let folder = recovery::folder(self.options.data_dir.as_deref());
        // A benchmark or a screenshot shows the same thing on every machine: no session
        // of its own is kept, none is offered (a modal's backdrop costs a benchmark's
        // frame 25 ms on llvmpipe).
        let measuring = self.options.bench_ui || self.options.screenshot.is_some();
        let wanted = (self.options.autosave_seconds > 0.0 && !measuring) || self.options.recover;
        self.autosave.folder = folder.filter(|_| wanted);
        let Some(dir) = &self.autosave.folder else {
            return;
        };
        if let Some(left) = recovery::left_behind(dir) {
            if self.options.recover {
                self.restore_session(left);
            } else {
                self.autosave.offer = Some(left);
            }
        } else if self.options.recover {
            self.info("Nothing to recover");
        }
    }

    /// Each frame: writes the session when it changed and the interval has passed.
    pub(super) fn autosave_tick(&mut self) {
        let Some(dir) = self.autosave.folder.clone() else {
            return;
        };
        let every = self.options.autosave_seconds;
        if every <= 0.0
            || self.autosave.in_flight
            || self.autosave.offer.is_some()
            || !self.modified()
            || self.autosave.written == Some(self.doc.revision)
        {
            return;
        }
        if self.now - self.autosave.last < every {
            // Come back when it is due, even if nothing else draws a frame.
            self.ctx
                .request_repaint_after(std::time::Duration::from_secs_f64(
                    every - (self.now - self.autosave.last),
                ));
            return;
        }
        self.autosave.last = self.now;
        self.autosave.in_flight = true;
        let (project, wrinkles) = (self.doc.project.clone(), self.doc.wrinkles.clone());
        let original = self.doc.path.clone();
        let revision = self.doc.revision;
        let folder = recovery::own(&dir);
        let delay = self.options.autosave_delay;
        self.io.spawn(move || {
            std::thread::sleep(delay);
            IoResult::Autosaved {
                revision,
                result: recovery::write(
                    &folder,
                    &project,
                    wrinkles.as_deref(),
                    original.as_deref(),
                ),
            }
        });
    }

    /// The file thread wrote (or failed to write) the session.
    pub(super) fn autosaved(&mut self, revision: u64, result: Result<(), String>) {
        self.autosave.in_flight = false;
        match result {
            Ok(()) => self.autosave.written = Some(revision),
            Err(e) => self.error(format!("Autosave failed: {e}")),
        }
        // A save that finished meanwhile leaves nothing to recover.
        if !self.modified() {
            self.clear_recovery();
        }
    }

    /// Whether an autosave is being written on the file thread.
    pub fn autosaving(&self) -> bool {
        self.autosave.in_flight
    }

    /// A clean exit: nothing to recover. An autosave still being written would put the
    /// folder back after it is removed (or be cut off half-written by the exit), so it is
    /// waited for first.
    pub(super) fn exit_cleanly(&mut self) {
        if self.autosave.in_flight {
            let autosaved = |r: &IoResult| matches!(r, IoResult::Autosaved { .. });
            let waited = self
                .io
                .wait_for(std::time::Duration::from_secs(10), autosaved);
            if !waited.iter().any(autosaved) {
                // Still writing: removing the folder now could leave half of it, or the
                // write could put it back. It stays, offered back at the next start.
                eprintln!(
                    "agesim: the autosave being written at exit did not finish in 10 s; \
                     the recovery folder is kept"
                );
                return;
            }
        }
        self.autosave.in_flight = false;
        self.clear_recovery();
    }

    /// No unsaved work any more (a save, a clean exit): the folder goes.
    pub(super) fn clear_recovery(&mut self) {
        if self.autosave.in_flight || self.autosave.offer.is_some() {
            return;
        }
        if let Some(dir) = &self.autosave.folder {
            recovery::clear(&recovery::own(dir));
            self.autosave.written = None;
        }
        if let Some(left) = self.autosave.restored_from.take() {
            recovery::clear(&left);
        }
    }

    /// Takes a left session as the document: marked modified, undo starts from it, a
    /// save goes where the document was saved before.
    pub(super) fn restore_session(&mut self, left: Left) {
        match recovery::read(&left) {
            Ok((project, wrinkles)) => {
                // The left folder stays until the work is saved or the editor exits
                // cleanly: the restored project still reads its wrinkle files there.
                self.autosave.restored_from = left.session.parent().map(|p| p.to_owned());
                self.replace_document(project, left.original.clone(), "recover");
                self.doc.wrinkles = wrinkles;
                self.doc.saved_revision = self.doc.revision.wrapping_sub(1);
                self.submit(false, "recover");
                self.info(format!(
                    "Recovered the unsaved work of the last session{}",
                    left.original
                        .as_ref()
                        .map_or(String::new(), |p| format!(" ({})", p.display()))
                ));
                println!("recovered {}", left.session.display());
            }
            Err(e) => self.error(format!("The last session could not be recovered: {e}")),
        }
    }

    /// The offer to restore a session left by a crash.
    pub(super) fn recovery_window(&mut self, ctx: &egui::Context) {
        let Some(left) = self.autosave.offer.clone() else {
            return;
        };
        match recovery_modal(ctx, &left.session) {
            Some(true) => {
                self.autosave.offer = None;
                self.restore_session(left);
            }
            Some(false) => {
                self.autosave.offer = None;
                if let Some(folder) = left.session.parent() {
                    recovery::clear(folder);
                }
            }
            None => {}
        }
    }
}

/// "Recover unsaved work?" over the session file `session` left by a crash: `Some(true)` to
/// restore it, `Some(false)` to discard it, `None` while unanswered.
fn recovery_modal(ctx: &egui::Context, session: &std::path::Path) -> Option<bool> {
    let mut choice = None;
    egui::Modal::new(egui::Id::unique("recover")).show(ctx, |ui| {
        ui.heading("Recover unsaved work?");
        ui.label("agesim did not exit cleanly last time. Its unsaved work was kept:");
        ui.label(
            egui::RichText::new(session.display().to_string())
                .monospace()
                .small(),
        );
        ui.horizontal(|ui| {
            if ui.button("Restore").clicked() {
                choice = Some(true);
            }
            if ui.button("Discard").clicked() {
                choice = Some(false);
            }
        });
    });
    choice
}
