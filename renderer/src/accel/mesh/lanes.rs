//! Packets of sixteen coherent rays (camera rays through neighbouring
//! pixels) traced together through the mesh BVH, one ray per SIMD lane
//! ([`crate::simd`]'s lane types: one AVX-512 register, two AVX2 ones, or
//! portable code). Each child box of a node is tested against the sixteen
//! rays at once, with a single ray's conservative slab test
//! ([`box_entry`]) lane by lane; each triangle of a leaf is tested against
//! the sixteen rays at once with [`ShearedRays::hit`], `WatertightRay`'s
//! arithmetic lane by lane, so each lane's α is its own ray's bit for bit;
//! at the same α the lowest triangle index wins, as in the single walk, so
//! each lane reports exactly [`MeshBvh::closest_hit`] of its ray.
//!
//! Children wait on the stack with every lane's entry distance, so a lane
//! leaves a waiting child as soon as its closest hit lies before the child.
//! When fewer than [`PACKET_AT_LEAST`] lanes enter a subtree they go on one
//! at a time ([`Walk`]), as Embree's hybrid traversal does: a packet pays
//! for all its lanes at every node it visits.
//!
//! [`box_entry`]: crate::accel::slab::box_entry

use super::{MeshBvh, MeshHit, Walk};
use crate::accel::slab::widen_up_lanes as widen_up;
use crate::accel::stack::Stack;
use crate::accel::triangle_pack::TrianglePack;
use crate::accel::wide::{ChildRef, WIDTH as CHILDREN, WideNode};
use crate::geometry::ray::Ray;
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Rays, ShearedRays, Vec3s, WIDTH};

/// Rays in a packet: one per lane.
pub(super) const LANES: usize = WIDTH;

/// A subtree that fewer than this many rays of a packet enter is traced
/// one ray at a time. (2, 3, 4 and 6 measured within the noise of each
/// other on the knot's primary rays, 10–12.5 Mrays/s on one thread with
/// packets of sixteen rays in a row.)
const PACKET_AT_LEAST: u32 = 2;

/// Rays whose directions are within this cosine of the first ray's, and
/// whose origins are within [`ORIGIN_SPREAD`] of the mesh's size of the first
/// ray's, are traced as a packet: they visit mostly the same nodes.
const COHERENT_COS: f32 = 0.995;

/// See [`COHERENT_COS`]: a fraction of the mesh box's diagonal.
const ORIGIN_SPREAD: f32 = 0.01;

/// The lanes of `rays` that travel well with lane 0's ray through a mesh
/// whose box has diagonal `size`: their directions have its signs (one
/// octant) and lie within [`COHERENT_COS`] of it, and their origins lie
/// within [`ORIGIN_SPREAD`] · `size` of its origin.
#[inline(always)]
fn coherent_lanes<F: FloatLanes>(rays: &Rays<F>, size: f32) -> u32 {
    let (d, o) = (rays.dir, rays.origin);
    let (d0, o0) = (Vec3s::splat(d.lane(0)), Vec3s::splat(o.lane(0)));
    let octant = same_sign(d.x) & same_sign(d.y) & same_sign(d.z);
    let cos = d.dot(d0);
    let cos2 = F::splat(COHERENT_COS * COHERENT_COS);
    let close = cos.simd_ge(F::ZERO)
        & (cos * cos).simd_ge(cos2 * (d.length_squared() * d0.length_squared()));
    let spread = F::splat((ORIGIN_SPREAD * size).powi(2));
    let near = (o - o0).length_squared().simd_le(spread);
    octant & (close & near).to_bitmask()
}

/// The lanes whose `x` has lane 0's sign bit.
#[inline(always)]
fn same_sign<F: FloatLanes>(x: F) -> u32 {
    let negative = x.is_sign_negative().to_bitmask();
    if negative & 1 == 0 {
        !negative
    } else {
        negative
    }
}

/// Sixteen rays of one octant prepared for box tests.
struct BoxLanes<F: FloatLanes> {
    /// P0.
    origin: Vec3s<F>,
    /// 1/v (±∞ for ±0).
    inv_dir: Vec3s<F>,
    /// Per axis k, the indices in a node's planes of the near and the far
    /// plane (the same for every lane: one octant).
    near_far: [(usize, usize); 3],
}

impl<F: FloatLanes> BoxLanes<F> {
    /// `rays`, whose directions have the signs of `first`'s.
    #[inline(always)]
    fn new(rays: &Rays<F>, first: &Ray) -> Self {
        let negative = first.dir.is_negative_bitmask();
        Self {
            origin: rays.origin,
            inv_dir: Vec3s {
                x: F::ONE / rays.dir.x,
                y: F::ONE / rays.dir.y,
                z: F::ONE / rays.dir.z,
            },
            near_far: std::array::from_fn(|k| {
                let n = ((negative >> k) & 1) as usize;
                (2 * k + n, 2 * k + 1 - n)
            }),
        }
    }

    /// Each lane's entry distance into child `slot` of `node`, and the lanes
    /// that enter it below their `limit`: `box_entry` with t_min = 0 lane
    /// by lane (its maximum and minimum ignore a NaN distance, 0 · ∞).
    #[inline(always)]
    fn enter(&self, node: &WideNode, slot: usize, limit: F) -> (F, F::Mask) {
        let [(n0, f0), (n1, f1), (n2, f2)] = self.near_far;
        let (o, inv) = (&self.origin, &self.inv_dir);
        // Written out, without a closure: one LLVM declined to inline would
        // be compiled without the lanes' instruction set.
        let near = [
            (F::splat(node.plane(n0, slot)) - o.x) * inv.x,
            (F::splat(node.plane(n1, slot)) - o.y) * inv.y,
            (F::splat(node.plane(n2, slot)) - o.z) * inv.z,
        ];
        let far = [
            (F::splat(node.plane(f0, slot)) - o.x) * inv.x,
            (F::splat(node.plane(f1, slot)) - o.y) * inv.y,
            (F::splat(node.plane(f2, slot)) - o.z) * inv.z,
        ];
        // `t > acc ? t : acc` and `t < acc ? t : acc`, one instruction each
        // (`maxps`, `minps`): a NaN t keeps acc.
        let mut entry = F::ZERO;
        let mut exit = limit;
        for k in 0..3 {
            entry = near[k].fast_max(entry);
            exit = far[k].fast_min(exit);
        }
        (entry, entry.simd_le(widen_up(exit)))
    }
}

/// [`Nearest::triangle`] of a lane without a hit.
const NONE: i32 = i32::MAX;

/// A packet's search: each lane's closest α so far and where it lies.
struct Nearest<F: FloatLanes> {
    /// Per lane, the ray's t_max, then the α of its closest hit.
    limit: F,
    /// Per lane, the rays' own t_max (hits at or beyond it do not count).
    t_max: F,
    /// Per lane, the index of the closest triangle so far, `i32::MAX` for
    /// none (at the same α the lowest index wins, as for a single ray).
    triangle: F::Ints,
    /// Per lane, its edge function V (β = V / det).
    v: F,
    /// Per lane, its edge function W (γ = W / det).
    w: F,
    /// Per lane, its determinant.
    det: F,
}

impl MeshBvh {
    /// [`MeshBvh::closest_hit`] of each of `rays` (1 to [`LANES`]), written
    /// to `hits`, when they are coherent enough to travel as a packet
    /// through this mesh (they start at α = 0, and [`coherent_lanes`] holds
    /// for all): the same hit bit for bit, the lowest triangle index on a
    /// tie. False, and `hits` untouched, when they are not.
    #[inline(always)]
    pub(super) fn trace_lanes<F: FloatLanes>(
        &self,
        rays: &[Ray],
        hits: &mut [Option<MeshHit>],
    ) -> bool {
        let n = rays.len();
        debug_assert!((1..=LANES).contains(&n) && hits.len() == n);
        if rays.iter().any(|r| r.t_min != 0.0) {
            return false;
        }
        let lanes: [Ray; LANES] = std::array::from_fn(|i| rays[i.min(n - 1)]);
        let packet = Rays::<F>::from_lanes(&lanes);
        let live = (1u32 << n) - 1;
        let size = (self.bounds.max - self.bounds.min).length();
        if coherent_lanes(&packet, size) & live != live {
            return false;
        }
        let Some(root) = self.root() else {
            hits.fill(None);
            return true;
        };
        let boxes = BoxLanes::new(&packet, &rays[0]);
        let sheared = ShearedRays::new(&packet, F::Mask::from_bitmask(live));
        let mut nearest = Nearest {
            limit: packet.t_max,
            t_max: packet.t_max,
            triangle: F::Ints::splat(NONE),
            v: F::ZERO,
            w: F::ZERO,
            det: F::ONE,
        };
        self.walk_lanes(&lanes, &boxes, &sheared, &mut nearest, root, live);
        let found = nearest.triangle.to_array();
        let (alpha, v, w, det) = (
            nearest.limit.as_array(),
            nearest.v.as_array(),
            nearest.w.as_array(),
            nearest.det.as_array(),
        );
        for (k, hit) in hits.iter_mut().enumerate() {
            *hit = None;
            if found[k] != NONE {
                *hit = Some(MeshHit {
                    triangle: found[k] as u32,
                    alpha: alpha[k],
                    // `PackHit::barycentrics`.
                    beta: v[k] / det[k],
                    gamma: w[k] / det[k],
                });
            }
        }
        true
    }

    /// Walks the subtree `root` for the lanes `live` of the packet.
    #[inline(always)]
    fn walk_lanes<F: FloatLanes>(
        &self,
        rays: &[Ray; LANES],
        boxes: &BoxLanes<F>,
        sheared: &ShearedRays<F>,
        nearest: &mut Nearest<F>,
        root: ChildRef,
        live: u32,
    ) {
        let mut stack = Stack::<(ChildRef, u32, F), 48>::new();
        let mut next = Some((root, live));
        while let Some((current, lanes)) = next {
            if let Some(range) = current.packs() {
                for index in range {
                    self.pack_lanes(index, sheared, nearest);
                }
            } else {
                let node = &self.nodes[current.0 as usize];
                // The entered children, their lanes and entries, nearest
                // (by the first lane's entry) last.
                let mut entered = [(ChildRef::EMPTY, 0u32, F::ZERO, 0.0f32); CHILDREN];
                let mut count = 0;
                let active = F::Mask::from_bitmask(lanes);
                for slot in 0..CHILDREN {
                    let child = node.children[slot];
                    if child == ChildRef::EMPTY {
                        continue;
                    }
                    let (entry, enters) = boxes.enter(node, slot, nearest.limit);
                    let mask = (enters & active).to_bitmask();
                    if mask == 0 {
                        continue;
                    }
                    self.prefetch(child);
                    let key = entry.as_array()[mask.trailing_zeros() as usize];
                    let mut j = count;
                    while j > 0 && entered[j - 1].3 < key {
                        entered[j] = entered[j - 1];
                        j -= 1;
                    }
                    entered[j] = (child, mask, entry, key);
                    count += 1;
                }
                if count > 0 {
                    for &(child, mask, entry, _) in &entered[..count - 1] {
                        stack.push((child, mask, entry));
                    }
                    let (child, mask, _, _) = entered[count - 1];
                    next = self.few_alone_lanes(rays, nearest, child, mask);
                    if next.is_some() {
                        continue;
                    }
                }
            }
            // The next waiting child that some lane may still find a
            // closer hit in.
            next = loop {
                let Some((child, lanes, entry)) = stack.pop() else {
                    break None;
                };
                let reaching = entry.simd_le(widen_up(nearest.limit)).to_bitmask() & lanes;
                if reaching != 0
                    && let Some(next) = self.few_alone_lanes(rays, nearest, child, reaching)
                {
                    break Some(next);
                }
            };
        }
    }

    /// Tests the triangles of pack `index` against every lane, taking the
    /// hits nearer than each lane's closest so far (a lane that did not
    /// enter the leaf can only find a real hit there, which is as good).
    #[inline(always)]
    fn pack_lanes<F: FloatLanes>(
        &self,
        index: usize,
        sheared: &ShearedRays<F>,
        nearest: &mut Nearest<F>,
    ) {
        let pack: &TrianglePack = &self.packs[index];
        for lane in 0..pack.triangle_count() {
            let t = sheared.hit(&pack.corner_arrays(lane), nearest.t_max);
            let id = F::Ints::splat(pack.id(lane) as i32);
            // Nearer, or as near with a lower index (`MeshBvh::step`'s rule).
            let take = t.hit
                & (t.alpha.simd_lt(nearest.limit)
                    | (t.alpha.simd_eq(nearest.limit) & nearest.triangle.simd_gt(id)));
            nearest.limit = take.select(t.alpha, nearest.limit);
            nearest.triangle = F::Ints::select(take, id, nearest.triangle);
            nearest.v = take.select(t.v, nearest.v);
            nearest.w = take.select(t.w, nearest.w);
            nearest.det = take.select(t.det, nearest.det);
        }
    }

    /// `Some((child, lanes))` when enough lanes enter `child` to go on as a
    /// packet; else traces each of those lanes through `child` alone (the
    /// single ray's walk, within its closest α so far) and returns `None`.
    #[inline(always)]
    fn few_alone_lanes<F: FloatLanes>(
        &self,
        rays: &[Ray; LANES],
        nearest: &mut Nearest<F>,
        child: ChildRef,
        lanes: u32,
    ) -> Option<(ChildRef, u32)> {
        if lanes.count_ones() >= PACKET_AT_LEAST {
            return Some((child, lanes));
        }
        let mut todo = lanes;
        let mut triangle = nearest.triangle.to_array();
        while todo != 0 {
            let i = todo.trailing_zeros() as usize;
            todo &= todo - 1;
            // The walk goes on from the lane's closest hit so far.
            let ray = rays[i].with_t_max(nearest.limit.as_array()[i]);
            let mut walk = Walk::new(&ray, Some(child));
            if triangle[i] != NONE {
                walk.best_index = triangle[i] as u32;
            }
            while self.step::<false>(&mut walk) {}
            if let Some((_, hit)) = walk.best {
                triangle[i] = walk.best_index as i32;
                nearest.limit.as_mut_array()[i] = hit.alpha;
                // β / 1 and γ / 1 are β and γ exactly.
                let (beta, gamma) = hit.barycentrics();
                nearest.v.as_mut_array()[i] = beta;
                nearest.w.as_mut_array()[i] = gamma;
                nearest.det.as_mut_array()[i] = 1.0;
            }
        }
        nearest.triangle = F::Ints::from_array(triangle);
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::Vec3;

    /// Sixteen rays from one eye through neighbouring points of a view window.
    fn camera_rays() -> Vec<Ray> {
        let eye = Vec3::new(0.0, 0.0, 5.0);
        (0..LANES)
            .map(|i| {
                let target = Vec3::new(0.01 * (i % 4) as f32, 0.01 * (i / 4) as f32, -1.0);
                Ray::new(eye, target - eye)
            })
            .collect()
    }

    /// Whether `rays` travel as one packet, in lanes `F`.
    #[derive(Clone)]
    struct Coherent<'a>(&'a [Ray]);

    impl WithLanes for Coherent<'_> {
        type Output = bool;
        fn run<F: FloatLanes>(self) -> bool {
            let n = self.0.len();
            let lanes: [Ray; LANES] = std::array::from_fn(|i| self.0[i.min(n - 1)]);
            coherent_lanes(&Rays::<F>::from_lanes(&lanes), 10.0) == (1 << LANES) - 1
        }
    }

    fn coherent(rays: &[Ray]) -> bool {
        let answers = on_every_lane_type(Coherent(rays));
        assert!(answers.iter().all(|&a| a == answers[0]), "lane types agree");
        answers[0]
    }

    #[test]
    fn neighbouring_camera_rays_are_coherent_and_scattered_rays_are_not() {
        let rays = camera_rays();
        assert!(coherent(&rays));
        assert!(coherent(&rays[..3]));
        // One ray in another octant (its x component's sign differs).
        let mut other = rays.clone();
        other[5].dir.x = -1e-3;
        assert!(!coherent(&other));
        // Directions 10° apart.
        let mut other = rays.clone();
        other[2].dir = glam::Quat::from_rotation_x(0.17) * other[2].dir;
        assert!(!coherent(&other));
        // Origins a fifth of the mesh apart.
        let mut other = rays.clone();
        other[7].origin.y += 2.0;
        assert!(!coherent(&other));
    }

    /// A bumpy closed surface of about 5,000 small triangles around the
    /// origin (a sphere of radius ~1 whose vertices are pushed in and out),
    /// so that camera rays meet it at every angle, and near its silhouette.
    fn bumpy_sphere() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let (nu, nv) = (72u32, 36u32);
        let mut positions = Vec::new();
        for j in 0..=nv {
            for i in 0..nu {
                let (u, v) = (
                    i as f32 / nu as f32 * std::f32::consts::TAU,
                    j as f32 / nv as f32 * std::f32::consts::PI,
                );
                let r = 1.0 + 0.05 * ((7.0 * u).sin() * (5.0 * v).cos());
                positions.push(r * Vec3::new(v.sin() * u.cos(), v.cos(), v.sin() * u.sin()));
            }
        }
        let mut triangles = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                let at = |i: u32, j: u32| j * nu + i % nu;
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        (positions, triangles)
    }

    /// Tiles in a row of [`tile_rays`].
    const TILE_ROW: u32 = 32;

    /// Camera rays through 4 × 4 tiles of a view window in front of the
    /// surface, tile by tile, some of them ending short of it (t_max).
    fn tile_rays(eye: Vec3) -> Vec<Ray> {
        let (w, h) = (TILE_ROW * 4, 96u32);
        let mut rays = Vec::new();
        for tile_j in (0..h).step_by(4) {
            for tile_i in (0..w).step_by(4) {
                for j in tile_j..tile_j + 4 {
                    for i in tile_i..tile_i + 4 {
                        let target = Vec3::new(
                            -1.4 + 2.8 * (i as f32 + 0.5) / w as f32,
                            1.05 - 2.1 * (j as f32 + 0.5) / h as f32,
                            0.0,
                        );
                        let mut ray = Ray::new(eye, target - eye);
                        if (i * 7 + j * 3) % 11 == 0 {
                            ray.t_max = 0.62;
                        }
                        rays.push(ray);
                    }
                }
            }
        }
        rays
    }

    /// Each ray's packet hit, in lanes `F`, and how many packets went as
    /// packets.
    #[derive(Clone)]
    struct TracedInLanes<'a>(&'a MeshBvh, &'a [Ray]);

    impl WithLanes for TracedInLanes<'_> {
        type Output = (Vec<Option<MeshHit>>, usize);
        fn run<F: FloatLanes>(self) -> Self::Output {
            let (bvh, rays) = (self.0, self.1);
            let mut hits = vec![None; rays.len()];
            let mut packets = 0;
            for (chunk, out) in rays.chunks(LANES).zip(hits.chunks_mut(LANES)) {
                if bvh.trace_lanes::<F>(chunk, out) {
                    packets += 1;
                } else {
                    for (ray, hit) in chunk.iter().zip(out) {
                        *hit = bvh.closest_hit(ray);
                    }
                }
            }
            (hits, packets)
        }
    }

    #[test]
    fn packets_find_each_rays_own_hit_bit_for_bit_on_every_lane_type() {
        let (positions, triangles) = bumpy_sphere();
        let bvh = MeshBvh::build(&positions, &triangles);
        for eye in [Vec3::new(0.0, 0.0, 2.5), Vec3::new(0.3, -0.2, 1.6)] {
            let rays = tile_rays(eye);
            for (hits, packets) in on_every_lane_type(TracedInLanes(&bvh, &rays)) {
                assert!(
                    packets >= rays.len() / LANES * 9 / 10,
                    "{packets} of {} tiles went as packets",
                    rays.len() / LANES
                );
                let mut found = 0;
                for (ray, hit) in rays.iter().zip(&hits) {
                    // α, β, γ and the triangle (the lowest index on a tie),
                    // bit for bit.
                    assert_eq!(*hit, bvh.closest_hit(ray), "{ray:?}");
                    found += hit.is_some() as usize;
                }
                assert!(found > rays.len() / 3, "{found} hits of {}", rays.len());
            }
        }
    }

    #[test]
    fn a_packet_of_one_ray_or_of_a_few_is_traced_too() {
        let (positions, triangles) = bumpy_sphere();
        let bvh = MeshBvh::build(&positions, &triangles);
        let rays = tile_rays(Vec3::new(0.0, 0.0, 2.5));
        // Some rays of a tile in the middle of the view, fewer than a packet.
        let middle = (rays.len() / LANES / 2 + TILE_ROW as usize / 2) * LANES;
        for n in [1, 2, 5, LANES - 1] {
            let chunk = &rays[middle..][..n];
            for (hits, packets) in on_every_lane_type(TracedInLanes(&bvh, chunk)) {
                assert_eq!(packets, 1);
                for (ray, hit) in chunk.iter().zip(&hits) {
                    assert_eq!(hit.map(|h| h.alpha), bvh.closest_hit(ray).map(|h| h.alpha));
                    assert!(hit.is_some(), "the middle of the view meets the surface");
                }
            }
        }
    }
}
