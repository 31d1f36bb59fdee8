//! Triangle meshes of the scene's primitives for the debug view: each
//! primitive drawn by its own shape, placed by the same [`Placement`] the tracer
//! uses, so the drawing and the image agree.

use glam::Vec3;
use renderer::shapes::Placement;
use scene::Geometry;
use std::f32::consts::TAU;

/// Segments around a circle (spheres, cylinders, cones, tori).
const AROUND: u32 = 40;
/// Rings from pole to pole of a sphere, and around a torus tube.
const RINGS: u32 = 20;

/// One corner of a shaded triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshVertex {
    /// Position in the world.
    pub position: Vec3,
    /// Unit surface normal (outward for closed shapes).
    pub normal: Vec3,
}

/// Appends the triangles of `geometry` to `out` (three vertices each).
/// An infinite plane is drawn as a square of half-size `plane_extent` centred
/// at the point of the plane nearest to `focus`.
pub fn tessellate(geometry: &Geometry, focus: Vec3, plane_extent: f32, out: &mut Vec<MeshVertex>) {
    match *geometry {
        Geometry::Sphere { center, radius } => sphere(Placement::at(center), radius, out),
        Geometry::Box {
            center,
            size,
            rotate,
        } => cuboid(
            Placement::from_euler_degrees(center, rotate),
            0.5 * size,
            out,
        ),
        Geometry::Cylinder {
            base,
            radius,
            height,
            rotate,
        } => cylinder(
            Placement::from_euler_degrees(base, rotate),
            radius,
            height,
            out,
        ),
        Geometry::Cone {
            base,
            radius,
            height,
            rotate,
        } => cone(
            Placement::from_euler_degrees(base, rotate),
            radius,
            height,
            out,
        ),
        Geometry::Torus {
            center,
            major,
            minor,
            rotate,
        } => torus(
            Placement::from_euler_degrees(center, rotate),
            major,
            minor,
            out,
        ),
        Geometry::Triangle { t0, t1, t2 } => {
            let normal = (t1 - t0).cross(t2 - t0).normalize_or(Vec3::Y);
            for position in [t0, t1, t2] {
                out.push(MeshVertex { position, normal });
            }
        }
        Geometry::Plane { point, normal } => plane(point, normal, focus, plane_extent, out),
        Geometry::Mesh {
            ref model,
            world_from_model,
            ..
        } => mesh(model, world_from_model, out),
    }
}

/// Most triangles of one model drawn as they are; a bigger model is drawn
/// as the boxes around its instances (lavapipe draws on the CPU).
const MESH_TRIANGLE_LIMIT: usize = 200_000;

/// A model's instances: each triangle with its vertex normals, placed like
/// the tracer places them; the instances' boxes for models too big to draw.
fn mesh(model: &scene::ModelFile, world_from_model: glam::Mat4, out: &mut Vec<MeshVertex>) {
    let draw_triangles = model.drawn_triangles() <= MESH_TRIANGLE_LIMIT;
    for instance in &model.instances {
        let mesh = &model.meshes[instance.mesh as usize];
        let transform = world_from_model * instance.model_from_mesh;
        if !draw_triangles {
            if let Some((lo, hi)) = mesh.bounds() {
                let center = 0.5 * (lo + hi);
                let local = Placement::at(Vec3::ZERO);
                let start = out.len();
                cuboid(local, 0.5 * (hi - lo), out);
                for v in &mut out[start..] {
                    v.position = transform.transform_point3(v.position + center);
                    v.normal = transform.transform_vector3(v.normal).normalize_or(Vec3::Y);
                }
            }
            continue;
        }
        let normal_matrix = glam::Mat3::from_mat4(transform).inverse().transpose();
        for &[a, b, c] in &mesh.triangles {
            let corners = [a, b, c].map(|k| mesh.positions[k as usize]);
            let face = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            for (k, p) in [a, b, c].into_iter().zip(corners) {
                let n = mesh.normals.get(k as usize).copied().unwrap_or(face);
                out.push(MeshVertex {
                    position: transform.transform_point3(p),
                    normal: (normal_matrix * n).normalize_or(Vec3::Y),
                });
            }
        }
    }
}

/// Objects beyond which each is drawn as its bounding box (lavapipe draws
/// on the CPU: ten thousand tessellated spheres would be 16 million triangles).
pub const OBJECTS_DRAWN_IN_FULL: usize = 2_000;

/// Appends the axis-aligned box around `geometry` (an infinite plane as
/// [`tessellate`] draws it).
pub fn tessellate_bounds(
    geometry: &Geometry,
    focus: Vec3,
    plane_extent: f32,
    out: &mut Vec<MeshVertex>,
) {
    match scene::layout::bounds(geometry) {
        Some(b) => cuboid(Placement::at(b.center()), 0.5 * (b.max - b.min), out),
        None => tessellate(geometry, focus, plane_extent, out),
    }
}

/// Pushes the quad a, b, c, d (counter-clockwise seen from outside) as two triangles.
fn quad(out: &mut Vec<MeshVertex>, [a, b, c, d]: [MeshVertex; 4]) {
    out.extend([a, b, c, a, c, d]);
}

/// The square with corners `corner(±1, ±1)`, counter-clockwise from (−1, −1).
fn square(out: &mut Vec<MeshVertex>, corner: impl Fn(f32, f32) -> MeshVertex) {
    quad(
        out,
        [
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
        ],
    );
}

/// An object-space vertex in the world.
fn placed(frame: &Placement, position: Vec3, normal: Vec3) -> MeshVertex {
    MeshVertex {
        position: frame.point_to_world(position),
        normal: frame.vector_to_world(normal),
    }
}

/// A point on the unit circle in the local xz-plane.
fn around(k: u32) -> Vec3 {
    let phi = TAU * k as f32 / AROUND as f32;
    Vec3::new(phi.cos(), 0.0, -phi.sin())
}

fn sphere(frame: Placement, radius: f32, out: &mut Vec<MeshVertex>) {
    let vertex = |k: u32, ring: u32| {
        let polar = std::f32::consts::PI * ring as f32 / RINGS as f32;
        let n = around(k) * polar.sin() + Vec3::Y * polar.cos();
        placed(&frame, n * radius, n)
    };
    for ring in 0..RINGS {
        for k in 0..AROUND {
            let [a, b, c, d] = [
                vertex(k, ring),
                vertex(k, ring + 1),
                vertex(k + 1, ring + 1),
                vertex(k + 1, ring),
            ];
            // At the poles one triangle of the quad is a point.
            if ring + 1 < RINGS {
                out.extend([a, b, c]);
            }
            if ring > 0 {
                out.extend([a, c, d]);
            }
        }
    }
}

fn cuboid(frame: Placement, half: Vec3, out: &mut Vec<MeshVertex>) {
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            // Two in-face axes forming a right-handed (a, b, n) basis.
            let a = Vec3::from_array(std::array::from_fn(|k| {
                if k == (axis + 1) % 3 { 1.0 } else { 0.0 }
            }));
            let b = n.cross(a);
            square(out, |s, t| placed(&frame, (n + s * a + t * b) * half, n));
        }
    }
}

/// A flat disk of `radius` at local height `y`, facing `normal_y` (±1).
fn disk(frame: &Placement, radius: f32, y: f32, normal_y: f32, out: &mut Vec<MeshVertex>) {
    let n = Vec3::Y * normal_y;
    let centre = placed(frame, Vec3::Y * y, n);
    for k in 0..AROUND {
        let (a, b) = if normal_y > 0.0 {
            (k, k + 1)
        } else {
            (k + 1, k)
        };
        out.extend([
            centre,
            placed(frame, around(a) * radius + Vec3::Y * y, n),
            placed(frame, around(b) * radius + Vec3::Y * y, n),
        ]);
    }
}

fn cylinder(frame: Placement, radius: f32, height: f32, out: &mut Vec<MeshVertex>) {
    for k in 0..AROUND {
        let side = |k: u32, y: f32| placed(&frame, around(k) * radius + Vec3::Y * y, around(k));
        quad(
            out,
            [
                side(k, 0.0),
                side(k + 1, 0.0),
                side(k + 1, height),
                side(k, height),
            ],
        );
    }
    disk(&frame, radius, 0.0, -1.0, out);
    disk(&frame, radius, height, 1.0, out);
}

fn cone(frame: Placement, radius: f32, height: f32, out: &mut Vec<MeshVertex>) {
    // The side's normal leans up by the slope R/H.
    let normal = |k: u32| (around(k) * height + Vec3::Y * radius).normalize_or(Vec3::Y);
    for k in 0..AROUND {
        let apex_normal = (normal(k) + normal(k + 1)).normalize_or(Vec3::Y);
        out.extend([
            placed(&frame, around(k) * radius, normal(k)),
            placed(&frame, around(k + 1) * radius, normal(k + 1)),
            placed(&frame, Vec3::Y * height, apex_normal),
        ]);
    }
    disk(&frame, radius, 0.0, -1.0, out);
}

fn torus(frame: Placement, major: f32, minor: f32, out: &mut Vec<MeshVertex>) {
    let vertex = |k: u32, ring: u32| {
        let psi = TAU * ring as f32 / RINGS as f32;
        let n = around(k) * psi.cos() + Vec3::Y * psi.sin();
        placed(&frame, around(k) * major + n * minor, n)
    };
    for k in 0..AROUND {
        for ring in 0..RINGS {
            quad(
                out,
                [
                    vertex(k, ring),
                    vertex(k + 1, ring),
                    vertex(k + 1, ring + 1),
                    vertex(k, ring + 1),
                ],
            );
        }
    }
}

fn plane(point: Vec3, normal: Vec3, focus: Vec3, extent: f32, out: &mut Vec<MeshVertex>) {
    let n = normal.normalize_or(Vec3::Y);
    let centre = focus - (focus - point).dot(n) * n;
    let a = n.any_orthonormal_vector();
    let b = n.cross(a);
    square(out, |s, t| MeshVertex {
        position: centre + extent * (s * a + t * b),
        normal: n,
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderer::geometry::ray::Ray;
    use renderer::shapes::Shape;

    fn shapes() -> Vec<Geometry> {
        let rotate = Vec3::new(20.0, -35.0, 10.0);
        vec![
            Geometry::Sphere {
                center: Vec3::new(1.0, 2.0, -3.0),
                radius: 0.7,
            },
            Geometry::Box {
                center: Vec3::new(-1.0, 0.5, 0.0),
                size: Vec3::new(1.0, 2.0, 0.5),
                rotate,
            },
            Geometry::Cylinder {
                base: Vec3::new(0.0, -1.0, 2.0),
                radius: 0.4,
                height: 1.5,
                rotate,
            },
            Geometry::Cone {
                base: Vec3::new(2.0, 0.0, 1.0),
                radius: 0.6,
                height: 1.2,
                rotate,
            },
            Geometry::Torus {
                center: Vec3::new(0.0, 1.0, -1.0),
                major: 1.0,
                minor: 0.25,
                rotate,
            },
            Geometry::Triangle {
                t0: Vec3::ZERO,
                t1: Vec3::X,
                t2: Vec3::Y,
            },
            Geometry::Plane {
                point: Vec3::new(0.0, -2.0, 0.0),
                normal: Vec3::new(0.1, 1.0, 0.0),
            },
        ]
    }

    /// Every triangle lies on the traced surface: from points inside each
    /// triangle (near each corner), a ray started half a unit outside along
    /// the mesh normal and sent back hits the shape at α ≈ ½ (up to the
    /// chord's sag), where the tracer's normal agrees with the mesh normal.
    #[test]
    fn mesh_triangles_lie_on_the_traced_surface_with_its_normal() {
        for geometry in shapes() {
            let shape = Shape::from_geometry(&geometry).expect("an analytic shape");
            let mut mesh = Vec::new();
            tessellate(&geometry, Vec3::ZERO, 3.0, &mut mesh);
            assert_eq!(mesh.len() % 3, 0);
            assert!(!mesh.is_empty());
            for tri in mesh.chunks_exact(3) {
                let centroid = (tri[0].position + tri[1].position + tri[2].position) / 3.0;
                let mean = (tri[0].normal + tri[1].normal + tri[2].normal) / 3.0;
                for v in tri {
                    assert!((v.normal.length() - 1.0).abs() < 1e-4, "{geometry:?}");
                    let p = 0.8 * v.position + 0.2 * centroid;
                    let n = (0.8 * v.normal + 0.2 * mean).normalize();
                    let ray = Ray::new(p + 0.5 * n, -n);
                    let Some(alpha) = shape.intersect(&ray, renderer::Method::Robust) else {
                        panic!("{geometry:?}: the ray back to {p} misses");
                    };
                    assert!(
                        (alpha - 0.5).abs() < 0.01,
                        "{geometry:?}: α = {alpha} at {p}"
                    );
                    let normal = shape.surface(&ray, alpha).normal;
                    assert!(normal.dot(n) > 0.98, "{geometry:?}: {normal} vs {n} at {p}");
                }
            }
        }
    }

    #[test]
    fn triangles_wind_counter_clockwise_around_their_outward_normal() {
        for geometry in shapes() {
            let mut mesh = Vec::new();
            tessellate(&geometry, Vec3::ZERO, 3.0, &mut mesh);
            for tri in mesh.chunks_exact(3) {
                let face =
                    (tri[1].position - tri[0].position).cross(tri[2].position - tri[0].position);
                let mean = tri[0].normal + tri[1].normal + tri[2].normal;
                assert!(face.dot(mean) > 0.0, "{geometry:?}: {tri:?}");
            }
        }
    }
}
