//! Mouse navigation of the camera: orbit around a target, pan, dolly.
//! Each move is a pure function on an [`OrbitView`], written back to the
//! scene's P0 and t (u, the world's up, is left alone).

use glam::{Quat, Vec3};

/// The camera as an eye looking at a target point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitView {
    /// P0, the eye point.
    pub eye: Vec3,
    /// The point orbited around; t = target − P0.
    pub target: Vec3,
    /// u, the up vector orbits turn about (any length).
    pub up: Vec3,
}

/// Closest the eye gets to the pole of `up` while orbiting, in radians.
const POLE_MARGIN: f32 = 0.02;
/// Closest the eye gets to the target while dollying.
const MIN_DISTANCE: f32 = 1e-3;

/// The mouse bindings, shown in the help overlay.
pub const HELP: &[(&str, &str)] = &[
    (
        "Left or middle drag",
        "orbit around the point in the image centre",
    ),
    ("Shift + drag", "pan the camera"),
    (
        "Ctrl + drag, or wheel",
        "dolly toward / away from the target",
    ),
    (
        "Click",
        "select the object under the pointer and inspect its pixel",
    ),
    ("Alt + hover", "inspect the pixel under the pointer"),
    ("Ctrl + wheel, or pinch", "zoom the image (not the camera)"),
    ("Right drag", "pan the zoomed image"),
    ("F / 1", "fit the image / show it at 100 %"),
    (
        "M",
        "next display mode: colour, depth, normal, albedo, object id, spp, variance, cost",
    ),
    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo"),
    ("Ctrl+O / Ctrl+S / Ctrl+Shift+S", "open / save / save as"),
    ("Ctrl+E", "save the rendered image"),
    (
        "G",
        "show or hide the 3D debug view (drag: orbit, Shift/right drag: pan, wheel: zoom)",
    ),
    ("H", "show or hide this help"),
];

impl OrbitView {
    /// The distance from the eye to the target.
    pub fn distance(&self) -> f32 {
        self.eye.distance(self.target)
    }

    /// t, the toward vector to write back (from the eye to the target).
    pub fn toward(&self) -> Vec3 {
        self.target - self.eye
    }

    /// P0 and t as a scene file can hold them (finite, every coordinate
    /// within ±[`scene::MAX_MAGNITUDE`]), or `None` when the eye has moved
    /// past that: a camera the file could not read back is never made. A t
    /// too long to hold is written as its unit direction, which looks the
    /// same way.
    pub fn as_stored(&self) -> Option<(Vec3, Vec3)> {
        let fits = |v: Vec3| v.is_finite() && v.abs().max_element() <= scene::MAX_MAGNITUDE;
        let toward = self.toward();
        let toward = if fits(toward) {
            toward
        } else {
            toward.normalize_or_zero()
        };
        (fits(self.eye) && fits(toward) && toward != Vec3::ZERO).then_some((self.eye, toward))
    }

    /// Turns the eye about the target: `yaw` radians about u, then `pitch`
    /// radians about r (positive pitch raises the eye), stopping short of
    /// the poles so t never becomes parallel to u.
    pub fn orbit(self, yaw: f32, pitch: f32) -> OrbitView {
        let up = self.up.normalize_or(Vec3::Y);
        let offset = Quat::from_axis_angle(up, yaw) * (self.eye - self.target);
        let length = offset.length();
        if length == 0.0 {
            return self;
        }
        // Elevation φ ∈ (0, π) from the up axis, kept off the poles.
        let polar = (offset.dot(up) / length).clamp(-1.0, 1.0).acos();
        let new_polar = (polar - pitch).clamp(POLE_MARGIN, std::f32::consts::PI - POLE_MARGIN);
        let right = up.cross(offset).normalize_or_zero();
        let offset = if right == Vec3::ZERO {
            offset
        } else {
            Quat::from_axis_angle(right, new_polar - polar) * offset
        };
        OrbitView {
            eye: self.target + offset,
            ..self
        }
    }

    /// Moves eye and target together by `right` units along r and `up` along
    /// the camera's screen-up direction.
    pub fn pan(self, right: f32, up: f32) -> OrbitView {
        let t = self.toward().normalize_or_zero();
        let r = t.cross(self.up).normalize_or_zero();
        let screen_up = r.cross(t);
        let shift = r * right + screen_up * up;
        OrbitView {
            eye: self.eye + shift,
            target: self.target + shift,
            up: self.up,
        }
    }

    /// Scales the eye's distance to the target by `factor` (< 1 moves closer),
    /// never closer than a millimetre.
    pub fn dolly(self, factor: f32) -> OrbitView {
        let offset = self.eye - self.target;
        let distance = offset.length();
        if distance == 0.0 || !factor.is_finite() {
            return self;
        }
        let new_distance = (distance * factor).max(MIN_DISTANCE);
        OrbitView {
            eye: self.target + offset * (new_distance / distance),
            ..self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn view(eye: [f32; 3], target: [f32; 3]) -> OrbitView {
        OrbitView {
            eye: Vec3::from(eye),
            target: Vec3::from(target),
            up: Vec3::Y,
        }
    }

    fn is_close(a: Vec3, b: Vec3, tolerance: f32) -> bool {
        (a - b).length() <= tolerance * (1.0 + a.length().max(b.length()))
    }

    #[test]
    fn a_full_turn_of_yaw_returns_to_the_start() {
        let start = view([3.0, 2.0, 5.0], [0.0, 1.0, 0.0]);
        let mut v = start;
        for _ in 0..8 {
            v = v.orbit(std::f32::consts::FRAC_PI_4, 0.0);
        }
        assert!(is_close(v.eye, start.eye, 1e-5), "{:?}", v.eye);
    }

    #[test]
    fn a_camera_a_scene_file_cannot_hold_is_never_made() {
        let far = scene::MAX_MAGNITUDE;
        assert_eq!(
            view([0.0, 0.0, 5.0], [0.0; 3]).as_stored(),
            Some((Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -5.0)))
        );
        assert_eq!(view([0.0, 0.0, far * 1.5], [0.0; 3]).as_stored(), None);
        assert_eq!(view([0.0, 0.0, f32::NAN], [0.0; 3]).as_stored(), None);
        assert_eq!(view([0.0; 3], [0.0; 3]).as_stored(), None, "t = 0");
        // An eye near the limit looking at a target past it: t shortened.
        let (eye, toward) = view([0.0, 0.0, far], [0.0, 0.0, -far])
            .as_stored()
            .expect("the eye fits");
        assert_eq!((eye.z, toward), (far, Vec3::NEG_Z));
        // Dollying out from a far eye stops being written once past the limit.
        let mut v = view([0.0, 0.0, 1.0e5], [0.0; 3]);
        let mut last = None;
        for _ in 0..40 {
            v = v.dolly(1.5);
            match v.as_stored() {
                Some((eye, _)) => last = Some(eye),
                None => break,
            }
        }
        let last = last.expect("the first steps fit");
        assert!(last.z <= far && last.z > far / 1.5, "{last}");
    }

    #[test]
    fn pitching_past_the_pole_stops_short_of_it() {
        let v = view([0.0, 0.0, 5.0], [0.0, 0.0, 0.0]).orbit(0.0, 10.0);
        let t = v.toward().normalize();
        assert!(
            t.cross(Vec3::Y).length() > 0.01,
            "t must not be parallel to u"
        );
        assert!(v.eye.y > 4.9, "the eye went over the top: {:?}", v.eye);
    }

    proptest! {
        #[test]
        fn orbiting_keeps_the_distance_and_the_target(
            eye in prop::array::uniform3(-50.0f32..50.0),
            target in prop::array::uniform3(-5.0f32..5.0),
            yaw in -7.0f32..7.0,
            pitch in -3.0f32..3.0,
        ) {
            let v = view(eye, target);
            prop_assume!(v.distance() > 0.1);
            prop_assume!(v.toward().normalize().cross(Vec3::Y).length() > 0.05);
            let turned = v.orbit(yaw, pitch);
            prop_assert!((turned.distance() - v.distance()).abs() <= 1e-4 * v.distance());
            prop_assert_eq!(turned.target, v.target);
            prop_assert!(turned.toward().normalize().cross(Vec3::Y).length() > 0.01);
        }

        #[test]
        fn panning_moves_eye_and_target_alike_across_the_view(
            eye in prop::array::uniform3(-50.0f32..50.0),
            target in prop::array::uniform3(-5.0f32..5.0),
            right in -10.0f32..10.0,
            up in -10.0f32..10.0,
        ) {
            let v = view(eye, target);
            prop_assume!(v.distance() > 0.1);
            prop_assume!(v.toward().normalize().cross(Vec3::Y).length() > 0.05);
            let moved = v.pan(right, up);
            prop_assert!(is_close(moved.toward(), v.toward(), 1e-5));
            let shift = moved.eye - v.eye;
            prop_assert!((shift.length() - right.hypot(up)).abs() <= 1e-3 * (1.0 + shift.length()));
            prop_assert!(shift.dot(v.toward().normalize()).abs() <= 1e-3 * (1.0 + shift.length()));
        }

        #[test]
        fn dollying_keeps_the_direction_and_never_reaches_the_target(
            eye in prop::array::uniform3(-50.0f32..50.0),
            factor in 0.0f32..4.0,
        ) {
            let v = view(eye, [0.0, 0.0, 0.0]);
            prop_assume!(v.distance() > 0.1);
            let moved = v.dolly(factor);
            prop_assert!(moved.distance() >= MIN_DISTANCE * 0.99);
            prop_assert!(is_close(moved.toward().normalize(), v.toward().normalize(), 1e-5));
        }
    }
}
