//! The XML scene writer: `<scene>`, two-space indent, one self-closing element
//! per line, only values that differ from their defaults, in a fixed order.

use crate::color::format_color;
use crate::model::defaults;
use crate::model::{
    Camera, Light, LightKind, MaterialDef, MaterialParams, Object, Scene, Shape, Tonemap,
};
use glam::Vec3;
use std::fmt::Display;

/// Writes a scene as XML, only non-default values, in a stable order: the
/// camera (if not the default), then lights, the sky (if any), the view (if
/// not the default), materials and
/// objects in model order. Reading the result gives back an equal [`Scene`].
pub fn write_string(scene: &Scene) -> String {
    let mut out = String::from("<scene>\n");
    if scene.camera != Camera::default() {
        camera(&mut out, &scene.camera);
    }
    for l in &scene.lights {
        light(&mut out, l);
    }
    if let Some(sky) = &scene.sky {
        let mut tag = Tag::new(&mut out, "sky");
        if sky.map.is_none() || sky.color != Vec3::ONE {
            tag.attr("color", format_color(sky.color));
        }
        if let Some(map) = &sky.map {
            tag.text("map", Some(&map.src));
        }
        tag.vec("rotate", Some(sky.rotate), Some(Vec3::ZERO));
        tag.num("strength", sky.strength, Some(1.0));
        tag.close();
    }
    if !scene.view.is_identity() {
        let mut tag = Tag::new(&mut out, "view");
        tag.num("exposure", scene.view.exposure, Some(0.0));
        if scene.view.tonemap != Tonemap::default() {
            tag.attr("tonemap", scene.view.tonemap.name());
        }
        tag.close();
    }
    for m in &scene.materials {
        material(&mut out, m);
    }
    for o in &scene.objects {
        object(&mut out, o);
    }
    out.push_str("</scene>\n");
    out
}

/// One self-closing element being written.
struct Tag<'o> {
    out: &'o mut String,
}

impl<'o> Tag<'o> {
    /// Starts `  <name`.
    fn new(out: &'o mut String, name: &str) -> Self {
        out.push_str("  <");
        out.push_str(name);
        Tag { out }
    }

    /// ` name="value"` (the value must not need escaping).
    fn attr(&mut self, name: &str, value: impl Display) -> &mut Self {
        self.out.push_str(&format!(" {name}=\"{value}\""));
        self
    }

    /// A number, in shortest round-trip form, unless it equals `default`.
    fn num(&mut self, name: &str, v: f32, default: Option<f32>) -> &mut Self {
        if default != Some(v) {
            self.attr(name, v);
        }
        self
    }

    /// A vector "x y z", unless it equals `default`.
    fn vec(&mut self, name: &str, v: Option<Vec3>, default: Option<Vec3>) -> &mut Self {
        if let Some(v) = v
            && default != Some(v)
        {
            self.attr(name, format_args!("{} {} {}", v.x, v.y, v.z));
        }
        self
    }

    /// An optional number; nothing for `None`.
    fn opt_num(&mut self, name: &str, v: Option<f32>) -> &mut Self {
        if let Some(v) = v {
            self.attr(name, v);
        }
        self
    }

    /// An integer unless it equals `default`.
    fn int(&mut self, name: &str, v: u32, default: u32) -> &mut Self {
        if v != default {
            self.attr(name, v);
        }
        self
    }

    /// A string, escaped; nothing for `None`.
    fn text(&mut self, name: &str, v: Option<&str>) -> &mut Self {
        if let Some(v) = v {
            self.attr(name, escape(v));
        }
        self
    }

    /// The material parameters that are set.
    fn params(&mut self, p: &MaterialParams) -> &mut Self {
        if let Some(c) = p.color {
            self.attr("color", format_color(c));
        }
        for (name, v) in [
            ("ior", p.ior),
            ("shininess", p.shininess),
            ("specular", p.specular),
            ("reflectivity", p.reflectivity),
            ("roughness", p.roughness),
        ] {
            if let Some(v) = v {
                self.attr(name, v);
            }
        }
        if let Some(e) = p.emission {
            self.attr("emission", format_color(e));
        }
        self
    }

    /// Ends the element with `/>` and a newline.
    fn close(&mut self) {
        self.out.push_str("/>\n");
    }
}

/// Escapes a string for a double-quoted attribute so that it reads back
/// unchanged (attribute-value normalization would turn raw tabs and line
/// breaks into spaces, so those become character references).
fn escape(s: &str) -> String {
    quick_xml::escape::escape(s)
        .replace('\t', "&#9;")
        .replace('\n', "&#10;")
        .replace('\r', "&#13;")
}

/// `<camera …/>` with its non-default attributes.
fn camera(out: &mut String, c: &Camera) {
    let d = Camera::default();
    Tag::new(out, "camera")
        .vec("eye", c.eye, None)
        .vec("toward", c.toward, None)
        .vec("up", Some(c.up), Some(d.up))
        .num("theta", c.theta_deg, Some(d.theta_deg))
        .opt_num("d", c.d)
        .int("width", c.width, d.width)
        .int("height", c.height, d.height)
        .close();
}

/// `<light …/>`; the type is omitted for a point light.
fn light(out: &mut String, l: &Light) {
    let mut tag = Tag::new(out, "light");
    match l.kind {
        LightKind::Point { position } => {
            tag.vec("position", Some(position), Some(defaults::LIGHT_POSITION));
        }
        LightKind::Directional { direction } => {
            tag.attr("type", "directional").vec(
                "direction",
                Some(direction),
                Some(defaults::LIGHT_DIRECTION),
            );
        }
        LightKind::Ambient => {
            tag.attr("type", "ambient");
        }
    }
    if l.color != defaults::LIGHT_COLOR {
        tag.attr("color", format_color(l.color));
    }
    tag.num(
        "intensity",
        l.intensity,
        Some(defaults::light_intensity(&l.kind)),
    )
    .text("name", l.name.as_deref())
    .close();
}

/// `<material name=… base=… …/>`; the base is omitted when it is `matte`.
fn material(out: &mut String, m: &MaterialDef) {
    let base = (m.base != "matte").then_some(m.base.as_str());
    Tag::new(out, "material")
        .text("name", Some(&m.name))
        .text("base", base)
        .params(&m.params)
        .close();
}

/// A shape element with its non-default parameters, then name, material and
/// parameter overrides.
fn object(out: &mut String, o: &Object) {
    let tag_name = o.shape.tag();
    let mut tag = Tag::new(out, tag_name);
    let default = Shape::default_for_tag(tag_name);
    match (o.shape.clone(), default) {
        (Shape::Sphere { center, radius }, Some(Shape::Sphere { radius: r, .. })) => {
            tag.vec("center", center, None)
                .num("radius", radius, Some(r));
        }
        (
            Shape::Box {
                center,
                size,
                rotate,
            },
            Some(Shape::Box { size: s, .. }),
        ) => {
            tag.vec("center", center, None)
                .vec("size", Some(size), Some(s))
                .vec("rotate", Some(rotate), Some(Vec3::ZERO));
        }
        (
            Shape::Cylinder {
                base,
                radius,
                height,
                rotate,
            },
            Some(Shape::Cylinder {
                radius: r,
                height: h,
                ..
            }),
        )
        | (
            Shape::Cone {
                base,
                radius,
                height,
                rotate,
            },
            Some(Shape::Cone {
                radius: r,
                height: h,
                ..
            }),
        ) => {
            tag.vec("base", base, None)
                .num("radius", radius, Some(r))
                .num("height", height, Some(h))
                .vec("rotate", Some(rotate), Some(Vec3::ZERO));
        }
        (
            Shape::Torus {
                center,
                major,
                minor,
                rotate,
            },
            Some(Shape::Torus {
                major: ma,
                minor: mi,
                ..
            }),
        ) => {
            tag.vec("center", center, None)
                .num("major", major, Some(ma))
                .num("minor", minor, Some(mi))
                .vec("rotate", Some(rotate), Some(Vec3::ZERO));
        }
        (
            Shape::Triangle { t0, t1, t2 },
            Some(Shape::Triangle {
                t0: d0,
                t1: d1,
                t2: d2,
            }),
        ) => {
            tag.vec("t0", Some(t0), Some(d0))
                .vec("t1", Some(t1), Some(d1))
                .vec("t2", Some(t2), Some(d2));
        }
        (
            Shape::Plane { point, normal },
            Some(Shape::Plane {
                point: p,
                normal: n,
            }),
        ) => {
            tag.vec("point", Some(point), Some(p))
                .vec("normal", Some(normal), Some(n));
        }
        (Shape::Floor { y }, Some(Shape::Floor { y: d })) => {
            tag.num("y", y, Some(d));
        }
        (
            Shape::Mesh {
                source,
                translate,
                rotate,
                scale,
            },
            _,
        ) => {
            tag.text("src", Some(&source.src))
                .vec("translate", translate, None)
                .vec("rotate", Some(rotate), Some(Vec3::ZERO))
                .vec("scale", Some(scale), Some(Vec3::ONE));
        }
        _ => {}
    }
    tag.text("name", o.name.as_deref())
        .text("material", o.material.as_deref())
        .params(&o.params)
        .close();
}
