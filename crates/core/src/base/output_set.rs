//! Output sets: files written together, all or none, even when the process is killed.
//!
//! Every file of a set is first written to a hidden temporary beside its target and synced.
//! Then [`OutputSet::commit`] puts them in place:
//!
//! 1. a **commit journal** is written (atomically) beside the set's last file,
//!    `.<name>.agesim-commit`: each temporary, its target and where the old file is moved
//!    aside. From this point the set is committed: whatever happens, the new set wins;
//! 2. the old files are moved aside, the new ones renamed into place, in staging order;
//! 3. the old files and the journal are removed.
//!
//! A process killed in step 2 or 3 (SIGKILL, a power cut after the journal reached the
//! disk) leaves the journal; [`finish_interrupted_commit`] rolls it forward — every
//! temporary still there is renamed into place, the old files removed — so the files are the
//! new set, never a mix. It runs before every commit to the same set and when a project
//! is loaded ([`crate::project::Project::load`]). A process killed before the journal was
//! written leaves the old set whole, and only hidden temporaries, which the next commit
//! beside them removes (those of processes no longer running).
//!
//! A commit that fails in step 2 (a rename refused) turns its journal round to *back* and
//! restores the old files, so an interruption of that undo is also finished the same way
//! (back) by [`finish_interrupted_commit`].

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};

use crate::base::error::Error;

/// The temporary sibling of `path`: `.<name>.<pid>.<n>.tmp`, hidden and unique per call.
fn temp_path(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.{n}.tmp", std::process::id()))
}

/// Writes a file through `write` to a temporary name beside `path`, syncs it and renames
/// it into place. On any error the temporary file is removed and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> Result<(), Error> {
    let set = OutputSet::new();
    set.stage(path, write)?;
    set.commit()
}

/// One staged file: (staging rank, temporary, final path, signal-cleanup slot).
type Staged = (u64, PathBuf, PathBuf, Option<usize>);

/// Files written to temporaries and renamed into place together (module docs). `stage`
/// takes `&self`, so files can be staged from several threads at once.
#[derive(Debug, Default)]
pub struct OutputSet {
    staged: std::sync::Mutex<Vec<Staged>>,
    /// Staging positions, so the commit order is the order `stage` was *called*.
    order: AtomicU64,
}

impl OutputSet {
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes `path`'s content to its temporary (synced to disk); nothing at `path` changes
    /// until [`OutputSet::commit`]. Files are renamed in the order this was called.
    pub fn stage(
        &self,
        path: &Path,
        write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
    ) -> Result<(), Error> {
        let rank = self.order.fetch_add(1, Ordering::Relaxed);
        let tmp = temp_path(path);
        let slot = signals::register(&tmp);
        let result = (|| {
            let file = File::create(&tmp)?;
            let mut w = BufWriter::with_capacity(1 << 20, file);
            write(&mut w)?;
            let file = w.into_inner().map_err(|e| e.into_error())?;
            file.sync_all()
        })();
        if let Err(e) = result {
            let _ = std::fs::remove_file(&tmp);
            signals::unregister(slot);
            return Err(Error::io(path, e));
        }
        let mut staged = self.staged.lock().unwrap_or_else(|p| p.into_inner());
        staged.push((rank, tmp, path.to_owned(), slot));
        drop(staged);
        kill_point();
        Ok(())
    }

    /// Puts every staged file in place, in staging order, all or none (module docs): on an
    /// error what was done is undone (the old files come back), the temporaries are
    /// removed and the error names the file. A target that is a directory is refused
    /// before anything moves.
    pub fn commit(self) -> Result<(), Error> {
        let mut staged =
            std::mem::take(&mut *self.staged.lock().unwrap_or_else(|p| p.into_inner()));
        staged.sort_by_key(|(rank, ..)| *rank);
        let result = commit_staged(&staged);
        for (_, tmp, _, slot) in &staged {
            if result.is_err() {
                let _ = std::fs::remove_file(tmp);
            }
            signals::unregister(*slot);
        }
        result
    }
}

fn commit_staged(staged: &[Staged]) -> Result<(), Error> {
    let Some((_, _, last, _)) = staged.last() else {
        return Ok(());
    };
    for (_, _, path, _) in staged {
        if path.is_dir() {
            return Err(Error::io(
                path,
                std::io::Error::other("is a directory; a file cannot replace it"),
            ));
        }
    }
    // An earlier commit of this set, killed half way, is finished first.
    finish_interrupted_commit(last)?;
    remove_stale_temporaries(staged.iter().map(|(_, _, path, _)| path.as_path()));
    let mut journal = Journal {
        path: journal_path(last),
        back: false,
        files: staged
            .iter()
            .map(|(_, tmp, target, _)| Entry {
                tmp: tmp.clone(),
                target: target.clone(),
                aside: target
                    .exists()
                    .then(|| temp_path(target).with_extension("old")),
            })
            .collect(),
    };
    journal.write()?;
    kill_point();
    let undo = |journal: &mut Journal, path: &Path, e: std::io::Error| {
        journal.back = true;
        // Even when the turned journal cannot be written, the old files are put back now.
        let _ = journal.write();
        journal.roll_back();
        journal.remove();
        Error::io(path, e)
    };
    // The old files aside.
    for e in &journal.files {
        if let Some(aside) = &e.aside
            && let Err(err) = std::fs::rename(&e.target, aside)
        {
            let target = e.target.clone();
            return Err(undo(&mut journal, &target, err));
        }
        kill_point();
    }
    // The new files in.
    for e in &journal.files {
        if let Err(err) = std::fs::rename(&e.tmp, &e.target) {
            let target = e.target.clone();
            return Err(undo(&mut journal, &target, err));
        }
        kill_point();
    }
    journal.roll_forward();
    journal.remove();
    Ok(())
}

/// Finishes a commit of the set whose last file is `last` that a killed process left half
/// done (module docs): forward to the new set, or back to the old one when the commit had
/// failed and was being undone. Returns whether there was one. Nothing to do is the
/// common case: one `stat`.
pub fn finish_interrupted_commit(last: &Path) -> Result<bool, Error> {
    let path = journal_path(last);
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(false),
        Err(e) => return Err(Error::io(&path, e)),
    };
    let journal = Journal::parse(path.clone(), &text).ok_or_else(|| {
        Error::io(
            &path,
            std::io::Error::other(
                "not a commit journal agesim can read; the files it names are as the \
                 interrupted save left them (remove it once they are checked)",
            ),
        )
    })?;
    if journal.back {
        journal.roll_back();
    } else {
        journal.roll_forward();
    }
    journal.remove();
    Ok(true)
}

/// `.<name>.agesim-commit` beside `last`.
fn journal_path(last: &Path) -> PathBuf {
    let name = last
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    last.with_file_name(format!(".{name}.agesim-commit"))
}

/// A commit in progress, as written to disk.
struct Journal {
    path: PathBuf,
    /// The commit failed and is being undone.
    back: bool,
    files: Vec<Entry>,
}

struct Entry {
    tmp: PathBuf,
    target: PathBuf,
    /// Where the old file goes while the new one is put in place (`None`: there was none).
    aside: Option<PathBuf>,
}

const JOURNAL_HEADER: &str = "agesim commit journal 1";

impl Journal {
    /// Header, direction, then one line per file: temporary, target, aside (`-` for
    /// none), tab-separated, each path escaped ([`escape`]).
    fn text(&self) -> String {
        let mut s = format!(
            "{JOURNAL_HEADER}\n{}\n",
            if self.back { "back" } else { "forward" }
        );
        for e in &self.files {
            let aside = e.aside.as_deref().map_or_else(|| "-".to_owned(), escape);
            s += &format!("{}\t{}\t{aside}\n", escape(&e.tmp), escape(&e.target));
        }
        s
    }

    fn parse(path: PathBuf, text: &str) -> Option<Self> {
        let mut lines = text.lines();
        if lines.next()? != JOURNAL_HEADER {
            return None;
        }
        let back = match lines.next()? {
            "forward" => false,
            "back" => true,
            _ => return None,
        };
        let mut files = Vec::new();
        for line in lines {
            let mut cols = line.split('\t');
            let tmp = unescape(cols.next()?)?;
            let target = unescape(cols.next()?)?;
            let aside = match cols.next()? {
                "-" => None,
                a => Some(unescape(a)?),
            };
            if cols.next().is_some() {
                return None;
            }
            files.push(Entry { tmp, target, aside });
        }
        Some(Self { path, back, files })
    }

    /// Writes the journal in place atomically (a temporary, synced, renamed) and syncs
    /// its folder, so it is on the disk before any target moves.
    fn write(&self) -> Result<(), Error> {
        let tmp = self.path.with_extension("agesim-commit-tmp");
        let result = (|| {
            let mut file = File::create(&tmp)?;
            std::io::Write::write_all(&mut file, self.text().as_bytes())?;
            file.sync_all()?;
            std::fs::rename(&tmp, &self.path)?;
            sync_dir(&self.path)
        })();
        result.map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            Error::io(&self.path, e)
        })
    }

    /// Every temporary still there into place, then the old files removed.
    fn roll_forward(&self) {
        for e in &self.files {
            if e.tmp.exists() {
                let _ = std::fs::rename(&e.tmp, &e.target);
            }
        }
        kill_point();
        for aside in self.files.iter().filter_map(|e| e.aside.as_ref()) {
            let _ = std::fs::remove_file(aside);
        }
        kill_point();
    }

    /// The old files back, a new file that had no old one removed, the temporaries removed.
    fn roll_back(&self) {
        for e in self.files.iter().rev() {
            match &e.aside {
                Some(aside) if aside.exists() => {
                    let _ = std::fs::rename(aside, &e.target);
                }
                // Placed (its temporary is gone) where there was nothing before.
                None if !e.tmp.exists() => {
                    let _ = std::fs::remove_file(&e.target);
                }
                _ => {}
            }
        }
        for e in &self.files {
            let _ = std::fs::remove_file(&e.tmp);
        }
    }

    fn remove(&self) {
        let _ = std::fs::remove_file(&self.path);
        let _ = sync_dir(&self.path);
        kill_point();
    }
}

/// Syncs the folder holding `path`, so renames in it are on the disk (POSIX; elsewhere a
/// no-op).
fn sync_dir(path: &Path) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
        File::open(dir.unwrap_or(Path::new(".")))?.sync_all()
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        Ok(())
    }
}

/// A path as one journal field: bytes other than printable ASCII, `%` and tab are `%XX`
/// (so any file name, not only Unicode ones, round-trips).
fn escape(path: &Path) -> String {
    let bytes = path_bytes(path);
    let mut s = String::with_capacity(bytes.len());
    for b in bytes {
        if (0x20..0x7f).contains(&b) && b != b'%' {
            s.push(b as char);
        } else {
            s += &format!("%{b:02X}");
        }
    }
    s
}

fn unescape(s: &str) -> Option<PathBuf> {
    let mut out = Vec::with_capacity(s.len());
    let mut bytes = s.bytes();
    while let Some(b) = bytes.next() {
        if b == b'%' {
            let hex = [bytes.next()?, bytes.next()?];
            out.push(u8::from_str_radix(std::str::from_utf8(&hex).ok()?, 16).ok()?);
        } else {
            out.push(b);
        }
    }
    bytes_path(out)
}

#[cfg(unix)]
fn path_bytes(path: &Path) -> Vec<u8> {
    use std::os::unix::ffi::OsStrExt as _;
    path.as_os_str().as_bytes().to_vec()
}
#[cfg(unix)]
fn bytes_path(bytes: Vec<u8>) -> Option<PathBuf> {
    use std::os::unix::ffi::OsStringExt as _;
    Some(PathBuf::from(std::ffi::OsString::from_vec(bytes)))
}
#[cfg(not(unix))]
fn path_bytes(path: &Path) -> Vec<u8> {
    path.to_string_lossy().into_owned().into_bytes()
}
#[cfg(not(unix))]
fn bytes_path(bytes: Vec<u8>) -> Option<PathBuf> {
    String::from_utf8(bytes).ok().map(PathBuf::from)
}

/// Removes the temporaries (`.<name>.<pid>.<n>.tmp` / `.old`) that killed processes left
/// beside `targets`: only those whose process is no longer running.
fn remove_stale_temporaries<'a>(targets: impl Iterator<Item = &'a Path>) {
    let mut by_dir: std::collections::BTreeMap<PathBuf, Vec<String>> = Default::default();
    for t in targets {
        let dir = t.parent().unwrap_or(Path::new("")).to_owned();
        if let Some(name) = t.file_name() {
            by_dir
                .entry(dir)
                .or_default()
                .push(name.to_string_lossy().into_owned());
        }
    }
    for (dir, names) in by_dir {
        let listing = if dir.as_os_str().is_empty() {
            std::fs::read_dir(".")
        } else {
            std::fs::read_dir(&dir)
        };
        let Ok(listing) = listing else { continue };
        for entry in listing.flatten() {
            let file = entry.file_name().to_string_lossy().into_owned();
            let stale = names
                .iter()
                .any(|name| stale_pid(&file, name).is_some_and(|pid| !process_is_running(pid)));
            if stale {
                let _ = std::fs::remove_file(entry.path());
            }
        }
    }
}

/// The process id in `file` when it is a temporary of `name` (`.<name>.<pid>.<n>.tmp` or
/// `.old`).
fn stale_pid(file: &str, name: &str) -> Option<u32> {
    let rest = file
        .strip_prefix('.')?
        .strip_prefix(name)?
        .strip_prefix('.')?;
    let rest = rest
        .strip_suffix(".tmp")
        .or_else(|| rest.strip_suffix(".old"))?;
    let (pid, n) = rest.split_once('.')?;
    n.parse::<u64>().ok()?;
    pid.parse().ok()
}

fn process_is_running(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    #[cfg(target_os = "linux")]
    {
        Path::new("/proc").join(pid.to_string()).exists()
    }
    #[cfg(not(target_os = "linux"))]
    {
        true
    }
}

/// The step at which [`kill_point`] kills the process (`u32::MAX`: never), and the steps
/// passed so far.
static KILL_AT: AtomicU32 = AtomicU32::new(u32::MAX);
static STEPS: AtomicU32 = AtomicU32::new(0);

/// For the crash tests: the process kills itself with SIGKILL at the `step`-th point of a
/// save (counting from 0: each file staged, the journal written, each file moved aside,
/// each file placed, the journal's removal, the steps of a roll forward). `None` never.
#[doc(hidden)]
pub fn kill_at_step_for_tests(step: Option<u32>) {
    STEPS.store(0, Ordering::SeqCst);
    KILL_AT.store(step.unwrap_or(u32::MAX), Ordering::SeqCst);
}

fn kill_point() {
    if KILL_AT.load(Ordering::Relaxed) == u32::MAX {
        return;
    }
    if STEPS.fetch_add(1, Ordering::SeqCst) == KILL_AT.load(Ordering::SeqCst) {
        #[cfg(unix)]
        // SAFETY: sending a signal to this process; SIGKILL cannot be caught.
        unsafe {
            libc::kill(libc::getpid(), libc::SIGKILL);
        }
        std::process::abort();
    }
}

impl Drop for OutputSet {
    /// An uncommitted set (an error elsewhere, a panic) leaves no temporary behind.
    fn drop(&mut self) {
        let staged = std::mem::take(&mut *self.staged.lock().unwrap_or_else(|p| p.into_inner()));
        for (_, tmp, _, slot) in staged {
            let _ = std::fs::remove_file(&tmp);
            signals::unregister(slot);
        }
    }
}

/// Removes every staged temporary when the process gets SIGINT or SIGTERM, then exits
/// with 128 + the signal number. Call once from a program's `main` (the command line);
/// a library user with its own handlers can leave it out.
pub fn remove_temporaries_on_signals() {
    signals::install();
}

/// The temporaries a signal handler must remove: a fixed table of C strings, read with
/// only async-signal-safe calls (`unlink`, `_exit`) from the handler.
mod signals {
    use std::path::Path;
    #[cfg(target_os = "linux")]
    use std::sync::atomic::{AtomicPtr, Ordering};

    #[cfg(target_os = "linux")]
    const SLOTS: usize = 64;
    #[cfg(target_os = "linux")]
    #[allow(clippy::declare_interior_mutable_const)]
    const EMPTY: AtomicPtr<libc::c_char> = AtomicPtr::new(std::ptr::null_mut());
    #[cfg(target_os = "linux")]
    static TABLE: [AtomicPtr<libc::c_char>; SLOTS] = [EMPTY; SLOTS];

    /// Records `tmp`; `None` when the table is full (the file is then only removed by the
    /// normal paths).
    #[cfg(target_os = "linux")]
    pub(super) fn register(tmp: &Path) -> Option<usize> {
        use std::os::unix::ffi::OsStrExt as _;
        let c = std::ffi::CString::new(tmp.as_os_str().as_bytes()).ok()?;
        let raw = c.into_raw();
        for (i, slot) in TABLE.iter().enumerate() {
            if slot
                .compare_exchange(
                    std::ptr::null_mut(),
                    raw,
                    Ordering::AcqRel,
                    Ordering::Relaxed,
                )
                .is_ok()
            {
                return Some(i);
            }
        }
        // SAFETY: `raw` came from `CString::into_raw` just above and was not stored.
        drop(unsafe { std::ffi::CString::from_raw(raw) });
        None
    }

    #[cfg(target_os = "linux")]
    pub(super) fn unregister(slot: Option<usize>) {
        if let Some(i) = slot {
            let raw = TABLE[i].swap(std::ptr::null_mut(), Ordering::AcqRel);
            if !raw.is_null() {
                // SAFETY: every non-null pointer in the table came from `CString::into_raw`
                // in `register`, and the swap took it out, so it is freed exactly once.
                drop(unsafe { std::ffi::CString::from_raw(raw) });
            }
        }
    }

    #[cfg(target_os = "linux")]
    extern "C" fn on_signal(sig: libc::c_int) {
        for slot in &TABLE {
            let p = slot.load(Ordering::Acquire);
            if !p.is_null() {
                // SAFETY: `p` is a valid NUL-terminated string owned by the table;
                // `unlink` is async-signal-safe.
                unsafe { libc::unlink(p) };
            }
        }
        // SAFETY: `_exit` is async-signal-safe and ends the process at once.
        unsafe { libc::_exit(128 + sig) };
    }

    #[cfg(target_os = "linux")]
    pub(super) fn install() {
        let handler = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
        for sig in [libc::SIGINT, libc::SIGTERM] {
            // SAFETY: installing a handler that only calls async-signal-safe functions.
            unsafe { libc::signal(sig, handler) };
        }
    }

    #[cfg(not(target_os = "linux"))]
    pub(super) fn register(_: &Path) -> Option<usize> {
        None
    }
    #[cfg(not(target_os = "linux"))]
    pub(super) fn unregister(_: Option<usize>) {}
    #[cfg(not(target_os = "linux"))]
    pub(super) fn install() {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn journal_text_round_trips_any_file_name() {
        let odd = {
            #[cfg(unix)]
            {
                bytes_path(b"/tmp/a\tb%c\n\xff.wrk".to_vec()).unwrap()
            }
            #[cfg(not(unix))]
            {
                PathBuf::from("C:/a\tb%c.wrk")
            }
        };
        let j = Journal {
            path: PathBuf::from("/tmp/.p.agesim-commit"),
            back: true,
            files: vec![
                Entry {
                    tmp: PathBuf::from("/tmp/.p.json.1.0.tmp"),
                    target: odd.clone(),
                    aside: None,
                },
                Entry {
                    tmp: PathBuf::from("/x/.y.1.1.tmp"),
                    target: PathBuf::from("/x/y"),
                    aside: Some(PathBuf::from("/x/.y.1.2.old")),
                },
            ],
        };
        let back = Journal::parse(j.path.clone(), &j.text()).unwrap();
        assert!(back.back);
        assert_eq!(back.files[0].target, odd);
        assert_eq!(back.files[0].aside, None);
        assert_eq!(back.files[1].aside, j.files[1].aside);
        assert!(Journal::parse(j.path.clone(), "agesim commit journal 1\nsideways\n").is_none());
    }

    #[test]
    fn a_journal_left_by_a_killed_commit_is_rolled_forward() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.wrk"), dir.path().join("p.json"));
        std::fs::write(&a, "old a").unwrap();
        std::fs::write(&b, "old b").unwrap();
        // As a commit killed after moving `a` aside and before placing anything.
        let (ta, tb) = (temp_path(&a), temp_path(&b));
        std::fs::write(&ta, "new a").unwrap();
        std::fs::write(&tb, "new b").unwrap();
        let aside = temp_path(&a).with_extension("old");
        let j = Journal {
            path: journal_path(&b),
            back: false,
            files: vec![
                Entry {
                    tmp: ta,
                    target: a.clone(),
                    aside: Some(aside.clone()),
                },
                Entry {
                    tmp: tb,
                    target: b.clone(),
                    aside: Some(temp_path(&b).with_extension("old")),
                },
            ],
        };
        j.write().unwrap();
        std::fs::rename(&a, &aside).unwrap();
        assert!(finish_interrupted_commit(&b).unwrap());
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new a");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new b");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 2, "only the two files are left");
        assert!(!finish_interrupted_commit(&b).unwrap());
    }

    #[test]
    fn stale_temporaries_are_named_by_their_target_and_process() {
        assert_eq!(stale_pid(".p.json.123.4.tmp", "p.json"), Some(123));
        assert_eq!(stale_pid(".p.json.123.4.old", "p.json"), Some(123));
        assert_eq!(stale_pid(".p.json.x.4.tmp", "p.json"), None);
        assert_eq!(stale_pid(".q.json.123.4.tmp", "p.json"), None);
        assert_eq!(stale_pid("p.json", "p.json"), None);
    }
}
