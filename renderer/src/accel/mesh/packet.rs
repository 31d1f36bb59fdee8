//! Packets of up to eight coherent rays (camera rays through neighbouring
//! pixels, say) traced together through the mesh BVH. Each node is loaded
//! once for the whole packet and each of its children's boxes is tested
//! against every ray of the packet at once, one ray per SIMD lane, with the
//! same conservative slab test as a single ray's ([`box_entry`], which
//! [`WideRay::child_hits`] calls too), so a ray enters exactly the boxes it
//! would enter alone with the same t_max. When only a few rays of a packet still enter a subtree they go on
//! one at a time ([`Walk`]), as Embree's hybrid traversal does: a packet
//! pays for all its lanes at every node it visits.
//!
//! [`WideRay::child_hits`]: super::WideRay::child_hits

use super::{ChildRef, MeshBvh, Stack, TrianglePack, WIDTH, Walk};
use crate::accel::slab::{SlabRay, box_entry, widen_up};
use crate::accel::triangle_pack::PackHit;
use crate::accel::wide::WideNode;
use crate::geometry::ray::Ray;
use crate::shapes::WatertightRay;

/// Rays in a packet (one per lane of an 8-lane SIMD register).
pub const LANES: usize = 8;

/// A subtree that fewer than this many rays of a packet enter is traced
/// one ray at a time. On the million-triangle knot's primary rays through
/// `World::intersect_batch` (one thread, three alternated runs of three
/// casts each), 1, 2 and 3 gave 10.22, 10.56 and 10.33 Mrays/s on average.
const PACKET_AT_LEAST: u32 = 2;

/// Rays whose directions are within this cosine of the first ray's, and
/// whose origins are within [`ORIGIN_SPREAD`] of the mesh's size of the first
/// ray's, are traced as a packet: they visit mostly the same nodes.
const COHERENT_COS: f32 = 0.995;

/// See [`COHERENT_COS`]: a fraction of the mesh box's diagonal.
const ORIGIN_SPREAD: f32 = 0.01;

/// The closest hit of one lane so far: its pack and the hit in it.
pub(super) type LaneBest<'a> = Option<(&'a TrianglePack, PackHit)>;

/// Up to [`LANES`] rays with one octant (the same sign bits of 1/v), laid
/// out lane by lane for the node test.
pub(super) struct Packet {
    /// The rays (lanes outside `lanes` repeat the last ray and are never
    /// traced).
    rays: [Ray; LANES],
    /// Lanes holding rays: bit i for lane i.
    lanes: u32,
    /// P0, per coordinate and lane.
    origin: [[f32; LANES]; 3],
    /// 1/v, per coordinate and lane.
    inv_dir: [[f32; LANES]; 3],
    /// Each lane's t_min (used exactly).
    t_min: [f32; LANES],
    /// Each lane's t_max, lowered by each closer hit.
    t_max: [f32; LANES],
    /// Each lane's t_max enlarged as in [`SlabRay::t_max_wide`].
    t_max_wide: [f32; LANES],
    /// Per axis, the index in the node's planes of the near and far planes
    /// (the same for every lane: one octant).
    near_far: [(usize, usize); 3],
    /// The rays prepared for the triangle test.
    triangle_rays: [WatertightRay; LANES],
}

impl Packet {
    /// An empty packet, to be [`Packet::load`]ed.
    pub(super) fn new() -> Packet {
        let ray = Ray::new(glam::Vec3::ZERO, glam::Vec3::X);
        Packet {
            rays: [ray; LANES],
            lanes: 0,
            origin: [[0.0; LANES]; 3],
            inv_dir: [[0.0; LANES]; 3],
            t_min: [0.0; LANES],
            t_max: [0.0; LANES],
            t_max_wide: [0.0; LANES],
            near_far: [(0, 1); 3],
            triangle_rays: [WatertightRay::new(&ray); LANES],
        }
    }

    /// Makes this the packet of `rays` (1 to [`LANES`] of them) and returns
    /// true when they are coherent enough to gain from travelling together
    /// through a mesh whose box has diagonal `size`: one octant, directions
    /// within [`COHERENT_COS`] of the first's, origins within
    /// [`ORIGIN_SPREAD`] · `size` of the first's. Returns false (the packet
    /// left unusable) otherwise.
    #[inline(always)]
    pub(super) fn load(&mut self, rays: &[Ray], size: f32) -> bool {
        let Some(first) = rays.first() else {
            return false;
        };
        let octant = |v: glam::Vec3| v.to_array().map(f32::is_sign_negative);
        let (dir0, octant0) = (first.dir, octant(first.dir));
        let (cos2, spread2) = (COHERENT_COS * COHERENT_COS, (ORIGIN_SPREAD * size).powi(2));
        for ray in rays {
            let (dir, cos) = (ray.dir, ray.dir.dot(dir0));
            if octant(dir) != octant0
                || cos < 0.0
                || cos * cos < cos2 * (dir.length_squared() * dir0.length_squared())
                || (ray.origin - first.origin).length_squared() > spread2
            {
                return false;
            }
        }
        for i in 0..LANES {
            let ray = &rays[i.min(rays.len() - 1)];
            let slab = SlabRay::new(ray);
            self.rays[i] = *ray;
            for k in 0..3 {
                self.origin[k][i] = slab.origin[k];
                self.inv_dir[k][i] = slab.inv_dir[k];
            }
            self.t_min[i] = slab.t_min;
            self.t_max[i] = slab.t_max;
            self.t_max_wide[i] = slab.t_max_wide;
            self.triangle_rays[i] = WatertightRay::new(ray);
        }
        self.lanes = (1u32 << rays.len()) - 1;
        self.near_far = std::array::from_fn(|k| {
            let n = octant0[k] as usize;
            (2 * k + n, 2 * k + 1 - n)
        });
        true
    }

    /// The lanes among the `active` ones that enter child `slot` of `node`
    /// within their intervals, and the smallest of their entry distances.
    #[inline(always)]
    fn child_lanes(&self, node: &WideNode, slot: usize, active: &[bool; LANES]) -> (u32, f32) {
        let [(n0, f0), (n1, f1), (n2, f2)] = self.near_far;
        let plane = |p: usize| node.plane(p, slot);
        let (nx, ny, nz) = (plane(n0), plane(n1), plane(n2));
        let (fx, fy, fz) = (plane(f0), plane(f1), plane(f2));
        let [ox, oy, oz] = &self.origin;
        let [ix, iy, iz] = &self.inv_dir;
        let mut entry = [f32::INFINITY; LANES];
        // Bit i when lane i enters the box (a lane's bit in its own place, so
        // that the mask is an OR across lanes, which vectorises).
        let mut bits = [0u32; LANES];
        // One lane per ray, with a single ray's test (`WideRay::child_hits`).
        for i in 0..LANES {
            let (near, hit) = box_entry(
                [ox[i], oy[i], oz[i]],
                [ix[i], iy[i], iz[i]],
                [nx, ny, nz],
                [fx, fy, fz],
                self.t_min[i],
                self.t_max[i],
            );
            // `&`, not `&&`: a short-circuit makes the loop conditional, and LLVM
            // if-converts it into masked stores (vpmaskmovd) to `bits` that the
            // fold below reloads at once; the loads cannot be forwarded from
            // masked stores and stall (on the AMD EPYC measured, packets ran at
            // 5.4 Mrays/s instead of 10 on the knot's primary rays).
            let hit = hit & active[i];
            bits[i] = (hit as u32) << i;
            entry[i] = if hit { near } else { f32::INFINITY };
        }
        let mask = bits.iter().fold(0, |m, b| m | b);
        // Entry distances are never NaN (they start from t_min).
        let nearest = entry
            .iter()
            .fold(f32::INFINITY, |m, &e| if e < m { e } else { m });
        (mask, nearest)
    }

    /// The lanes among `lanes` whose (shrunk) interval still reaches `entry`.
    #[inline(always)]
    fn reaching(&self, lanes: u32, entry: f32) -> u32 {
        let mut mask = 0u32;
        for (i, &t) in self.t_max_wide.iter().enumerate() {
            mask |= ((entry <= t) as u32) << i;
        }
        mask & lanes
    }

    /// Records a hit of lane `i` at `alpha`, which shrinks its interval.
    #[inline(always)]
    fn set_t_max(&mut self, i: usize, alpha: f32) {
        self.t_max[i] = alpha;
        self.t_max_wide[i] = widen_up(alpha);
    }
}

impl MeshBvh {
    /// The closest hit of every ray of `packet`, in `best` (lane by lane):
    /// the same α as [`MeshBvh::closest_hit`] of each ray (on a tie between
    /// triangles either may be reported).
    #[inline(always)]
    pub(super) fn trace_packet<'a>(
        &'a self,
        packet: &mut Packet,
        best: &mut [LaneBest<'a>; LANES],
    ) {
        let Some(root) = self.root() else { return };
        let mut stack = Stack::<(ChildRef, u32, f32), 48>::new();
        let mut next = Some((root, packet.lanes));
        while let Some((current, lanes)) = next {
            if let Some(range) = current.packs() {
                for pack in &self.packs[range] {
                    let mut todo = lanes;
                    while todo != 0 {
                        let i = todo.trailing_zeros() as usize;
                        todo &= todo - 1;
                        let ray = &packet.triangle_rays[i];
                        if let Some(hit) = pack.nearest(ray, packet.t_min[i], packet.t_max[i]) {
                            packet.set_t_max(i, hit.alpha);
                            best[i] = Some((pack, hit));
                        }
                    }
                }
            } else {
                let node = &self.nodes[current.0 as usize];
                let active: [bool; LANES] = std::array::from_fn(|i| lanes & (1 << i) != 0);
                // The entered children and their lanes, nearest last.
                let mut hits = [(ChildRef::EMPTY, 0u32, 0.0f32); WIDTH];
                let mut n = 0;
                for slot in 0..WIDTH {
                    let child = node.children[slot];
                    if child == ChildRef::EMPTY {
                        continue;
                    }
                    let (mask, entry) = packet.child_lanes(node, slot, &active);
                    if mask == 0 {
                        continue;
                    }
                    self.prefetch(child);
                    let mut j = n;
                    while j > 0 && hits[j - 1].2 < entry {
                        hits[j] = hits[j - 1];
                        j -= 1;
                    }
                    hits[j] = (child, mask, entry);
                    n += 1;
                }
                if n > 0 {
                    for &h in &hits[..n - 1] {
                        stack.push(h);
                    }
                    let (child, mask, _) = hits[n - 1];
                    next = self.few_alone(packet, best, child, mask);
                    if next.is_some() {
                        continue;
                    }
                }
            }
            // The next waiting child that some lane may still find a closer hit in.
            next = loop {
                let Some((child, lanes, entry)) = stack.pop() else {
                    break None;
                };
                let lanes = packet.reaching(lanes, entry);
                if lanes != 0
                    && let Some(next) = self.few_alone(packet, best, child, lanes)
                {
                    break Some(next);
                }
            };
        }
    }

    /// `Some((child, lanes))` when enough lanes enter `child` to go on as a
    /// packet; else traces each of those lanes through `child` alone and
    /// returns `None`.
    #[inline(always)]
    fn few_alone<'a>(
        &'a self,
        packet: &mut Packet,
        best: &mut [LaneBest<'a>; LANES],
        child: ChildRef,
        lanes: u32,
    ) -> Option<(ChildRef, u32)> {
        if lanes.count_ones() >= PACKET_AT_LEAST {
            return Some((child, lanes));
        }
        let mut todo = lanes;
        while todo != 0 {
            let i = todo.trailing_zeros() as usize;
            todo &= todo - 1;
            let ray = packet.rays[i].with_t_max(packet.t_max[i]);
            let mut walk = Walk::new(&ray, Some(child));
            while self.step::<false>(&mut walk) {}
            if let Some((pack, hit)) = walk.best {
                packet.set_t_max(i, hit.alpha);
                best[i] = Some((pack, hit));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Eight rays from one eye through neighbouring points of a view window.
    fn camera_rays() -> Vec<Ray> {
        (0..8)
            .map(|i| {
                let target = Vec3::new(0.01 * (i % 4) as f32, 0.01 * (i / 4) as f32, -1.0);
                Ray::new(Vec3::new(0.0, 0.0, 5.0), target - Vec3::new(0.0, 0.0, 5.0))
            })
            .collect()
    }

    #[test]
    fn neighbouring_camera_rays_form_a_packet_and_scattered_rays_do_not() {
        let mut packet = Packet::new();
        let rays = camera_rays();
        assert!(packet.load(&rays, 10.0));
        assert_eq!(packet.lanes, 0xff);
        assert!(packet.load(&rays[..3], 10.0));
        assert_eq!(packet.lanes, 0b111);
        // One ray in another octant (its x component's sign differs).
        let mut other = rays.clone();
        other[5].dir.x = -1e-3;
        assert!(!packet.load(&other, 10.0));
        // Directions 10° apart.
        let mut other = rays.clone();
        other[2].dir = glam::Quat::from_rotation_x(0.17) * other[2].dir;
        assert!(!packet.load(&other, 10.0));
        // Origins a fifth of the mesh apart.
        let mut other = rays.clone();
        other[7].origin.y += 2.0;
        assert!(!packet.load(&other, 10.0));
        assert!(!packet.load(&[], 10.0));
    }
}
