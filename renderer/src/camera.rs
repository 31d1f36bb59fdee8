//! The lecture's camera: P0, t, u, r, θ, d, w, h, ρ, H_d, W_d, C00, P_ij, v_ij.

use crate::geometry::ray::Ray;
use glam::{DVec3, Vec2, Vec3};
use scene::ResolvedCamera;

/// Why a camera cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CameraError {
    /// t is zero (or not finite).
    #[error("the toward vector t is zero or not finite")]
    ZeroToward,
    /// u is zero (or not finite).
    #[error("the up vector u is zero or not finite")]
    ZeroUp,
    /// u is parallel to t, so r = t × u is undefined.
    #[error("the up vector u is parallel to the toward vector t")]
    UpParallelToToward,
    /// θ outside (0°, 90°).
    #[error("the half-height angle θ must lie strictly between 0° and 90°, got {0}°")]
    Theta(f32),
    /// d not a positive finite number.
    #[error("the view-window distance d must be positive, got {0}")]
    Distance(f32),
    /// θ so small that a pixel subtends less than f32 ray directions resolve.
    #[error(
        "the half-height angle θ = {theta}° is too narrow for {height} pixel rows: a pixel would \
         subtend {pixel:.1e} rad, below the {min:.1e} rad that f32 ray directions can tell apart; \
         widen θ or lower the height",
        min = Camera::MIN_PIXEL_ANGLE
    )]
    TooNarrow {
        /// θ in degrees.
        theta: f32,
        /// h, the image height.
        height: u32,
        /// The angle one pixel subtends, 2 tan θ / h, in radians.
        pixel: f64,
    },
    /// w or h outside 1..=16384.
    #[error("the image size must be 1..=16384 pixels per side, got {0}×{1}")]
    Size(u32, u32),
}

/// The lecture's camera with every derived quantity precomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// P0, the viewpoint.
    pub p0: Vec3,
    /// t, the unit toward vector.
    pub t: Vec3,
    /// u, the unit up vector, made orthogonal to t in the plane of t and the given up.
    pub u: Vec3,
    /// r = t × u, the unit right vector.
    pub r: Vec3,
    /// θ, the half-height angle, in radians.
    pub theta: f32,
    /// d, the distance from P0 to the view window.
    pub d: f32,
    /// w, the image width in pixels.
    pub w: u32,
    /// h, the image height in pixels.
    pub h: u32,
    /// ρ = w / h, the aspect ratio.
    pub rho: f32,
    /// H_d = 2 d tan θ, the view window's height.
    pub h_d: f32,
    /// W_d = ρ H_d, the view window's width.
    pub w_d: f32,
    /// C00 = P0 + d t + (H_d/2) u − (W_d/2) r, the view window's top-left corner.
    pub c00: Vec3,
    /// C00 − P0 in f64 (see [`Camera::window_offset`]).
    corner_offset: DVec3,
    /// (W_d / w) r in f64: one pixel to the right on the view window.
    pixel_right: DVec3,
    /// (H_d / h) u in f64: one pixel up on the view window.
    pixel_up: DVec3,
}

impl Camera {
    /// The smallest angle a pixel may subtend (radians): 8 f32 ulps of a
    /// unit direction, so that rays through neighbouring pixels differ and
    /// each lands within about 0.06 pixel of where it should.
    pub const MIN_PIXEL_ANGLE: f64 = 8.0 * f32::EPSILON as f64;

    /// Builds the camera from the scene's inputs. t is normalised; u is made
    /// orthogonal to t (Gram–Schmidt in f64, so the basis is orthonormal to
    /// f32 precision); d defaults to the lecture's h / (2 tan θ).
    pub fn new(input: &ResolvedCamera) -> Result<Self, CameraError> {
        let (w, h) = (input.width, input.height);
        if !(1..=scene::Camera::MAX_SIZE).contains(&w)
            || !(1..=scene::Camera::MAX_SIZE).contains(&h)
        {
            return Err(CameraError::Size(w, h));
        }
        if !(input.theta_deg > 0.0 && input.theta_deg < 90.0) {
            return Err(CameraError::Theta(input.theta_deg));
        }
        let pixel = 2.0 * f64::from(input.theta_deg).to_radians().tan() / f64::from(h);
        if pixel < Self::MIN_PIXEL_ANGLE {
            return Err(CameraError::TooNarrow {
                theta: input.theta_deg,
                height: h,
                pixel,
            });
        }
        let t = input
            .toward
            .as_dvec3()
            .try_normalize()
            .ok_or(CameraError::ZeroToward)?;
        let up = input
            .up
            .as_dvec3()
            .try_normalize()
            .ok_or(CameraError::ZeroUp)?;
        let u_perp = up - up.dot(t) * t;
        if u_perp.length() < 1e-6 {
            return Err(CameraError::UpParallelToToward);
        }
        let u: DVec3 = u_perp.normalize();
        let r = t.cross(u);
        let theta = input.theta_deg.to_radians();
        let d = match input.d {
            Some(d) => d,
            None => h as f32 / (2.0 * theta.tan()),
        };
        if !(d > 0.0 && d.is_finite()) {
            return Err(CameraError::Distance(d));
        }
        // The window's geometry in f64: d scales every term, and in f64 its
        // rounding stays ~1e-16 relative, far below f32 precision, so the f32
        // directions v_ij — and the image — come out the same for any d.
        let d64 = f64::from(d);
        let h_d64 = 2.0 * d64 * f64::from(theta).tan();
        let w_d64 = f64::from(w) / f64::from(h) * h_d64;
        let corner_offset = d64 * t + (h_d64 / 2.0) * u - (w_d64 / 2.0) * r;
        let pixel_right = (w_d64 / f64::from(w)) * r;
        let pixel_up = (h_d64 / f64::from(h)) * u;
        let (t, u, r) = (t.as_vec3(), u.as_vec3(), r.as_vec3());
        let rho = w as f32 / h as f32;
        let h_d = h_d64 as f32;
        let w_d = w_d64 as f32;
        let p0 = input.eye;
        let c00 = p0 + corner_offset.as_vec3();
        Ok(Self {
            p0,
            t,
            u,
            r,
            theta,
            d,
            w,
            h,
            rho,
            h_d,
            w_d,
            c00,
            corner_offset,
            pixel_right,
            pixel_up,
        })
    }

    /// This camera with its view window at distance `d` (> 0) instead: H_d,
    /// W_d, C00 and the pixel steps scale with d about P0, so every P_ij
    /// moves along its ray and every v_ij stays the same (to rounding): as
    /// the lecture says, d does not change the image. For drawing the
    /// window where it can be seen.
    pub fn with_window_at(&self, d: f32) -> Camera {
        let s = f64::from(d) / f64::from(self.d);
        let corner_offset = self.corner_offset * s;
        Camera {
            d,
            h_d: (f64::from(self.h_d) * s) as f32,
            w_d: (f64::from(self.w_d) * s) as f32,
            c00: self.p0 + corner_offset.as_vec3(),
            corner_offset,
            pixel_right: self.pixel_right * s,
            pixel_up: self.pixel_up * s,
            ..*self
        }
    }

    /// The point on the view window at pixel coordinates (i + x, j + y) minus
    /// P0: the lecture's P_ij − P0 = (C00 − P0) + (i + x)(W_d/w) r − (j + y)(H_d/h) u,
    /// with the ½ replaced by `offset`. Formed relative to P0 (so far-away
    /// cameras keep their precision) and in f64, from terms precomputed in
    /// [`Camera::new`].
    fn window_offset(&self, i: u32, j: u32, offset: Vec2) -> DVec3 {
        self.corner_offset + (f64::from(i) + f64::from(offset.x)) * self.pixel_right
            - (f64::from(j) + f64::from(offset.y)) * self.pixel_up
    }

    /// P_ij = C00 + (i + ½)(W_d/w) r − (j + ½)(H_d/h) u, the centre of pixel (i, j) on the view window.
    pub fn pixel_center(&self, i: u32, j: u32) -> Vec3 {
        self.window_point(i, j, Vec2::splat(0.5))
    }

    /// The point of the view window at pixel coordinates (i + x, j + y): P_ij
    /// with the ½ replaced by `offset` (where a jittered sample's ray passes).
    pub fn window_point(&self, i: u32, j: u32, offset: Vec2) -> Vec3 {
        self.p0 + self.window_offset(i, j, offset).as_vec3()
    }

    /// v_ij = (P_ij − P0)/‖P_ij − P0‖ with the ½ replaced by `offset` in [0, 1)²
    /// (jittered samples; `Vec2::splat(0.5)` is the pixel centre).
    pub fn direction(&self, i: u32, j: u32, offset: Vec2) -> Vec3 {
        self.window_offset(i, j, offset).normalize().as_vec3()
    }

    /// The directions v_ij of `N` samples at once, per coordinate: lane k
    /// is [`Camera::direction`]`(i[k], j[k], (x[k], y[k]))` bit for bit (the
    /// same f64 operations in the same order), written over arrays so that
    /// the compiler vectorises it.
    #[inline(always)]
    pub fn directions<const N: usize>(
        &self,
        i: &[u32; N],
        j: &[u32; N],
        x: &[f32; N],
        y: &[f32; N],
    ) -> [[f32; N]; 3] {
        let (c, r, u) = (self.corner_offset, self.pixel_right, self.pixel_up);
        let mut v = [[0.0f32; N]; 3];
        for k in 0..N {
            // `window_offset`: (C00 − P0) + s r' − t u'.
            let s = f64::from(i[k]) + f64::from(x[k]);
            let t = f64::from(j[k]) + f64::from(y[k]);
            let w = [
                c.x + s * r.x - t * u.x,
                c.y + s * r.y - t * u.y,
                c.z + s * r.z - t * u.z,
            ];
            // `DVec3::normalize`: w · (1 / ‖w‖), the dot summed x, y, z.
            let recip = 1.0 / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            for axis in 0..3 {
                v[axis][k] = (w[axis] * recip) as f32;
            }
        }
        v
    }

    /// R_ij = (P0, v_ij): the primary ray through pixel (i, j) at `offset`.
    pub fn ray(&self, i: u32, j: u32, offset: Vec2) -> Ray {
        Ray::new(self.p0, self.direction(i, j, offset))
    }

    /// The ray through the pixel centre P_ij.
    pub fn center_ray(&self, i: u32, j: u32) -> Ray {
        self.ray(i, j, Vec2::splat(0.5))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Many directions at once are each sample's direction alone, bit for bit.
        #[test]
        fn directions_at_once_are_each_direction_alone(
            i in proptest::array::uniform8(0u32..4),
            j in proptest::array::uniform8(0u32..3),
            x in proptest::array::uniform8(0.0f32..1.0),
            y in proptest::array::uniform8(0.0f32..1.0),
            eye in proptest::array::uniform3(-1e3f32..1e3),
            theta in 1.0f32..89.0,
        ) {
            let camera = Camera::new(&ResolvedCamera {
                eye: Vec3::from_array(eye),
                theta_deg: theta,
                ..input()
            })
            .expect("a valid camera");
            let v = camera.directions(&i, &j, &x, &y);
            for k in 0..8 {
                let alone = camera.direction(i[k], j[k], Vec2::new(x[k], y[k]));
                let at_once = Vec3::new(v[0][k], v[1][k], v[2][k]);
                prop_assert_eq!(at_once.to_array().map(f32::to_bits), alone.to_array().map(f32::to_bits));
            }
        }
    }

    fn input() -> ResolvedCamera {
        ResolvedCamera {
            eye: Vec3::new(0.0, 0.0, 0.0),
            toward: Vec3::new(0.0, 0.0, -1.0),
            up: Vec3::Y,
            theta_deg: 45.0,
            d: Some(1.0),
            width: 4,
            height: 2,
        }
    }

    #[test]
    fn derived_values_match_hand_computation() {
        let c = Camera::new(&input()).expect("valid");
        // r = t × u = (0,0,−1) × (0,1,0) = (1,0,0).
        assert!((c.r - Vec3::X).length() < 1e-7);
        assert_eq!(c.rho, 2.0);
        assert!((c.h_d - 2.0).abs() < 1e-6); // 2 · 1 · tan 45°
        assert!((c.w_d - 4.0).abs() < 1e-6);
        // C00 = (0,0,0) + 1·(0,0,−1) + 1·(0,1,0) − 2·(1,0,0).
        assert!((c.c00 - Vec3::new(-2.0, 1.0, -1.0)).length() < 1e-6);
        // P_00 = C00 + ½·1·r − ½·1·u; P_31 = C00 + 3.5 r − 1.5 u.
        assert!((c.pixel_center(0, 0) - Vec3::new(-1.5, 0.5, -1.0)).length() < 1e-6);
        assert!((c.pixel_center(3, 1) - Vec3::new(1.5, -0.5, -1.0)).length() < 1e-6);
        let v = c.center_ray(3, 1).dir;
        assert!((v - Vec3::new(1.5, -0.5, -1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn default_distance_makes_the_window_h_pixels_high() {
        let mut inp = input();
        inp.d = None;
        inp.theta_deg = 30.0;
        let c = Camera::new(&inp).expect("valid");
        // d = h / (2 tan θ) ⇒ H_d = h and W_d = w, as in the lecture.
        assert!(
            (c.h_d - 2.0).abs() < 1e-5 && (c.w_d - 4.0).abs() < 1e-5,
            "{c:?}"
        );
    }

    #[test]
    fn theta_too_narrow_for_f32_rays_is_refused_and_just_wide_enough_is_accepted() {
        let tall = ResolvedCamera {
            theta_deg: 1e-4,
            width: 64,
            height: 48,
            ..input()
        };
        let error = Camera::new(&tall).expect_err("a pixel of 7e-8 rad");
        assert!(
            matches!(error, CameraError::TooNarrow { height: 48, .. }),
            "{error}"
        );
        assert!(error.to_string().contains("too narrow"), "{error}");
        // 2 tan θ / h just above 8 ε: accepted, and neighbouring pixels get different rays.
        let theta = (Camera::MIN_PIXEL_ANGLE * 1.01 * 24.0).atan().to_degrees() as f32;
        let c = Camera::new(&ResolvedCamera {
            theta_deg: theta,
            ..tall
        })
        .expect("wide enough");
        assert_ne!(c.center_ray(10, 20).dir, c.center_ray(11, 20).dir);
        assert_ne!(c.center_ray(10, 20).dir, c.center_ray(10, 21).dir);
    }

    #[test]
    fn degenerate_inputs_are_errors() {
        let cases = [
            (
                ResolvedCamera {
                    toward: Vec3::ZERO,
                    ..input()
                },
                CameraError::ZeroToward,
            ),
            (
                ResolvedCamera {
                    up: Vec3::ZERO,
                    ..input()
                },
                CameraError::ZeroUp,
            ),
            (
                ResolvedCamera {
                    up: Vec3::new(0.0, 0.0, 3.0),
                    ..input()
                },
                CameraError::UpParallelToToward,
            ),
            (
                ResolvedCamera {
                    theta_deg: 0.0,
                    ..input()
                },
                CameraError::Theta(0.0),
            ),
            (
                ResolvedCamera {
                    theta_deg: 90.0,
                    ..input()
                },
                CameraError::Theta(90.0),
            ),
            (
                ResolvedCamera {
                    theta_deg: f32::NAN,
                    ..input()
                },
                CameraError::Theta(f32::NAN),
            ),
            (
                ResolvedCamera {
                    d: Some(0.0),
                    ..input()
                },
                CameraError::Distance(0.0),
            ),
            (
                ResolvedCamera {
                    width: 0,
                    ..input()
                },
                CameraError::Size(0, 2),
            ),
            (
                ResolvedCamera {
                    height: 16385,
                    ..input()
                },
                CameraError::Size(4, 16385),
            ),
        ];
        for (inp, expected) in cases {
            let err = Camera::new(&inp).expect_err("must fail");
            // NaN ≠ NaN, so compare the messages.
            assert_eq!(err.to_string(), expected.to_string());
        }
    }

    #[test]
    fn ray_direction_is_independent_of_view_window_distance() {
        let near = Camera::new(&ResolvedCamera {
            d: Some(1e-3),
            ..input()
        })
        .expect("valid");
        let far = Camera::new(&ResolvedCamera {
            d: Some(1e3),
            ..input()
        })
        .expect("valid");
        for (i, j) in [(0, 0), (3, 1), (2, 0)] {
            assert_eq!(
                near.center_ray(i, j).dir,
                far.center_ray(i, j).dir,
                "pixel ({i}, {j})"
            );
        }
    }

    /// A camera moved to another d by `with_window_at` is the camera made
    /// with that d: the same window (C00, H_d, W_d, P_ij) and the same rays.
    #[test]
    fn a_window_moved_to_another_d_is_the_camera_made_with_that_d() {
        let far = Camera::new(&ResolvedCamera {
            d: Some(300.0),
            ..input()
        })
        .expect("valid");
        let near = Camera::new(&input()).expect("valid");
        let moved = far.with_window_at(1.0);
        assert_eq!(moved.d, 1.0);
        assert!(moved.c00.distance(near.c00) < 1e-6);
        assert!((moved.h_d - near.h_d).abs() < 1e-6 && (moved.w_d - near.w_d).abs() < 1e-6);
        for (i, j) in [(0, 0), (3, 1), (2, 0)] {
            assert!(moved.pixel_center(i, j).distance(near.pixel_center(i, j)) < 1e-6);
            let (a, b) = (moved.center_ray(i, j).dir, far.center_ray(i, j).dir);
            assert!(a.distance(b) < 1e-6, "pixel ({i}, {j}): {a} against {b}");
        }
    }

    proptest! {
        #[test]
        fn basis_is_orthonormal_for_any_valid_t_and_u(
            tx in -10.0f32..10.0, ty in -10.0f32..10.0, tz in -10.0f32..10.0,
            ux in -10.0f32..10.0, uy in -10.0f32..10.0, uz in -10.0f32..10.0,
            theta in 0.01f32..89.99,
        ) {
            let toward = Vec3::new(tx, ty, tz);
            let up = Vec3::new(ux, uy, uz);
            prop_assume!(toward.length() > 1e-3 && up.length() > 1e-3);
            prop_assume!(toward.normalize().cross(up.normalize()).length() > 1e-3);
            let c = Camera::new(&ResolvedCamera { toward, up, theta_deg: theta, ..input() }).expect("valid");
            for v in [c.t, c.u, c.r] {
                prop_assert!((v.length() - 1.0).abs() < 1e-6);
            }
            prop_assert!(c.t.dot(c.u).abs() < 1e-6 && c.t.dot(c.r).abs() < 1e-6 && c.u.dot(c.r).abs() < 1e-6);
            // u stays in the plane of t and the given up, on the same side as up.
            prop_assert!(c.u.dot(up) > 0.0);
            prop_assert!(c.r.dot(toward.cross(up)).abs() > 0.0);
        }
    }
}
