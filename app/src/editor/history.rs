//! Undo and redo: the document before each change, named after the change. The changes of
//! one drag (a slider, a fibre handle, the age playhead) are one step.

use agesim_core::project::Project;
use agesim_core::scene::{FileVersions, WrinkleSource};

/// The editable document: the project and the wrinkle files as edited (`None` until the
/// first fibre edit: then the files the project names are used as they are on disk).
#[derive(Clone, Debug)]
pub struct Doc {
    pub project: Project,
    pub wrinkles: Option<Vec<WrinkleSource>>,
    /// Which content of each input file changed on disk the document uses (a reload is
    /// a new version; undoing it goes back to the content before).
    pub files: FileVersions,
    /// Identifies this state, for the modified mark (the saved revision is remembered).
    pub revision: u64,
}

#[derive(Debug)]
struct Step {
    name: String,
    doc: Doc,
}

/// Steps are kept up to this many; the oldest go first.
const LIMIT: usize = 200;

#[derive(Debug, Default)]
pub struct History {
    undo: Vec<Step>,
    redo: Vec<Step>,
    /// The key of the drag whose first change is recorded and which is still going on.
    open: Option<String>,
}

impl History {
    /// Records `before`, the document as it was before a change named `name`. Changes
    /// with the same `key` while `dragging` (and the change that ends that drag) join the
    /// step of the drag's first change. Returns whether a step was added.
    pub fn record(&mut self, name: &str, key: &str, before: &Doc, dragging: bool) -> bool {
        let joins = self.open.as_deref() == Some(key);
        self.open = dragging.then(|| key.to_owned());
        if joins {
            return false;
        }
        self.undo.push(Step {
            name: name.to_owned(),
            doc: before.clone(),
        });
        if self.undo.len() > LIMIT {
            self.undo.remove(0);
        }
        self.redo.clear();
        true
    }

    /// Steps back: returns the document to restore; `current` becomes redoable.
    pub fn undo(&mut self, current: Doc) -> Option<(String, Doc)> {
        self.open = None;
        let step = self.undo.pop()?;
        let name = step.name.clone();
        self.redo.push(Step {
            name: step.name,
            doc: current,
        });
        Some((name, step.doc))
    }

    pub fn redo(&mut self, current: Doc) -> Option<(String, Doc)> {
        self.open = None;
        let step = self.redo.pop()?;
        let name = step.name.clone();
        self.undo.push(Step {
            name: step.name,
            doc: current,
        });
        Some((name, step.doc))
    }

    /// Takes back the newest step when `refused` says the change it recorded did not
    /// happen (the worker refused it), returning the document before it.
    pub fn discard_last_if(&mut self, refused: impl Fn(&Doc) -> bool) -> Option<Doc> {
        if self.undo.last().is_some_and(|s| refused(&s.doc)) {
            self.open = None;
            return self.undo.pop().map(|s| s.doc);
        }
        None
    }

    pub fn undo_name(&self) -> Option<&str> {
        self.undo.last().map(|s| s.name.as_str())
    }

    pub fn redo_name(&self) -> Option<&str> {
        self.redo.last().map(|s| s.name.as_str())
    }

    /// Forgets every step (a new or opened document).
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(gamma: f32, revision: u64) -> Doc {
        let mut project = Project::default();
        project.large.gamma = gamma;
        Doc {
            project,
            wrinkles: None,
            files: FileVersions::new(),
            revision,
        }
    }

    #[test]
    fn a_drag_is_one_step_and_redo_returns_its_end() {
        let mut h = History::default();
        // A drag from 1.0 through 1.5 to 2.0, released at 2.0.
        assert!(h.record("large.gamma", "large.gamma", &doc(1.0, 0), true));
        assert!(!h.record("large.gamma", "large.gamma", &doc(1.5, 1), true));
        assert!(!h.record("large.gamma", "large.gamma", &doc(1.8, 2), false));
        let (name, before) = h.undo(doc(2.0, 3)).unwrap();
        assert_eq!(
            (name.as_str(), before.project.large.gamma),
            ("large.gamma", 1.0)
        );
        assert!(h.undo(doc(1.0, 0)).is_none(), "one step only");
        let (_, after) = h.redo(doc(1.0, 0)).unwrap();
        assert_eq!(after.project.large.gamma, 2.0);
    }

    #[test]
    fn two_clicks_are_two_steps_and_a_new_change_drops_the_redo() {
        let mut h = History::default();
        h.record("a", "a", &doc(1.0, 0), false);
        h.record("a", "a", &doc(2.0, 1), false);
        assert_eq!(h.undo(doc(3.0, 2)).unwrap().1.project.large.gamma, 2.0);
        h.record("b", "b", &doc(2.0, 1), false);
        assert!(h.redo_name().is_none());
        assert_eq!(h.undo_name(), Some("b"));
    }
}
