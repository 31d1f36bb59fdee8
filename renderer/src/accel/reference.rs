//! Brute force: every triangle tested with the watertight test. The oracle
//! that [`super::MeshBvh`] must equal (and slow: O(triangles) per ray).

use super::mesh::MeshHit;
use crate::geometry::ray::Ray;
use crate::shapes::WatertightRay;
use glam::Vec3;

/// The hit with the smallest α over all triangles (the first such triangle
/// on ties), exactly as [`super::MeshBvh::closest_hit`] must report it.
pub fn closest_hit(positions: &[Vec3], triangles: &[[u32; 3]], ray: &Ray) -> Option<MeshHit> {
    let w = WatertightRay::new(ray);
    let mut best: Option<MeshHit> = None;
    for (i, t) in triangles.iter().enumerate() {
        let [a, b, c] = t.map(|k| positions[k as usize]);
        if let Some(h) = w.hit(ray, a, b, c)
            && best.is_none_or(|b| h.alpha < b.alpha)
        {
            best = Some(MeshHit {
                triangle: i as u32,
                alpha: h.alpha,
                beta: h.beta,
                gamma: h.gamma,
            });
        }
    }
    best
}

/// True when any triangle is hit in (t_min, t_max).
pub fn any_hit(positions: &[Vec3], triangles: &[[u32; 3]], ray: &Ray) -> bool {
    let w = WatertightRay::new(ray);
    triangles.iter().any(|t| {
        let [a, b, c] = t.map(|k| positions[k as usize]);
        w.hit(ray, a, b, c).is_some()
    })
}

/// The α of `triangle` for `ray`, if it is hit in the ray's interval.
pub fn triangle_alpha(positions: &[Vec3], triangle: [u32; 3], ray: &Ray) -> Option<f32> {
    let [a, b, c] = triangle.map(|k| positions[k as usize]);
    WatertightRay::new(ray).hit(ray, a, b, c).map(|h| h.alpha)
}
