//! The open document: the edited scene and render settings, the file they
//! belong to, what was last saved, and the undo history.

use super::history::History;
use renderer::integrator::Integrator;
use renderer::integrator::adaptive::Adaptive;
use renderer::{Method, RenderOptions, Sampling};
use scene::Scene;
use std::path::{Path, PathBuf};

/// Integrator settings the user edits alongside the scene (undoable, not saved in the file).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Whitted or path tracing.
    pub integrator: Integrator,
    /// Lecture or robust intersection formulas.
    pub method: Method,
    /// Maximum reflection/refraction bounces.
    pub max_depth: u32,
    /// Whitted: bounces whose weight in the pixel is below this are not traced.
    pub min_weight: f32,
    /// Independent or Sobol samples.
    pub sampling: Sampling,
    /// Adaptive sampling, when on.
    pub adaptive: Option<Adaptive>,
    /// Stop refining at this many samples per pixel; `None` refines until stopped.
    pub target_spp: Option<u32>,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            integrator: Integrator::Whitted,
            method: Method::Robust,
            max_depth: RenderOptions::default().max_depth,
            min_weight: RenderOptions::default().min_weight,
            sampling: Sampling::Independent,
            adaptive: None,
            target_spp: Some(64),
        }
    }
}

impl RenderSettings {
    /// The integrator options these settings ask for.
    pub fn options(&self) -> RenderOptions {
        RenderOptions {
            integrator: self.integrator,
            method: self.method,
            max_depth: self.max_depth,
            min_weight: self.min_weight,
            sampling: self.sampling,
            adaptive: self.adaptive,
            ..RenderOptions::default()
        }
    }
}

/// Everything an edit can change: what undo and redo step through.
#[derive(Clone, Debug, PartialEq)]
pub struct EditState {
    /// The scene as edited.
    pub scene: Scene,
    /// The integrator settings.
    pub render: RenderSettings,
}

/// A scene open in the window.
pub struct Document {
    /// The live, edited state.
    pub state: EditState,
    /// The file the scene is saved to; `None` until it is saved.
    pub path: Option<PathBuf>,
    /// The scene as last loaded or saved, to tell unsaved changes; `None`
    /// for a recovered scene, which is on disk nowhere but the recovery file.
    saved: Option<Scene>,
    /// Undo/redo over [`EditState`].
    pub history: History<EditState>,
    /// The model file (.gltf, .glb) an untitled scene was opened from: it
    /// names the document and is where Save As suggests a scene beside it.
    pub origin: Option<PathBuf>,
}

impl Document {
    /// A document showing `scene`, loaded from `path` (or new when `None`).
    pub fn new(scene: Scene, path: Option<PathBuf>, render: RenderSettings) -> Self {
        let state = EditState { scene, render };
        Self {
            history: History::new(&state),
            saved: Some(state.scene.clone()),
            state,
            path,
            origin: None,
        }
    }

    /// A document restored from a recovery file: `scene`, to be saved to
    /// `path`, marked unsaved until it is saved.
    pub fn recovered(scene: Scene, path: Option<PathBuf>, render: RenderSettings) -> Self {
        Self {
            saved: None,
            ..Self::new(scene, path, render)
        }
    }

    /// Reads the scene file (or model file) at `path`.
    pub fn open(path: &Path, render: RenderSettings) -> Result<Self, scene::SceneError> {
        let scene = scene::read_any(path)?;
        Ok(Self::new(scene, Self::scene_path(path), render).read_from(path))
    }

    /// This document, read from `path`: a model file becomes its origin.
    pub fn read_from(mut self, path: &Path) -> Self {
        if scene::is_model_path(path) {
            self.origin = Some(path.to_path_buf());
        }
        self
    }

    /// The file the document is saved to, else the model it was opened from.
    fn named_by(&self) -> Option<&Path> {
        self.path.as_deref().or(self.origin.as_deref())
    }

    /// The file name Save As suggests: the scene's own, or the model's with
    /// `.xml` (`Duck.gltf` → `Duck.xml`), or `untitled.xml`.
    pub fn scene_file_name(&self) -> String {
        let name = self.display_name();
        if name.ends_with(".xml") {
            return name;
        }
        let stem = Path::new(&name)
            .file_stem()
            .map_or_else(|| name.clone(), |s| s.to_string_lossy().into_owned());
        format!("{stem}.xml")
    }

    /// The folder the document's file, or its model, is in.
    pub fn folder(&self) -> Option<&Path> {
        self.named_by().and_then(Path::parent)
    }

    /// The file a document read from `path` saves to: the path itself for a
    /// scene file; none for a model file (.gltf, .glb), which raylab never
    /// overwrites — saving it asks where to write a new scene.
    pub fn scene_path(path: &Path) -> Option<PathBuf> {
        (!scene::is_model_path(path)).then(|| path.to_path_buf())
    }

    /// True when the scene differs from the file (undoing back to the saved
    /// state clears it).
    pub fn is_modified(&self) -> bool {
        self.saved.as_ref() != Some(&self.state.scene)
    }

    /// Writes the scene to `path` atomically, keeping the file it replaces
    /// as `path.bak` (see [`crate::io::atomic_file`]), and makes it the
    /// document's file. A failed save changes nothing: not the file, not
    /// the document (still unsaved, still pointing where it did).
    pub fn save_as(&mut self, path: &Path) -> std::io::Result<()> {
        let mut scene = self.state.scene.clone();
        rebase_file_sources(&mut scene, path);
        let text = scene::write_string(&scene);
        crate::io::atomic_file::replace_keeping_backup(path, text.as_bytes())?;
        self.state.scene = scene;
        self.path = Some(path.to_path_buf());
        self.saved = Some(self.state.scene.clone());
        Ok(())
    }

    /// The file name shown in the title and in default screenshot names.
    pub fn display_name(&self) -> String {
        self.named_by()
            .and_then(Path::file_name)
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "untitled".to_owned())
    }

    /// The window title: file name, folder, and `•` for unsaved changes.
    pub fn title(&self) -> String {
        let mark = if self.is_modified() { "• " } else { "" };
        let folder = self
            .folder()
            .map(|p| format!(" — {}", p.display()))
            .unwrap_or_default();
        format!("{mark}{}{folder} — raylab", self.display_name())
    }
}

/// Points every `<mesh src>` at its model file, and the `<sky map>` at its
/// image, from the folder `scene_path` is in: just the file name when the
/// file lies in that folder, else its absolute path (so a scene saved
/// elsewhere, or autosaved to the recovery folder, still finds them). A
/// built-in map (`raylab:studio`) is no file and keeps its name.
pub(in crate::gui) fn rebase_file_sources(scene: &mut Scene, scene_path: &Path) {
    let folder = scene_path.parent().and_then(|f| {
        std::fs::canonicalize(if f.as_os_str().is_empty() {
            Path::new(".")
        } else {
            f
        })
        .ok()
    });
    let rebased = |file: &Path| -> Option<String> {
        let file = std::fs::canonicalize(file).ok()?;
        Some(match (file.parent(), file.file_name(), &folder) {
            (Some(dir), Some(name), Some(folder)) if dir == folder => {
                name.to_string_lossy().into_owned()
            }
            _ => file.display().to_string(),
        })
    };
    for object in &mut scene.objects {
        if let scene::Shape::Mesh { source, .. } = &mut object.shape
            && let Some(src) = rebased(&source.model.path)
        {
            source.src = src;
        }
    }
    if let Some(map) = scene.sky.as_mut().and_then(|sky| sky.map.as_mut())
        && map.src != scene::STUDIO_MAP
        && let Some(src) = rebased(&map.image.path)
    {
        map.src = src;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saving_elsewhere_points_mesh_sources_at_their_models() {
        let dir = tempfile::tempdir().expect("tempdir");
        let models = dir.path().join("models");
        std::fs::create_dir(&models).expect("mkdir");
        let model_path = models.join("box.gltf");
        std::fs::write(&model_path, "{}").expect("write");
        let mut model = scene::ModelFile::default();
        model.path = model_path.clone();
        let mut scene = Scene::default();
        scene.objects.push(scene::Object {
            name: None,
            shape: scene::Shape::Mesh {
                source: scene::MeshSource {
                    src: "box.gltf".into(),
                    model: std::sync::Arc::new(model),
                },
                translate: None,
                rotate: glam::Vec3::ZERO,
                scale: glam::Vec3::ONE,
            },
            material: None,
            params: Default::default(),
        });
        let src = |scene: &Scene| match &scene.objects[0].shape {
            scene::Shape::Mesh { source, .. } => source.src.clone(),
            _ => unreachable!(),
        };
        // Beside the model: its file name.
        rebase_file_sources(&mut scene, &models.join("scene.xml"));
        assert_eq!(src(&scene), "box.gltf");
        // In another folder: the model's absolute path, which still opens.
        rebase_file_sources(&mut scene, &dir.path().join("scene.xml"));
        let absolute = PathBuf::from(src(&scene));
        assert!(absolute.is_absolute(), "{absolute:?}");
        assert_eq!(
            std::fs::canonicalize(absolute).expect("exists"),
            std::fs::canonicalize(model_path).expect("exists")
        );
    }

    #[test]
    fn saving_then_reopening_gives_the_same_scene_and_clears_the_mark() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("s.xml");
        let mut doc = Document::new(Scene::default(), None, RenderSettings::default());
        doc.state.scene.camera.theta_deg = 33.0;
        assert!(doc.is_modified());
        doc.save_as(&path).expect("saved");
        assert!(!doc.is_modified());
        assert!(doc.title().starts_with("s.xml"));
        let reopened = Document::open(&path, RenderSettings::default()).expect("reopens");
        assert_eq!(reopened.state.scene, doc.state.scene);
    }

    #[test]
    fn undoing_back_to_the_saved_scene_clears_the_unsaved_mark() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("s.xml");
        let mut doc = Document::new(Scene::default(), None, RenderSettings::default());
        doc.save_as(&path).expect("saved");
        doc.state.scene.camera.theta_deg = 10.0;
        assert!(doc.title().starts_with("• "));
        doc.history.undo(&mut doc.state);
        assert!(!doc.is_modified());
    }

    #[test]
    fn a_failed_save_keeps_the_old_file_and_the_unsaved_mark() {
        let dir = tempfile::tempdir().expect("temp dir");
        let missing = dir.path().join("no-such-folder").join("s.xml");
        let mut doc = Document::new(Scene::default(), None, RenderSettings::default());
        doc.state.scene.camera.theta_deg = 12.0;
        assert!(doc.save_as(&missing).is_err());
        assert!(doc.is_modified());
        assert_eq!(doc.path, None);
    }

    #[test]
    fn saving_elsewhere_points_the_sky_map_at_its_file_and_keeps_the_studio() {
        let dir = tempfile::tempdir().expect("tempdir");
        let maps = dir.path().join("maps");
        std::fs::create_dir(&maps).expect("mkdir");
        let map_path = maps.join("sky.exr");
        std::fs::write(&map_path, "not read here").expect("write");
        let image = scene::EnvImage {
            path: map_path.clone(),
            width: 2,
            height: 2,
            texels: vec![[1.0; 3]; 4],
        };
        let mut scene = Scene {
            sky: Some(scene::Sky {
                color: glam::Vec3::ONE,
                map: Some(scene::SkyMap {
                    src: "maps/sky.exr".into(),
                    image: std::sync::Arc::new(image),
                }),
                rotate: glam::Vec3::ZERO,
                strength: 1.0,
            }),
            ..Scene::default()
        };
        let src = |scene: &Scene| {
            scene
                .sky
                .as_ref()
                .and_then(|s| s.map.as_ref())
                .map(|m| m.src.clone())
        };
        rebase_file_sources(&mut scene, &maps.join("scene.xml"));
        assert_eq!(src(&scene).as_deref(), Some("sky.exr"));
        rebase_file_sources(&mut scene, &dir.path().join("other").join("scene.xml"));
        let absolute = std::fs::canonicalize(&map_path).expect("exists");
        assert_eq!(src(&scene), Some(absolute.display().to_string()));
        let mut studio = Scene {
            sky: Some(scene::Sky::studio()),
            ..Scene::default()
        };
        rebase_file_sources(&mut studio, &dir.path().join("scene.xml"));
        assert_eq!(src(&studio).as_deref(), Some(scene::STUDIO_MAP));
    }

    #[test]
    fn a_model_opened_alone_names_the_window_and_suggests_a_scene_beside_it() {
        let doc = Document::new(Scene::default(), None, RenderSettings::default())
            .read_from(Path::new("/models/duck/Duck.gltf"));
        assert_eq!(doc.path, None, "a model file is never saved over");
        assert_eq!(doc.display_name(), "Duck.gltf");
        assert_eq!(doc.title(), "Duck.gltf — /models/duck — raylab");
        assert_eq!(doc.scene_file_name(), "Duck.xml");
        assert_eq!(doc.folder(), Some(Path::new("/models/duck")));
        let untitled = Document::new(Scene::default(), None, RenderSettings::default());
        assert_eq!(
            (untitled.display_name(), untitled.scene_file_name()),
            ("untitled".to_owned(), "untitled.xml".to_owned())
        );
        let scene = Document::new(Scene::default(), None, RenderSettings::default())
            .read_from(Path::new("/scenes/seed.xml"));
        assert_eq!(
            scene.origin, None,
            "a scene file is its own path, not an origin"
        );
    }
}
