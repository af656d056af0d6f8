//! Files the document names, watched for changes on disk: a thread looks at their size and
//! modification time a few times a second and reports a file once it has changed and then
//! stayed the same for one look (a file being written is read once it is complete). Its
//! state when it starts being watched is the baseline (one `stat` on the UI thread, when
//! the list changes). No file is read here, only looked at.

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
    /// The watched files with their state when they were added.
    paths: Arc<Mutex<Vec<(PathBuf, Stamp)>>>,
    changed: Receiver<PathBuf>,
}

impl Watcher {
    /// Starts the thread; `wake` asks the UI for a repaint when a file changed.
    pub fn new(wake: impl Fn() + Send + 'static) -> Self {
        let paths: Arc<Mutex<Vec<(PathBuf, Stamp)>>> = Arc::default();
        let (tx, changed) = channel();
        let watched = Arc::downgrade(&paths);
        std::thread::Builder::new()
            .name("agesim-watch".into())
            .spawn(move || {
                // Per path: (what was reported or the baseline, what the last look saw).
                let mut seen: HashMap<PathBuf, (Stamp, Stamp)> = HashMap::new();
                loop {
                    std::thread::sleep(PERIOD);
                    // The editor is gone: so is the thread.
                    let Some(paths) = watched.upgrade() else {
                        return;
                    };
                    let list = paths.lock().map(|p| p.clone()).unwrap_or_default();
                    drop(paths);
                    seen.retain(|p, _| list.iter().any(|(q, _)| q == p));
                    for (path, baseline) in list {
                        let now = stamp(&path);
                        match seen.get_mut(&path) {
                            None => {
                                seen.insert(path, (baseline, now));
                            }
                            Some((reported, last)) => {
                                // Changed since the report, and the same as a look ago.
                                if *reported != now && now == *last && now.is_some() {
                                    *reported = now;
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

    /// Watches exactly `paths` from now on (a path already watched keeps its state; a new
    /// one's state now is its baseline).
    pub fn set(&self, paths: &[PathBuf]) {
        if let Ok(mut p) = self.paths.lock()
            && (p.len() != paths.len() || p.iter().zip(paths).any(|((a, _), b)| a != b))
        {
            let old = std::mem::take(&mut *p);
            *p = paths
                .iter()
                .map(|path| match old.iter().find(|(q, _)| q == path) {
                    Some(kept) => kept.clone(),
                    None => (path.clone(), stamp(path)),
                })
                .collect();
        }
    }

    /// The files that changed since the last call.
    pub fn poll(&self) -> Vec<PathBuf> {
        self.changed.try_iter().collect()
    }
}
