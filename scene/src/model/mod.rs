//! The editable scene: exactly what a scene file says, nothing derived.
//!
//! Anchors that have context-dependent defaults (an object's position, the
//! camera's eye and toward vector) are `Option`s here; [`crate::resolve()`]
//! fills them in. Everything else carries its fixed default, and the writer
//! omits values equal to it, so a saved scene says no more than it needs.

pub mod model_file;
mod sky;
mod view;

pub use sky::{EnvImage, STUDIO_KEY_DIRECTION, STUDIO_MAP, Sky, SkyMap, studio_image};
pub use view::{Tonemap, View};

use glam::Vec3;
use model_file::ModelFile;
use std::sync::Arc;

/// A whole scene: camera, lights, sky, named materials and objects, in document order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The lecture's camera (P0, t, u, θ, d, w, h).
    pub camera: Camera,
    /// Light sources; none (and nothing emissive, and no sky) means default lighting.
    pub lights: Vec<Light>,
    /// `<sky>`: radiance arriving from every direction no object blocks (a
    /// colour or an environment map); `None` is a black background.
    pub sky: Option<Sky>,
    /// `<material name=… base=…>` definitions, in document order.
    pub materials: Vec<MaterialDef>,
    /// The objects to render, in document order.
    pub objects: Vec<Object>,
    /// `<view>`: the exposure and view transform it is shown with (a
    /// display setting: it changes no sample).
    pub view: View,
}

impl Scene {
    /// True when `self` and `other` render the same samples: equal but for
    /// how they are shown ([`Scene::view`]).
    pub fn renders_like(&self, other: &Scene) -> bool {
        let Scene {
            camera,
            lights,
            sky,
            materials,
            objects,
            view: _,
        } = self;
        *camera == other.camera
            && *lights == other.lights
            && *sky == other.sky
            && *materials == other.materials
            && *objects == other.objects
    }
}

/// The camera as the lecture specifies it; angles in degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// P0, the viewpoint; `None` frames all finite objects.
    pub eye: Option<Vec3>,
    /// t, the toward vector (any length); `None` looks at the scene's centre.
    pub toward: Option<Vec3>,
    /// u, the up vector (any length, not parallel to t).
    pub up: Vec3,
    /// θ, the half-height angle of the view volume, in degrees, in (0, 90).
    pub theta_deg: f32,
    /// d, the distance to the view window; `None` means the lecture's h / (2 tan θ).
    pub d: Option<f32>,
    /// w, the image width in pixels (1..=16384).
    pub width: u32,
    /// h, the image height in pixels (1..=16384).
    pub height: u32,
}

impl Camera {
    /// Default up vector u.
    pub const DEFAULT_UP: Vec3 = Vec3::Y;
    /// Default half-height angle θ in degrees.
    pub const DEFAULT_THETA_DEG: f32 = 25.0;
    /// Default image width w.
    pub const DEFAULT_WIDTH: u32 = 800;
    /// Default image height h.
    pub const DEFAULT_HEIGHT: u32 = 600;
    /// Largest accepted image side, in pixels.
    pub const MAX_SIZE: u32 = 16384;
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            eye: None,
            toward: None,
            up: Self::DEFAULT_UP,
            theta_deg: Self::DEFAULT_THETA_DEG,
            d: None,
            width: Self::DEFAULT_WIDTH,
            height: Self::DEFAULT_HEIGHT,
        }
    }
}

/// A light source. `intensity × color` is radiant intensity in W/sr for a point
/// light, irradiance (W/m²) for a directional light, and radiance for ambient.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Optional display name.
    pub name: Option<String>,
    /// Where the light is and how it shines.
    pub kind: LightKind,
    /// Linear RGB colour (default white).
    pub color: Vec3,
    /// Scalar multiplier of `color` (default [`defaults::light_intensity`] of the kind).
    pub intensity: f32,
}

/// The kinds of light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// An isotropic point light at `position`.
    Point {
        /// Where the light is.
        position: Vec3,
    },
    /// A light at infinity shining along `direction` (any length, not zero).
    Directional {
        /// The direction the light travels.
        direction: Vec3,
    },
    /// Uniform ambient radiance arriving from every direction, unshadowed.
    Ambient,
}

/// The built-in materials every scene can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BaseMaterial {
    /// Lambertian diffuse (the default).
    Matte,
    /// Lambert plus a Blinn-Phong highlight.
    Plastic,
    /// A perfect mirror; reflectance = colour.
    Mirror,
    /// A mirror tinted by its colour, with Schlick Fresnel toward white.
    Metal,
    /// A smooth dielectric (IOR 1.5), Fresnel and total internal reflection.
    Glass,
    /// Procedural solid-noise veins, slightly glossy.
    Marble,
}

impl BaseMaterial {
    /// Every built-in material, in the order the documentation lists them.
    pub const ALL: [BaseMaterial; 6] = [
        Self::Matte,
        Self::Plastic,
        Self::Mirror,
        Self::Metal,
        Self::Glass,
        Self::Marble,
    ];

    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Matte => "matte",
            Self::Plastic => "plastic",
            Self::Mirror => "mirror",
            Self::Metal => "metal",
            Self::Glass => "glass",
            Self::Marble => "marble",
        }
    }

    /// The built-in material with this scene-file name, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// A concrete material: a base with every parameter decided.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Which built-in behaviour.
    pub base: BaseMaterial,
    /// Linear RGB albedo (matte, plastic, marble), reflectance (mirror, metal) or tint (glass).
    pub color: Vec3,
    /// Index of refraction inside (glass).
    pub ior: f32,
    /// Blinn-Phong exponent.
    pub shininess: f32,
    /// Blinn-Phong highlight strength in [0, 1].
    pub specular: f32,
    /// Mirror-reflected fraction in [0, 1] (plastic, marble).
    pub reflectivity: f32,
    /// Microfacet roughness in [0, 1] of mirror, metal and glass (GGX α =
    /// roughness²; 0 is perfectly smooth).
    pub roughness: f32,
    /// Emitted radiance from the front side.
    pub emission: Vec3,
}

/// Material parameters that override a base material; `None` keeps the base's value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MaterialParams {
    /// Linear RGB albedo / reflectance / tint.
    pub color: Option<Vec3>,
    /// Index of refraction (glass).
    pub ior: Option<f32>,
    /// Blinn-Phong exponent of the highlight.
    pub shininess: Option<f32>,
    /// Strength of the Blinn-Phong highlight, in [0, 1].
    pub specular: Option<f32>,
    /// Fraction of light mirror-reflected, in [0, 1].
    pub reflectivity: Option<f32>,
    /// Microfacet roughness of mirror, metal and glass, in [0, 1] (GGX α = roughness²).
    pub roughness: Option<f32>,
    /// Emitted radiance (linear RGB, may exceed 1), from the front side.
    pub emission: Option<Vec3>,
}

impl MaterialParams {
    /// `self` with every value that `over` sets replaced by `over`'s.
    pub fn overridden_by(self, over: MaterialParams) -> MaterialParams {
        MaterialParams {
            color: over.color.or(self.color),
            ior: over.ior.or(self.ior),
            shininess: over.shininess.or(self.shininess),
            specular: over.specular.or(self.specular),
            reflectivity: over.reflectivity.or(self.reflectivity),
            roughness: over.roughness.or(self.roughness),
            emission: over.emission.or(self.emission),
        }
    }

    /// True when no parameter is set.
    pub fn is_empty(&self) -> bool {
        *self == MaterialParams::default()
    }
}

/// `<material name=… base=… …/>`: a named material derived from a built-in
/// material or from a material defined earlier in the file.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDef {
    /// The name objects refer to.
    pub name: String,
    /// A built-in material's name or an earlier `<material>`'s name.
    pub base: String,
    /// The overrides on top of the base.
    pub params: MaterialParams,
}

/// One object: a shape with a material.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Optional display name.
    pub name: Option<String>,
    /// The geometry and its placement.
    pub shape: Shape,
    /// A built-in or defined material's name; `None` is `matte`.
    pub material: Option<String>,
    /// Per-object overrides of the material's parameters (`<sphere color=…>`).
    pub params: MaterialParams,
}

/// The shapes of the lecture (sphere, triangle, box, cylinder, cone, torus)
/// plus planes. `rotate` is in degrees about x, then y, then z, about the
/// shape's own anchor (centre or base). An anchor of `None` means "rest on the
/// floor, side by side with the other unplaced objects in document order".
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere {
        /// C, the centre.
        center: Option<Vec3>,
        /// r, the radius (> 0).
        radius: f32,
    },
    /// An oriented box.
    Box {
        /// The centre.
        center: Option<Vec3>,
        /// Edge lengths along the box's own x, y, z (> 0).
        size: Vec3,
        /// Rotation in degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// A capped cylinder standing on the disk at `base`, axis along local +y.
    Cylinder {
        /// Centre of the bottom disk.
        base: Option<Vec3>,
        /// Radius (> 0).
        radius: f32,
        /// Height (> 0).
        height: f32,
        /// Rotation in degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// A capped cone standing on the disk at `base`, apex at base + height·y.
    Cone {
        /// Centre of the base disk.
        base: Option<Vec3>,
        /// Base radius (> 0).
        radius: f32,
        /// Height (> 0).
        height: f32,
        /// Rotation in degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// A torus in the local xz-plane around `center`.
    Torus {
        /// The centre.
        center: Option<Vec3>,
        /// R, the major radius (> 0).
        major: f32,
        /// r, the minor (tube) radius (> 0).
        minor: f32,
        /// Rotation in degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// The triangle T with vertices t0, t1, t2; its normal is (t1 − t0) × (t2 − t0).
    Triangle {
        /// t0.
        t0: Vec3,
        /// t1.
        t1: Vec3,
        /// t2.
        t2: Vec3,
    },
    /// An infinite plane through `point` with normal `normal`.
    Plane {
        /// A point s on the plane.
        point: Vec3,
        /// n, the normal (any length, not zero).
        normal: Vec3,
    },
    /// The infinite floor plane y = `y`.
    Floor {
        /// Height of the floor.
        y: f32,
    },
    /// A model file (glTF) placed in the scene: scaled, then rotated (x, then
    /// y, then z), then moved so that the model's origin is at `translate`.
    Mesh {
        /// The file as the scene names it, and what was loaded from it.
        source: MeshSource,
        /// Where the model's origin goes.
        translate: Option<Vec3>,
        /// Rotation in degrees about x, then y, then z.
        rotate: Vec3,
        /// Scale along the model's own x, y, z (> 0).
        scale: Vec3,
    },
}

/// A `<mesh src=…>` reference: the path as written in the scene file
/// (relative to the scene file's folder) and the model loaded from it.
#[derive(Clone)]
pub struct MeshSource {
    /// The path as written in the scene file.
    pub src: String,
    /// The loaded model, shared by every object that names the same file.
    pub model: Arc<ModelFile>,
}

impl PartialEq for MeshSource {
    /// Two references are equal when they name the same file (the loaded
    /// contents follow from the name).
    fn eq(&self, other: &Self) -> bool {
        self.src == other.src
    }
}

impl std::fmt::Debug for MeshSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The model's vertex arrays are far too long to print.
        f.debug_struct("MeshSource")
            .field("src", &self.src)
            .field("triangles", &self.model.drawn_triangles())
            .finish()
    }
}

/// Default shape parameters used by the reader, the writer and the editor.
pub mod defaults {
    use glam::Vec3;
    /// Default sphere radius.
    pub const SPHERE_RADIUS: f32 = 1.0;
    /// Default box size.
    pub const BOX_SIZE: Vec3 = Vec3::splat(1.5);
    /// Default cylinder radius.
    pub const CYLINDER_RADIUS: f32 = 0.6;
    /// Default cylinder height.
    pub const CYLINDER_HEIGHT: f32 = 1.8;
    /// Default cone base radius.
    pub const CONE_RADIUS: f32 = 0.8;
    /// Default cone height.
    pub const CONE_HEIGHT: f32 = 2.0;
    /// Default torus major radius R.
    pub const TORUS_MAJOR: f32 = 1.0;
    /// Default torus minor radius r.
    pub const TORUS_MINOR: f32 = 0.3;
    /// Default plane point.
    pub const PLANE_POINT: Vec3 = Vec3::ZERO;
    /// Default plane normal.
    pub const PLANE_NORMAL: Vec3 = Vec3::Y;
    /// Default floor height.
    pub const FLOOR_Y: f32 = 0.0;
    /// Default triangle vertices (the lecture's example triangle).
    pub const TRIANGLE: [Vec3; 3] = [
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    /// Default light colour.
    pub const LIGHT_COLOR: Vec3 = Vec3::ONE;
    /// Default position of a point light.
    pub const LIGHT_POSITION: Vec3 = Vec3::new(-4.0, 6.0, 4.0);
    /// Default direction of a directional light (the way its light travels).
    pub const LIGHT_DIRECTION: Vec3 = Vec3::new(-1.0, -2.0, -1.0);

    /// Default intensity of a light of this kind: 60 W/sr for a point light,
    /// 2 W/m² for a directional light, 0.1 for ambient light.
    pub fn light_intensity(kind: &super::LightKind) -> f32 {
        match kind {
            super::LightKind::Point { .. } => 60.0,
            super::LightKind::Directional { .. } => 2.0,
            super::LightKind::Ambient => 0.1,
        }
    }
}

impl Shape {
    /// The element name of this shape in scene files.
    pub fn tag(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "sphere",
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Cone { .. } => "cone",
            Shape::Torus { .. } => "torus",
            Shape::Triangle { .. } => "triangle",
            Shape::Plane { .. } => "plane",
            Shape::Floor { .. } => "floor",
            Shape::Mesh { .. } => "mesh",
        }
    }

    /// A shape of the given tag with every parameter at its default; `None` for an unknown tag.
    pub fn default_for_tag(tag: &str) -> Option<Shape> {
        use defaults::*;
        Some(match tag {
            "sphere" => Shape::Sphere {
                center: None,
                radius: SPHERE_RADIUS,
            },
            "box" => Shape::Box {
                center: None,
                size: BOX_SIZE,
                rotate: Vec3::ZERO,
            },
            "cylinder" => Shape::Cylinder {
                base: None,
                radius: CYLINDER_RADIUS,
                height: CYLINDER_HEIGHT,
                rotate: Vec3::ZERO,
            },
            "cone" => Shape::Cone {
                base: None,
                radius: CONE_RADIUS,
                height: CONE_HEIGHT,
                rotate: Vec3::ZERO,
            },
            "torus" => Shape::Torus {
                center: None,
                major: TORUS_MAJOR,
                minor: TORUS_MINOR,
                rotate: Vec3::ZERO,
            },
            "triangle" => Shape::Triangle {
                t0: TRIANGLE[0],
                t1: TRIANGLE[1],
                t2: TRIANGLE[2],
            },
            "plane" => Shape::Plane {
                point: PLANE_POINT,
                normal: PLANE_NORMAL,
            },
            "floor" => Shape::Floor { y: FLOOR_Y },
            _ => return None,
        })
    }

    /// The anchor (centre or base) of a shape that has one, for editing:
    /// `None` for triangles, planes and the floor.
    pub fn anchor_mut(&mut self) -> Option<&mut Option<Vec3>> {
        match self {
            Shape::Sphere { center, .. }
            | Shape::Box { center, .. }
            | Shape::Torus { center, .. } => Some(center),
            Shape::Cylinder { base, .. } | Shape::Cone { base, .. } => Some(base),
            Shape::Mesh { translate, .. } => Some(translate),
            Shape::Triangle { .. } | Shape::Plane { .. } | Shape::Floor { .. } => None,
        }
    }

    /// Every shape element name, for error suggestions.
    pub const TAGS: [&'static str; 9] = [
        "sphere", "box", "cylinder", "cone", "torus", "triangle", "plane", "floor", "mesh",
    ];
}
