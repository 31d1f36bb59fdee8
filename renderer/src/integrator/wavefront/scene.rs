//! What the wavefront path tracer needs of a world, laid out for lanes.

use crate::packet::PacketShapes;
use crate::shading::bsdf::PreparedBsdf;
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
    /// Every primitive, for packet tests.
    pub(crate) shapes: PacketShapes,
    /// Shading data by object id.
    pub(crate) objects: ObjectTable,
}

impl WavefrontScene {
    /// The wavefront view of `world`, or `None` when it holds something the
    /// wavefront has no lanes for yet: a shape other than a lone triangle,
    /// box or sphere, a model, too many primitives to test all at once, or a
    /// point or directional light. Every material is covered: plain
    /// Lambertian ones on lanes, the others (a highlight, a mirror lobe,
    /// marble's texture, conductors, glass) by the scalar code, lane by lane.
    pub(crate) fn new(world: &World) -> Option<Self> {
        if !world.lights.is_empty() {
            return None;
        }
        let mut objects = ObjectTable::default();
        for (id, material) in world.materials.iter().enumerate() {
            let lambertian = match *world.prepared_bsdf(id as u32) {
                PreparedBsdf::Layered {
                    diffuse,
                    glossy,
                    mirror,
                    ..
                } => glossy == 0.0 && mirror == 0.0 && diffuse > 0.0,
                _ => false,
            };
            let lambertian = lambertian && material.base != BaseMaterial::Marble;
            let diffuse = match *world.prepared_bsdf(id as u32) {
                PreparedBsdf::Layered { diffuse, .. } if lambertian => diffuse,
                _ => 0.0,
            };
            let hit = Hit {
                object: id as u32,
                alpha: 0.0,
                triangle: None,
            };
            objects.lambertian.push(lambertian);
            objects.albedo.push(material.color);
            objects.diffuse.push(diffuse);
            objects.emission.push(material.emission);
            objects.emitter.push(
                world
                    .emitters
                    .index_of(&hit)
                    .map_or(-1, |index| index as i32),
            );
            objects.magnitude.push(world.magnitude(id as u32));
        }
        let shapes = PacketShapes::new(world)?;
        Some(Self { shapes, objects })
    }
}
