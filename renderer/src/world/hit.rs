//! What a ray query of the [`World`](super::World) returns: the object hit,
//! α along the ray and, on a mesh, the triangle and where on it.

/// What the ray hit: which object, how far along the ray, and for meshes
/// which triangle where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The object's index (its object id).
    pub object: u32,
    /// α, the distance along the ray.
    pub alpha: f32,
    /// The triangle hit, when the object is a mesh.
    pub triangle: Option<TriangleRef>,
}

/// A triangle of a placed mesh, and where on it a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleRef {
    /// Index into [`World::meshes`](super::World::meshes).
    pub instance: u32,
    /// The triangle's index in its mesh.
    pub triangle: u32,
    /// β, the weight of t1.
    pub beta: f32,
    /// γ, the weight of t2.
    pub gamma: f32,
}

impl TriangleRef {
    /// The accelerator's view of this triangle hit at α = `alpha`.
    pub(super) fn mesh_hit(self, alpha: f32) -> crate::accel::MeshHit {
        crate::accel::MeshHit {
            triangle: self.triangle,
            alpha,
            beta: self.beta,
            gamma: self.gamma,
        }
    }
}
