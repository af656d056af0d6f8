//! Files the document names, watched for changes on disk: a thread looks at their size and
//! modification time a few times a second and reports a file once it has changed and then
//! stayed the same for one look (a file being written is read once it is complete). A
//! file is also reported once when it starts being watched (it may have changed since it
//! was read; the reader compares contents). No file is read here, only looked at; the UI
//! thread never waits on it.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, SystemTime};

/// How often the files are looked at.
const PERIOD: Duration = Duration::from_millis(250);

/// A file's state: its length and modification time (`None`: missing).
type Stamp = Option<(u64, SystemTime)>;

fn stamp(path: &PathBuf) -> Stamp {
    let m = std::fs::metadata(path).ok()?;
    Some((m.len(), m.modified().ok()?))
}

/// The watching thread's handle.
pub struct Watcher {
    paths: Arc<Mutex<Vec<PathBuf>>>,
    changed: Receiver<PathBuf>,
}

impl Watcher {
    /// Starts the thread; `wake` asks the UI for a repaint when a file changed.
    pub fn new(wake: impl Fn() + Send + 'static) -> Self {
        let paths: Arc<Mutex<Vec<PathBuf>>> = Arc::default();
        let (tx, changed) = channel();
        let watched = Arc::downgrade(&paths);
        std::thread::Builder::new()
            .name("agesim-watch".into())
            .spawn(move || {
                // Per path: (what was reported, none yet: `None`; what the last look saw).
                let mut seen: HashMap<PathBuf, (Option<Stamp>, Stamp)> = HashMap::new();
                loop {
                    std::thread::sleep(PERIOD);
                    // The editor is gone: so is the thread.
                    let Some(paths) = watched.upgrade() else {
                        return;
                    };
                    let list = paths.lock().map(|p| p.clone()).unwrap_or_default();
                    drop(paths);
                    seen.retain(|p, _| list.contains(p));
                    for path in list {
                        let now = stamp(&path);
                        match seen.get_mut(&path) {
                            None => {
                                seen.insert(path, (None, now));
                            }
                            Some((reported, last)) => {
                                // Changed since the report, and the same as a look ago.
                                if *reported != Some(now) && now == *last && now.is_some() {
                                    *reported = Some(now);
                                    if tx.send(path.clone()).is_err() {
                                        return;
                                    }
                                    wake();
                                }
                                *last = now;
                            }
                        }
                    }
                }
            })
            .ok();
        Self { paths, changed }
    }

    /// Watches exactly `paths` from now on (a path already watched keeps its state).
    pub fn set(&self, paths: &[PathBuf]) {
        if let Ok(mut p) = self.paths.lock()
            && *p != paths
        {
            *p = paths.to_vec();
        }
    }

    /// The files that changed since the last call.
    pub fn poll(&self) -> Vec<PathBuf> {
        self.changed.try_iter().collect()
    }
}
