//! The `<sphere>` objects of a world in one BVH of their own
//! ([`Method::Robust`] only), one item of the top level: leaves of up to
//! eight spheres, tested four at a time ([`SpherePack`]) with exactly the
//! arithmetic of [`Sphere::intersect`] (bit for bit the same α). A field of
//! spheres then costs a few SIMD tests per ray instead of a box test and a
//! scalar sphere test per sphere its box lets through.
//!
//! [`Method::Robust`]: crate::shapes::Method::Robust

use super::Hit;
use crate::accel::sphere_pack::{SPHERES_PER_PACK, SpherePack, SphereRay};
use crate::accel::{Aabb, SceneBvh};
use crate::geometry::ray::Ray;
use crate::shapes::Sphere;

/// Spheres are grouped from this many on: with fewer, the top level's own
/// box test per sphere is as cheap.
pub(super) const GROUPED_SPHERES: usize = 8;

/// Spheres in a leaf of the group's BVH (two packs).
const LEAF_SPHERES: usize = 2 * SPHERES_PER_PACK;

/// The lone spheres of a world in one BVH.
#[derive(Clone, Debug)]
pub(super) struct LoneSpheres {
    /// The BVH over the spheres' boxes; its leaf runs are `packs`.
    bvh: SceneBvh,
    /// One pack per leaf run of `bvh`, holding object ids.
    packs: Vec<SpherePack>,
}

impl LoneSpheres {
    /// The BVH over `spheres` (object id and sphere), each boxed by its
    /// entry of `bounds`; `None` when there are fewer than
    /// [`GROUPED_SPHERES`].
    pub(super) fn new(spheres: &[(u32, Sphere)], bounds: &[Aabb]) -> Option<Self> {
        if spheres.len() < GROUPED_SPHERES {
            return None;
        }
        let bvh = SceneBvh::build_runs(bounds, LEAF_SPHERES);
        let packs = bvh
            .runs()
            .map(|run| {
                let members: Vec<(u32, Sphere)> =
                    run.iter().map(|&k| spheres[k as usize]).collect();
                SpherePack::new(&members)
            })
            .collect();
        Some(Self { bvh, packs })
    }

    /// The nearest lone sphere hit in the ray's interval, as the object it
    /// is (on an exact tie between spheres, one of them).
    #[inline]
    pub(super) fn closest(&self, ray: &Ray) -> Option<Hit> {
        let prepared = SphereRay::new(ray);
        let (_, alpha, object) = self.bvh.closest_run_with(ray, |run, ray| {
            let pack = &self.packs[run as usize];
            let (lane, alpha) = pack.nearest(&prepared, ray.t_min, ray.t_max)?;
            Some((alpha, pack.id(lane)))
        })?;
        Some(Hit {
            object,
            alpha,
            triangle: None,
        })
    }

    /// True when some lone sphere lies on the ray inside its interval.
    #[inline]
    pub(super) fn any(&self, ray: &Ray) -> bool {
        let prepared = SphereRay::new(ray);
        self.bvh.any_run(ray, |run, ray| {
            self.packs[run as usize].any(&prepared, ray.t_min, ray.t_max)
        })
    }

    /// The box around every lone sphere.
    pub(super) fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }
}
