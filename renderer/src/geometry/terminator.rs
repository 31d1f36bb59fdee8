//! The shadow terminator of smooth-shaded meshes (Hanika, "Hacking the
//! Shadow Terminator", Ray Tracing Gems II ch. 4, 2021).
//!
//! A mesh's triangles are flat but its interpolated vertex normals describe a
//! curved surface. Near the terminator a light can lie above the shading
//! normal yet below the flat triangle, or graze it, and a shadow ray from the
//! flat triangle then meets the mesh itself: the lit side shows dark
//! triangular patches along the triangles' edges. Hanika starts such shadow
//! rays from a point on the curved surface instead: the hit point moved onto
//! each corner's tangent plane (where it lies below that plane), the three
//! moved points blended with the hit's barycentric weights. On a convex
//! patch that point lies above the flat triangle, roughly where the curved
//! surface is; on a flat or concave one it is the hit point itself.
//!
//! The point is used only where the light is below or close to the flat
//! triangle's plane (cos θ_g below [`TERMINATOR_BAND`], fading in linearly:
//! [`terminator_weight`]), so everywhere else shadow rays start where they
//! always did; Blender
//! Cycles limits its version of the offset the same way. A light well above
//! the flat triangle is never blocked by its convex neighbours anyway, while
//! a contact shadow from another object close to a coarse mesh is kept.

use super::offset::offset_ray_origin;
use super::ray::Ray;
use glam::Vec3;

/// The cosine between a light's direction and the flat triangle's normal
/// below which a shadow ray starts (partly) from the curved surface's point:
/// fully at cos θ_g ≤ 0, not at all from cos θ_g ≥ this (Cycles' default
/// for its geometry offset is the same 0.1).
pub const TERMINATOR_BAND: f32 = 0.1;

/// Hanika's point P′ over the hit point `p` of a triangle with corners
/// `corners`, unit vertex normals `normals` and barycentric weights
/// `weights` (α, β, γ): P′ = P − Σᵢ wᵢ · min(0, (P − Pᵢ)·nᵢ) · nᵢ, the
/// blend of P's projections onto the corners' tangent planes that lie above
/// it. All in one space (the mesh's own).
#[inline]
pub fn curved_surface_point(
    p: Vec3,
    corners: [Vec3; 3],
    normals: [Vec3; 3],
    weights: [f32; 3],
) -> Vec3 {
    let mut lifted = p;
    for ((corner, normal), weight) in corners.into_iter().zip(normals).zip(weights) {
        let below = (p - corner).dot(normal).min(0.0);
        lifted -= (weight * below) * normal;
    }
    lifted
}

/// How far a shadow ray toward a light at cosine `cos_geometric` to the flat
/// triangle's normal starts toward the curved surface's point: 1 at
/// cos θ_g ≤ 0, falling linearly to 0 at [`TERMINATOR_BAND`] and above.
#[inline(always)]
pub fn terminator_weight(cos_geometric: f32) -> f32 {
    ((TERMINATOR_BAND - cos_geometric) / TERMINATOR_BAND).clamp(0.0, 1.0)
}

/// The unit direction from `origin` to `target` and the distance between
/// them: a shadow ray started from Hanika's point is aimed again at its
/// light's point, so that it still ends short of an emitter's surface.
/// Written out (1 / √(d·d) times d) so that the lanes repeat it bit for bit.
#[inline(always)]
pub fn aim(origin: Vec3, target: Vec3) -> (Vec3, f32) {
    let d = target - origin;
    let length = d.dot(d).sqrt();
    (d * (1.0 / length), length)
}

/// What a hit's shadow rays start from: the hit point, the unit geometric
/// normal on the lit side, the object's magnitude (the offset's scale) and,
/// on a mesh hit from the side its normals face, Hanika's point.
#[derive(Clone, Copy, Debug)]
pub struct ShadowStart {
    /// The hit point.
    pub point: Vec3,
    /// The unit geometric normal on the side the shadow rays leave from.
    pub geometric: Vec3,
    /// The largest coordinate of the object hit.
    pub magnitude: f32,
    /// Hanika's point ([`curved_surface_point`]), if the hit has one.
    pub curved: Option<Vec3>,
}

impl ShadowStart {
    /// The shadow ray toward the light `distance` along `to_light` from the
    /// hit point (∞ for light from infinitely far), ending at `reach` of the
    /// way there (short of an emitter's own surface). It starts just off the
    /// hit point; near the terminator just off the point moved toward
    /// Hanika's by [`terminator_weight`], and is then aimed from there at
    /// the light's point.
    #[inline]
    pub fn ray(&self, to_light: Vec3, distance: f32, reach: f32) -> Ray {
        let point = self.point;
        let (start, lifted) = match self.curved {
            Some(curved) => {
                let weight = terminator_weight(to_light.dot(self.geometric));
                (point + (curved - point) * weight, weight > 0.0)
            }
            None => (point, false),
        };
        let origin = offset_ray_origin(start, self.geometric, self.magnitude);
        if lifted && distance.is_finite() {
            let (dir, length) = aim(origin, point + to_light * distance);
            Ray::new(origin, dir).with_t_max(length * reach)
        } else {
            Ray::new(origin, to_light).with_t_max(distance * reach)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The corners of a triangle on the unit sphere around the origin (at
    /// θ, φ in radians, spanning `size` radians), with their normals.
    fn sphere_triangle(theta: f32, phi: f32, size: f32) -> ([Vec3; 3], [Vec3; 3]) {
        let at = |t: f32, p: f32| Vec3::new(t.sin() * p.cos(), t.cos(), t.sin() * p.sin());
        let normals = [
            at(theta, phi),
            at(theta + size, phi),
            at(theta + size, phi + size),
        ];
        (normals, normals)
    }

    fn weights(b: f32, c: f32) -> [f32; 3] {
        let (b, c) = if b + c > 1.0 {
            (1.0 - b, 1.0 - c)
        } else {
            (b, c)
        };
        [1.0 - b - c, b, c]
    }

    proptest! {
        /// On a unit sphere's chord triangle, P′ lies above the flat
        /// triangle, on the sphere's outside by no more than P lies inside
        /// it: the surface the normals describe, not the flat one.
        #[test]
        fn on_a_sphere_the_point_moves_out_toward_the_sphere(
            theta in 0.2f32..2.9, phi in -3.0f32..3.0, size in 0.05f32..0.6,
            b in 0.0f32..1.0, c in 0.0f32..1.0,
        ) {
            let (corners, normals) = sphere_triangle(theta, phi, size);
            let w = weights(b, c);
            let p = w[0] * corners[0] + w[1] * corners[1] + w[2] * corners[2];
            let flat = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
            let outward = if flat.dot(p) > 0.0 { flat } else { -flat };
            let q = curved_surface_point(p, corners, normals, w);
            prop_assert!((q - p).dot(outward) >= -1e-6, "P′ {q} below P {p}");
            let (inside, outside) = (1.0 - p.length(), q.length() - 1.0);
            prop_assert!(
                outside >= -1e-6 && outside <= inside + 1e-6,
                "P {p} is {inside} inside the sphere, P′ {q} {outside} outside it"
            );
        }

        /// A corner is its own point: P′ = Pᵢ at wᵢ = 1.
        #[test]
        fn at_a_corner_the_point_is_the_corner(
            theta in 0.2f32..2.9, phi in -3.0f32..3.0, size in 0.05f32..0.6, k in 0usize..3,
        ) {
            let (corners, normals) = sphere_triangle(theta, phi, size);
            let mut w = [0.0; 3];
            w[k] = 1.0;
            prop_assert_eq!(curved_surface_point(corners[k], corners, normals, w), corners[k]);
        }
    }

    #[test]
    fn a_flat_or_concave_patch_keeps_the_hit_point() {
        let corners = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let p = Vec3::new(0.25, 0.25, 0.0);
        let w = [0.5, 0.25, 0.25];
        // Flat: every normal is the face's.
        assert_eq!(curved_surface_point(p, corners, [Vec3::Z; 3], w), p);
        // Concave (a bowl): the normals lean inward, every corner's tangent
        // plane lies below P.
        let bowl = [
            Vec3::new(0.3, 0.3, 1.0).normalize(),
            Vec3::new(-0.5, 0.2, 1.0).normalize(),
            Vec3::new(0.2, -0.5, 1.0).normalize(),
        ];
        assert_eq!(curved_surface_point(p, corners, bowl, w), p);
    }

    #[test]
    fn the_weight_fades_from_below_the_triangle_to_the_band_edge() {
        assert_eq!(terminator_weight(-0.5), 1.0, "light below the triangle");
        assert_eq!(terminator_weight(0.0), 1.0, "light in its plane");
        let half = terminator_weight(0.5 * TERMINATOR_BAND);
        assert!((half - 0.5).abs() < 1e-6, "halfway: {half}");
        assert_eq!(
            terminator_weight(TERMINATOR_BAND),
            0.0,
            "at the band's edge"
        );
        assert_eq!(terminator_weight(0.7), 0.0, "light well above");
    }

    #[test]
    fn aim_points_at_the_target() {
        let (origin, target) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, -2.0, 3.0));
        let (dir, length) = aim(origin, target);
        assert_eq!(length, 5.0);
        assert!((origin + dir * length - target).length() < 1e-6);
    }
}
