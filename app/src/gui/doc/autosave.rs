//! Autosave: while the document has unsaved changes, its scene is written
//! to this process's recovery file (see [`super::recovery`]) a few seconds
//! after it changes; once nothing is unsaved (saved, undone, discarded) or
//! the window closes cleanly, the file is removed.
//!
//! The write happens on the UI thread: a scene file is a few kilobytes
//! (meshes stay in their model files), written at most once per interval,
//! which takes well under a millisecond.

use super::document::Document;
use super::recovery;
use scene::Scene;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How long after a change the recovery file is written.
pub const INTERVAL: Duration = Duration::from_secs(5);

/// What the recovery file holds: the scene and the file it belongs to.
type Content = (Scene, Option<PathBuf>);

/// This process's recovery file and when to write it next.
pub struct Autosave {
    /// The recovery file.
    file: PathBuf,
    /// The delay between a change and its autosave.
    interval: Duration,
    /// What the file holds, when it exists.
    written: Option<Content>,
    /// When the pending change is due to be written.
    due: Option<Instant>,
    /// The last write failed and the user was told.
    failing: bool,
}

/// What a poll did, for the app to act on.
#[derive(Debug, Default, PartialEq)]
pub struct Poll {
    /// Poll again after this long (a change waits to be written).
    pub again_in: Option<Duration>,
    /// A write failed for the first time since the last success.
    pub error: Option<String>,
}

impl Autosave {
    /// Autosaves into `recovery-PID.xml` in `dir`, `interval` after a change.
    pub fn new(dir: &Path, interval: Duration) -> Self {
        Self {
            file: recovery::file_of(dir, std::process::id()),
            interval,
            written: None,
            due: None,
            failing: false,
        }
    }

    /// The recovery file this process writes.
    #[cfg(test)]
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// Writes `doc`'s scene when it has unsaved changes not yet written and
    /// `interval` has passed since they were first seen (`now` being the
    /// time); removes the file when nothing is unsaved.
    pub fn poll(&mut self, now: Instant, doc: &Document) -> Poll {
        if !doc.is_modified() {
            self.remove();
            return Poll::default();
        }
        let unwritten = self
            .written
            .as_ref()
            .is_none_or(|(scene, path)| *scene != doc.state.scene || *path != doc.path);
        if !unwritten {
            self.due = None;
            return Poll::default();
        }
        let due = *self.due.get_or_insert(now + self.interval);
        if now < due {
            return Poll {
                again_in: Some(due - now),
                error: None,
            };
        }
        match recovery::write(&self.file, &doc.state.scene, doc.path.as_deref()) {
            Ok(()) => {
                self.written = Some((doc.state.scene.clone(), doc.path.clone()));
                self.due = None;
                self.failing = false;
                Poll::default()
            }
            Err(e) => {
                // Try again an interval later; tell the user once.
                self.due = Some(now + self.interval);
                let first = !self.failing;
                self.failing = true;
                Poll {
                    again_in: Some(self.interval),
                    error: first
                        .then(|| format!("Cannot autosave to {}: {e}", self.file.display())),
                }
            }
        }
    }

    /// Takes over a recovery file left by another process, restored as
    /// `content`: it becomes this process's file (one rename, so the work
    /// is on disk throughout).
    pub fn adopt(&mut self, left: &Path, content: Content) {
        if std::fs::rename(left, &self.file).is_ok() {
            self.written = Some(content);
        }
    }

    /// Removes the recovery file (nothing unsaved, or a clean exit).
    pub fn remove(&mut self) {
        if self.written.take().is_some() {
            let _ = std::fs::remove_file(&self.file);
        }
        self.due = None;
    }
}

#[cfg(test)]
mod tests {
    use super::super::document::RenderSettings;
    use super::*;

    fn edited_doc(path: Option<PathBuf>) -> Document {
        let mut doc = Document::new(Scene::default(), path, RenderSettings::default());
        doc.state.scene.camera.theta_deg = 17.0;
        doc
    }

    #[test]
    fn an_unsaved_change_is_written_one_interval_after_it_is_first_seen() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut autosave = Autosave::new(dir.path(), INTERVAL);
        let doc = edited_doc(Some(PathBuf::from("/scenes/a.xml")));
        let t0 = Instant::now();
        let poll = autosave.poll(t0, &doc);
        assert_eq!(poll.again_in, Some(INTERVAL));
        assert!(!autosave.file().exists());
        let poll = autosave.poll(t0 + Duration::from_secs(4), &doc);
        assert_eq!(poll.again_in, Some(Duration::from_secs(1)));
        assert!(!autosave.file().exists());
        assert_eq!(autosave.poll(t0 + INTERVAL, &doc), Poll::default());
        let (scene, source) = recovery::read(autosave.file()).expect("reads");
        assert_eq!(scene, doc.state.scene);
        assert_eq!(source.as_deref(), Some(Path::new("/scenes/a.xml")));
    }

    #[test]
    fn an_unchanged_scene_is_not_written_again() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut autosave = Autosave::new(dir.path(), Duration::ZERO);
        let doc = edited_doc(None);
        let t0 = Instant::now();
        autosave.poll(t0, &doc);
        std::fs::write(autosave.file(), "marker").expect("write");
        autosave.poll(t0 + Duration::from_secs(60), &doc);
        assert_eq!(
            std::fs::read_to_string(autosave.file()).expect("read"),
            "marker"
        );
    }

    #[test]
    fn nothing_unsaved_writes_nothing_and_removes_the_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut autosave = Autosave::new(dir.path(), Duration::ZERO);
        let mut doc = Document::new(Scene::default(), None, RenderSettings::default());
        let t0 = Instant::now();
        autosave.poll(t0, &doc);
        assert!(!autosave.file().exists(), "no changes, no file");
        doc.state.scene.camera.theta_deg = 17.0;
        autosave.poll(t0, &doc);
        assert!(autosave.file().exists());
        doc.state.scene = Scene::default();
        autosave.poll(t0, &doc);
        assert!(!autosave.file().exists(), "back to the saved scene");
    }

    #[test]
    fn a_failing_write_is_reported_once_and_retried() {
        let dir = tempfile::tempdir().expect("temp dir");
        // A file where the folder should be: no write can succeed.
        let blocked = dir.path().join("blocked");
        std::fs::write(&blocked, "").expect("write");
        let mut autosave = Autosave::new(&blocked, Duration::ZERO);
        let doc = edited_doc(None);
        let t0 = Instant::now();
        assert!(autosave.poll(t0, &doc).error.is_some());
        let again = autosave.poll(t0, &doc);
        assert_eq!(again.error, None, "said once");
        assert_eq!(again.again_in, Some(Duration::ZERO));
    }
}
