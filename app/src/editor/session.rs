//! The bake session of the document: the worker that turns every edit into maps, the
//! last snapshot it sent back, and what the status line says of it.

use super::worker::{Snapshot, Worker};

pub(super) struct Session {
    pub(super) worker: Worker,
    /// The last finished bake (or a running job's first look at a new head).
    pub(super) snapshot: Snapshot,
    /// What was shown before a running job's first look (a dense head shown before its
    /// bake ends): back on show if the job fails, dropped when a job ends well.
    pub(super) before_first_look: Option<Snapshot>,
    /// The newest job that reported.
    pub(super) reported: u64,
    pub(super) last_bake_ms: f64,
    pub(super) last_what: String,
    /// An age change waits for the worker (see [`super::EditorApp::set_age`]).
    pub(super) age_pending: bool,
    /// A head was imported: the bakes say how its units were decided until one has.
    pub(super) measure_mesh: bool,
    /// Input files changed on disk: the bakes read them again until one has.
    pub(super) reload: Vec<std::path::PathBuf>,
}

impl Session {
    /// Starts the worker; `wake` asks the UI for a repaint when a bake reports.
    pub(super) fn new(wake: impl Fn() + Send + 'static) -> Self {
        Self {
            worker: Worker::spawn(wake),
            snapshot: Snapshot::default(),
            before_first_look: None,
            reported: 0,
            last_bake_ms: 0.0,
            last_what: String::new(),
            age_pending: false,
            measure_mesh: false,
            reload: Vec::new(),
        }
    }

    /// Whether the newest request has not been baked yet.
    pub(super) fn busy(&self) -> bool {
        self.worker.busy(self.reported)
    }
}
