//! Scenes that must load, and the values they load to.

use glam::Vec3;
use scene::color::srgb_to_linear;
use scene::{
    Camera, Light, LightKind, MaterialDef, MaterialParams, Object, Scene, Shape, read_str,
};

/// The lecture's snippet, exactly as written (unclosed tags and all).
const LECTURE: &str = r#"<scene> <cone material="glass"> <sphere color="red"> <box color="purple"> <floor material="marble"> </scene>"#;

/// The format's full example.
const EXAMPLE: &str = r##"<scene>
  <camera eye="0 1.5 6" toward="0 -0.2 -1" up="0 1 0" theta="25" d="3" width="800" height="600"/>
  <light type="point" position="-4 6 4" color="white" intensity="60"/>
  <light type="directional" direction="-1 -2 -1" color="white" intensity="0.5"/>
  <material name="blue-glass" base="glass" color="0.6 0.8 1"/>
  <sphere center="0 1 0" radius="1" color="red"/>
  <box center="2.5 0.75 0" size="1.5 1.5 1.5" rotate="0 30 0" color="purple"/>
  <cylinder base="-2.5 0 0" radius="0.6" height="1.8" color="#3080ff"/>
  <cone base="0 0 -2" radius="0.8" height="2" material="blue-glass"/>
  <torus center="0 0.3 2" major="1" minor="0.3" material="metal" color="gold"/>
  <triangle t0="-1 0 0" t1="1 0 0" t2="0 1 0"/>
  <plane point="0 -1 0" normal="0 1 0"/>
  <floor material="marble"/>
</scene>
"##;

fn read(text: &str) -> Scene {
    match read_str(text, "test.xml") {
        Ok(s) => s,
        Err(e) => panic!("{e}\n--- input ---\n{text}"),
    }
}

/// Linear RGB of an sRGB hex colour.
fn hex(r: u8, g: u8, b: u8) -> Vec3 {
    let c = |v: u8| srgb_to_linear(f32::from(v) / 255.0);
    Vec3::new(c(r), c(g), c(b))
}

fn object(shape: Shape, material: Option<&str>, color: Option<Vec3>) -> Object {
    Object {
        name: None,
        shape,
        material: material.map(String::from),
        params: MaterialParams {
            color,
            ..MaterialParams::default()
        },
    }
}

fn default_shape(tag: &str) -> Shape {
    Shape::default_for_tag(tag).unwrap_or_else(|| panic!("no shape {tag}"))
}

/// The lecture's four objects with default parameters and no anchors.
fn lecture_objects() -> Vec<Object> {
    vec![
        object(default_shape("cone"), Some("glass"), None),
        object(
            default_shape("sphere"),
            None,
            Some(Vec3::new(1.0, 0.0, 0.0)),
        ),
        object(default_shape("box"), None, Some(hex(0x80, 0, 0x80))),
        object(default_shape("floor"), Some("marble"), None),
    ]
}

#[test]
fn lecture_snippet_loads_as_written() {
    let scene = read(LECTURE);
    assert_eq!(scene.objects, lecture_objects());
    assert_eq!(scene.camera, Camera::default());
    assert!(scene.lights.is_empty() && scene.materials.is_empty());
}

#[test]
fn well_formed_equivalents_of_the_lecture_snippet_load_the_same() {
    let self_closing = r#"<?xml version="1.0"?>
<!-- the lecture's scene, well-formed -->
<scene>
  <cone material="glass"/>
  <sphere color="red"/>
  <box color="purple"/>
  <floor material="marble"/>
</scene>
"#;
    let closed = r#"<scene><cone material="glass"></cone><sphere color="red"></sphere>
<box color="purple"></box><floor material="marble"></floor></scene>"#;
    let mixed = "<scene>\r\n<cone material='glass'/><sphere color='RED'>\r\n<box color=\"Purple\"></box>\n<floor material=\"marble\"> </floor> </scene>\n<!-- end -->\n";
    for text in [self_closing, closed, mixed] {
        assert_eq!(read(text).objects, lecture_objects(), "{text}");
    }
}

#[test]
fn full_example_loads_with_the_expected_values() {
    let s = read(EXAMPLE);
    assert_eq!(
        s.camera,
        Camera {
            eye: Some(Vec3::new(0.0, 1.5, 6.0)),
            toward: Some(Vec3::new(0.0, -0.2, -1.0)),
            up: Vec3::Y,
            theta_deg: 25.0,
            d: Some(3.0),
            width: 800,
            height: 600,
        }
    );
    assert_eq!(
        s.lights,
        vec![
            Light {
                name: None,
                kind: LightKind::Point {
                    position: Vec3::new(-4.0, 6.0, 4.0)
                },
                color: Vec3::ONE,
                intensity: 60.0,
            },
            Light {
                name: None,
                kind: LightKind::Directional {
                    direction: Vec3::new(-1.0, -2.0, -1.0)
                },
                color: Vec3::ONE,
                intensity: 0.5,
            },
        ]
    );
    assert_eq!(
        s.materials,
        vec![MaterialDef {
            name: "blue-glass".into(),
            base: "glass".into(),
            params: MaterialParams {
                color: Some(Vec3::new(0.6, 0.8, 1.0)),
                ..MaterialParams::default()
            },
        }]
    );
    let v = Vec3::new;
    let expected = vec![
        object(
            Shape::Sphere {
                center: Some(v(0.0, 1.0, 0.0)),
                radius: 1.0,
            },
            None,
            Some(v(1.0, 0.0, 0.0)),
        ),
        object(
            Shape::Box {
                center: Some(v(2.5, 0.75, 0.0)),
                size: Vec3::splat(1.5),
                rotate: v(0.0, 30.0, 0.0),
            },
            None,
            Some(hex(0x80, 0, 0x80)),
        ),
        object(
            Shape::Cylinder {
                base: Some(v(-2.5, 0.0, 0.0)),
                radius: 0.6,
                height: 1.8,
                rotate: Vec3::ZERO,
            },
            None,
            Some(hex(0x30, 0x80, 0xff)),
        ),
        object(
            Shape::Cone {
                base: Some(v(0.0, 0.0, -2.0)),
                radius: 0.8,
                height: 2.0,
                rotate: Vec3::ZERO,
            },
            Some("blue-glass"),
            None,
        ),
        object(
            Shape::Torus {
                center: Some(v(0.0, 0.3, 2.0)),
                major: 1.0,
                minor: 0.3,
                rotate: Vec3::ZERO,
            },
            Some("metal"),
            Some(hex(255, 215, 0)),
        ),
        object(default_shape("triangle"), None, None),
        object(
            Shape::Plane {
                point: v(0.0, -1.0, 0.0),
                normal: Vec3::Y,
            },
            None,
            None,
        ),
        object(default_shape("floor"), Some("marble"), None),
    ];
    assert_eq!(s.objects, expected);
}

#[test]
fn full_example_with_unclosed_tags_loads_the_same() {
    let lenient = EXAMPLE.replace("/>", ">");
    assert_eq!(read(&lenient), read(EXAMPLE));
}

#[test]
fn lights_take_their_type_defaults() {
    let s = read(
        r#"<scene><light/><light type="directional"/><light type="ambient" color="0.5 0.5 1" name="sky"/></scene>"#,
    );
    assert_eq!(
        s.lights[0].kind,
        LightKind::Point {
            position: Vec3::new(-4.0, 6.0, 4.0)
        }
    );
    assert_eq!(s.lights[0].intensity, 60.0);
    assert_eq!(
        s.lights[1].kind,
        LightKind::Directional {
            direction: Vec3::new(-1.0, -2.0, -1.0)
        }
    );
    assert_eq!(s.lights[1].intensity, 2.0);
    assert_eq!(s.lights[2].kind, LightKind::Ambient);
    assert_eq!(s.lights[2].intensity, 0.1);
    assert_eq!(s.lights[2].color, Vec3::new(0.5, 0.5, 1.0));
    assert_eq!(s.lights[2].name.as_deref(), Some("sky"));
}

#[test]
fn vectors_accept_commas_and_whitespace_and_materials_chain_and_forward_references_resolve() {
    let s = read(
        "<scene>\n<sphere material='late' center='1,2,3' name='a &amp; b'/>\n\
         <material name='base1' base='plastic' ior='1.3'/>\n<material name='late' base='base1' emission='2 2 2'/>\n</scene>",
    );
    assert_eq!(
        s.objects[0].shape,
        Shape::Sphere {
            center: Some(Vec3::new(1.0, 2.0, 3.0)),
            radius: 1.0
        }
    );
    assert_eq!(s.objects[0].name.as_deref(), Some("a & b"));
    assert_eq!(s.materials[1].base, "base1");
    assert_eq!(s.materials[1].params.emission, Some(Vec3::splat(2.0)));
    let s = read("<scene><box size=' 1 ,2\t, 3 '/></scene>");
    assert!(
        matches!(s.objects[0].shape, Shape::Box { size, .. } if size == Vec3::new(1.0, 2.0, 3.0))
    );
}

#[test]
fn empty_scene_and_byte_order_mark_load_as_the_default() {
    for text in [
        "<scene/>",
        "<scene></scene>",
        "\u{feff}<scene>\n</scene>\n",
        "<?xml version='1.0'?><scene/>\n\n",
    ] {
        assert_eq!(read(text), Scene::default(), "{text:?}");
    }
}

#[test]
fn a_sky_loads_as_linear_radiance_in_any_colour_syntax() {
    assert_eq!(read("<scene/>").sky, None);
    let sky = |text: &str| read(text).sky;
    assert_eq!(
        sky(r#"<scene><sky color="0.5, 0.7 1"/></scene>"#),
        Some(scene::Sky::constant(Vec3::new(0.5, 0.7, 1.0)))
    );
    assert_eq!(
        sky(r##"<scene><sky color="#87CEEB"></sky></scene>"##),
        Some(scene::Sky::constant(hex(0x87, 0xce, 0xeb)))
    );
    // Unclosed, as the lecture writes elements; the sphere after it still loads.
    let scene = read(r#"<scene> <sky color="skyblue"> <sphere> </scene>"#);
    assert_eq!(scene.sky, Some(scene::Sky::constant(hex(0x87, 0xce, 0xeb))));
    assert_eq!(scene.objects.len(), 1);
}
