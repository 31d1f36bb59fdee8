//! Any scene the reader accepts renders without a panic, without a NaN or
//! infinite pixel, and without a sample the film's guard had to discard:
//! generated scenes with extreme but valid values (tiny and huge sizes and
//! distances, grazing and near-90° angles, every material at the ends of its
//! parameters), rendered tiny with both integrators and both methods.

use proptest::prelude::*;
use renderer::integrator::{Integrator, RenderOptions};
use renderer::shapes::Method;
use renderer::{Film, World};

/// A number across the range a scene accepts (±1e6, see
/// `scene::MAX_MAGNITUDE`), with a few just beyond it: 0, the
/// bounds, or ±m · 10^e for e in [-30, 9].
fn extreme() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        Just(0.0f32),
        Just(1.0e6f32),
        Just(-1.0e6f32),
        (-9.0f32..9.0, -30i32..=5).prop_map(|(m, e)| m * 10f32.powi(e)),
        -1.0e3f32..1.0e3,
    ]
}

/// A positive number from 1e-30 to 1e6.
fn positive() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        Just(1.0e6f32),
        (1.0f32..9.9, -30i32..=5).prop_map(|(m, e)| m * 10f32.powi(e)),
    ]
}

fn triple(s: impl Strategy<Value = f32> + Clone) -> impl Strategy<Value = String> {
    (s.clone(), s.clone(), s).prop_map(|(x, y, z)| format!("{x:e} {y:e} {z:e}"))
}

fn unit() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![Just(0.0f32), Just(1.0f32), 0.0f32..=1.0]
}

/// The common attributes: a material at the ends of its parameters.
fn looks() -> impl Strategy<Value = String> {
    (
        prop_oneof![
            Just("matte"),
            Just("plastic"),
            Just("mirror"),
            Just("metal"),
            Just("glass"),
            Just("marble")
        ],
        triple(unit()),
        prop_oneof![Just(1.0f32), Just(0.1f32), Just(10.0f32), 1.0f32..3.0],
        prop_oneof![Just(0.0f32), Just(1.0e6f32), 0.0f32..1000.0],
        (unit(), unit(), unit()),
        prop_oneof![Just("0 0 0".to_owned()), triple(unit()), triple(positive())],
    )
        .prop_map(|(material, color, ior, shininess, (spec, refl, rough), emission)| {
            format!(
                r#"material="{material}" color="{color}" ior="{ior:e}" shininess="{shininess:e}" specular="{spec}" reflectivity="{refl}" roughness="{rough}" emission="{emission}""#
            )
        })
}

fn shape() -> impl Strategy<Value = String> {
    let p = || triple(extreme());
    prop_oneof![
        (p(), positive()).prop_map(|(c, r)| format!(r#"<sphere center="{c}" radius="{r:e}""#)),
        (p(), triple(positive()), p())
            .prop_map(|(c, s, r)| format!(r#"<box center="{c}" size="{s}" rotate="{r}""#)),
        (p(), positive(), positive(), p()).prop_map(|(b, r, h, rot)| format!(
            r#"<cylinder base="{b}" radius="{r:e}" height="{h:e}" rotate="{rot}""#
        )),
        (p(), positive(), positive(), p()).prop_map(|(b, r, h, rot)| format!(
            r#"<cone base="{b}" radius="{r:e}" height="{h:e}" rotate="{rot}""#
        )),
        (p(), positive(), positive(), p()).prop_map(|(c, a, b, rot)| format!(
            r#"<torus center="{c}" major="{a:e}" minor="{b:e}" rotate="{rot}""#
        )),
        (p(), p(), p()).prop_map(|(a, b, c)| format!(r#"<triangle t0="{a}" t1="{b}" t2="{c}""#)),
        (p(), p()).prop_map(|(a, n)| format!(r#"<plane point="{a}" normal="{n}""#)),
        extreme().prop_map(|y| format!(r#"<floor y="{y:e}""#)),
    ]
}

fn light() -> impl Strategy<Value = String> {
    (
        prop_oneof![Just("point"), Just("directional"), Just("ambient")],
        triple(extreme()),
        triple(unit()),
        prop_oneof![Just(0.0f32), positive()],
    )
        .prop_map(|(kind, v, color, intensity)| {
            let place = match kind {
                "point" => format!(r#"position="{v}""#),
                "directional" => format!(r#"direction="{v}""#),
                _ => String::new(),
            };
            format!(r#"<light type="{kind}" {place} color="{color}" intensity="{intensity:e}"/>"#)
        })
}

fn camera() -> impl Strategy<Value = String> {
    (
        triple(extreme()),
        triple(extreme()),
        triple(extreme()),
        prop_oneof![Just(1.0e-3f32), Just(89.999f32), 0.01f32..89.99],
        prop_oneof![Just(String::new()), positive().prop_map(|d| format!(r#"d="{d:e}""#))],
    )
        .prop_map(|(eye, toward, up, theta, d)| {
            format!(
                r#"<camera eye="{eye}" toward="{toward}" up="{up}" theta="{theta}" {d} width="6" height="4"/>"#
            )
        })
}

fn scene() -> impl Strategy<Value = String> {
    (
        camera(),
        prop::collection::vec(light(), 0..3),
        prop::collection::vec((shape(), looks()), 1..4),
        prop_oneof![
            Just(String::new()),
            triple(unit()).prop_map(|c| format!(r#"<sky color="{c}"/>"#))
        ],
    )
        .prop_map(|(camera, lights, shapes, sky)| {
            let shapes: Vec<String> = shapes
                .into_iter()
                .map(|(s, l)| format!("{s} {l}/>"))
                .collect();
            format!(
                "<scene>\n{camera}\n{sky}\n{}\n{}\n</scene>\n",
                lights.join("\n"),
                shapes.join("\n")
            )
        })
}

/// The generator must mostly make scenes the reader and renderer accept, or
/// the property below would test little.
#[test]
fn most_generated_scenes_are_accepted() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let accepted = (0..200)
        .filter(|_| {
            let text = scene().new_tree(&mut runner).expect("tree").current();
            scene::read_str(&text, "extreme.xml")
                .ok()
                .is_some_and(|s| World::from_scene(&s).is_ok())
        })
        .count();
    assert!(
        accepted >= 100,
        "only {accepted} of 200 generated scenes were accepted"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn every_accepted_extreme_scene_renders_finite_pixels_without_discarded_samples(text in scene()) {
        // Scenes the reader or the renderer refuse are fine: the property is about those accepted.
        let Ok(scene) = scene::read_str(&text, "extreme.xml") else { return Ok(()) };
        let Ok(world) = World::from_scene(&scene) else { return Ok(()) };
        for integrator in [Integrator::Whitted, Integrator::Path] {
            for method in [Method::Robust, Method::Lecture] {
                let options = RenderOptions { integrator, method, max_depth: 6, ..RenderOptions::default() };
                let film = Film::render(&world, &options, 2);
                let pixels = film.linear();
                let bad = pixels.iter().position(|p| !p.is_finite());
                prop_assert!(bad.is_none(), "{integrator:?} {method:?}: pixel {bad:?} = {:?}\n{text}", bad.map(|k| pixels[k]));
                prop_assert_eq!(film.discarded(), 0, "{:?} {:?} discarded samples\n{}", integrator, method, text);
            }
        }
    }
}
