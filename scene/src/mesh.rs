//! Triangle meshes: shared vertex arrays indexed by triangles, as glTF
//! primitives and generated models provide them.

use glam::{Vec2, Vec3};

/// An indexed triangle mesh in its own (mesh) space. Shared through an `Arc`
/// by every object and instance that draws it, so its acceleration structure
/// is built once however often it is placed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles t0, t1, t2 as indices into `positions`; the geometric normal
    /// is (t1 − t0) × (t2 − t0), as for `<triangle>`.
    pub triangles: Vec<[u32; 3]>,
    /// One unit shading normal per vertex (interpolated across triangles for
    /// smooth shading); computed from the faces when a file has none.
    pub normals: Vec<Vec3>,
    /// One texture coordinate per vertex, or empty when the mesh has none.
    pub uvs: Vec<Vec2>,
}

impl TriangleMesh {
    /// The smallest axis-aligned box holding every vertex that a triangle
    /// uses, as (min, max); `None` for a mesh without triangles.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut corners = self
            .triangles
            .iter()
            .flatten()
            .map(|&v| self.positions[v as usize]);
        let first = corners.next()?;
        Some(corners.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// Area-weighted vertex normals from the faces (for files without
    /// normals); a vertex no triangle with area uses gets +y.
    pub fn face_normals_per_vertex(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
        let mut sum = vec![Vec3::ZERO; positions.len()];
        for &[a, b, c] in triangles {
            let (pa, pb, pc) = (
                positions[a as usize],
                positions[b as usize],
                positions[c as usize],
            );
            // The cross product's length is twice the area: an area weight.
            let n = (pb - pa).cross(pc - pa);
            for v in [a, b, c] {
                sum[v as usize] += n;
            }
        }
        sum.into_iter()
            .map(|n| n.try_normalize().unwrap_or(Vec3::Y))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_normals_of_a_flat_quad_point_along_its_winding() {
        let positions = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(0.0, 0.0, -1.0),
        ];
        let triangles = vec![[0, 1, 2], [0, 2, 3]];
        let normals = TriangleMesh::face_normals_per_vertex(&positions, &triangles);
        assert!(
            normals.iter().all(|n| (*n - Vec3::Y).length() < 1e-6),
            "{normals:?}"
        );
    }

    #[test]
    fn bounds_ignore_vertices_no_triangle_uses() {
        let mesh = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::splat(100.0)],
            triangles: vec![[0, 1, 2]],
            ..Default::default()
        };
        assert_eq!(mesh.bounds(), Some((Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0))));
        assert_eq!(TriangleMesh::default().bounds(), None);
    }
}
