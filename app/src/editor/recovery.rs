//! Autosave and crash recovery: while a document has unsaved changes, the whole session
//! (the project and its edited wrinkle files, as a normal project that also opens by hand)
//! is written, all or nothing, to a recovery folder in the platform's data directory
//! (`$XDG_DATA_HOME/agesim/recovery/`, else `~/.local/share/agesim/recovery/`), in a
//! folder of each running editor's own (`<pid>/`), so two editors open at once never
//! overwrite or remove each other's. A clean exit or a save removes the editor's folder;
//! one left by an editor that is no longer running is offered back at the next start
//! (`agesim --recover` restores it without asking; the newest when several are left).

use std::path::{Path, PathBuf};

use agesim_core::project::Project;
use agesim_core::scene::WrinkleSource;

/// The session's project file in the recovery folder.
pub const SESSION_FILE: &str = "session.agesim.json";
/// What the recovery folder remembers beside the project: the document's own path and
/// the editor that wrote it.
const INFO_FILE: &str = "recovery.json";

/// The recovery folder: `override_dir` (tests), else `$XDG_DATA_HOME/agesim/recovery`,
/// else `$HOME/.local/share/agesim/recovery`; `None` with neither variable set.
pub fn folder(override_dir: Option<&Path>) -> Option<PathBuf> {
    if let Some(d) = override_dir {
        return Some(d.to_owned());
    }
    let data = std::env::var_os("XDG_DATA_HOME")
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".local/share")))?;
    Some(data.join("agesim").join("recovery"))
}

/// A session left behind by an editor that did not exit cleanly.
#[derive(Clone, Debug, PartialEq)]
pub struct Left {
    /// The recovered project file (in the recovery folder).
    pub session: PathBuf,
    /// Where the document was saved before, if it was.
    pub original: Option<PathBuf>,
}

/// This editor's own folder in the recovery folder `dir`.
pub fn own(dir: &Path) -> PathBuf {
    dir.join(std::process::id().to_string())
}

/// The newest session in the recovery folder `dir` left by an editor that is no longer
/// running, if any. (This process's own folder counts: at start it has written nothing,
/// so one there is an earlier editor's in this process.)
pub fn left_behind(dir: &Path) -> Option<Left> {
    let mut found: Vec<(std::time::SystemTime, Left)> = Vec::new();
    for entry in std::fs::read_dir(dir).ok()?.flatten() {
        let folder = entry.path();
        let session = folder.join(SESSION_FILE);
        let Ok(meta) = std::fs::metadata(&session) else {
            continue;
        };
        let pid = entry.file_name().to_string_lossy().parse::<u64>().ok();
        // A running editor's autosave is not a crash's.
        if let Some(pid) = pid
            && pid != u64::from(std::process::id())
            && alive(pid)
        {
            continue;
        }
        let info: serde_json::Value = std::fs::read(folder.join(INFO_FILE))
            .ok()
            .and_then(|b| serde_json::from_slice(&b).ok())
            .unwrap_or_default();
        let left = Left {
            session,
            original: info["original"].as_str().map(PathBuf::from),
        };
        found.push((meta.modified().unwrap_or(std::time::UNIX_EPOCH), left));
    }
    found.sort_by_key(|(t, _)| *t);
    found.pop().map(|(_, left)| left)
}

/// Whether a process with this id runs (Linux: `/proc/<pid>`; elsewhere assumed not).
fn alive(pid: u64) -> bool {
    Path::new(&format!("/proc/{pid}")).exists()
}

/// Writes the session to `dir` (this editor's folder, [`own`]): the recovery note, then
/// the project and its edited wrinkle files as one all-or-nothing set
/// (`files::save_project`).
pub fn write(
    dir: &Path,
    project: &Project,
    wrinkles: Option<&[WrinkleSource]>,
    original: Option<&Path>,
) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let info = serde_json::json!({
        "pid": std::process::id(),
        "original": original.map(|p| p.display().to_string()),
    });
    let set = agesim_core::output::export::OutputSet::new();
    set.stage(&dir.join(INFO_FILE), |w| {
        std::io::Write::write_all(w, info.to_string().as_bytes())
    })
    .and_then(|()| set.commit())
    .map_err(|e| e.to_string())?;
    super::files::save_project(&dir.join(SESSION_FILE), project, wrinkles, None).map(|_| ())
}

/// Removes a session's folder (a clean exit, a save, a session restored or discarded).
pub fn clear(folder: &Path) {
    let _ = std::fs::remove_dir_all(folder);
}

/// Reads a left session back: the project, and its wrinkle files as edited documents (so
/// a save writes them beside the project, not pointing into the recovery folder, which
/// goes away). The built-in mask the session carried for built-in wrinkles is the
/// built-in one again.
pub fn read(left: &Left) -> Result<(Project, Option<Vec<WrinkleSource>>), String> {
    let mut project = Project::load(&left.session).map_err(|e| e.to_string())?;
    let dir = left.session.parent().unwrap_or(Path::new(""));
    if project
        .large
        .mask
        .as_deref()
        .is_some_and(|m| m.starts_with(dir))
    {
        project.large.mask = None;
    }
    let wrinkles = if project.large.wrinkles.iter().any(|w| w.starts_with(dir)) {
        let sources = agesim_core::scene::load_wrinkles(&project.large.wrinkles)
            .map_err(|e| e.to_string())?;
        Some(sources)
    } else {
        None
    };
    Ok((project, wrinkles))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_session_is_written_found_read_and_cleared() {
        let dir = tempfile::tempdir().unwrap();
        let rec = dir.path().join("recovery");
        assert!(left_behind(&rec).is_none());
        let mut p = Project::default();
        p.noise.strength = 0.77;
        write(&own(&rec), &p, None, Some(Path::new("/work/p.agesim.json"))).unwrap();
        // This process wrote it: found (an earlier editor of this process).
        let left = left_behind(&rec).unwrap();
        assert_eq!(left.original, Some(PathBuf::from("/work/p.agesim.json")));
        let (back, wrinkles) = read(&left).unwrap();
        assert_eq!(back.noise.strength, 0.77);
        assert!(wrinkles.is_none());
        // Another editor that still runs (pid 1, init) keeps its own: not offered.
        write(&rec.join("1"), &p, None, None).unwrap();
        clear(&own(&rec));
        assert!(
            left_behind(&rec).is_none(),
            "a running editor's session is its own"
        );
        // One whose editor is gone is.
        std::fs::rename(rec.join("1"), rec.join("4000000000")).unwrap();
        assert!(left_behind(&rec).is_some());
        if let Some(f) = folder(None) {
            assert!(f.ends_with("agesim/recovery"), "{}", f.display());
        }
    }
}
