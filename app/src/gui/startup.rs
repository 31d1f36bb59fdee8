//! What the window opens on: the scene named on the command line or, when
//! it cannot be read, the default scene as an untitled document with the
//! error in front of it (file, line, column and why). Someone who started
//! raylab from a file manager has no terminal to read an error on stderr.

use std::path::{Path, PathBuf};

/// The window's first document, and the error to show over it, if any.
pub struct Startup {
    /// The scene to edit.
    pub scene: scene::Scene,
    /// Its file (`None`: untitled, so that a save asks for a name).
    pub path: Option<PathBuf>,
    /// The model file it was read from (a .gltf or .glb opened directly).
    pub origin: Option<PathBuf>,
    /// Why the file could not be opened (the reader's error: file, line,
    /// column and why).
    pub problem: Option<String>,
}

impl Startup {
    /// What the window says in front of the scene, when the file could not
    /// be opened.
    pub fn message(&self) -> Option<String> {
        self.problem.as_ref().map(|problem| {
            format!(
                "Cannot open the scene.\n\n{problem}\n\nShown instead: the default scene, untitled."
            )
        })
    }
}

/// The scene at `path`, or the one at `default` (untitled) with the error
/// that `path` gave; an empty scene if `default` fails too.
pub fn open_or_explain(path: &Path, default: &Path) -> Startup {
    match scene::read_any(path) {
        Ok(scene) => Startup {
            scene,
            path: super::Document::scene_path(path),
            origin: scene::is_model_path(path).then(|| path.to_path_buf()),
            problem: None,
        },
        Err(error) => Startup {
            scene: scene::read_any(default).unwrap_or_default(),
            path: None,
            origin: None,
            problem: Some(error.to_string()),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gui::RaylabApp;
    use crate::gui::tests::{harness, seed_path, step_shown};
    use egui_kittest::kittest::Queryable;

    #[test]
    fn a_scene_that_cannot_be_read_opens_the_default_scene_untitled_with_the_error_in_front() {
        let dir = tempfile::tempdir().expect("tempdir");
        let bad = dir.path().join("bad.xml");
        std::fs::write(&bad, "<scene>\n  <sphere radius=\"x\"/>\n</scene>\n").expect("written");
        let startup = open_or_explain(&bad, &seed_path());
        let problem = startup.message().expect("an error to show");
        assert!(
            problem.contains("bad.xml:2:") && problem.contains("radius"),
            "the error says where: {problem}"
        );
        assert_eq!(
            startup.path, None,
            "untitled: a save must not go to the bad file"
        );
        let seed = scene::read_file(&seed_path()).expect("the seed scene loads");
        assert_eq!(startup.scene, seed, "the default scene behind the error");

        let app = RaylabApp::new(startup.scene, startup.path).with_message(problem);
        let mut h = harness(app);
        step_shown(&mut h);
        assert!(
            h.query_by_label_contains("Cannot open the scene").is_some(),
            "the error is in the window"
        );
        h.get_by_label("OK").click();
        step_shown(&mut h);
        assert!(h.query_by_label_contains("Cannot open the scene").is_none());
    }

    #[test]
    fn a_missing_file_is_explained_the_same_way_and_a_good_one_opens_as_itself() {
        let missing = Path::new("/nonexistent/raylab/missing.xml");
        let startup = open_or_explain(missing, &seed_path());
        assert!(
            startup.problem.is_some_and(|p| p.contains("missing.xml")),
            "the missing file is named"
        );
        let good = open_or_explain(&seed_path(), &seed_path());
        assert_eq!((good.path, good.problem), (Some(seed_path()), None));
    }
}
