//! What a mesh BVH reports of a ray's closest hit.

/// The closest hit of a ray with a mesh: P0 + α v = (1 − β − γ) t0 + β t1 + γ t2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Index of the triangle in the caller's `triangles`.
    pub triangle: u32,
    /// α, the ray parameter of the hit (the ray's direction is not normalised
    /// by the BVH, so this is the caller's α).
    pub alpha: f32,
    /// β, the weight of t1.
    pub beta: f32,
    /// γ, the weight of t2.
    pub gamma: f32,
}
