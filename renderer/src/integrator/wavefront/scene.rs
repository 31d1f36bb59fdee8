//! What the wavefront path tracer needs of a world, laid out for lanes.

use super::emitter_table::EmitterTable;
use super::refill::RefillChoice;
use crate::packet_shapes::PacketShapes;
use crate::shading::bsdf::PreparedBsdf;
use crate::shapes::Method;
use crate::world::{Hit, World};
use glam::Vec3;
use scene::{BaseMaterial, Material};

/// Which BSDF the lanes evaluate for an object (`Bsdf` without the
/// per-hit parts). Every material has one; only an emitting mesh
/// instance's row has none (no flags), as its emitters are per triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LaneBsdf {
    /// A Lambertian lobe, a white GGX highlight of α =
    /// [`ObjectTable::alpha`] and a mirror lobe (matte, plastic, marble).
    Layered {
        /// Whether the albedo is marble's solid texture through the colour.
        marble: bool,
    },
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

/// Per object, what shading a hit on it takes: one row of [`Column`]s per
/// object id, then one per mesh instance ([`ObjectTable::mesh_row`]; an
/// emitting one is shaded by the scalar code), laid out so that a lane's
/// hit reads one cache line, and a last row for lanes that hit nothing (no
/// BSDF on lanes, no emitter).
#[derive(Clone, Debug, Default)]
pub(crate) struct ObjectTable {
    /// The rows, [`ROW`] numbers each.
    rows: Vec<f32>,
    /// The row of the first mesh instance ([`ObjectTable::mesh_row`]).
    meshes: usize,
}

/// The numbers in a row of an [`ObjectTable`].
pub(crate) const ROW: usize = 16;

/// Where each number sits in a row of an [`ObjectTable`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Column {
    /// The material's colour (three numbers): a layered albedo, a
    /// conductor's reflectance f0, glass's tint.
    Color = 0,
    /// The weight of a layered BSDF's Lambertian lobe.
    Diffuse = 3,
    /// The weight of a layered BSDF's mirror lobe.
    Mirror = 4,
    /// Glass's η met from outside (1 / ior).
    EtaFront = 5,
    /// Glass's η met from inside (ior).
    EtaBack = 6,
    /// A rough conductor's, rough glass's or a layered highlight's GGX α.
    Alpha = 7,
    /// The radiance the front side emits (three numbers; zero for most).
    Emission = 8,
    /// [`World::magnitude`]: secondary rays start off its surface by an
    /// offset that scales with it.
    Magnitude = 11,
    /// [`LaneBsdf::flags`], as the bits of an `f32`.
    Flags = 12,
    /// The object's index among the world's emitters, −1 when it is none,
    /// as the bits of an `f32`.
    Emitter = 13,
    /// The weight of a layered BSDF's white GGX highlight.
    Glossy = 14,
}

impl LaneBsdf {
    /// Set when the lanes shade the BSDF.
    pub(crate) const ON_LANES: i32 = 1;
    /// Set for [`LaneBsdf::Layered`].
    pub(crate) const LAYERED: i32 = 2;
    /// Set for [`LaneBsdf::Conductor`].
    pub(crate) const CONDUCTOR: i32 = 4;
    /// Set for a conductor, smooth or rough, with Schlick's reflectance.
    pub(crate) const SCHLICK: i32 = 8;
    /// Set for [`LaneBsdf::RoughConductor`].
    pub(crate) const ROUGH: i32 = 16;
    /// Set for [`LaneBsdf::RoughDielectric`].
    pub(crate) const ROUGH_GLASS: i32 = 32;
    /// Set for [`LaneBsdf::Dielectric`].
    pub(crate) const DIELECTRIC: i32 = 64;
    /// Set for a layered BSDF whose albedo is marble's texture.
    pub(crate) const MARBLE: i32 = 128;

    /// The BSDF as a set of the flags above.
    pub(crate) fn flags(self) -> i32 {
        match self {
            LaneBsdf::Layered { marble } => {
                Self::ON_LANES | Self::LAYERED | if marble { Self::MARBLE } else { 0 }
            }
            LaneBsdf::Conductor { schlick } => {
                Self::ON_LANES | Self::CONDUCTOR | if schlick { Self::SCHLICK } else { 0 }
            }
            LaneBsdf::Dielectric => Self::ON_LANES | Self::DIELECTRIC,
            LaneBsdf::RoughConductor { schlick } => {
                Self::ON_LANES | Self::ROUGH | if schlick { Self::SCHLICK } else { 0 }
            }
            LaneBsdf::RoughDielectric => Self::ON_LANES | Self::ROUGH_GLASS,
        }
    }
}

/// A world as the wavefront path tracer sees it.
pub(crate) struct WavefrontScene {
    /// Every primitive, for packet tests, when the world is lone triangles
    /// (small meshes' included), boxes, spheres and planes, at most
    /// [`PacketShapes::MAX_PRIMITIVES`] (robust formulas); `None`: each
    /// lane's rays go through the world's BVH.
    pub(crate) shapes: Option<PacketShapes>,
    /// Shading data by object id.
    pub(crate) objects: ObjectTable,
    /// The emitters, for light samples on lanes.
    pub(crate) emitters: EmitterTable,
    /// How groups refill their lanes, measured on this thread.
    pub(crate) refill: RefillChoice,
}

impl WavefrontScene {
    /// The wavefront view of `world` traced with the formulas of `method`.
    /// Every world is covered: every material is shaded on lanes
    /// ([`LaneBsdf`]; only an emitting mesh triangle goes to the scalar
    /// code, lane by lane, as its emitter is per triangle); rays are tested
    /// in packets when the world allows it ([`PacketShapes::new`]), else
    /// lane by lane through its BVH.
    ///
    /// The film's path tracer takes it for every world. Through the BVH
    /// each lane's ray takes the scalar query, so the lanes gain on shading
    /// only; measured against the scalar lanes it replaced there (path,
    /// 16 spp, 2 threads, medians of 5 alternated runs, 2026-11-28):
    /// seed.xml 2.40 → 2.20 s and roughness.xml 2.14 → 1.88 s (their marble
    /// floors on lanes), Duck.gltf beside a cylinder 0.99 → 0.92 s (its
    /// texture on lanes).
    pub(crate) fn new(world: &World, method: Method) -> Self {
        Self {
            shapes: packet_shapes(world, method),
            objects: ObjectTable::new(world),
            emitters: EmitterTable::new(&world.emitters),
            refill: RefillChoice::default(),
        }
    }
}

/// `world`'s primitives for packet tests, when it has few enough lone
/// triangles (small meshes' included), boxes and spheres, any infinite
/// planes, and nothing else, and `method` is the robust one (the packet
/// tests are its formulas).
fn packet_shapes(world: &World, method: Method) -> Option<PacketShapes> {
    match method {
        Method::Robust => PacketShapes::new(world),
        Method::Lecture => None,
    }
}

impl ObjectTable {
    /// The row of lanes that hit nothing: η 1, no emitter, nothing on lanes.
    fn miss_row() -> [f32; ROW] {
        let mut row = [0.0; ROW];
        row[Column::EtaFront as usize] = 1.0;
        row[Column::EtaBack as usize] = 1.0;
        row[Column::Emitter as usize] = f32::from_bits((-1i32) as u32);
        row
    }

    /// The row of object `id`, or the miss row for an id past the objects.
    #[cfg(test)]
    pub(crate) fn row(&self, id: usize) -> &[f32; ROW] {
        let last = self.rows.len() / ROW - 1;
        let at = id.min(last) * ROW;
        self.rows[at..at + ROW]
            .try_into()
            .expect("rows are ROW numbers long")
    }

    /// Every row's numbers, one row after the other.
    #[inline(always)]
    pub(crate) fn numbers(&self) -> &[f32] {
        &self.rows
    }

    /// The rows' count, the miss row's index.
    pub(crate) fn miss(&self) -> usize {
        self.rows.len() / ROW - 1
    }

    /// The table of every object of `world`, then of every mesh instance
    /// (whose material may be its model file's, not its object's).
    fn new(world: &World) -> Self {
        let mut objects = ObjectTable::default();
        for (id, material) in world.materials.iter().enumerate() {
            let hit = Hit {
                object: id as u32,
                alpha: 0.0,
                triangle: None,
            };
            let emitter = world
                .emitters
                .index_of(&hit)
                .map_or(-1, |index| index as i32);
            let bsdf = world.prepared_bsdf(id as u32);
            let magnitude = world.magnitude(id as u32);
            objects.push_row(material, bsdf, magnitude, emitter);
        }
        objects.meshes = objects.rows.len() / ROW;
        for mesh in &world.meshes {
            let magnitude = world.magnitude(mesh.object);
            if mesh.material.emission == Vec3::ZERO {
                objects.push_row(&mesh.material, &mesh.bsdf, magnitude, -1);
            } else {
                // A mesh's emitters are its triangles, one index each: the
                // scalar code finds which.
                objects.rows.extend_from_slice(&Self::miss_row());
            }
        }
        objects.rows.extend_from_slice(&Self::miss_row());
        objects
    }

    /// The row of mesh instance `instance` (an index into `World::meshes`).
    #[inline(always)]
    pub(crate) fn mesh_row(&self, instance: u32) -> usize {
        self.meshes + instance as usize
    }

    /// Appends the row of a surface of `material` with the prepared `bsdf`,
    /// the object's `magnitude` and its index among the emitters (−1: none).
    fn push_row(&mut self, material: &Material, bsdf: &PreparedBsdf, magnitude: f32, emitter: i32) {
        let mut alpha = 1.0;
        let mut glossy = 0.0;
        let (bsdf, diffuse, mirror, eta) = match *bsdf {
            PreparedBsdf::Layered {
                diffuse,
                glossy: highlight,
                mirror,
                ggx,
            } => {
                alpha = ggx.alpha;
                glossy = highlight;
                let marble = material.base == BaseMaterial::Marble;
                (LaneBsdf::Layered { marble }, diffuse, mirror, (1.0, 1.0))
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
        };
        let mut row = [0.0f32; ROW];
        let color = Column::Color as usize;
        row[color..color + 3].copy_from_slice(&material.color.to_array());
        row[Column::Diffuse as usize] = diffuse;
        row[Column::Mirror as usize] = mirror;
        row[Column::Glossy as usize] = glossy;
        (
            row[Column::EtaFront as usize],
            row[Column::EtaBack as usize],
        ) = eta;
        row[Column::Alpha as usize] = alpha;
        let emission = Column::Emission as usize;
        row[emission..emission + 3].copy_from_slice(&material.emission.to_array());
        row[Column::Magnitude as usize] = magnitude;
        row[Column::Flags as usize] = f32::from_bits(bsdf.flags() as u32);
        row[Column::Emitter as usize] = f32::from_bits(emitter as u32);
        self.rows.extend_from_slice(&row);
    }
}
