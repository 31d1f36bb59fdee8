//! Sixteen paths in flight, one per lane, and one bounce of all of them.

use super::delta::{dielectric_samples, fresnel_schlick, mirrored};
use super::draws::{cosine_warps, emitter_draws, environment_draws, roulette_draws, scatter_draws};
use super::glossy::{Highlights, RoughConductors};
use super::handover::{Handover, Target};
use super::lane_math::{Frame, offset_origins, power_heuristics};
use super::paths::Paths;
use super::rough_glass::RoughDielectrics;
use super::scene::WavefrontScene;
use super::shadow_sides::ShadowSides;
use super::surfaces::Surfaces;
use super::tracing;
use crate::geometry::ray::Ray;
use crate::integrator::lanes::{SampleRef, SampleResult};
use crate::integrator::path::{RR_DEPTH, SHADOW_SHORTENING};
use crate::integrator::sampler::PixelStream;
use crate::integrator::sampler::lanes::StreamLanes;
use crate::integrator::{RenderOptions, path::power_heuristic};
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Rays, Vec3s, WIDTH, lane_set, mask_from};
use crate::shading::texture::{marble_noise_point, marble_with};
use crate::shading::turbulence::TURBULENCE;
use crate::world::World;
use crate::world::light::Light;
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;

/// Sixteen paths: each lane's radiance so far, throughput and next ray, as
/// `PathLane` keeps them for one path.
pub(super) struct PathGroup<F: FloatLanes> {
    /// Per lane, the index of its sample in the caller's list; `None` for a
    /// dead lane.
    sample: [Option<usize>; WIDTH],
    /// The paths' state, lane by lane.
    pub(super) paths: Paths<F>,
    /// The lanes a bounce hands to the scalar code (kept for its buffers).
    handover: Handover,
    /// Per light, the lanes whose shadow ray toward it is blocked (scratch).
    blocked_toward_lights: Vec<F::Mask>,
    /// Shape tests each lane's rays cost so far.
    shape_tests: [u64; WIDTH],
    /// Each lane's pixel (i, j).
    pixel: [(u32, u32); WIDTH],
    /// Lanes started whose camera rays are still to be made (bit k for lane k).
    unaimed: u32,
}

impl<F: FloatLanes> PathGroup<F> {
    /// Sixteen dead lanes.
    #[inline(always)]
    pub(super) fn new() -> Self {
        let dead = Ray::NOTHING;
        Self {
            sample: [None; WIDTH],
            paths: Paths {
                streams: StreamLanes::new(),
                rays: Rays::from_lanes(&[dead; WIDTH]),
                radiance: Vec3s::ZERO,
                throughput: Vec3s::ZERO,
                previous_point: Vec3s::ZERO,
                previous_pdf: F::ZERO,
                has_previous: F::Mask::NONE,
                eta_scale: F::ONE,
                depth: [0; WIDTH],
            },
            shape_tests: [0; WIDTH],
            pixel: [(0, 0); WIDTH],
            unaimed: 0,
            handover: Handover::new(),
            blocked_toward_lights: Vec::new(),
        }
    }

    /// The camera rays of the lanes started since the last bounce, R_ij
    /// through each one's pixel at its jitter — the first draw of its
    /// stream, drawn on lanes — as `camera_sample` makes them.
    #[inline(always)]
    fn aim(&mut self, world: &World) {
        if self.unaimed == 0 {
            return;
        }
        let (x, y) = self.paths.streams.numbers(F::Ints::splat(0));
        let i = self.pixel.map(|(i, _)| i);
        let j = self.pixel.map(|(_, j)| j);
        // Every lane's v_ij at once (the scalar camera's bits); kept where unaimed.
        let [dx, dy, dz] = world.camera.directions(&i, &j, x.as_array(), y.as_array());
        let unaimed = self.unaimed;
        let aim = F::Mask::from_bitmask(unaimed);
        let rays = &mut self.paths.rays;
        let dir = Vec3s::new(F::from_array(dx), F::from_array(dy), F::from_array(dz));
        rays.dir = Vec3s::select(aim, dir, rays.dir);
        rays.origin = Vec3s::select(aim, Vec3s::splat(world.camera.p0), rays.origin);
        rays.t_max = aim.select(F::INFINITY, rays.t_max);
        self.unaimed = 0;
    }

    /// Whether any lane is tracing.
    #[inline(always)]
    pub(super) fn any_live(&self) -> bool {
        self.sample.iter().any(Option::is_some)
    }

    /// Lane `lane` starts sample `s` (the `index`th of the caller's list):
    /// its stream, and its camera ray at the next [`PathGroup::step`].
    #[inline(always)]
    pub(super) fn start(
        &mut self,
        options: &RenderOptions,
        lane: usize,
        index: usize,
        s: SampleRef,
    ) {
        let stream = PixelStream::new(options.sampling, options.seed, s.i, s.j, s.sample);
        self.sample[lane] = Some(index);
        self.paths.streams.set(lane, &stream);
        self.pixel[lane] = (s.i, s.j);
        self.unaimed |= 1 << lane;
        self.paths.radiance.set_lane(lane, Vec3::ZERO);
        self.paths.throughput.set_lane(lane, Vec3::ONE);
        self.paths.has_previous = self.paths.has_previous & !F::Mask::from_bitmask(1 << lane);
        self.paths.eta_scale.as_mut_array()[lane] = 1.0;
        self.paths.depth[lane] = 0;
        self.shape_tests[lane] = 0;
    }

    /// Ends lane `lane` (finished by the last [`PathGroup::step`]): its
    /// sample's index and result; the lane is dead until started again.
    #[inline(always)]
    pub(super) fn take(&mut self, lane: usize) -> (usize, SampleResult) {
        let index = self.sample[lane]
            .take()
            .expect("only a finished lane is taken");
        self.paths.rays.t_max.as_mut_array()[lane] = 0.0;
        let result = SampleResult {
            radiance: self.paths.radiance.lane(lane),
            shape_tests: self.shape_tests[lane],
        };
        (index, result)
    }

    /// The live lanes.
    #[inline(always)]
    fn live(&self) -> F::Mask {
        mask_from::<F>(|k| self.sample[k].is_some())
    }

    /// One bounce of every live lane: the closest hits of their rays,
    /// emission, a light sample with its shadow ray and a BSDF sample for
    /// the next ray, exactly as `PathLane::shade` and `PathLane::finish`.
    /// Returns the lanes that finished (bit k for lane k); their results
    /// are ready to [`PathGroup::take`].
    #[inline(always)]
    pub(super) fn step(
        &mut self,
        world: &World,
        scene: &WavefrontScene,
        options: &RenderOptions,
    ) -> u32 {
        self.aim(world);
        let live = self.live();
        let method = options.method;
        let closest = tracing::closest(
            world,
            scene,
            method,
            &self.paths.rays,
            live,
            &mut self.shape_tests,
        );
        let hits = &closest.packet;
        let hit = live & hits.alpha.simd_lt(F::INFINITY);
        // A ray that escapes sees the sky.
        let miss = live & !hit;
        if let Some(sky) = world.environment.constant_radiance() {
            let seen = self.paths.radiance + self.paths.throughput.mul_lanes(Vec3s::splat(sky));
            self.paths.radiance = Vec3s::select(miss, seen, self.paths.radiance);
        } else if miss.any() {
            // The sky in each ray's direction (its texel coordinates on
            // lanes), weighted against its light sample as `escaped` weighs it.
            let environment = &world.environment;
            let (radiance, pdf) = environment.radiance_and_pdf_lanes(self.paths.rays.dir, miss);
            let weighed = if environment.is_sampled() {
                self.paths.has_previous
            } else {
                F::Mask::NONE
            };
            let weight = weighed.select(power_heuristics(self.paths.previous_pdf, pdf), F::ONE);
            let seen = self.paths.radiance + self.paths.throughput.mul_lanes(radiance * weight);
            self.paths.radiance = Vec3s::select(miss, seen, self.paths.radiance);
        }
        let mut finished = miss.to_bitmask();
        if !hit.any() {
            return finished;
        }

        let mut at = Surfaces::<F>::gather(&scene.objects, hit, closest.rows(&scene.objects));
        // Hits on emitting mesh triangles go to the scalar code.
        let scalar = hit & !at.on_lanes;
        let hit = hit & at.on_lanes;
        self.handover
            .shade(&mut self.paths, world, options, scalar, &closest);
        let mesh = hit & closest.mesh;
        let (mut point, mut normal) =
            tracing::surfaces(world, scene, &self.paths.rays, &closest, hit & !mesh);
        // The shading normal: the geometric one, but on a mesh triangle
        // the normals interpolated, with its point, geometric normal and
        // colour (a texture's included) as the scalar code finds them.
        let mut shading = normal;
        // And the point of the surface its normals describe, where shadow
        // rays near the terminator start.
        let mut curved_point = point;
        for k in (0..WIDTH).filter(|&k| lane_set(mesh, k)) {
            let s = world.hit_surface(&self.paths.rays.lane(k), &closest.hit(k));
            point.set_lane(k, s.surface.point);
            normal.set_lane(k, s.surface.normal);
            shading.set_lane(k, s.shading_normal);
            at.color.set_lane(k, s.color);
            if let Some(curved) = s.curved_point {
                curved_point.set_lane(k, curved);
            }
        }
        let dir = self.paths.rays.dir;
        let front = dir.dot(normal).simd_lt(F::ZERO);
        // Both normals turned to the side the ray came from: the geometric
        // one decides sides and offsets, the shading one is the BSDF's frame.
        let n = Vec3s::select(front, normal, -normal);
        let ns = Vec3s::select(front, shading, -shading);

        // Emission seen from the front, weighted against light sampling.
        let emitting = hit & front & at.emission.nonzero();
        for k in (0..WIDTH).filter(|&k| lane_set(emitting, k)) {
            let emitter = at.emitter[k];
            let weight = if lane_set(self.paths.has_previous, k) && emitter >= 0 {
                power_heuristic(
                    self.paths.previous_pdf.as_array()[k],
                    world.emitters.pdf(
                        self.paths.previous_point.lane(k),
                        emitter as usize,
                        point.lane(k),
                        normal.lane(k),
                    ),
                )
            } else {
                1.0
            };
            let gained = self.paths.throughput.lane(k) * weight * at.emission.lane(k);
            self.paths
                .radiance
                .set_lane(k, self.paths.radiance.lane(k) + gained);
        }

        // The depth limit ends a path at its hit.
        let depth = self.paths.depth;
        let last = hit & mask_from::<F>(|k| depth[k] + 1 >= options.max_depth);
        finished |= last.to_bitmask();
        let go = hit & !last;
        // Marble's albedo: its solid texture through the colour, at the
        // point; the noise of every marble lane at once.
        let mut marbled = (go & at.marble).to_bitmask();
        if marbled != 0 {
            let (mut lanes, mut noise_points, mut count) = ([0; WIDTH], [[0.0; 3]; WIDTH], 0);
            while marbled != 0 {
                let k = marbled.trailing_zeros() as usize;
                marbled &= marbled - 1;
                (lanes[count], noise_points[count]) = (k, marble_noise_point(point.lane(k)));
                count += 1;
            }
            let mut noise = [0.0; WIDTH];
            TURBULENCE.at_each::<F>(&noise_points[..count], &mut noise[..count]);
            for (&k, &noise) in lanes[..count].iter().zip(&noise) {
                at.color
                    .set_lane(k, marble_with(point.lane(k), at.color.lane(k), noise));
            }
        }

        let frame = Frame::new(ns);
        let wo = frame.to_local(-dir);
        // Lights are sampled where a lobe is not a delta: a Lambertian, a
        // highlight, a rough conductor's or rough glass's. Rough glass also
        // sees lights behind the surface, through shadow rays from below it.
        let sides = ShadowSides::new(point, n, ns, curved_point, mesh & front, at.magnitude);
        let rough = go & at.rough;
        let rough_glass = go & at.rough_glass;
        let lit = go & ((at.diffuse + at.glossy).simd_gt(F::ZERO) | rough | rough_glass);
        let frosted = RoughDielectrics {
            alpha: at.alpha,
            eta: front.select(at.eta.0, at.eta.1),
            tint: at.color,
        };
        let microfacets = RoughConductors {
            alpha: at.alpha,
            f0: at.color,
            schlick: at.schlick,
        };
        // f · cos θ_i toward a local direction and the density of sampling it.
        let lobes = Lobes {
            color: at.color,
            diffuse: at.diffuse,
            shiny: go & at.layered & at.glossy.simd_gt(F::ZERO),
            glossy: at.glossy,
            highlights: Highlights { alpha: at.alpha },
            rough,
            microfacets,
            rough_glass,
            frosted,
        };
        // The light sample: a point drawn on the emitters, its BSDF value
        // and MIS weight, and the shadow ray toward it.
        let light = emitter_draws(
            world,
            &scene.emitters,
            lit,
            &self.paths.streams,
            &self.paths.depth,
            point,
        );
        let (toward, light_rays) =
            sides.toward(light.to_light, light.distance, 1.0 - SHADOW_SHORTENING);
        let (f, bsdf_pdf) = lobes.eval_pdf(wo, frame.to_local(light.to_light));
        let mis = power_heuristics(light.pdf, bsdf_pdf);
        let light_through = f.mul_lanes(light.radiance) * (mis / light.pdf);
        let shadowed = lit & light.found & (toward | rough_glass) & f.nonzero();
        // The sky map's light sample: a direction drawn from it, its BSDF
        // value and MIS weight, and the shadow ray toward it (nothing for a
        // constant sky or none, which BSDF sampling alone sees).
        let sampled_sky = world.environment.is_sampled();
        let (sky_rays, sky_through, sky_shadowed) = if sampled_sky {
            let sky = environment_draws(world, lit, &self.paths.streams, &self.paths.depth);
            let (toward, rays) = sides.toward(sky.dir, F::INFINITY, 1.0);
            let (f, bsdf_pdf) = lobes.eval_pdf(wo, frame.to_local(sky.dir));
            let mis = power_heuristics(sky.pdf, bsdf_pdf);
            let through = f.mul_lanes(sky.radiance) * (mis / sky.pdf);
            let shadowed = lit & sky.found & (toward | rough_glass) & f.nonzero();
            (rays, through, shadowed)
        } else {
            let nothing = Rays {
                origin: Vec3s::ZERO,
                dir: Vec3s::ZERO,
                t_max: F::ZERO,
            };
            (nothing, Vec3s::ZERO, F::Mask::NONE)
        };
        let lit_by = self.paths.throughput;

        // The BSDF sample. A layered lane picks its mirror lobe when the
        // lobe's number falls below the mirror's weight, its highlight below
        // the two weights' sum (a direction reflected about a GGX
        // micronormal; none below the surface), else a cosine-weighted
        // direction; a rough conductor reflects about a visible
        // micronormal; all weigh f·cos/pdf. A conductor reflects, glass
        // reflects or refracts.
        let (u_lobe, u) = scatter_draws(&self.paths.streams, &self.paths.depth);
        let layered_mirror = go & at.layered & u_lobe.simd_lt(at.mirror);
        let glossy = go & at.layered & !layered_mirror & u_lobe.simd_lt(at.mirror + at.glossy);
        let diffuse = go & at.layered & !layered_mirror & !glossy;
        let mut wi = cosine_warps(u);
        let mut reflected = glossy;
        if glossy.any() {
            let (glossy_wi, above) = lobes.highlights.sample(glossy, wo, u);
            wi = Vec3s::select(glossy, glossy_wi, wi);
            reflected = above;
        }
        let (mut f_cos, mut pdf) = lobes.eval_pdf(wo, wi);
        pdf = (glossy & !reflected).select(F::ZERO, pdf);
        let mut radiance_scale = F::ONE;
        if rough.any() {
            let (rough_wi, rough_f, rough_pdf) = microfacets.sample(rough, wo, u);
            wi = Vec3s::select(rough, rough_wi, wi);
            f_cos = Vec3s::select(rough, rough_f, f_cos);
            pdf = rough.select(rough_pdf, pdf);
        }
        if rough_glass.any() {
            let (glass_wi, glass_f, glass_pdf, scale) = frosted.sample(rough_glass, wo, u_lobe, u);
            wi = Vec3s::select(rough_glass, glass_wi, wi);
            f_cos = Vec3s::select(rough_glass, glass_f, f_cos);
            pdf = rough_glass.select(glass_pdf, pdf);
            radiance_scale = rough_glass.select(scale, radiance_scale);
        }
        let scattered = diffuse | glossy | rough | rough_glass;
        let conductor = go & at.conductor;
        let glass = go & at.dielectric;
        let delta = layered_mirror | conductor | glass;
        wi = Vec3s::select(scattered, wi, mirrored(wo));
        let mut weight = Vec3s::select(scattered, f_cos.div_lanes(pdf), Vec3s::splat(Vec3::ONE));
        if conductor.any() {
            let tinted = Vec3s::select(at.schlick, fresnel_schlick(wo.z, at.color), at.color);
            weight = Vec3s::select(conductor, tinted, weight);
        }
        if glass.any() {
            let eta = front.select(at.eta.0, at.eta.1);
            let sample = dielectric_samples(wo, eta, at.color, u_lobe);
            wi = Vec3s::select(glass, sample.wi, wi);
            weight = Vec3s::select(glass, sample.weight, weight);
            radiance_scale = glass.select(sample.radiance_scale, radiance_scale);
        }
        let moving = (scattered & pdf.simd_gt(F::ZERO)) | delta;
        let wi_world = frame.to_world(wi);
        let throughput = Vec3s::select(
            moving,
            self.paths.throughput.mul_lanes(weight),
            self.paths.throughput,
        );
        self.paths.eta_scale =
            moving.select(self.paths.eta_scale * radiance_scale, self.paths.eta_scale);
        let side = Vec3s::select(wi_world.dot(n).simd_ge(F::ZERO), n, -n);
        let origin = offset_origins(point, side, at.magnitude);

        // Russian roulette from the RR_DEPTH-th scattering event on.
        let roulette = moving & mask_from::<F>(|k| depth[k] + 1 >= RR_DEPTH);
        let u_roulette = roulette_draws(roulette, &self.paths.streams, &self.paths.depth);
        let keep = (throughput.max_element() / self.paths.eta_scale).min(F::splat(0.95));
        let killed = roulette & !u_roulette.simd_lt(keep);
        let throughput = Vec3s::select(roulette & !killed, throughput.div_lanes(keep), throughput);
        let dark = moving & !killed & !throughput.max_element().simd_gt(F::ZERO);
        let going_on = moving & !killed & !dark;
        self.paths.throughput = throughput;
        self.paths.rays.origin = Vec3s::select(going_on, origin, self.paths.rays.origin);
        self.paths.rays.dir = Vec3s::select(going_on, wi_world, self.paths.rays.dir);
        self.paths.rays.t_max = going_on.select(F::splat(f32::INFINITY), F::ZERO);
        self.paths.previous_point = Vec3s::select(going_on, point, self.paths.previous_point);
        self.paths.previous_pdf = going_on.select(pdf, self.paths.previous_pdf);
        // After a delta lobe no light sample competes with what the ray hits.
        self.paths.has_previous = going_on & !delta;
        for (k, depth) in self.paths.depth.iter_mut().enumerate() {
            if lane_set(going_on, k) {
                *depth += 1;
            }
        }
        finished |= (go & !going_on).to_bitmask();

        // The shadow rays, toward each point or directional light in turn,
        // then toward the emitters' point; the light they let through is
        // summed in that order, as `PathLane::finish` sums it.
        let mut sum = Vec3s::ZERO;
        self.blocked_toward_lights.clear();
        for (index, light) in world.lights.iter().enumerate() {
            let s = light_samples(light, point);
            let (toward, rays) = sides.toward(s.to_light, s.distance, 1.0);
            let (f, _) = lobes.eval_pdf(wo, frame.to_local(s.to_light));
            let shadowed = lit & s.found & (toward | rough_glass) & f.nonzero();
            let rays = Rays {
                t_max: shadowed.select(rays.t_max, F::ZERO),
                ..rays
            };
            let target = Target::Light(index);
            let rays = self.handover.add_shadow_rays(target, rays);
            let traced = shadowed | self.handover.shadowed::<F>(target);
            let blocked =
                tracing::occluded(world, scene, method, &rays, traced, &mut self.shape_tests);
            sum = sum + Vec3s::select(shadowed & !blocked, f.mul_lanes(s.irradiance), Vec3s::ZERO);
            self.blocked_toward_lights.push(blocked);
        }
        let shadows = Rays {
            t_max: shadowed.select(light_rays.t_max, F::ZERO),
            ..light_rays
        };
        let shadows = self.handover.add_shadow_rays(Target::Emitter, shadows);
        let traced = shadowed | self.handover.shadowed::<F>(Target::Emitter);
        let blocked = tracing::occluded(
            world,
            scene,
            method,
            &shadows,
            traced,
            &mut self.shape_tests,
        );
        let mut sum = sum + Vec3s::select(shadowed & !blocked, light_through, Vec3s::ZERO);
        let mut sky_blocked = F::Mask::NONE;
        if sampled_sky {
            let rays = Rays {
                t_max: sky_shadowed.select(sky_rays.t_max, F::ZERO),
                ..sky_rays
            };
            let rays = self.handover.add_shadow_rays(Target::Environment, rays);
            let traced = sky_shadowed | self.handover.shadowed::<F>(Target::Environment);
            sky_blocked =
                tracing::occluded(world, scene, method, &rays, traced, &mut self.shape_tests);
            sum = sum + Vec3s::select(sky_shadowed & !sky_blocked, sky_through, Vec3s::ZERO);
        }
        self.paths.radiance = Vec3s::select(
            lit,
            self.paths.radiance + lit_by.mul_lanes(sum),
            self.paths.radiance,
        );
        finished
            | self.handover.finish(
                &mut self.paths,
                &self.blocked_toward_lights,
                blocked,
                sky_blocked,
            )
    }
}

/// The non-delta lobes of sixteen hits: a layered BSDF's Lambertian lobe
/// and white highlight, a rough conductor's or rough glass's GGX lobes, per
/// lane.
struct Lobes<F: FloatLanes> {
    /// The Lambertian albedo.
    color: Vec3s<F>,
    /// The Lambertian lobe's weight (0 where there is none).
    diffuse: F,
    /// Layered lanes with a highlight.
    shiny: F::Mask,
    /// The highlight's weight.
    glossy: F,
    /// The highlights.
    highlights: Highlights<F>,
    /// Lanes with a rough conductor.
    rough: F::Mask,
    /// The rough conductors.
    microfacets: RoughConductors<F>,
    /// Lanes with rough glass.
    rough_glass: F::Mask,
    /// The rough glass.
    frosted: RoughDielectrics<F>,
}

impl<F: FloatLanes> Lobes<F> {
    /// f · cos θ_i from `wo` toward `wi` (local) and the density of
    /// sampling `wi`: `Bsdf::eval` and `Bsdf::pdf` lane by lane.
    #[inline(always)]
    fn eval_pdf(&self, wo: Vec3s<F>, wi: Vec3s<F>) -> (Vec3s<F>, F) {
        let lambert = self.diffuse * F::splat(FRAC_1_PI);
        let dark_side = wi.z.simd_le(F::ZERO) | wo.z.simd_le(F::ZERO);
        let mut f = Vec3s::select(dark_side, Vec3s::ZERO, self.color * (lambert * wi.z));
        let mut pdf = dark_side.select(
            F::ZERO,
            self.diffuse * (wi.z.max(F::ZERO) * F::splat(FRAC_1_PI)),
        );
        if self.shiny.any() {
            // `diffuse + Vec3::splat(glossy · reflection)`, both above.
            let (glossy_f, glossy_pdf) = self.highlights.eval_pdf(wo, wi);
            let shiny = self.shiny & !dark_side;
            let white = self.glossy * glossy_f;
            f = Vec3s::select(shiny, f + Vec3s::new(white, white, white), f);
            pdf = shiny.select(pdf + self.glossy * glossy_pdf, pdf);
        }
        if self.rough.any() {
            let (rough_f, rough_pdf) = self.microfacets.eval_pdf(wo, wi);
            f = Vec3s::select(self.rough, rough_f, f);
            pdf = self.rough.select(rough_pdf, pdf);
        }
        if self.rough_glass.any() {
            let (glass_f, glass_pdf) = self.frosted.eval_pdf(wo, wi);
            f = Vec3s::select(self.rough_glass, glass_f, f);
            pdf = self.rough_glass.select(glass_pdf, pdf);
        }
        (f, pdf)
    }
}

/// Each lane's sample of one point or directional light (`Light::sample`
/// lane by lane).
struct LightSamples<F: FloatLanes> {
    /// Lanes with a sample (a point light not at the point itself).
    found: F::Mask,
    /// Unit directions toward the light.
    to_light: Vec3s<F>,
    /// Distances to it (+∞ for a directional light).
    distance: F,
    /// Irradiance arriving from it.
    irradiance: Vec3s<F>,
}

/// `light.sample(point)` lane by lane, bit for bit.
#[inline(always)]
fn light_samples<F: FloatLanes>(light: &Light, point: Vec3s<F>) -> LightSamples<F> {
    match *light {
        Light::Point {
            position,
            intensity,
        } => {
            let to = Vec3s::splat(position) - point;
            let distance_sq = to.length_squared();
            let distance = distance_sq.sqrt();
            LightSamples {
                found: distance_sq.simd_gt(F::ZERO),
                to_light: to.div_lanes(distance),
                distance,
                irradiance: Vec3s::splat(intensity).div_lanes(distance_sq),
            }
        }
        Light::Directional {
            to_light,
            irradiance,
        } => LightSamples {
            found: !F::Mask::NONE,
            to_light: Vec3s::splat(to_light),
            distance: F::INFINITY,
            irradiance: Vec3s::splat(irradiance),
        },
        // Ambient light is folded into `World::ambient`, never listed.
        Light::Ambient { .. } => LightSamples {
            found: F::Mask::NONE,
            to_light: Vec3s::splat(glam::Vec3::Y),
            distance: F::ZERO,
            irradiance: Vec3s::ZERO,
        },
    }
}
