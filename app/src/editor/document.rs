//! The document an artist edits: the project, the wrinkle files as edited, the undo
//! history and the revisions that say whether it is saved.

use std::path::PathBuf;

use agesim_core::project::Project;
use agesim_core::scene::{FileVersions, WrinkleSource};

use super::history::History;

pub(super) struct Document {
    pub(super) project: Project,
    /// The last project the worker accepted: restored when an edit is refused.
    pub(super) last_good: Project,
    /// The wrinkle files as edited here (`None` until the first fibre edit).
    pub(super) wrinkles: Option<Vec<WrinkleSource>>,
    /// The versions of the input files reloaded from disk ([`FileVersions`]); the next
    /// version handed out is `next_file_version` (never reused, so a version always
    /// names one content).
    pub(super) files: FileVersions,
    pub(super) next_file_version: u64,
    pub(super) history: History,
    /// The document's revision, the newest handed out, the saved one and the one being
    /// saved (see [`History`]).
    pub(super) revision: u64,
    pub(super) next_revision: u64,
    pub(super) saved_revision: u64,
    pub(super) saving_revision: Option<u64>,
    /// The project file of the document.
    pub(super) path: Option<PathBuf>,
}

impl Document {
    /// The project file's name, or `untitled` when it has none yet.
    pub(super) fn file_name(&self, untitled: &str) -> String {
        self.path
            .as_ref()
            .and_then(|p| p.file_name())
            .map_or_else(|| untitled.to_owned(), |n| n.to_string_lossy().into_owned())
    }

    /// `project`, unmodified, from `path` (`None`: not saved yet).
    pub(super) fn new(project: Project, path: Option<PathBuf>) -> Self {
        Self {
            last_good: project.clone(),
            project,
            wrinkles: None,
            files: FileVersions::new(),
            next_file_version: 0,
            history: History::default(),
            revision: 0,
            next_revision: 0,
            saved_revision: 0,
            saving_revision: None,
            path,
        }
    }
}
