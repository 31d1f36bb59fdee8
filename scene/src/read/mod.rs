//! The XML scene reader: the document's structure (one `<scene>` root whose
//! children are flat elements), leniently accepting unclosed child tags as in
//! the lecture's snippets, and exact `line:column` errors.

mod camera;
mod element;
mod file;
mod objects;
mod position;
mod values;

use camera::{CAMERA_ATTRS, LIGHT_ATTRS, SKY_ATTRS, VIEW_ATTRS};
pub use file::read_file;
use objects::{MATERIAL_ATTRS, shape_attrs};

use crate::SceneError;
use crate::gltf::load_model;
use crate::model::model_file::ModelFile;
use crate::model::{BaseMaterial, Scene};
use crate::suggest::suggest;
use element::Element;
use position::Locator;
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Parses scene XML; `file` labels error messages.
///
/// Every problem is a [`SceneError`] at the 1-based line and column (in
/// characters) of the offending thing: an attribute's value, an element's `<`,
/// or where the XML stops being well-formed.
pub fn read_str(text: &str, file: &str) -> Result<Scene, SceneError> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    let loc = Locator { text: body, file };
    let mut reader = Reader::from_str(body);
    let config = reader.config_mut();
    config.check_end_names = false;
    config.allow_unmatched_ends = true;
    let mut doc = Document {
        loc: &loc,
        scene: Scene::default(),
        phase: Phase::Before,
        camera_at: None,
        sky_at: None,
        view_at: None,
        material_names: Vec::new(),
        material_refs: Vec::new(),
        dir: Path::new(file)
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default(),
        models: HashMap::new(),
    };
    loop {
        let event = reader.read_event().map_err(|e| {
            let at = usize::try_from(reader.error_position()).unwrap_or(usize::MAX);
            loc.error(at, format!("malformed XML: {e}"))
        })?;
        let end = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
        match event {
            Event::Start(start) => doc.start(&start, false)?,
            Event::Empty(start) => doc.start(&start, true)?,
            Event::End(end_tag) => doc.end(end_tag.name().0)?,
            Event::Text(t) => doc.text(&t, end)?,
            Event::CData(t) => doc.text(&t, end)?,
            Event::GeneralRef(r) => {
                let at = loc.offset_of(&r).map_or(end, |o| o.saturating_sub(1));
                return Err(doc.unexpected_text(at, &format!("&{};", &*r)));
            }
            Event::Decl(_) | Event::PI(_) | Event::Comment(_) | Event::DocType(_) => {}
            Event::Eof => return doc.finish(),
        }
    }
}

/// Where the reader is in the document.
#[derive(Clone, Copy, PartialEq)]
enum Phase {
    /// Before the `<scene>` start tag.
    Before,
    /// Inside `<scene>`, which starts at this offset.
    Inside(usize),
    /// After `</scene>` (or `<scene/>`).
    After,
}

/// The children `<scene>` may have.
const CHILDREN: [&str; 14] = [
    "camera", "light", "sky", "view", "material", "sphere", "box", "cylinder", "cone", "torus",
    "triangle", "plane", "floor", "mesh",
];

/// The reader's state while walking the events.
struct Document<'a> {
    loc: &'a Locator<'a>,
    scene: Scene,
    phase: Phase,
    /// Offset of the `<camera>` seen so far.
    camera_at: Option<usize>,
    /// Offset of the `<sky>` seen so far.
    sky_at: Option<usize>,
    /// Offset of the `<view>` seen so far.
    view_at: Option<usize>,
    /// Names of the `<material>`s so far, with their name offsets.
    material_names: Vec<(String, usize)>,
    /// Material names used by shapes, with their value offsets (checked at the end).
    material_refs: Vec<(String, usize)>,
    /// The folder `<mesh src>` paths are relative to: the scene file's.
    dir: PathBuf,
    /// Model files loaded so far, by `src`, so that a file named twice is loaded once.
    models: HashMap<String, Arc<ModelFile>>,
}

impl Document<'_> {
    /// A start tag (`empty` for `<x/>`).
    fn start(&mut self, start: &BytesStart<'_>, empty: bool) -> Result<(), SceneError> {
        let tag = start.name().0;
        let at = self.loc.offset_of(tag).unwrap_or(0).saturating_sub(1);
        match (self.phase, tag) {
            (Phase::Before, "scene") => {
                Element::parse(start, self.loc, &[])?;
                self.phase = if empty {
                    Phase::After
                } else {
                    Phase::Inside(at)
                };
                Ok(())
            }
            (Phase::Before, _) => Err(self.loc.error(
                at,
                format!("expected the root element <scene>, found <{tag}>"),
            )),
            (Phase::Inside(_), "scene") => {
                Err(self.loc.error(at, "<scene> cannot contain another <scene>"))
            }
            (Phase::Inside(_), _) => self.child(start, at),
            (Phase::After, _) => Err(self.loc.error(
                at,
                format!("unexpected <{tag}> after </scene>; everything belongs inside <scene>"),
            )),
        }
    }

    /// A child of `<scene>` starting at `at`.
    fn child(&mut self, start: &BytesStart<'_>, at: usize) -> Result<(), SceneError> {
        let loc = self.loc;
        let tag = start.name().0;
        match tag {
            "camera" => {
                only_one(loc, "camera", &mut self.camera_at, at)?;
                let el = Element::parse(start, loc, &CAMERA_ATTRS)?;
                self.scene.camera = camera::camera(&el)?;
            }
            "light" => {
                let el = Element::parse(start, loc, &LIGHT_ATTRS)?;
                self.scene.lights.push(camera::light(&el)?);
            }
            "sky" => {
                only_one(loc, "sky", &mut self.sky_at, at)?;
                let el = Element::parse(start, loc, &SKY_ATTRS)?;
                self.scene.sky = Some(camera::sky(&el, &self.dir)?);
            }
            "view" => {
                only_one(loc, "view", &mut self.view_at, at)?;
                let el = Element::parse(start, loc, &VIEW_ATTRS)?;
                self.scene.view = camera::view(&el)?;
            }
            "material" => {
                let el = Element::parse(start, loc, &MATERIAL_ATTRS)?;
                let def = objects::material(&el, &self.material_names)?;
                let name_at = el.raw("name").map_or(at, |(_, a)| a);
                self.material_names.push((def.name.clone(), name_at));
                self.scene.materials.push(def);
            }
            _ if shape_attrs(tag).is_some() => {
                let el = Element::parse(start, loc, &objects::allowed_on_shape(tag))?;
                let object = if tag == "mesh" {
                    objects::mesh(&el, |src| self.load_model(src))?
                } else {
                    objects::object(&el)?
                };
                if let Some((name, value_at)) = el.raw("material") {
                    self.material_refs.push((name.to_owned(), value_at));
                }
                self.scene.objects.push(object);
            }
            _ => {
                return Err(loc.error(
                    at,
                    format!(
                        "unknown element <{tag}>{} (expected one of: {})",
                        did_you_mean_tag(tag, "<"),
                        CHILDREN.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The model file `src` names (relative to the scene file), loaded once.
    fn load_model(&mut self, src: &str) -> Result<Arc<ModelFile>, String> {
        if let Some(model) = self.models.get(src) {
            return Ok(model.clone());
        }
        if let Some((scheme, _)) = src.split_once("://")
            && scheme != "file"
        {
            return Err(format!(
                "\"{scheme}://…\" is a network address; raylab never fetches files from the \
                 network (download the model and name the file)"
            ));
        }
        let model = Arc::new(load_model(&self.dir.join(src)).map_err(|e| e.to_string())?);
        self.models.insert(src.to_owned(), model.clone());
        Ok(model)
    }

    /// An end tag `</name>`.
    fn end(&mut self, name: &str) -> Result<(), SceneError> {
        let at = self.loc.offset_of(name).unwrap_or(0).saturating_sub(2);
        match self.phase {
            Phase::Inside(_) if name == "scene" => {
                self.phase = Phase::After;
                Ok(())
            }
            Phase::Inside(_) if CHILDREN.contains(&name) => Ok(()),
            Phase::Inside(_) => Err(self.loc.error(
                at,
                format!(
                    "unexpected end tag </{name}>{}",
                    did_you_mean_tag(name, "</")
                ),
            )),
            Phase::Before => Err(self
                .loc
                .error(at, format!("unexpected end tag </{name}> before <scene>"))),
            Phase::After => Err(self
                .loc
                .error(at, format!("unexpected end tag </{name}> after </scene>"))),
        }
    }

    /// Character data: only whitespace is allowed anywhere.
    fn text(&self, text: &str, end: usize) -> Result<(), SceneError> {
        match text.find(|c: char| !c.is_whitespace()) {
            None => Ok(()),
            Some(i) => {
                let at = self.loc.offset_of(text).map_or(end, |o| o + i);
                Err(self.unexpected_text(at, text.trim()))
            }
        }
    }

    /// The error for non-whitespace text at `at`.
    fn unexpected_text(&self, at: usize, text: &str) -> SceneError {
        let shown: String = text.chars().take(24).collect();
        let shown = if shown.len() < text.len() {
            format!("{shown}…")
        } else {
            shown
        };
        let place = match self.phase {
            Phase::Before => "before <scene>",
            Phase::Inside(_) => "inside <scene>; a scene holds only elements such as <sphere/>",
            Phase::After => "after </scene>",
        };
        self.loc
            .error(at, format!("unexpected text {shown:?} {place}"))
    }

    /// End of input: the scene must be closed and every material name known.
    fn finish(self) -> Result<Scene, SceneError> {
        let eof = self.loc.text.len();
        match self.phase {
            Phase::Before => {
                return Err(self
                    .loc
                    .error(eof, "expected a <scene> element, found end of file"));
            }
            Phase::Inside(at) => {
                return Err(self.loc.error(
                    eof,
                    format!(
                        "unexpected end of file: expected </scene> to close the <scene> at {}",
                        self.loc.describe(at)
                    ),
                ));
            }
            Phase::After => {}
        }
        for (name, at) in &self.material_refs {
            let defined = self.material_names.iter().any(|(n, _)| n == name);
            if BaseMaterial::from_name(name).is_none() && !defined {
                let names = BaseMaterial::ALL
                    .map(BaseMaterial::name)
                    .into_iter()
                    .chain(self.material_names.iter().map(|(n, _)| n.as_str()));
                return Err(self.loc.error(
                    *at,
                    format!(
                        "unknown material {name:?}{} (expected a built-in material ({}) or the \
                         name of a <material> in this file)",
                        crate::suggest::did_you_mean(name, names),
                        objects::builtin_names()
                    ),
                ));
            }
        }
        Ok(self.scene)
    }
}

/// `; did you mean <x>?` (`open` is `<` or `</`) for a misspelt element name.
/// Records that the element `<tag>` a scene may hold once starts at `at`;
/// an error naming where the first one is when `first` already holds one.
fn only_one(
    loc: &Locator,
    tag: &str,
    first: &mut Option<usize>,
    at: usize,
) -> Result<(), SceneError> {
    if let Some(first) = *first {
        return Err(loc.error(
            at,
            format!(
                "a scene has at most one <{tag}>; the first is at {}",
                loc.describe(first)
            ),
        ));
    }
    *first = Some(at);
    Ok(())
}

fn did_you_mean_tag(tag: &str, open: &str) -> String {
    suggest(tag, CHILDREN.iter().copied().chain(["scene"]))
        .map(|s| format!("; did you mean {open}{s}>?"))
        .unwrap_or_default()
}
