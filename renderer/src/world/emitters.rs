//! Emissive surfaces as area lights: every shape or mesh triangle whose
//! material emits, with a way to draw a point on them as seen from a shading
//! point (next-event estimation) and the density of having drawn a point a
//! BSDF-sampled ray found (for multiple importance sampling).
//!
//! Radiance leaves the front side only: the outside of closed shapes, the
//! side of a triangle that (t1 − t0) × (t2 − t0) faces. An emitter is chosen
//! in proportion to its power (luminance of its radiance × area); a sphere
//! seen from outside is sampled over the cone of directions it subtends, any
//! other shape over its area. An infinite plane cannot be sampled: rays find
//! it by BSDF sampling alone.

use crate::geometry::alias_table::AliasTable;
use crate::geometry::ray::Ray;
use crate::shapes::{Method, Shape, Triangle, TriangleSampler};
use crate::world::Hit;
use crate::world::placed_mesh::PlacedMesh;
use glam::{Vec2, Vec3};
use scene::color::luminance;
use std::f32::consts::TAU;

/// No emitter.
const NONE: u32 = u32::MAX;

/// One emissive surface in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emitter {
    /// Its shape (a mesh triangle as a world-space triangle).
    pub shape: Shape,
    /// Radiance leaving its front side (linear RGB).
    pub radiance: Vec3,
}

/// A point drawn on an emitter, as seen from the shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterSample {
    /// The index of the emitter drawn.
    pub index: usize,
    /// Unit direction from the shading point toward the drawn point.
    pub to_light: Vec3,
    /// Distance to the drawn point (the shadow ray's t_max, shortened by the caller).
    pub distance: f32,
    /// Radiance arriving from it (zero when its back faces the shading point).
    pub radiance: Vec3,
    /// The density of this direction in solid angle, the choice of emitter included.
    pub pdf: f32,
}

/// Every emitter of a world, with the distribution that chooses among them.
#[derive(Clone, Debug, Default)]
pub struct Emitters {
    emitters: Vec<Emitter>,
    /// Probability of choosing each emitter.
    pmf: Vec<f32>,
    /// Per emitter, its triangle prepared for drawing points (`None` for
    /// other shapes): the area, normal and density computed once instead of
    /// at every path vertex, with the same results bit for bit.
    triangles: Vec<Option<TriangleSampler>>,
    /// Chooses an emitter in proportion to its power in O(1); `None` when
    /// nothing emits any power (no emitter can be drawn).
    choice: Option<AliasTable>,
    /// Per object id: its emitter, for analytic shapes.
    by_object: Vec<u32>,
    /// Per mesh instance: the emitter of its triangle 0 (its triangles follow in order).
    by_instance: Vec<u32>,
}

/// Whether radiance is worth a light: any positive, finite channel.
fn emits(radiance: Vec3) -> bool {
    radiance.is_finite() && radiance.max_element() > 0.0
}

impl Emitters {
    /// The emitters among `shapes` (one per object id, `None` for models,
    /// with each object's emission) and the emissive mesh instances.
    pub fn new(shapes: &[(Option<Shape>, Vec3)], meshes: &[PlacedMesh]) -> Emitters {
        let mut emitters = Vec::new();
        let mut by_object = vec![NONE; shapes.len()];
        for (id, (shape, radiance)) in shapes.iter().enumerate() {
            if let Some(shape) = shape
                && emits(*radiance)
            {
                by_object[id] = emitters.len() as u32;
                emitters.push(Emitter {
                    shape: *shape,
                    radiance: *radiance,
                });
            }
        }
        let mut by_instance = vec![NONE; meshes.len()];
        for (k, placed) in meshes.iter().enumerate() {
            if !emits(placed.material.emission) {
                continue;
            }
            by_instance[k] = emitters.len() as u32;
            let mesh = &placed.mesh;
            for &[a, b, c] in &mesh.triangles {
                let [pa, pb, pc] = [a, b, c].map(|v| mesh.positions[v as usize]);
                let local_normal = (pb - pa).cross(pc - pa);
                let [wa, mut wb, mut wc] = [pa, pb, pc].map(|p| placed.instance.point_to_world(p));
                // A mirroring placement turns the winding around; keep the
                // emitting side where the world's geometric normal is.
                if (wb - wa)
                    .cross(wc - wa)
                    .dot(placed.instance.normal_to_world(local_normal))
                    < 0.0
                {
                    std::mem::swap(&mut wb, &mut wc);
                }
                emitters.push(Emitter {
                    shape: Shape::Triangle(Triangle::new(wa, wb, wc)),
                    radiance: placed.material.emission,
                });
            }
        }
        let power: Vec<f32> = emitters
            .iter()
            .map(|e| {
                let p = luminance(e.radiance).max(0.0) * e.shape.area();
                if p.is_finite() { p } else { 0.0 }
            })
            .collect();
        let total: f64 = power.iter().map(|&p| f64::from(p)).sum();
        let pmf: Vec<f32> = if total > 0.0 {
            power
                .iter()
                .map(|&p| (f64::from(p) / total) as f32)
                .collect()
        } else {
            vec![0.0; power.len()]
        };
        let choice = AliasTable::new(&power);
        let triangles = emitters
            .iter()
            .map(|e| match e.shape {
                Shape::Triangle(t) => t.area_sampler(),
                _ => None,
            })
            .collect();
        Emitters {
            emitters,
            pmf,
            triangles,
            choice,
            by_object,
            by_instance,
        }
    }

    /// Whether no emitter can be drawn (none, or none with power).
    pub fn is_empty(&self) -> bool {
        self.choice.is_none()
    }

    /// The distribution [`Emitters::choose`] draws from, and each emitter's
    /// probability under it; `None` when no emitter can be drawn.
    pub fn choice(&self) -> Option<(&AliasTable, &[f32])> {
        Some((self.choice.as_ref()?, &self.pmf))
    }

    /// The emitters, in index order.
    pub fn emitters(&self) -> &[Emitter] {
        &self.emitters
    }

    /// The emitter a hit landed on, if its surface is one.
    pub fn index_of(&self, hit: &Hit) -> Option<usize> {
        let index = match hit.triangle {
            Some(t) => self
                .by_instance
                .get(t.instance as usize)
                .copied()
                .filter(|&first| first != NONE)
                .map(|first| first + t.triangle),
            None => self
                .by_object
                .get(hit.object as usize)
                .copied()
                .filter(|&e| e != NONE),
        }?;
        Some(index as usize)
    }

    /// The emitter `u_select` chooses (what [`Emitters::sample`] draws
    /// first) and the probability of choosing it; `None` when that is not
    /// positive.
    #[inline]
    pub fn choose(&self, u_select: f32) -> Option<(usize, f32)> {
        let index = self.choice.as_ref()?.sample(u_select);
        let pmf = self.pmf[index];
        (pmf > 0.0).then_some((index, pmf))
    }

    /// Emitter `index` when it is a triangle, prepared for drawing points
    /// (as [`Emitters::sample`] draws them), with its radiance.
    #[inline]
    pub fn triangle(&self, index: usize) -> Option<(&TriangleSampler, Vec3)> {
        let triangle = self.triangles.get(index)?.as_ref()?;
        Some((triangle, self.emitters[index].radiance))
    }

    /// Draws an emitter with `u_select` and a point on it with `u`, as seen
    /// from `from`; `None` when nothing can be drawn.
    pub fn sample(&self, from: Vec3, u_select: f32, u: Vec2) -> Option<EmitterSample> {
        let (index, pmf) = self.choose(u_select)?;
        let emitter = &self.emitters[index];
        if let Shape::Sphere(sphere) = emitter.shape
            && let Some(cone) = SphereCone::new(from, sphere.center, sphere.radius)
        {
            let dir = cone.sample(u);
            let ray = Ray::new(from, dir);
            let alpha = sphere.intersect(&ray, Method::Robust)?;
            return Some(EmitterSample {
                index,
                to_light: dir,
                distance: alpha,
                radiance: emitter.radiance,
                pdf: pmf * cone.pdf(),
            });
        }
        let s = match &self.triangles[index] {
            Some(triangle) => triangle.sample(u),
            None => emitter.shape.sample_area(u)?,
        };
        let to = s.point - from;
        let distance_sq = to.length_squared();
        if !(distance_sq > 0.0) {
            return None;
        }
        let distance = distance_sq.sqrt();
        let to_light = to / distance;
        let cos_light = -to_light.dot(s.normal);
        if !(cos_light > 0.0) {
            return None;
        }
        Some(EmitterSample {
            index,
            to_light,
            distance,
            radiance: emitter.radiance,
            pdf: pmf * s.pdf_area * distance_sq / cos_light,
        })
    }

    /// The density in solid angle with which [`Emitters::sample`], from
    /// `from`, draws the direction toward `point` (normal `normal`) on
    /// emitter `index`.
    pub fn pdf(&self, from: Vec3, index: usize, point: Vec3, normal: Vec3) -> f32 {
        let (Some(emitter), Some(&pmf)) = (self.emitters.get(index), self.pmf.get(index)) else {
            return 0.0;
        };
        if let Shape::Sphere(sphere) = emitter.shape
            && let Some(cone) = SphereCone::new(from, sphere.center, sphere.radius)
        {
            return pmf * cone.pdf();
        }
        let to = point - from;
        let distance_sq = to.length_squared();
        let cos_light = (-to.dot(normal)) / distance_sq.sqrt();
        if !(cos_light > 0.0) {
            return 0.0;
        }
        let pdf_area = match &self.triangles[index] {
            Some(triangle) => triangle.pdf_area,
            None => emitter.shape.pdf_area(point),
        };
        pmf * pdf_area * distance_sq / cos_light
    }
}

/// The cone of directions from a point outside a sphere toward it.
struct SphereCone {
    /// Unit axis toward the centre.
    axis: Vec3,
    /// 1 − cos θ_max, formed without cancellation for small spheres.
    one_minus_cos: f32,
}

impl SphereCone {
    /// The cone from `from`, or `None` when `from` is on or inside the sphere.
    fn new(from: Vec3, center: Vec3, radius: f32) -> Option<Self> {
        let to = center - from;
        let distance_sq = to.length_squared();
        let radius_sq = radius * radius;
        if !(distance_sq > radius_sq * 1.0001) {
            return None;
        }
        let sin2 = radius_sq / distance_sq;
        let cos = (1.0 - sin2).max(0.0).sqrt();
        Some(Self {
            axis: to / distance_sq.sqrt(),
            one_minus_cos: sin2 / (1.0 + cos),
        })
    }

    /// A direction uniform in solid angle inside the cone.
    fn sample(&self, u: Vec2) -> Vec3 {
        let one_minus_cos = u.x * self.one_minus_cos;
        let cos = 1.0 - one_minus_cos;
        let sin = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
        let phi = TAU * u.y;
        let (s, t) = self.axis.any_orthonormal_pair();
        (sin * phi.cos() * s + sin * phi.sin() * t + cos * self.axis).normalize()
    }

    /// Its uniform density, 1 / solid angle.
    fn pdf(&self) -> f32 {
        1.0 / (TAU * self.one_minus_cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::shapes::{Cone, Cuboid, Cylinder, Sphere, Torus};

    /// The solid angle a shape subtends from `from`, estimated by light
    /// sampling (E[1 / pdf] over front-facing samples) and by brute-force
    /// ray casting over the sphere of directions; they must agree.
    fn solid_angle_two_ways(shape: Shape, from: Vec3) -> (f64, f64) {
        let emitters = Emitters::new(&[(Some(shape), Vec3::ONE)], &[]);
        let mut sampler = Sampler::for_sample(3, 1, 2, 0);
        let n = 200_000;
        let mut by_light = 0.0f64;
        for _ in 0..n {
            let u_select = sampler.next_f32();
            if let Some(s) = emitters.sample(from, u_select, sampler.next_2d()) {
                // Count only directions where this point is the first hit.
                let hit = shape.intersect(&Ray::new(from, s.to_light), Method::Robust);
                if hit.is_some_and(|a| (a - s.distance).abs() <= 1e-3 * s.distance) {
                    by_light += 1.0 / f64::from(s.pdf);
                }
            }
        }
        // Directions on a Fibonacci lattice: far less noisy than random ones.
        let lattice = 1_000_000u32;
        let golden = (1.0 + 5.0f64.sqrt()) / 2.0;
        let mut hits = 0u32;
        for k in 0..lattice {
            let z = 1.0 - (2.0 * f64::from(k) + 1.0) / f64::from(lattice);
            let phi = std::f64::consts::TAU * (f64::from(k) / golden).fract();
            let r = (1.0 - z * z).sqrt();
            let d = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
            if shape
                .intersect(&Ray::new(from, d), Method::Robust)
                .is_some()
            {
                hits += 1;
            }
        }
        (
            by_light / f64::from(n),
            4.0 * std::f64::consts::PI * f64::from(hits) / f64::from(lattice),
        )
    }

    #[test]
    fn light_sampling_densities_integrate_to_each_shapes_solid_angle() {
        let from = Vec3::new(0.3, 2.5, 1.9);
        let shapes = [
            Shape::Sphere(Sphere::new(Vec3::ZERO, 0.8)),
            Shape::Triangle(Triangle::new(
                Vec3::new(-1.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 1.5, 0.3),
            )),
            Shape::Box(Cuboid::new(
                Vec3::ZERO,
                Vec3::new(1.0, 0.6, 1.4),
                Vec3::new(10.0, 30.0, 0.0),
            )),
            Shape::Cylinder(Cylinder::new(
                Vec3::ZERO,
                0.5,
                1.2,
                Vec3::new(0.0, 0.0, 20.0),
            )),
            Shape::Cone(Cone::new(Vec3::ZERO, 0.7, 1.1, Vec3::new(15.0, 0.0, 0.0))),
            Shape::Torus(Torus::new(Vec3::ZERO, 0.8, 0.25, Vec3::new(40.0, 0.0, 0.0))),
        ];
        for shape in shapes {
            let (by_light, by_rays) = solid_angle_two_ways(shape, from);
            assert!(
                (by_light - by_rays).abs() < 0.01 * by_rays,
                "{}: light sampling {by_light}, ray casting {by_rays}",
                shape.kind_name()
            );
        }
    }
}
