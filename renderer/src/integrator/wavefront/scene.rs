//! What the wavefront path tracer needs of a world, laid out for lanes.

use crate::packet::PacketShapes;
use crate::shading::bsdf::PreparedBsdf;
use crate::shapes::Method;
use crate::world::{Hit, World};
use glam::Vec3;
use scene::BaseMaterial;

/// Per object, what shading a hit on it takes (gathered lane by lane by the
/// object id hit).
#[derive(Clone, Debug, Default)]
pub(crate) struct ObjectTable {
    /// Whether the object's material is plainly Lambertian, which the lanes
    /// shade; a hit on any other is shaded by the scalar path tracer's code.
    pub(crate) lambertian: Vec<bool>,
    /// The Lambertian albedo (the material's colour).
    pub(crate) albedo: Vec<Vec3>,
    /// The weight of the Lambertian lobe.
    pub(crate) diffuse: Vec<f32>,
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
    /// Every primitive, for packet tests, when the world is a few lone
    /// triangles, boxes and spheres (robust formulas); `None`: each lane's
    /// rays go through the world's BVH.
    pub(crate) shapes: Option<PacketShapes>,
    /// Shading data by object id.
    pub(crate) objects: ObjectTable,
}

impl WavefrontScene {
    /// The wavefront view of `world` traced with the formulas of `method`.
    /// Every world is covered: plain Lambertian hits on analytic shapes are
    /// shaded on lanes, the others (a highlight, a mirror lobe, marble's
    /// texture, conductors, glass, mesh triangles) by the scalar code, lane
    /// by lane; rays are tested in packets when the world allows it
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
    /// packets: a few lone triangles, boxes and spheres and the robust
    /// formulas. Asks that first, so a big world costs next to nothing.
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
            // A plain Lambertian lobe: no highlight, no mirror, no texture.
            let diffuse = match *world.prepared_bsdf(id as u32) {
                PreparedBsdf::Layered {
                    diffuse,
                    glossy: 0.0,
                    mirror: 0.0,
                    ..
                } if diffuse > 0.0 && material.base != BaseMaterial::Marble => Some(diffuse),
                _ => None,
            };
            let hit = Hit {
                object: id as u32,
                alpha: 0.0,
                triangle: None,
            };
            objects.lambertian.push(diffuse.is_some());
            objects.albedo.push(material.color);
            objects.diffuse.push(diffuse.unwrap_or(0.0));
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
