//! Camera moves by mouse on the image: a drag orbits the camera about the
//! point the image centre shows, Shift pans it, Ctrl and the wheel dolly it.
//! The moves are written back to the scene's camera as they happen; the
//! orbit being dragged is kept until the drag ends.

use super::image_view::Gestures;
use super::navigation::OrbitView;
use crate::gui::session::Prepared;
use renderer::Method;
use renderer::geometry::ray::Ray;

/// Orbit speed, radians per point dragged.
const ORBIT_SPEED: f32 = 0.008;
/// Dolly speed: the distance shrinks by e^(speed · points).
const DOLLY_SPEED: f32 = 0.004;

/// The camera drag in progress, if any.
#[derive(Default)]
pub struct CameraDrag {
    /// The camera being orbited, panned or dollied by a drag in progress.
    pub view: Option<OrbitView>,
}

impl CameraDrag {
    /// Ends the drag: the camera was replaced (undo, redo, another document).
    pub fn end(&mut self) {
        self.view = None;
    }

    /// Moves `camera` by this frame's `gestures` on the image of `prepared`
    /// (`dragging`: a button is still down). A move past what a scene file
    /// holds is not made.
    pub fn apply(
        &mut self,
        gestures: &Gestures,
        dragging: bool,
        prepared: Option<&Prepared>,
        method: Method,
        camera: &mut scene::Camera,
    ) {
        let moved = gestures.orbit != egui::Vec2::ZERO
            || gestures.pan != egui::Vec2::ZERO
            || gestures.dolly != 0.0;
        if !moved {
            if !dragging {
                self.view = None;
            }
            return;
        }
        let Some(mut view) = self
            .view
            .or_else(|| prepared.map(|p| orbit_view(p, method, camera.up)))
        else {
            return;
        };
        view = view.orbit(
            -gestures.orbit.x * ORBIT_SPEED,
            -gestures.orbit.y * ORBIT_SPEED,
        );
        if gestures.pan != egui::Vec2::ZERO
            && let Some(prepared) = prepared
        {
            let camera = &prepared.world.camera;
            // World units per screen point at the target's depth.
            let per_pixel = 2.0 * view.distance() * camera.theta.tan() / camera.h as f32;
            let scale = per_pixel * gestures.pixels_per_point;
            view = view.pan(-gestures.pan.x * scale, gestures.pan.y * scale);
        }
        view = view.dolly((gestures.dolly * DOLLY_SPEED).exp());
        // A move past what a scene file holds is not made (the camera stays).
        let Some((eye, toward)) = view.as_stored() else {
            return;
        };
        camera.eye = Some(eye);
        camera.toward = Some(toward);
        self.view = dragging.then_some(view);
    }
}

/// The camera of `prepared` as an eye orbiting the point the image centre
/// shows (or, looking at nothing, the scene's centre depth), with `up`.
fn orbit_view(prepared: &Prepared, method: Method, up: glam::Vec3) -> OrbitView {
    let camera = &prepared.world.camera;
    let hit = prepared
        .world
        .intersect(&Ray::new(camera.p0, camera.t), method)
        .map(|h| h.alpha)
        .filter(|a| a.is_finite() && *a > 1e-3);
    let depth = hit.unwrap_or_else(|| {
        let focus = prepared
            .resolved
            .objects
            .iter()
            .filter_map(|o| scene::layout::bounds(&o.geometry))
            .fold(scene::layout::Aabb::EMPTY, scene::layout::Aabb::union);
        if focus.is_empty() {
            5.0
        } else {
            (focus.center() - camera.p0).dot(camera.t).max(1.0)
        }
    });
    OrbitView {
        eye: camera.p0,
        target: camera.p0 + camera.t * depth,
        up,
    }
}
