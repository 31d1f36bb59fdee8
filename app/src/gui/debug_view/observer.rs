//! The observer: the debug view's own camera, which looks at the scene, the
//! ray-tracing camera and its view window from outside. Moving it never
//! moves the ray-tracing camera.

use crate::gui::viewport::navigation::OrbitView;
use glam::camera::rh::{proj::directx::perspective, view::look_at_mat4};
use glam::{Mat4, Vec3, Vec4Swizzles};

/// Vertical field of view of the observer, in radians.
const FOV_Y: f32 = 0.8;

/// An orbiting observer camera with a perspective projection for wgpu (z in [0, 1]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    /// Eye, target and up, moved by the same orbit/pan/dolly as the main camera.
    pub view: OrbitView,
}

impl Observer {
    /// An observer that sees every point in `points` (the scene's bounds, the
    /// camera and its view window), looking from above and behind-left of
    /// `camera_eye` toward their centre, with `up` as the world's up.
    pub fn framing(points: &[Vec3], camera_eye: Vec3, camera_toward: Vec3, up: Vec3) -> Observer {
        let up = up.normalize_or(Vec3::Y);
        let (min, max) = points.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let (center, radius) = if min.is_finite() && max.is_finite() {
            (0.5 * (min + max), (0.5 * (max - min).length()).max(1e-3))
        } else {
            (camera_eye + camera_toward, 1.0)
        };
        // Look from the side of the ray-tracing camera, raised and turned so
        // that the camera, its view window and the scene are all seen at an angle.
        let forward = (center - camera_eye).normalize_or(Vec3::NEG_Z);
        let side = forward.cross(up).normalize_or(Vec3::X);
        let from = (-forward * 0.7 - side * 0.9 + up * 0.8).normalize_or(Vec3::Z);
        let distance = radius / (0.5 * FOV_Y).sin() * 1.05;
        Observer {
            view: OrbitView {
                eye: center + from * distance,
                target: center,
                up,
            },
        }
    }

    /// The world-to-clip matrix for a view of `aspect` = width / height.
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let distance = self.view.distance().max(1e-3);
        let near = (distance * 1e-3).max(1e-4);
        let far = distance * 1e3;
        let up = self.view.up.normalize_or(Vec3::Y);
        perspective(FOV_Y, aspect.max(1e-3), near, far)
            * look_at_mat4(self.view.eye, self.view.target, up)
    }

    /// Where world points land in the view rectangle `rect` (points).
    pub fn screen(&self, rect: egui::Rect) -> Screen {
        Screen {
            view_proj: self.view_proj(rect.aspect_ratio()),
            rect,
        }
    }

    /// World units per screen point at the target's depth, for panning.
    pub fn units_per_point(&self, rect: egui::Rect) -> f32 {
        2.0 * self.view.distance() * (0.5 * FOV_Y).tan() / rect.height().max(1.0)
    }
}

/// The observer's projection onto a view rectangle, computed once per frame.
#[derive(Clone, Copy, Debug)]
pub struct Screen {
    /// World to clip space.
    pub view_proj: Mat4,
    /// The view rectangle, in points.
    pub rect: egui::Rect,
}

impl Screen {
    /// Where a world point lands (points), or `None` when it is behind the observer.
    pub fn project(&self, point: Vec3) -> Option<egui::Pos2> {
        let clip = self.view_proj * point.extend(1.0);
        if clip.w <= 1e-6 {
            return None;
        }
        let ndc = clip.xy() / clip.w;
        Some(egui::pos2(
            self.rect.left() + (0.5 + 0.5 * ndc.x) * self.rect.width(),
            self.rect.top() + (0.5 - 0.5 * ndc.y) * self.rect.height(),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect() -> egui::Rect {
        egui::Rect::from_min_size(egui::pos2(10.0, 20.0), egui::vec2(400.0, 300.0))
    }

    #[test]
    fn the_target_projects_to_the_centre_of_the_view() {
        let observer = Observer {
            view: OrbitView {
                eye: Vec3::new(3.0, 2.0, 5.0),
                target: Vec3::new(0.5, 0.0, -1.0),
                up: Vec3::Y,
            },
        };
        let p = observer
            .screen(rect())
            .project(observer.view.target)
            .expect("in front");
        assert!((p - rect().center()).length() < 1e-3, "{p:?}");
    }

    #[test]
    fn points_behind_the_observer_do_not_project() {
        let observer = Observer {
            view: OrbitView {
                eye: Vec3::ZERO,
                target: Vec3::NEG_Z,
                up: Vec3::Y,
            },
        };
        assert!(observer.screen(rect()).project(Vec3::Z).is_none());
    }

    #[test]
    fn up_in_the_world_is_up_on_screen() {
        let observer = Observer {
            view: OrbitView {
                eye: Vec3::new(0.0, 0.0, 5.0),
                target: Vec3::ZERO,
                up: Vec3::Y,
            },
        };
        let centre = observer
            .screen(rect())
            .project(Vec3::ZERO)
            .expect("in front");
        let above = observer.screen(rect()).project(Vec3::Y).expect("in front");
        let right = observer.screen(rect()).project(Vec3::X).expect("in front");
        assert!(above.y < centre.y);
        assert!(right.x > centre.x);
    }

    #[test]
    fn framing_sees_every_point() {
        let points = [
            Vec3::new(-2.0, 0.0, -6.0),
            Vec3::new(2.0, 1.5, -3.0),
            Vec3::new(0.0, 1.0, 4.0),
            Vec3::new(0.3, 1.2, 3.0),
        ];
        let observer = Observer::framing(&points, points[2], Vec3::NEG_Z, Vec3::Y);
        for p in points {
            let s = observer.screen(rect()).project(p).expect("in front");
            assert!(rect().expand(1.0).contains(s), "{p} lands at {s:?}");
        }
    }
}
