//! What the wavefront path tracer needs of a world, laid out for lanes.

use crate::packet::PacketShapes;
use crate::shading::bsdf::PreparedBsdf;
use crate::shapes::Method;
use crate::world::{Hit, World};
use glam::Vec3;
use scene::BaseMaterial;

/// Which BSDF the lanes evaluate for an object (`Bsdf` without the
/// per-hit parts), or none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum LaneBsdf {
    /// None: a hit on it is shaded by the scalar path tracer's code.
    #[default]
    Scalar,
    /// A Lambertian lobe and a mirror lobe (matte, or plastic without a
    /// highlight; no texture).
    Layered,
    /// A smooth conductor (mirror, or metal with Schlick's tint toward
    /// white at grazing angles when `schlick`).
    Conductor {
        /// Whether the reflectance follows Schlick's approximation.
        schlick: bool,
    },
    /// Smooth glass.
    Dielectric,
    /// A rough conductor: GGX microfacets of α = [`ObjectTable::alpha`].
    RoughConductor {
        /// Whether the reflectance follows Schlick's approximation.
        schlick: bool,
    },
    /// Rough glass: GGX microfacets of α = [`ObjectTable::alpha`], η as
    /// [`ObjectTable::eta`].
    RoughDielectric,
}

/// Per object, what shading a hit on it takes (gathered lane by lane by the
/// object id hit).
#[derive(Clone, Debug, Default)]
pub(crate) struct ObjectTable {
    /// What the lanes evaluate.
    pub(crate) bsdf: Vec<LaneBsdf>,
    /// The material's colour: a layered albedo, a conductor's reflectance
    /// f0, glass's tint.
    pub(crate) color: Vec<Vec3>,
    /// The weight of a layered BSDF's Lambertian lobe.
    pub(crate) diffuse: Vec<f32>,
    /// The weight of a layered BSDF's mirror lobe.
    pub(crate) mirror: Vec<f32>,
    /// Glass's η met from outside (1 / ior) and from inside (ior).
    pub(crate) eta: Vec<(f32, f32)>,
    /// A rough conductor's or rough glass's GGX α.
    pub(crate) alpha: Vec<f32>,
    /// The radiance the front side emits (zero for most).
    pub(crate) emission: Vec<Vec3>,
    /// The object's index among the world's emitters, −1 when it is none.
    pub(crate) emitter: Vec<i32>,
    /// [`World::magnitude`]: secondary rays start off its surface by an
    /// offset that scales with it.
    pub(crate) magnitude: Vec<f32>,
}

/// A world as the wavefront path tracer sees it.
pub(crate) struct WavefrontScene {
    /// Every primitive, for packet tests, when the world is lone triangles,
    /// boxes and spheres, at most [`PacketShapes::MAX_PRIMITIVES`] (robust
    /// formulas); `None`: each lane's rays go through the world's BVH.
    pub(crate) shapes: Option<PacketShapes>,
    /// Shading data by object id.
    pub(crate) objects: ObjectTable,
}

impl WavefrontScene {
    /// The wavefront view of `world` traced with the formulas of `method`.
    /// Every world is covered: hits on analytic shapes with smooth lobes
    /// ([`LaneBsdf`]) are shaded on lanes, the others (a highlight,
    /// marble's texture, mesh triangles) by the scalar code,
    /// lane by lane; rays are tested in packets when the world allows it
    /// ([`WavefrontScene::with_packets`]), else lane by lane through its BVH.
    /// Only the tests trace worlds without packets with it, for now: the
    /// film keeps the scalar lanes there (`trace_samples.rs` says why).
    #[cfg(test)]
    pub(crate) fn new(world: &World, method: Method) -> Self {
        Self {
            shapes: packet_shapes(world, method),
            objects: ObjectTable::new(world),
        }
    }

    /// The wavefront view of `world` when its rays can be tested in
    /// packets: lone triangles, boxes and spheres (at most
    /// [`PacketShapes::MAX_PRIMITIVES`]) and the robust formulas. Asks that
    /// first, so a world without packets costs next to nothing.
    pub(crate) fn with_packets(world: &World, method: Method) -> Option<Self> {
        let shapes = packet_shapes(world, method)?;
        Some(Self {
            shapes: Some(shapes),
            objects: ObjectTable::new(world),
        })
    }
}

/// `world`'s primitives for packet tests, when it has few enough lone
/// triangles, boxes and spheres and nothing else, and `method` is the
/// robust one (the packet tests are its formulas).
fn packet_shapes(world: &World, method: Method) -> Option<PacketShapes> {
    match method {
        Method::Robust => PacketShapes::new(world),
        Method::Lecture => None,
    }
}

impl ObjectTable {
    /// The table of every object of `world`.
    fn new(world: &World) -> Self {
        let mut objects = ObjectTable::default();
        for (id, material) in world.materials.iter().enumerate() {
            // No highlight, no texture.
            let mut alpha = 1.0;
            let (bsdf, diffuse, mirror, eta) = match *world.prepared_bsdf(id as u32) {
                PreparedBsdf::Layered {
                    diffuse,
                    glossy: 0.0,
                    mirror,
                    ..
                } if material.base != BaseMaterial::Marble => {
                    (LaneBsdf::Layered, diffuse, mirror, (1.0, 1.0))
                }
                PreparedBsdf::Conductor { schlick, ggx: None } => {
                    (LaneBsdf::Conductor { schlick }, 0.0, 0.0, (1.0, 1.0))
                }
                PreparedBsdf::Conductor {
                    schlick,
                    ggx: Some(ggx),
                } => {
                    alpha = ggx.alpha;
                    (LaneBsdf::RoughConductor { schlick }, 0.0, 0.0, (1.0, 1.0))
                }
                PreparedBsdf::Dielectric {
                    eta_front,
                    eta_back,
                    ggx: None,
                } => (LaneBsdf::Dielectric, 0.0, 0.0, (eta_front, eta_back)),
                PreparedBsdf::Dielectric {
                    eta_front,
                    eta_back,
                    ggx: Some(ggx),
                } => {
                    alpha = ggx.alpha;
                    (LaneBsdf::RoughDielectric, 0.0, 0.0, (eta_front, eta_back))
                }
                _ => (LaneBsdf::Scalar, 0.0, 0.0, (1.0, 1.0)),
            };
            let hit = Hit {
                object: id as u32,
                alpha: 0.0,
                triangle: None,
            };
            objects.bsdf.push(bsdf);
            objects.color.push(material.color);
            objects.diffuse.push(diffuse);
            objects.mirror.push(mirror);
            objects.eta.push(eta);
            objects.alpha.push(alpha);
            objects.emission.push(material.emission);
            objects.emitter.push(
                world
                    .emitters
                    .index_of(&hit)
                    .map_or(-1, |index| index as i32),
            );
            objects.magnitude.push(world.magnitude(id as u32));
        }
        objects
    }
}
