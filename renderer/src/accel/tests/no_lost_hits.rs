//! The BVH never loses a hit: on the cases where BVH traversals are known to
//! fail (shared edges and vertices of tiled meshes, flat boxes of
//! axis-aligned triangles, hits at α in [1e-6, 1e-4], rays lying in box faces,
//! ±0 direction components, t_min > 0), closest hits equal brute force (same
//! α; a triangle hit at that α, with its β, γ) and any-hit agrees.

use super::meshes::{grid, mapped, merge};
use crate::accel::mesh::{MeshBvh, MeshHit};
use crate::accel::reference;
use crate::diagnostics::generate::rays_at_shared_edges;
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::WatertightRay;
use glam::Vec3;
use proptest::prelude::*;
use rayon::prelude::*;

type Mesh = (Vec<Vec3>, Vec<[u32; 3]>);

/// Checks every ray against brute force (closest hit one ray at a time and
/// in interleaved batches, and any hit); panics listing the first
/// disagreements. Returns how many rays hit.
fn assert_equals_brute_force(mesh: &Mesh, rays: &[Ray], what: &str) -> usize {
    let (p, t) = mesh;
    // Batches interleaved, as a mesh too large for the cache traces them
    // (one ray after another, the other way, is `closest_hit` below).
    let bvh = MeshBvh::build(p, t).with_interleaving(true);
    let mut batched = vec![None; rays.len()];
    rays.par_chunks(1000)
        .zip(batched.par_chunks_mut(1000))
        .for_each(|(r, h)| bvh.closest_hits(r, h));
    let outcomes: Vec<Result<bool, String>> = rays
        .par_iter()
        .zip(&batched)
        .map(|(ray, batched)| {
            let want = reference::closest_hit(p, t, ray);
            let got = bvh.closest_hit(ray);
            agrees(mesh, ray, "closest_hit", got, want)?;
            agrees(mesh, ray, "closest_hits", *batched, want)?;
            let any = bvh.any_hit(ray);
            if any != want.is_some() {
                return Err(format!("{ray:?}: any_hit {any}, brute force {want:?}"));
            }
            Ok(want.is_some())
        })
        .collect();
    let failures: Vec<&String> = outcomes.iter().filter_map(|o| o.as_ref().err()).collect();
    assert!(
        failures.is_empty(),
        "{what}: {} of {} rays disagree with brute force, e.g.\n{}",
        failures.len(),
        rays.len(),
        failures
            .iter()
            .take(5)
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
    outcomes.iter().filter(|o| matches!(o, Ok(true))).count()
}

/// Ok when `got` (what `how` found) has brute force's α `want` and names a
/// triangle hit at that α with its own β, γ.
fn agrees(
    (p, t): &Mesh,
    ray: &Ray,
    how: &str,
    got: Option<MeshHit>,
    want: Option<MeshHit>,
) -> Result<(), String> {
    match (want, got) {
        (None, None) => Ok(()),
        (Some(w), Some(g)) if g.alpha != w.alpha => Err(format!(
            "{ray:?}: {how} α {} ≠ brute force {}",
            g.alpha, w.alpha
        )),
        // The same triangle (the lowest index on a tie), β and γ.
        (Some(w), Some(g)) if g == w => Ok(()),
        (Some(w), Some(g)) => {
            let [a, b, c] = t[g.triangle as usize].map(|k| p[k as usize]);
            let own = WatertightRay::new(ray).hit(ray, a, b, c);
            Err(format!(
                "{ray:?}: {how} {g:?} (that triangle gives {own:?}), brute force {w:?}"
            ))
        }
        (w, g) => Err(format!("{ray:?}: {how} {g:?}, brute force {w:?}")),
    }
}

#[test]
fn closest_hit_equals_brute_force_at_shared_edges_and_vertices_of_a_220x220_floor() {
    let n = 220; // 96,800 triangles
    let mesh = grid(n, n, 0.0);
    let rays = rays_at_shared_edges(n, 2_500, 1);
    let hits = assert_equals_brute_force(&mesh, &rays, "220×220 floor");
    // Watertight: every ray aimed at an inner edge or vertex hits.
    assert_eq!(hits, rays.len(), "brute force itself leaked");
}

#[test]
fn closest_hit_equals_brute_force_at_shared_edges_and_vertices_with_many_rays() {
    let n = 24;
    let mesh = grid(n, n, 0.0);
    let rays = rays_at_shared_edges(n, 40_000, 2);
    let hits = assert_equals_brute_force(&mesh, &rays, "24×24 floor");
    assert_eq!(hits, rays.len(), "brute force itself leaked");
}

#[test]
fn packets_of_parallel_rays_at_shared_edges_and_vertices_lose_no_hit() {
    // Eight parallel rays at a time (coherent enough for a packet), each
    // aimed at an edge or vertex shared by neighbouring cells, from steep
    // to grazing.
    let n = 64;
    let mesh = grid(n, n, 0.0);
    let mut rng = Sampler::for_sample(11, 0, 0, 0);
    let mut rays = Vec::new();
    for k in 0..4000 {
        let elevation = if k % 4 == 3 {
            1e-3 + 0.05 * rng.next_f32()
        } else {
            0.05 + 1.5 * rng.next_f32()
        };
        let azimuth = std::f32::consts::TAU * rng.next_f32();
        let side = if k % 5 == 0 { -1.0 } else { 1.0 };
        let dir = -Vec3::new(
            elevation.cos() * azimuth.cos(),
            elevation.cos() * azimuth.sin(),
            side * elevation.sin(),
        );
        let (i, j) = (
            2 + (rng.next_f32() * (n - 6) as f32) as u32,
            2 + (rng.next_f32() * (n - 6) as f32) as u32,
        );
        let distance = 0.5 + 30.0 * rng.next_f32();
        for lane in 0..8u32 {
            // Lanes alternate between the edge along x from vertex (i, j)
            // and the edge along y from it, a sixteenth apart (lane 0 at
            // the vertex): a packet's origins lie within half a cell.
            let f = (lane / 2) as f32 / 8.0;
            let (x, y) = (i as f32, j as f32);
            let target = if lane % 2 == 0 {
                Vec3::new(x + f, y, 0.0)
            } else {
                Vec3::new(x, y + f, 0.0)
            };
            rays.push(Ray::new(target - dir * distance, dir));
        }
    }
    let hits = assert_equals_brute_force(&mesh, &rays, "parallel packets, 64×64 floor");
    assert_eq!(hits, rays.len(), "brute force itself leaked");
}

/// A floor (z = 0) and two walls (x = 0.5 + k and y = 0.5 + k planes): all
/// triangles axis-aligned, all boxes flat.
fn axis_aligned_scene() -> Mesh {
    let mut mesh = grid(16, 16, 0.0);
    for k in 0..4 {
        let c = 0.5 + 4.0 * k as f32;
        merge(
            &mut mesh,
            mapped(grid(16, 3, 0.0), |v| Vec3::new(c, v.x, v.y)),
        );
        merge(
            &mut mesh,
            mapped(grid(16, 3, 0.0), |v| Vec3::new(v.x, c, v.y)),
        );
    }
    mesh
}

#[test]
fn closest_hit_equals_brute_force_on_axis_aligned_triangles_with_flat_boxes() {
    let mesh = axis_aligned_scene();
    let mut rng = Sampler::for_sample(3, 0, 0, 0);
    let rays: Vec<Ray> = (0..20_000)
        .map(|k| {
            let origin = Vec3::new(
                -2.0 + 20.0 * rng.next_f32(),
                -2.0 + 20.0 * rng.next_f32(),
                -1.0 + 6.0 * rng.next_f32(),
            );
            // Aim at lattice points (shared vertices) or anywhere.
            let mut target = Vec3::new(
                16.0 * rng.next_f32(),
                16.0 * rng.next_f32(),
                3.0 * rng.next_f32(),
            );
            if k % 2 == 0 {
                target = target.round();
            }
            Ray::new(origin, (target - origin).normalize())
        })
        .collect();
    let hits = assert_equals_brute_force(&mesh, &rays, "axis-aligned scene");
    assert!(hits > rays.len() / 2, "{hits}");
}

#[test]
fn hits_at_alpha_between_1e_6_and_1e_4_are_found() {
    let mesh = grid(40, 40, 0.0);
    let mut rng = Sampler::for_sample(4, 0, 0, 0);
    let mut near = 0;
    let rays: Vec<Ray> = (0..20_000)
        .map(|k| {
            let alpha = 10f32.powf(-6.0 + 2.0 * rng.next_f32());
            let mut target = Vec3::new(
                1.0 + 38.0 * rng.next_f32(),
                1.0 + 38.0 * rng.next_f32(),
                0.0,
            );
            if k % 3 == 0 {
                target = target.round(); // a shared vertex
            }
            let mut dir = -rng.next_direction();
            if dir.z > 0.0 {
                dir.z = -dir.z;
            }
            let dir = (dir - Vec3::new(0.0, 0.0, 0.05)).normalize();
            Ray::new(target - alpha * dir, dir)
        })
        .collect();
    for ray in &rays {
        if let Some(h) = reference::closest_hit(&mesh.0, &mesh.1, ray)
            && h.alpha <= 1e-4
        {
            near += 1;
        }
    }
    assert!(
        near > rays.len() * 9 / 10,
        "only {near} hits closer than 1e-4"
    );
    assert_equals_brute_force(&mesh, &rays, "hits closer than 1e-4");
}

#[test]
fn rays_lying_in_box_faces_find_the_same_hits() {
    // Walls in the planes x = 0.5 + 4k span y in [0, 16], z in [0, 3]: their
    // boxes have faces at z = 0, z = 3, y = 0, y = 16. Rays travel in those
    // planes with the perpendicular component ±0, through the flat floor's boxes.
    let mesh = axis_aligned_scene();
    let mut rays = Vec::new();
    for zero in [0.0f32, -0.0] {
        for face_z in [0.0f32, 3.0, 1.0, 2.5] {
            for face_y in [0.0f32, 16.0, 0.5, 7.0, 8.25] {
                for dx in [1.0f32, -1.0] {
                    let ox = if dx > 0.0 { -1.0 } else { 17.0 };
                    // Along x in the plane z = face_z, also with a y component.
                    for dy in [zero, 0.25, -0.25] {
                        rays.push(Ray::new(
                            Vec3::new(ox, face_y, face_z),
                            Vec3::new(dx, dy, zero),
                        ));
                    }
                    // Along x in the plane y = face_y, also with a z component.
                    for dz in [zero, 0.125, -0.125] {
                        rays.push(Ray::new(
                            Vec3::new(ox, face_y, face_z),
                            Vec3::new(dx, zero, dz),
                        ));
                    }
                }
            }
        }
    }
    let hits = assert_equals_brute_force(&mesh, &rays, "rays in box faces");
    assert!(hits > rays.len() / 3, "{hits} of {}", rays.len());
}

#[test]
fn zero_direction_components_find_the_same_hits() {
    let mesh = axis_aligned_scene();
    let mut rays = Vec::new();
    let z = [0.0f32, -0.0];
    for i in 0..=16 {
        for j in 0..=16 {
            let (x, y) = (i as f32, j as f32);
            for (a, b) in [(z[0], z[0]), (z[0], z[1]), (z[1], z[0]), (z[1], z[1])] {
                // Straight down onto lattice points: shared vertices and edges.
                rays.push(Ray::new(Vec3::new(x, y, 5.0), Vec3::new(a, b, -1.0)));
                rays.push(Ray::new(Vec3::new(x + 0.5, y, 5.0), Vec3::new(a, b, -1.0)));
                rays.push(Ray::new(Vec3::new(x, y, -5.0), Vec3::new(a, b, 1.0)));
                // Horizontal, into the walls' shared edges.
                rays.push(Ray::new(
                    Vec3::new(-1.0, y, 1.0 + 0.5 * (i % 3) as f32),
                    Vec3::new(1.0, a, b),
                ));
                rays.push(Ray::new(Vec3::new(x, -1.0, 2.0), Vec3::new(a, 1.0, b)));
                // One zero component.
                rays.push(Ray::new(
                    Vec3::new(x, y, 4.0),
                    Vec3::new(0.3, b, -1.0).normalize(),
                ));
            }
        }
    }
    let hits = assert_equals_brute_force(&mesh, &rays, "±0 direction components");
    assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
}

#[test]
fn t_min_skips_nearer_hits_exactly() {
    // Five stacked 10 × 10 floors at z = 0 … 4; rays come down from z = 10.
    let mut mesh = grid(10, 10, 0.0);
    for k in 1..5 {
        merge(&mut mesh, grid(10, 10, k as f32));
    }
    let bvh = MeshBvh::build(&mesh.0, &mesh.1);
    let mut rng = Sampler::for_sample(6, 0, 0, 0);
    let mut rays = Vec::new();
    for _ in 0..2_000 {
        let origin = Vec3::new(10.0 * rng.next_f32(), 10.0 * rng.next_f32(), 10.0);
        let target = Vec3::new(10.0 * rng.next_f32(), 10.0 * rng.next_f32(), 0.0);
        let ray = Ray::new(origin, (target - origin).normalize());
        // Every layer's exact α: t_min at it must skip it (open interval),
        // just below it must keep it.
        let mut t_min = 0.0;
        while let Some(h) = reference::closest_hit(&mesh.0, &mesh.1, &Ray { t_min, ..ray }) {
            let skip = Ray {
                t_min: h.alpha,
                ..ray
            };
            let keep = Ray {
                t_min: h.alpha * (1.0 - 1e-6),
                ..ray
            };
            assert_eq!(
                bvh.closest_hit(&keep).map(|g| g.alpha),
                Some(h.alpha),
                "{keep:?}"
            );
            let next = bvh.closest_hit(&skip);
            assert!(next.is_none_or(|g| g.alpha > h.alpha), "{skip:?}: {next:?}");
            rays.extend([skip, keep]);
            t_min = h.alpha;
        }
    }
    assert_equals_brute_force(&mesh, &rays, "t_min > 0");
}

#[test]
fn closest_hit_equals_brute_force_on_a_torus_knot_for_primary_and_incoherent_rays() {
    // The benchmark's scene, small: the knot and its floor square as one
    // world-space mesh, the camera's primary rays and incoherent rays.
    let mut scene = ::scene::generate::knot_scene(20_000);
    (scene.camera.width, scene.camera.height) = (64, 36);
    let world = crate::World::from_scene(&scene).expect("valid");
    let mut mesh = (Vec::new(), Vec::new());
    for placed in &world.meshes {
        let part = placed.mesh.positions.clone();
        let placed_part = (part, placed.mesh.triangles.clone());
        merge(
            &mut mesh,
            mapped(placed_part, |p| placed.instance.point_to_world(p)),
        );
    }
    let knot = world.meshes[0].bounds;
    let mut rays = crate::diagnostics::throughput::primary_rays(&world);
    rays.extend(crate::diagnostics::throughput::incoherent_rays(
        knot.min, knot.max, 2_000, 7,
    ));
    let hits = assert_equals_brute_force(&mesh, &rays, "torus knot");
    assert!(hits > rays.len() / 2, "{hits}");
}

/// A random mesh: vertices on a coarse lattice (so edges and vertices are
/// shared and many triangles axis-aligned) or anywhere in a box.
fn soup() -> impl Strategy<Value = Mesh> {
    let vertex = prop_oneof![
        (0i32..5, 0i32..5, 0i32..5)
            .prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * 0.5),
        (0.0f32..2.0, 0.0f32..2.0, 0.0f32..2.0).prop_map(|(x, y, z)| Vec3::new(x, y, z)),
    ];
    (
        prop::collection::vec(vertex, 3..60),
        prop::collection::vec((0usize..60, 0usize..60, 0usize..60), 1..120),
    )
        .prop_map(|(p, t)| {
            let n = p.len();
            let t = t
                .into_iter()
                .map(|(a, b, c)| [(a % n) as u32, (b % n) as u32, (c % n) as u32])
                .collect();
            (p, t)
        })
}

/// A random ray: origin in or around the mesh's box (sometimes on the
/// lattice), direction with components sometimes exactly ±0, t_min sometimes > 0.
fn any_ray() -> impl Strategy<Value = Ray> {
    let comp = prop_oneof![
        Just(0.0f32),
        Just(-0.0f32),
        -1.0f32..1.0,
        Just(1.0f32),
        Just(-0.5f32)
    ];
    let coord = prop_oneof![-1.0f32..3.0, (0i32..5).prop_map(|k| k as f32 * 0.5)];
    (
        coord.clone(),
        coord.clone(),
        coord,
        comp.clone(),
        comp.clone(),
        comp,
        prop_oneof![Just(0.0f32), 0.0f32..2.0, 1e-6f32..1e-4],
    )
        .prop_filter("zero direction", |(_, _, _, x, y, z, _)| {
            *x != 0.0 || *y != 0.0 || *z != 0.0
        })
        .prop_map(|(ox, oy, oz, dx, dy, dz, t_min)| Ray {
            origin: Vec3::new(ox, oy, oz),
            dir: Vec3::new(dx, dy, dz),
            t_min,
            t_max: f32::INFINITY,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn closest_and_any_hit_equal_brute_force_on_random_meshes_and_rays(
        mesh in soup(), rays in prop::collection::vec(any_ray(), 1..40),
    ) {
        let bvh = MeshBvh::build(&mesh.0, &mesh.1);
        for ray in &rays {
            let want = reference::closest_hit(&mesh.0, &mesh.1, ray);
            let got = bvh.closest_hit(ray);
            // α, β, γ and the triangle (the lowest index on a tie).
            prop_assert_eq!(got, want, "{:?}", ray);
            prop_assert_eq!(bvh.any_hit(ray), want.is_some(), "{:?}", ray);
        }
    }
}

#[test]
fn scene_bvh_over_triangle_boxes_equals_brute_force_at_shared_edges() {
    // The top level with exact (flat) triangle boxes as items, the caller
    // testing each triangle: the Ize slab test must not lose any.
    let n = 60;
    let (p, t) = grid(n, n, 0.0);
    let boxes: Vec<crate::accel::Aabb> = t
        .iter()
        .map(|tri| crate::accel::Aabb::around(tri.map(|k| p[k as usize])))
        .collect();
    let bvh = crate::accel::SceneBvh::build(&boxes);
    let rays = rays_at_shared_edges(n, 20_000, 8);
    let lost = rays
        .par_iter()
        .filter(|ray| {
            let want = reference::closest_hit(&p, &t, ray).map(|h| h.alpha);
            let got = bvh
                .closest(ray, |i, r| reference::triangle_alpha(&p, t[i as usize], r))
                .map(|(_, a)| a);
            let any = bvh.any(ray, |i, r| {
                reference::triangle_alpha(&p, t[i as usize], r).is_some()
            });
            got != want || any != want.is_some()
        })
        .count();
    assert_eq!(
        lost,
        0,
        "{lost} of {} rays disagree with brute force",
        rays.len()
    );
}
