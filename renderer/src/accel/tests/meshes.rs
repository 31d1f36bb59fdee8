//! Meshes for the tests: tiled grids whose shared edges and vertices lie on
//! exact lattice coordinates, and stacks of them.

use glam::Vec3;

/// [`crate::diagnostics::generate::tiled_floor`] as a (positions, triangles) pair.
pub(crate) fn grid(nx: u32, ny: u32, z: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let m = crate::diagnostics::generate::tiled_floor(nx, ny, z);
    (m.positions, m.triangles)
}

/// Appends mesh `b` to mesh `a`.
pub(crate) fn merge(a: &mut (Vec<Vec3>, Vec<[u32; 3]>), b: (Vec<Vec3>, Vec<[u32; 3]>)) {
    let base = a.0.len() as u32;
    a.0.extend(b.0);
    a.1.extend(b.1.into_iter().map(|t| t.map(|k| k + base)));
}

/// `mesh` with every position mapped by `f`.
pub(crate) fn mapped(
    mesh: (Vec<Vec3>, Vec<[u32; 3]>),
    f: impl Fn(Vec3) -> Vec3,
) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    (mesh.0.into_iter().map(f).collect(), mesh.1)
}
