//! Shapes are data: a closed enum with one file per variant, each with its
//! intersection and its tests beside it.
//!
//! Intersection is two-phase (as in pbrt): [`Shape::intersect`] returns only
//! the distance α of the nearest hit inside the ray's interval, cheap enough
//! to run against every candidate; [`Shape::surface`] computes the hit point
//! and normal for the one closest hit.

pub(crate) mod bound;
mod cone;
mod cuboid;
mod cylinder;
pub mod placement;
mod plane;
pub mod quadratic;
mod sphere;
mod torus;
mod triangle;

pub use cone::Cone;
pub use cuboid::Cuboid;
pub use cylinder::Cylinder;
pub use placement::Placement;
pub use plane::Plane;
pub use sphere::{Sphere, SphereQuadratic, SphereRoots};
pub use torus::Torus;
pub use triangle::{Triangle, TriangleHit, TriangleSampler, WatertightRay};

use crate::geometry::ray::Ray;
use glam::Vec3;
use scene::Geometry;

/// Which intersection formula to use where the lecture gives one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// The lecture's formulas exactly: the sphere's quadratic in α, the
    /// triangle's ray–plane α followed by the 2×2 barycentric solve.
    Lecture,
    /// Numerically robust forms: Ray Tracing Gems ch. 7 for the sphere,
    /// watertight Woop–Benthin–Wald 2013 for the triangle.
    #[default]
    Robust,
}

/// Where a ray meets a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The hit point, placed on the surface as accurately as the shape can.
    pub point: Vec3,
    /// The unit geometric normal, pointing out of closed shapes (for
    /// triangles: along (t1 − t0) × (t2 − t0); for planes: along n).
    pub normal: Vec3,
}

/// A point drawn on a shape's surface, for sampling it as a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaSample {
    /// The point on the surface.
    pub point: Vec3,
    /// The unit outward (for triangles: (t1 − t0) × (t2 − t0)) normal there.
    pub normal: Vec3,
    /// The density of drawing it, per unit area.
    pub pdf_area: f32,
}

/// Every primitive raylab can render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// A triangle.
    Triangle(Triangle),
    /// An oriented box.
    Box(Cuboid),
    /// A capped cylinder.
    Cylinder(Cylinder),
    /// A capped cone.
    Cone(Cone),
    /// A torus.
    Torus(Torus),
    /// An infinite plane.
    Plane(Plane),
}

impl Shape {
    /// The renderable shape for a resolved scene geometry; `None` for a mesh
    /// (meshes are triangles in a BVH, see [`crate::world::placed_mesh`]).
    pub fn from_geometry(geometry: &Geometry) -> Option<Shape> {
        Some(match *geometry {
            Geometry::Sphere { center, radius } => Shape::Sphere(Sphere::new(center, radius)),
            Geometry::Triangle { t0, t1, t2 } => Shape::Triangle(Triangle::new(t0, t1, t2)),
            Geometry::Box {
                center,
                size,
                rotate,
            } => Shape::Box(Cuboid::new(center, size, rotate)),
            Geometry::Cylinder {
                base,
                radius,
                height,
                rotate,
            } => Shape::Cylinder(Cylinder::new(base, radius, height, rotate)),
            Geometry::Cone {
                base,
                radius,
                height,
                rotate,
            } => Shape::Cone(Cone::new(base, radius, height, rotate)),
            Geometry::Torus {
                center,
                major,
                minor,
                rotate,
            } => Shape::Torus(Torus::new(center, major, minor, rotate)),
            Geometry::Plane { point, normal } => Shape::Plane(Plane::new(point, normal)),
            Geometry::Mesh { .. } => return None,
        })
    }

    /// The shape's kind as scene files name it ("sphere", "triangle", "box",
    /// "cylinder", "cone", "torus", "plane").
    pub fn kind_name(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Triangle(_) => "triangle",
            Shape::Box(_) => "box",
            Shape::Cylinder(_) => "cylinder",
            Shape::Cone(_) => "cone",
            Shape::Torus(_) => "torus",
            Shape::Plane(_) => "plane",
        }
    }

    /// α of the nearest hit inside the ray's interval, or `None`.
    /// `method` matters for the sphere and the triangle only.
    #[inline]
    pub fn intersect(&self, ray: &Ray, method: Method) -> Option<f32> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, method),
            Shape::Triangle(s) => s.intersect(ray, method),
            Shape::Box(s) => s.intersect(ray),
            Shape::Cylinder(s) => s.intersect(ray),
            Shape::Cone(s) => s.intersect(ray),
            Shape::Torus(s) => s.intersect(ray),
            Shape::Plane(s) => s.intersect(ray),
        }
    }

    /// The loose bounding sphere the shape's [`Shape::intersect`] tests
    /// first, for the shapes that have one (cylinders, cones and tori): a
    /// ray it turns away gets `None` from `intersect`.
    pub(crate) fn bounding_sphere(&self) -> Option<&bound::BoundingSphere> {
        match self {
            Shape::Cylinder(s) => Some(s.bound()),
            Shape::Cone(s) => Some(s.bound()),
            Shape::Torus(s) => Some(s.bound()),
            _ => None,
        }
    }

    /// The surface area (+∞ for a plane).
    pub fn area(&self) -> f32 {
        match self {
            Shape::Sphere(s) => s.area(),
            Shape::Triangle(s) => s.area(),
            Shape::Box(s) => s.area(),
            Shape::Cylinder(s) => s.area(),
            Shape::Cone(s) => s.area(),
            Shape::Torus(s) => s.area(),
            Shape::Plane(_) => f32::INFINITY,
        }
    }

    /// A point drawn on the surface from `u` ∈ [0, 1)², with its density per
    /// unit area: uniform, except on the torus (see [`Torus::sample_area`]);
    /// `None` for a plane (infinite) and a shape of no area.
    pub fn sample_area(&self, u: glam::Vec2) -> Option<AreaSample> {
        match self {
            Shape::Sphere(s) => s.sample_area(u),
            Shape::Triangle(s) => s.sample_area(u),
            Shape::Box(s) => s.sample_area(u),
            Shape::Cylinder(s) => s.sample_area(u),
            Shape::Cone(s) => s.sample_area(u),
            Shape::Torus(s) => s.sample_area(u),
            Shape::Plane(_) => None,
        }
    }

    /// The density per unit area with which [`Shape::sample_area`] draws
    /// `point` (a point on the surface).
    pub fn pdf_area(&self, point: Vec3) -> f32 {
        match self {
            Shape::Torus(s) => s.pdf_area(point),
            Shape::Plane(_) => 0.0,
            other => {
                let area = other.area();
                if area > 0.0 { 1.0 / area } else { 0.0 }
            }
        }
    }

    /// Hit point and normal of the hit at distance `alpha` along `ray`.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        match self {
            Shape::Sphere(s) => s.surface(ray, alpha),
            Shape::Triangle(s) => s.surface(ray, alpha),
            Shape::Box(s) => s.surface(ray, alpha),
            Shape::Cylinder(s) => s.surface(ray, alpha),
            Shape::Cone(s) => s.surface(ray, alpha),
            Shape::Torus(s) => s.surface(ray, alpha),
            Shape::Plane(s) => s.surface(ray, alpha),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_stays_small() {
        // Shapes are stored by value in flat arrays; keep them compact.
        assert!(
            std::mem::size_of::<Shape>() <= 80,
            "{}",
            std::mem::size_of::<Shape>()
        );
    }
}
