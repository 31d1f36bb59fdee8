//! The name of an edit, for Edit › Undo and Redo ("Undo θ", "Undo orbit",
//! "Undo colour of sphere 2"): read from what differs between the state
//! before and after it, so that no edit has to announce itself.

use super::document::EditState;
use scene::{Camera, Object};

/// What changed from `before` to `after`, in a few words. `camera_move`
/// names the camera gesture of the image ("orbit", "pan", "dolly"), when a
/// drag or the wheel moved the eye.
pub fn describe(before: &EditState, after: &EditState, camera_move: Option<&str>) -> String {
    let (a, b) = (&before.scene, &after.scene);
    if a.camera != b.camera {
        return camera_change(&a.camera, &b.camera, camera_move);
    }
    if a.objects != b.objects {
        return objects_change(&a.objects, &b.objects);
    }
    if a.lights != b.lights {
        return match (a.lights.len(), b.lights.len()) {
            (n, m) if m > n => "add light".into(),
            (n, m) if m < n => "delete light".into(),
            _ => "light".into(),
        };
    }
    if a.sky != b.sky {
        return "sky".into();
    }
    if a.view != b.view {
        return "view".into();
    }
    if a.materials != b.materials {
        return "materials".into();
    }
    if before.render != after.render {
        return "render settings".into();
    }
    "edit".into()
}

/// The camera's change: a single field by the lecture's symbol, or the
/// image gesture that moved it.
fn camera_change(a: &Camera, b: &Camera, camera_move: Option<&str>) -> String {
    let changed: Vec<&str> = [
        (a.eye != b.eye, "P0"),
        (a.toward != b.toward, "t"),
        (a.up != b.up, "u"),
        (a.theta_deg != b.theta_deg, "θ"),
        (a.d != b.d, "d"),
        (a.width != b.width || a.height != b.height, "image size"),
    ]
    .into_iter()
    .filter_map(|(differs, name)| differs.then_some(name))
    .collect();
    match (changed.as_slice(), camera_move) {
        ([one], None) => (*one).into(),
        (_, Some(gesture)) if a.eye != b.eye || a.toward != b.toward => gesture.into(),
        ([one], Some(_)) => (*one).into(),
        _ => "camera".into(),
    }
}

/// The objects' change: one added or deleted, or what changed of the first
/// object that differs.
fn objects_change(a: &[Object], b: &[Object]) -> String {
    if b.len() > a.len() {
        return format!("add {}", b[b.len() - 1].shape.tag());
    }
    if b.len() < a.len() {
        return "delete".into();
    }
    let Some((k, (x, y))) = a.iter().zip(b).enumerate().find(|(_, (x, y))| x != y) else {
        return "objects".into();
    };
    let name = y
        .name
        .clone()
        .unwrap_or_else(|| format!("{} {}", y.shape.tag(), k + 1));
    let what = if x.name != y.name {
        return format!("rename {name}");
    } else if x.shape != y.shape {
        "shape of"
    } else if x.material != y.material {
        "material of"
    } else if x.params.color != y.params.color {
        "colour of"
    } else {
        "material of"
    };
    format!("{what} {name}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gui::doc::document::RenderSettings;
    use glam::Vec3;

    fn state() -> EditState {
        let scene = scene::read_str(
            "<scene><camera eye=\"0 1 5\" toward=\"0 0 -1\"/>\
             <sphere center=\"0 1 0\" radius=\"1\"/><box name=\"crate\"/>\
             <light type=\"point\" position=\"0 5 0\"/></scene>",
            "test.xml",
        )
        .expect("a scene");
        EditState {
            scene,
            render: RenderSettings::default(),
        }
    }

    #[test]
    fn an_edit_is_named_by_the_lecture_symbol_or_the_object_it_changed() {
        let before = state();
        let named = |edit: &dyn Fn(&mut EditState), gesture: Option<&str>| {
            let mut after = before.clone();
            edit(&mut after);
            describe(&before, &after, gesture)
        };
        assert_eq!(named(&|s| s.scene.camera.theta_deg = 30.0, None), "θ");
        assert_eq!(named(&|s| s.scene.camera.d = Some(2.0), None), "d");
        let orbit = |s: &mut EditState| {
            s.scene.camera.eye = Some(Vec3::new(1.0, 1.0, 5.0));
            s.scene.camera.toward = Some(Vec3::new(-0.2, 0.0, -1.0));
        };
        assert_eq!(named(&orbit, Some("orbit")), "orbit");
        assert_eq!(named(&orbit, None), "camera");
        assert_eq!(
            named(&|s| s.scene.objects[0].params.color = Some(Vec3::X), None),
            "colour of sphere 1"
        );
        assert_eq!(
            named(
                &|s| s.scene.objects[1].material = Some("mirror".into()),
                None
            ),
            "material of crate"
        );
        assert_eq!(
            named(&|s| s.scene.objects.push(s.scene.objects[0].clone()), None),
            "add sphere"
        );
        assert_eq!(
            named(
                &|s| {
                    s.scene.objects.remove(0);
                },
                None
            ),
            "delete"
        );
        assert_eq!(named(&|s| s.scene.lights[0].intensity = 3.0, None), "light");
        assert_eq!(named(&|s| s.render.max_depth += 1, None), "render settings");
    }
}
