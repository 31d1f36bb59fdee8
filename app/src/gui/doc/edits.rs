//! Structural edits of a scene: adding, duplicating and deleting objects and
//! lights. New objects go where the camera looks, resting on the floor,
//! beside (not inside) what is already there.

use glam::Vec3;
use scene::layout::{self, Aabb};
use scene::{Light, LightKind, Object, ResolvedScene, Scene, Shape, Sky};

/// What is selected in the scene panel (and highlighted in the list).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Selection {
    /// Nothing.
    #[default]
    None,
    /// The object at this index of `scene.objects`.
    Object(usize),
    /// The light at this index of `scene.lights`.
    Light(usize),
    /// The sky (`scene.sky`).
    Sky,
}

impl Selection {
    /// The selection, or `None` if it points past the end of the scene's lists.
    pub fn valid_in(self, scene: &Scene) -> Selection {
        match self {
            Selection::Object(i) if i < scene.objects.len() => self,
            Selection::Light(i) if i < scene.lights.len() => self,
            Selection::Sky if scene.sky.is_some() => self,
            _ => Selection::None,
        }
    }
}

/// A change to the scene's structure, asked for by a panel or a menu.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Add a shape of this tag with default parameters.
    AddObject(&'static str),
    /// Add a light of this kind with default parameters.
    AddLight(LightKind),
    /// Add a sky of a constant colour (when the scene has none).
    AddSky,
    /// Ask for an environment map file for the sky (a file dialog, not an
    /// edit: the app carries it out).
    ChooseSkyMap,
    /// Duplicate the selection.
    Duplicate,
    /// Delete the selection.
    Delete,
}

/// The colour of a sky added from the menu: a clear day's blue.
const DEFAULT_SKY: Vec3 = Vec3::new(0.5, 0.7, 1.0);

/// Gap left between a new object and its neighbours.
const GAP: f32 = 0.3;

/// Applies `action` to `scene`, given its prepared form `resolved` (for the
/// camera and the objects' places); returns the new selection.
pub fn apply(
    action: Action,
    scene: &mut Scene,
    resolved: Option<&ResolvedScene>,
    selection: Selection,
) -> Selection {
    match action {
        Action::AddObject(tag) => {
            let Some(shape) = Shape::default_for_tag(tag) else {
                return selection;
            };
            let shape = match resolved {
                Some(r) => place_in_view(shape, r, floor_height(scene)),
                None => shape,
            };
            scene.objects.push(Object {
                name: None,
                shape,
                material: None,
                params: Default::default(),
            });
            Selection::Object(scene.objects.len() - 1)
        }
        Action::AddLight(kind) => {
            if scene.lights.is_empty()
                && let Some(r) = resolved
            {
                // Keep the picture's lighting: the default lights become real ones.
                scene.lights = r.lights.clone();
            }
            scene.lights.push(Light {
                name: None,
                color: scene::defaults::LIGHT_COLOR,
                intensity: scene::defaults::light_intensity(&kind),
                kind,
            });
            Selection::Light(scene.lights.len() - 1)
        }
        Action::AddSky => {
            scene.sky.get_or_insert_with(|| Sky::constant(DEFAULT_SKY));
            Selection::Sky
        }
        Action::ChooseSkyMap => selection,
        Action::Duplicate => match selection.valid_in(scene) {
            Selection::Object(i) => {
                let mut copy = scene.objects[i].clone();
                copy.name = copy.name.map(|n| format!("{n} copy"));
                let step = resolved
                    .and_then(|r| r.objects.get(i))
                    .and_then(|o| layout::bounds(&o.geometry))
                    .map_or(1.0, |b| b.max.x - b.min.x + GAP);
                copy.shape = translated(copy.shape, Vec3::X * step);
                scene.objects.insert(i + 1, copy);
                Selection::Object(i + 1)
            }
            Selection::Light(i) => {
                let copy = scene.lights[i].clone();
                scene.lights.insert(i + 1, copy);
                Selection::Light(i + 1)
            }
            Selection::Sky | Selection::None => selection.valid_in(scene),
        },
        Action::Delete => {
            match selection.valid_in(scene) {
                Selection::Object(i) => {
                    scene.objects.remove(i);
                }
                Selection::Light(i) => {
                    scene.lights.remove(i);
                }
                Selection::Sky => scene.sky = None,
                Selection::None => {}
            }
            Selection::None
        }
    }
}

/// The floor's height (0 without a floor).
fn floor_height(scene: &Scene) -> f32 {
    scene
        .objects
        .iter()
        .find_map(|o| match o.shape {
            Shape::Floor { y } => Some(y),
            _ => None,
        })
        .unwrap_or(0.0)
}

/// `shape` moved by `by`: placed anchors and triangle vertices move,
/// automatic anchors stay automatic, infinite planes stay put.
fn translated(mut shape: Shape, by: Vec3) -> Shape {
    if let Shape::Triangle { t0, t1, t2 } = &mut shape {
        for v in [t0, t1, t2] {
            *v += by;
        }
    } else if let Some(Some(anchor)) = shape.anchor_mut() {
        *anchor += by;
    }
    shape
}

/// `shape` with its anchor set so that it rests on the floor where the
/// camera's centre ray meets it, moved sideways (along the camera's r) until
/// it overlaps no other finite object. Shapes without an anchor are returned as is.
pub fn place_in_view(shape: Shape, resolved: &ResolvedScene, floor_y: f32) -> Shape {
    if !layout::is_unplaced(&shape) {
        return shape;
    }
    let Some(footprint) = layout::bounds(&layout::geometry_at(&shape, Vec3::ZERO)) else {
        return shape;
    };
    let camera = &resolved.camera;
    let t = camera.toward.normalize_or(Vec3::NEG_Z);
    let others: Vec<Aabb> = resolved
        .objects
        .iter()
        .filter_map(|o| layout::bounds(&o.geometry))
        .collect();
    let focus = others.iter().copied().fold(Aabb::EMPTY, Aabb::union);
    // Where the centre ray meets the floor, or the depth of the scene's centre.
    let along = if t.y < -1e-3 {
        (floor_y - camera.eye.y) / t.y
    } else if !focus.is_empty() {
        (focus.center() - camera.eye).dot(t).max(1.0)
    } else {
        5.0
    };
    let spot = camera.eye + t * along;
    let mut anchor = Vec3::new(
        spot.x - footprint.center().x,
        floor_y - footprint.min.y,
        spot.z - footprint.center().z,
    );
    let right = Vec3::new(-t.z, 0.0, t.x).normalize_or(Vec3::X);
    let width = (footprint.max - footprint.min).max_element();
    for _ in 0..64 {
        let moved = Aabb {
            min: footprint.min + anchor,
            max: footprint.max + anchor,
        };
        if !others.iter().any(|o| overlaps(o, &moved)) {
            break;
        }
        anchor += right * (width + GAP) * 0.5;
    }
    with_anchor(shape, anchor)
}

/// True when two boxes share interior points.
fn overlaps(a: &Aabb, b: &Aabb) -> bool {
    a.min.cmplt(b.max).all() && b.min.cmplt(a.max).all()
}

/// `shape` with its anchor (centre or base) fixed at `anchor`.
fn with_anchor(mut shape: Shape, anchor: Vec3) -> Shape {
    if let Some(slot) = shape.anchor_mut() {
        *slot = Some(anchor);
    }
    shape
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed() -> Scene {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
        scene::read_file(&path).expect("the seed scene loads")
    }

    #[test]
    fn an_added_sphere_rests_on_the_floor_in_view_and_overlaps_nothing() {
        let mut s = seed();
        let resolved = scene::resolve(&s).expect("valid");
        let selection = apply(
            Action::AddObject("sphere"),
            &mut s,
            Some(&resolved),
            Selection::None,
        );
        assert_eq!(selection, Selection::Object(4));
        let after = scene::resolve(&s).expect("valid");
        let new = layout::bounds(&after.objects[4].geometry).expect("finite");
        assert!(
            (new.min.y - 0.0).abs() < 1e-4,
            "rests on the floor: {new:?}"
        );
        for (old, o) in resolved.objects.iter().zip(&after.objects) {
            assert_eq!(old.geometry, o.geometry, "nothing else moved");
            if let Some(b) = layout::bounds(&o.geometry) {
                assert!(!overlaps(&b, &new), "{} overlaps the new sphere", o.name);
            }
        }
        // In view: the centre projects inside the view volume of the resolved camera.
        let camera = renderer::Camera::new(&resolved.camera).expect("camera");
        let v = (new.center() - camera.p0).normalize();
        let forward = v.dot(camera.t.normalize());
        assert!(
            forward > (resolved.camera.theta_deg.to_radians() * 1.5).cos(),
            "{forward}"
        );
    }

    #[test]
    fn adding_the_first_light_keeps_the_default_lights() {
        let mut s = seed();
        let resolved = scene::resolve(&s).expect("valid");
        assert!(s.lights.is_empty());
        apply(
            Action::AddLight(LightKind::Ambient),
            &mut s,
            Some(&resolved),
            Selection::None,
        );
        assert_eq!(s.lights.len(), resolved.lights.len() + 1);
    }

    #[test]
    fn duplicate_then_delete_restores_the_scene() {
        let mut s = seed();
        let before = s.clone();
        let resolved = scene::resolve(&s).expect("valid");
        let copy = apply(
            Action::Duplicate,
            &mut s,
            Some(&resolved),
            Selection::Object(1),
        );
        assert_eq!(copy, Selection::Object(2));
        assert_eq!(s.objects[2].shape.tag(), "sphere");
        assert_eq!(apply(Action::Delete, &mut s, None, copy), Selection::None);
        assert_eq!(s, before);
    }
}
