//! Meshes for the tests: tiled grids whose shared edges and vertices lie on
//! exact lattice coordinates, and stacks of them.

use glam::Vec3;

/// An `nx` × `ny` grid of unit squares in the plane z = `z`, corners at
/// integer (x, y), each square split along alternating diagonals into two
/// triangles: 2 nx ny triangles, every box flat in z.
pub(crate) fn grid(nx: u32, ny: u32, z: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut positions = Vec::with_capacity(((nx + 1) * (ny + 1)) as usize);
    for j in 0..=ny {
        for i in 0..=nx {
            positions.push(Vec3::new(i as f32, j as f32, z));
        }
    }
    let mut triangles = Vec::with_capacity((2 * nx * ny) as usize);
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            if (i + j).is_multiple_of(2) {
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            } else {
                triangles.push([a, b, d]);
                triangles.push([b, c, d]);
            }
        }
    }
    (positions, triangles)
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
