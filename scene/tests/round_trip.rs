//! Load → save → load: `read_str(&write_string(&s)) == Ok(s)` for arbitrary
//! valid scenes, and the writer's output for a default scene.

use glam::Vec3;
use proptest::prelude::*;
use scene::color::srgb_to_linear;
use scene::{
    BaseMaterial, Camera, Light, LightKind, MaterialDef, MaterialParams, Object, Scene, Shape, Sky,
    Tonemap, View, read_str, write_string,
};

/// Any number a scene may hold (within ±1e6): mostly human-sized, sometimes
/// extreme or subnormal.
fn finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -100.0f32..100.0,
        1 => Just(0.0f32),
        1 => (-20i32..20).prop_map(|i| i as f32 * 0.25),
        1 => (prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO)
            .prop_filter("within the scene format's ±1e6", |x| x.abs() <= 1.0e6),
        1 => Just(1.0e6f32),
    ]
}

/// A finite f32 > 0.
fn positive() -> impl Strategy<Value = f32> {
    finite().prop_filter_map("positive", |x| (x.abs() > 0.0).then_some(x.abs()))
}

/// A finite f32 ≥ 0.
fn non_negative() -> impl Strategy<Value = f32> {
    finite().prop_map(f32::abs)
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (finite(), finite(), finite()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn nonzero_vec3() -> impl Strategy<Value = Vec3> {
    vec3().prop_filter("non-zero", |v| *v != Vec3::ZERO)
}

fn positive_vec3() -> impl Strategy<Value = Vec3> {
    (positive(), positive(), positive()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A linear colour in [0, 1]: either exactly an sRGB byte triple or arbitrary floats.
fn color() -> impl Strategy<Value = Vec3> {
    let byte = |b: u8| srgb_to_linear(f32::from(b) / 255.0);
    prop_oneof![
        any::<[u8; 3]>().prop_map(move |[r, g, b]| Vec3::new(byte(r), byte(g), byte(b))),
        (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b)),
    ]
}

fn emission() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        color(),
        (non_negative(), non_negative(), non_negative()).prop_map(|(r, g, b)| Vec3::new(r, g, b)),
    ]
}

fn params() -> impl Strategy<Value = MaterialParams> {
    (
        prop::option::of(color()),
        prop::option::of(prop_oneof![0.1f32..=10.0, Just(0.1f32), Just(10.0f32)]),
        prop::option::of(non_negative()),
        prop::option::of(0.0f32..=1.0),
        prop::option::of(0.0f32..=1.0),
        prop::option::of(0.0f32..=1.0),
        prop::option::of(emission()),
    )
        .prop_map(
            |(color, ior, shininess, specular, reflectivity, roughness, emission)| MaterialParams {
                color,
                ior,
                shininess,
                specular,
                reflectivity,
                roughness,
                emission,
            },
        )
}

/// Display names, including characters that need escaping.
fn name() -> impl Strategy<Value = String> {
    "[a-zA-Z0-9 _&<>\"'\t\n-]{0,10}"
}

/// Whether two non-zero vectors are safely far from parallel.
fn clearly_not_parallel(a: Vec3, b: Vec3) -> bool {
    let (a, b) = (a.as_dvec3().normalize(), b.as_dvec3().normalize());
    a.cross(b).length() > 1e-3
}

fn camera() -> impl Strategy<Value = Camera> {
    (
        prop::option::of(vec3()),
        prop::option::of(nonzero_vec3()),
        prop_oneof![Just(Vec3::Y), nonzero_vec3()],
        prop_oneof![Just(25.0f32), 0.001f32..89.999],
        prop::option::of(positive()),
        prop_oneof![Just(800u32), 1u32..=16384],
        prop_oneof![Just(600u32), 1u32..=16384],
    )
        .prop_filter("up not parallel to toward", |(_, toward, up, ..)| {
            toward.is_none_or(|t| clearly_not_parallel(t, *up))
        })
        .prop_map(|(eye, toward, up, theta_deg, d, width, height)| Camera {
            eye,
            toward,
            up,
            theta_deg,
            d,
            width,
            height,
        })
}

fn light() -> impl Strategy<Value = Light> {
    let kind = prop_oneof![
        prop_oneof![Just(Vec3::new(-4.0, 6.0, 4.0)), vec3()]
            .prop_map(|position| LightKind::Point { position }),
        prop_oneof![Just(Vec3::new(-1.0, -2.0, -1.0)), nonzero_vec3()]
            .prop_map(|direction| LightKind::Directional { direction }),
        Just(LightKind::Ambient),
    ];
    (
        kind,
        prop::option::of(name()),
        color(),
        prop::option::of(non_negative()),
    )
        .prop_map(|(kind, name, color, intensity)| Light {
            name,
            color,
            intensity: intensity.unwrap_or_else(|| scene::defaults::light_intensity(&kind)),
            kind,
        })
}

fn rotate() -> impl Strategy<Value = Vec3> {
    prop_oneof![Just(Vec3::ZERO), vec3()]
}

/// Every shape kind, with default and arbitrary parameters.
fn shape() -> impl Strategy<Value = Shape> {
    let center = || prop::option::of(vec3());
    prop_oneof![
        (center(), positive()).prop_map(|(center, radius)| Shape::Sphere { center, radius }),
        (center(), positive_vec3(), rotate()).prop_map(|(center, size, rotate)| Shape::Box {
            center,
            size,
            rotate
        }),
        (center(), positive(), positive(), rotate()).prop_map(|(base, radius, height, rotate)| {
            Shape::Cylinder {
                base,
                radius,
                height,
                rotate,
            }
        }),
        (center(), positive(), positive(), rotate()).prop_map(|(base, radius, height, rotate)| {
            Shape::Cone {
                base,
                radius,
                height,
                rotate,
            }
        }),
        (center(), positive(), positive(), rotate()).prop_map(|(center, major, minor, rotate)| {
            Shape::Torus {
                center,
                major,
                minor,
                rotate,
            }
        }),
        (
            -50.0f32..50.0,
            -50.0f32..50.0,
            -50.0f32..50.0,
            vec3(),
            vec3()
        )
            .prop_map(|(x, y, z, t1, t2)| Shape::Triangle {
                t0: Vec3::new(x, y, z),
                t1,
                t2
            })
            .prop_filter("not degenerate", |s| match *s {
                Shape::Triangle { t0, t1, t2 } => {
                    let (e1, e2) = (t1.as_dvec3() - t0.as_dvec3(), t2.as_dvec3() - t0.as_dvec3());
                    e1.cross(e2).length() > 1e-3 * e1.length_squared().max(e2.length_squared())
                }
                _ => false,
            }),
        (vec3(), nonzero_vec3()).prop_map(|(point, normal)| Shape::Plane { point, normal }),
        finite().prop_map(|y| Shape::Floor { y }),
        prop::sample::select(Shape::TAGS.to_vec())
            .prop_filter_map("known tag", Shape::default_for_tag),
    ]
}

/// Materials whose bases chain to built-ins or earlier materials, and objects
/// that use built-ins, defined materials (forward references included) or none.
fn scene() -> impl Strategy<Value = Scene> {
    let materials = prop::collection::vec((name(), any::<prop::sample::Index>(), params()), 0..5);
    let objects = prop::collection::vec(
        (
            shape(),
            prop::option::of(name()),
            prop::option::of(any::<prop::sample::Index>()),
            params(),
        ),
        0..8,
    );
    let lights = prop::collection::vec(light(), 0..4);
    let sky = prop::option::of((color(), rotate(), non_negative()).prop_map(
        |(color, rotate, strength)| Sky {
            color,
            map: None,
            rotate,
            strength,
        },
    ));
    let view = (-20.0f32..=20.0, prop::sample::select(Tonemap::ALL.to_vec()))
        .prop_map(|(exposure, tonemap)| View { exposure, tonemap });
    (camera(), lights, sky, materials, objects, view).prop_map(
        |(camera, lights, sky, materials, objects, view)| {
            let builtins: Vec<String> = BaseMaterial::ALL
                .iter()
                .map(|m| m.name().to_owned())
                .collect();
            let mut defs: Vec<MaterialDef> = Vec::new();
            for (i, (prefix, base, params)) in materials.into_iter().enumerate() {
                let choices: Vec<&String> = builtins
                    .iter()
                    .chain(defs.iter().map(|d| &d.name))
                    .collect();
                let base = (*base.get(&choices)).clone();
                defs.push(MaterialDef {
                    name: format!("{prefix}-{i}"),
                    base,
                    params,
                });
            }
            let all: Vec<String> = builtins
                .iter()
                .chain(defs.iter().map(|d| &d.name))
                .cloned()
                .collect();
            let objects = objects
                .into_iter()
                .map(|(shape, name, material, params)| Object {
                    name,
                    shape,
                    material: material.map(|m| m.get(&all).clone()),
                    params,
                })
                .collect();
            Scene {
                camera,
                lights,
                sky,
                materials: defs,
                objects,
                view,
            }
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn reading_the_written_scene_gives_back_the_same_scene(s in scene()) {
        let text = write_string(&s);
        prop_assert_eq!(read_str(&text, "written.xml"), Ok(s), "{}", text);
    }
}

#[test]
fn default_scene_writes_a_bare_scene_that_reads_back_as_the_default() {
    let text = write_string(&Scene::default());
    assert_eq!(text, "<scene>\n</scene>\n");
    assert_eq!(read_str(&text, "default.xml"), Ok(Scene::default()));
}

#[test]
fn writer_omits_defaults_and_orders_elements_and_attributes() {
    let text = r##"<scene>
  <sphere color="red" material="glass" radius="2"/>
  <floor/>
  <material base="metal" name="m"/>
  <light intensity="60" type="point"/>
  <light type="directional" intensity="2" color="0.5 0.25 1"/>
  <sky color="skyblue"/>
  <camera width="640" theta="25" up="0 1 0" eye="0 1 5"/>
</scene>"##;
    let scene = read_str(text, "t.xml").unwrap_or_else(|e| panic!("{e}"));
    let expected = r##"<scene>
  <camera eye="0 1 5" width="640"/>
  <light/>
  <light type="directional" color="0.5 0.25 1"/>
  <sky color="#87ceeb"/>
  <material name="m" base="metal"/>
  <sphere radius="2" material="glass" color="#ff0000"/>
  <floor/>
</scene>
"##;
    assert_eq!(write_string(&scene), expected);
}

#[test]
fn sky_round_trips() {
    for color in [
        Vec3::new(0.5, 0.7, 1.0),
        Vec3::ZERO,
        Vec3::ONE,
        Vec3::new(srgb_to_linear(0x87 as f32 / 255.0), 0.1, 1e-30),
    ] {
        let s = Scene {
            sky: Some(Sky::constant(color)),
            ..Scene::default()
        };
        let text = write_string(&s);
        assert!(text.contains("  <sky color=\""), "{text}");
        assert_eq!(read_str(&text, "sky.xml"), Ok(s), "{text}");
    }
    let text = write_string(&Scene {
        sky: Some(Sky::constant(Vec3::new(0.5, 0.7, 1.0))),
        ..Scene::default()
    });
    assert_eq!(text, "<scene>\n  <sky color=\"0.5 0.7 1\"/>\n</scene>\n");
    // A strength other than 1 is written and read back.
    let bright = Scene {
        sky: Some(Sky {
            strength: 4.5,
            ..Sky::constant(Vec3::new(0.5, 0.7, 1.0))
        }),
        ..Scene::default()
    };
    let text = write_string(&bright);
    assert!(text.contains("strength=\"4.5\""), "{text}");
    assert_eq!(read_str(&text, "sky.xml"), Ok(bright), "{text}");
}

/// A sky with a map keeps the file's name as written (relative to the
/// scene), its tint and rotation; white is not written with a map.
#[test]
fn sky_map_round_trips() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let maps = dir.path().join("maps");
    std::fs::create_dir(&maps).expect("a folder");
    exr::prelude::write_rgb_file(maps.join("sky & sun.exr"), 4, 2, |x, y| {
        (x as f32, y as f32, 0.5)
    })
    .expect("written");
    let file = dir.path().join("scene.xml");
    let file = file.to_str().expect("a UTF-8 path");
    let text = r#"<scene><sky map="maps/sky &amp; sun.exr" rotate="0 90 0"/></scene>"#;
    let scene = read_str(text, file).expect("a valid map");
    let sky = scene.sky.clone().expect("a sky");
    assert_eq!(
        (sky.color, sky.rotate),
        (Vec3::ONE, Vec3::new(0.0, 90.0, 0.0))
    );
    let map = sky.map.expect("a map");
    assert_eq!(map.src, "maps/sky & sun.exr");
    assert_eq!((map.image.width, map.image.height), (4, 2));
    assert_eq!(map.image.texel(3, 1), [3.0, 1.0, 0.5]);
    let written = write_string(&scene);
    assert_eq!(
        written,
        "<scene>\n  <sky map=\"maps/sky &amp; sun.exr\" rotate=\"0 90 0\"/>\n</scene>\n"
    );
    assert_eq!(read_str(&written, file), Ok(scene.clone()));
    let mut tinted = scene;
    tinted.sky.as_mut().expect("a sky").color = Vec3::new(0.5, 0.25, 1.0);
    let written = write_string(&tinted);
    assert!(
        written.contains(r#"<sky color="0.5 0.25 1" map="#),
        "{written}"
    );
    assert_eq!(read_str(&written, file), Ok(tinted));
}

/// raylab's studio environment is named, not a file: it reads anywhere and
/// writes back as it was written.
#[test]
fn the_studio_sky_round_trips_without_a_file() {
    let text = "<scene>\n  <sky map=\"raylab:studio\" rotate=\"0 45 0\"/>\n</scene>\n";
    let scene = read_str(text, "/nowhere/scene.xml").expect("the built-in map");
    let sky = scene.sky.clone().expect("a sky");
    assert_eq!(
        sky.map.as_ref().map(|m| m.src.as_str()),
        Some("raylab:studio")
    );
    assert_eq!(write_string(&scene), text);
}

/// A bad map is an error at the `map` attribute that names the file and why.
#[test]
fn a_bad_sky_map_is_an_error_at_its_attribute() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let file = dir.path().join("scene.xml");
    let file = file.to_str().expect("a UTF-8 path");
    let error = |text: &str| read_str(text, file).expect_err(text).to_string();
    let e = error("<scene>\n  <sky map=\"missing.hdr\"/>\n</scene>");
    assert!(
        e.contains(":2:13") && e.contains("\"missing.hdr\"") && e.contains("cannot read"),
        "{e}"
    );
    std::fs::write(dir.path().join("flat.png"), b"\x89PNG\r\n\x1a\n").expect("written");
    let e = error(r#"<scene><sky map="flat.png"/></scene>"#);
    assert!(e.contains("high dynamic range"), "{e}");
    let e = error(r#"<scene><sky map="https://example.com/sky.hdr"/></scene>"#);
    assert!(e.contains("network"), "{e}");
    let e = error(r#"<scene><sky rotate="0 1 0"/></scene>"#);
    assert!(e.contains("a color or a map"), "{e}");
}

/// `<view>` keeps the exposure and the curve; the default view is not
/// written; a bad one is an error at its value, saying what is accepted.
#[test]
fn view_round_trips_and_bad_views_say_why() {
    let s = Scene {
        view: View {
            exposure: -1.5,
            tonemap: Tonemap::Neutral,
        },
        ..Scene::default()
    };
    let text = write_string(&s);
    assert_eq!(
        text,
        "<scene>\n  <view exposure=\"-1.5\" tonemap=\"neutral\"/>\n</scene>\n"
    );
    assert_eq!(read_str(&text, "view.xml"), Ok(s));
    assert_eq!(write_string(&Scene::default()), "<scene>\n</scene>\n");
    let error = |text: &str| read_str(text, "v.xml").expect_err(text).to_string();
    let e = error("<scene>\n  <view tonemap=\"neutrall\"/>\n</scene>");
    assert!(
        e.contains("2:")
            && e.contains("clamp or neutral")
            && e.contains("did you mean \"neutral\""),
        "{e}"
    );
    let e = error("<scene><view exposure=\"30\"/></scene>");
    assert!(e.contains("from -20 to 20"), "{e}");
    let e = error("<scene><view exposure=\"NaN\"/></scene>");
    assert!(e.contains("exposure"), "{e}");
    let e = error("<scene><view/><view/></scene>");
    assert!(e.contains("view"), "{e}");
}

/// A scene shown differently renders the same samples; any other edit does not.
#[test]
fn the_view_is_not_part_of_what_is_rendered() {
    let a = read_str("<scene><sphere/></scene>", "a.xml").expect("valid");
    let mut b = a.clone();
    b.view.exposure = 2.0;
    b.view.tonemap = Tonemap::Neutral;
    assert!(a.renders_like(&b) && a != b);
    b.sky = Some(Sky::constant(Vec3::ONE));
    assert!(!a.renders_like(&b));
}
