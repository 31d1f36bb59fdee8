//! An orthonormal shading frame around a normal: directions in local
//! coordinates have z along the normal, so cos θ is just `z`.

use glam::Vec3;

/// The local frame (s, t, n) of a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingFrame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent, n × s.
    pub t: Vec3,
    /// The unit normal, local +z.
    pub n: Vec3,
}

impl ShadingFrame {
    /// A frame around the unit normal `n` (Duff et al. 2017, through glam).
    pub fn new(n: Vec3) -> Self {
        let (s, t) = n.any_orthonormal_pair();
        Self { s, t, n }
    }

    /// World direction → local coordinates.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local coordinates → world direction.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        v.x * self.s + v.y * self.t + v.z * self.n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn local_and_world_coordinates_round_trip() {
        let n = Vec3::new(0.3, -0.5, 0.8).normalize();
        let f = ShadingFrame::new(n);
        let v = Vec3::new(-0.2, 0.9, 0.1);
        assert!((f.to_world(f.to_local(v)) - v).length() < 1e-6);
        assert!((f.to_local(n) - Vec3::Z).length() < 1e-6);
    }
}
