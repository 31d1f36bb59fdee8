//! TEMPORARY brute-force stand-in with the API of the BVH being written in
//! `accel/` (same signatures), so that meshes can be integrated meanwhile.

use crate::ray::Ray;
use crate::shapes::{Method, Triangle};
use glam::Vec3;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

/// A triangle hit in a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Index into the caller's triangles.
    pub triangle: u32,
    /// α.
    pub alpha: f32,
    /// β, weight of t1.
    pub beta: f32,
    /// γ, weight of t2.
    pub gamma: f32,
}

/// Bottom level over one mesh.
#[derive(Clone, Debug)]
pub struct MeshBvh {
    triangles: Vec<Triangle>,
    bounds: Aabb,
}

impl MeshBvh {
    /// Builds over the mesh.
    pub fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> MeshBvh {
        let tris: Vec<Triangle> = triangles
            .iter()
            .map(|&[a, b, c]| {
                Triangle::new(
                    positions[a as usize],
                    positions[b as usize],
                    positions[c as usize],
                )
            })
            .collect();
        let mut bounds = Aabb {
            min: Vec3::INFINITY,
            max: Vec3::NEG_INFINITY,
        };
        for t in &tris {
            for p in [t.t0, t.t1, t.t2] {
                bounds.min = bounds.min.min(p);
                bounds.max = bounds.max.max(p);
            }
        }
        MeshBvh {
            triangles: tris,
            bounds,
        }
    }

    /// Closest hit.
    pub fn closest_hit(&self, ray: &Ray) -> Option<MeshHit> {
        let mut search = *ray;
        let mut best = None;
        for (k, t) in self.triangles.iter().enumerate() {
            if let Some(h) = t.hit(&search, Method::Robust) {
                search.t_max = h.alpha;
                best = Some(MeshHit {
                    triangle: k as u32,
                    alpha: h.alpha,
                    beta: h.beta,
                    gamma: h.gamma,
                });
            }
        }
        best
    }

    /// Any hit.
    pub fn any_hit(&self, ray: &Ray) -> bool {
        self.triangles
            .iter()
            .any(|t| t.hit(ray, Method::Robust).is_some())
    }

    /// Bounds.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Bytes.
    pub fn bytes(&self) -> usize {
        self.triangles.len() * std::mem::size_of::<Triangle>()
    }
}

/// Top level over boxes.
#[derive(Clone, Debug, Default)]
pub struct SceneBvh {
    count: u32,
}

impl SceneBvh {
    /// Builds over the boxes.
    pub fn build(bounds: &[Aabb]) -> SceneBvh {
        SceneBvh {
            count: bounds.len() as u32,
        }
    }

    /// Closest item hit.
    pub fn closest(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let mut search = *ray;
        let mut best = None;
        for item in 0..self.count {
            if let Some(alpha) = test(item, &search) {
                search.t_max = alpha;
                best = Some((item, alpha));
            }
        }
        best
    }

    /// Any item hit.
    pub fn any(&self, ray: &Ray, mut test: impl FnMut(u32, &Ray) -> bool) -> bool {
        (0..self.count).any(|item| test(item, ray))
    }
}
