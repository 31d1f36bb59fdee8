//! The pixel under inspection: chosen by a click (or Alt + hover) on the
//! image, shown by the inspector panel and the debug view. Unpinned, it
//! follows the surface point it showed when the camera moves; pinned, it
//! keeps its (i, j).

use glam::Vec3;
use renderer::Camera;

/// The inspected pixel and how to follow it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InspectedPixel {
    /// (i, j), column and row from the top-left pixel.
    pub pixel: [u32; 2],
    /// Keep (i, j) when the camera changes (else follow the point it shows).
    pub pinned: bool,
    /// Which sample to re-trace; `None` is the ray through the pixel centre P_ij.
    pub sample: Option<u32>,
    /// The first hit of the ray through P_ij, followed when unpinned.
    pub point: Option<Vec3>,
}

impl InspectedPixel {
    /// A newly chosen pixel (the centre ray, unpinned).
    pub fn new(pixel: [u32; 2]) -> Self {
        Self {
            pixel,
            pinned: false,
            sample: None,
            point: None,
        }
    }

    /// The same inspection after the camera changed to `camera`: a pinned
    /// pixel keeps (i, j); an unpinned one moves to the pixel now showing the
    /// point it showed, when that point is in the image.
    pub fn follow(self, camera: &Camera) -> Self {
        let clamped = [
            self.pixel[0].min(camera.w.saturating_sub(1)),
            self.pixel[1].min(camera.h.saturating_sub(1)),
        ];
        let pixel = match (self.pinned, self.point) {
            (false, Some(point)) => pixel_of(camera, point).unwrap_or(clamped),
            _ => clamped,
        };
        Self { pixel, ..self }
    }
}

/// The pixel (i, j) whose square on the view window the line from P0 to
/// `point` crosses, or `None` when the point is behind the camera or outside
/// the image. Inverts P_ij = C00 + (i + ½)(W_d/w) r − (j + ½)(H_d/h) u.
pub fn pixel_of(camera: &Camera, point: Vec3) -> Option<[u32; 2]> {
    let to = point - camera.p0;
    let depth = to.dot(camera.t);
    if depth.is_nan() || depth <= 0.0 {
        return None;
    }
    // The crossing point on the window, relative to C00.
    let on_window = camera.p0 + to * (camera.d / depth) - camera.c00;
    let x = on_window.dot(camera.r) / (camera.w_d / camera.w as f32);
    let y = -on_window.dot(camera.u) / (camera.h_d / camera.h as f32);
    let inside = (0.0..camera.w as f32).contains(&x) && (0.0..camera.h as f32).contains(&y);
    inside.then_some([x as u32, y as u32])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use scene::ResolvedCamera;

    fn camera(eye: [f32; 3], toward: [f32; 3], theta_deg: f32, d: Option<f32>) -> Camera {
        Camera::new(&ResolvedCamera {
            eye: Vec3::from(eye),
            toward: Vec3::from(toward),
            up: Vec3::Y,
            theta_deg,
            d,
            width: 160,
            height: 90,
        })
        .expect("a valid camera")
    }

    proptest! {
        #[test]
        fn a_point_along_the_ray_through_p_ij_lies_in_pixel_i_j(
            i in 0u32..160, j in 0u32..90,
            k in 0.1f32..50.0,
            theta in 10.0f32..70.0,
            d in proptest::option::of(0.01f32..1000.0),
            eye in proptest::array::uniform3(-5.0f32..5.0),
            toward in proptest::array::uniform3(-1.0f32..1.0),
        ) {
            prop_assume!(Vec3::from(toward).length() > 0.2);
            prop_assume!(Vec3::from(toward).normalize().y.abs() < 0.95);
            let c = camera(eye, toward, theta, d);
            let p_ij = c.pixel_center(i, j);
            let point = c.p0 + (p_ij - c.p0).normalize() * k;
            prop_assert_eq!(pixel_of(&c, point), Some([i, j]));
        }
    }

    #[test]
    fn points_behind_the_camera_or_outside_the_image_have_no_pixel() {
        let c = camera([0.0, 1.0, 5.0], [0.0, 0.0, -1.0], 30.0, None);
        assert_eq!(pixel_of(&c, Vec3::new(0.0, 1.0, 9.0)), None);
        assert_eq!(pixel_of(&c, Vec3::new(100.0, 1.0, 0.0)), None);
    }

    #[test]
    fn an_unpinned_pixel_follows_its_point_and_a_pinned_one_keeps_i_j() {
        let before = camera([0.0, 1.0, 5.0], [0.0, 0.0, -1.0], 30.0, None);
        let point = before.center_ray(40, 30).at(6.0);
        let inspected = InspectedPixel {
            point: Some(point),
            ..InspectedPixel::new([40, 30])
        };
        let after = camera([1.0, 1.0, 5.0], [0.0, 0.0, -1.0], 30.0, None);
        let followed = inspected.follow(&after);
        assert_eq!(
            followed.pixel,
            pixel_of(&after, point).expect("still in view")
        );
        assert_ne!(followed.pixel, [40, 30]);
        let pinned = InspectedPixel {
            pinned: true,
            ..inspected
        };
        assert_eq!(pinned.follow(&after).pixel, [40, 30]);
    }
}
