//! Tests of the debug view's drawing: the grid, the window corners, the
//! labels and markers, and where the rays are drawn.

use super::*;

fn seed() -> (World, Vec<ResolvedObject>) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
    let scene = scene::read_file(&path).expect("the seed scene loads");
    let resolved = scene::resolve(&scene).expect("the seed scene resolves");
    let world = World::new(&resolved).expect("the seed scene renders");
    (world, resolved.objects)
}

#[test]
fn grid_lines_are_every_pixel_when_few_and_sparser_when_many() {
    assert_eq!(grid_every(16, 9), 1);
    assert_eq!(grid_every(64, 48), 1);
    assert_eq!(grid_every(128, 72), 2);
    assert_eq!(grid_every(1280, 720), 20);
    assert_eq!(grid_every(4000, 10), 100);
}

#[test]
fn window_corners_are_c00_plus_the_window_edges() {
    let (world, _) = seed();
    let c = &world.camera;
    let [c00, top_right, bottom_right, bottom_left] = window_corners(c);
    assert_eq!(c00, c.c00);
    assert!((top_right.distance(c00) - c.w_d).abs() < 1e-3 * c.w_d);
    assert!((bottom_left.distance(c00) - c.h_d).abs() < 1e-3 * c.h_d);
    assert!((bottom_right - top_right - (bottom_left - c00)).length() < 1e-3 * c.h_d);
    // P_ij of the first and last pixels lie half a pixel inside the corners.
    let first = c.pixel_center(0, 0);
    let half_pixel = 0.5 * (c.w_d / c.w as f32) * c.r - 0.5 * (c.h_d / c.h as f32) * c.u;
    assert!(first.distance(c00 + half_pixel) < 1e-3 * c.h_d);
}

#[test]
fn the_drawing_labels_p0_t_u_r_and_c00_and_marks_the_selected_p_ij() {
    let (world, objects) = seed();
    let drawing = build(&Inputs {
        world: &world,
        objects: &objects,
        selected_object: None,
        pixel: Some([10, 20]),
        rays: &[],
        options: DrawOptions::default(),
    });
    for name in ["P0", "t", "u", "r", "C00", "P_ij (10, 20)"] {
        assert!(
            drawing.labels.iter().any(|l| l.text == name),
            "no label {name}"
        );
    }
    // The seed scene's default d puts its window far beyond the scene: it
    // is drawn nearer, scaled, and says so; P_ij and C00 are its own.
    let shown = drawing.camera.expect("the camera as drawn");
    assert!(shown.d < world.camera.d);
    assert!(
        drawing
            .labels
            .iter()
            .any(|l| l.text.starts_with("view window drawn at d = ")
                && l.text.ends_with(&format!("(d = {:.0})", world.camera.d))),
        "the moved window says so"
    );
    let p_ij = shown.pixel_center(10, 20);
    assert!(drawing.markers.iter().any(|m| m.at == p_ij));
    assert!(drawing.markers.iter().any(|m| m.at == shown.c00));
    // On the traced pixel's ray: the same direction from P0.
    let v = world.camera.center_ray(10, 20).dir;
    assert!((p_ij - shown.p0).normalize().distance(v) < 1e-5);
    assert!(!drawing.triangles.is_empty());
}

/// A view window near the scene (d = 1) is drawn where it is, labelled
/// with its d alone.
#[test]
fn a_view_window_near_the_scene_is_drawn_where_it_is() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
    let mut scene = scene::read_file(&path).expect("the seed scene loads");
    scene.camera.d = Some(1.0);
    let resolved = scene::resolve(&scene).expect("resolves");
    let world = World::new(&resolved).expect("renders");
    let drawing = build(&Inputs {
        world: &world,
        objects: &resolved.objects,
        selected_object: None,
        pixel: None,
        rays: &[],
        options: DrawOptions::default(),
    });
    assert_eq!(drawing.camera, Some(world.camera));
    assert!(
        drawing
            .labels
            .iter()
            .any(|l| l.text == "view window, d = 1.000")
    );
}

/// The drawn primary ray of an inspected pixel lies on the line through
/// P0 and the drawn P_ij, for the centre ray and for jittered samples
/// (whose window point is inside the pixel, so the line passes P_ij's pixel).
#[test]
fn the_drawn_primary_ray_passes_through_the_drawn_p_ij() {
    let (world, objects) = seed();
    let options = renderer::RenderOptions::default();
    for (pixel, sample) in [
        ([400, 300], None),
        ([200, 450], None),
        ([700, 100], Some(3)),
    ] {
        let inspection = renderer::inspect_pixel(&world, &options, pixel[0], pixel[1], sample)
            .expect("in the image");
        let rays: Vec<DrawnRay> = super::super::rays::drawn_rays(&inspection).collect();
        let drawing = build(&Inputs {
            world: &world,
            objects: &objects,
            selected_object: None,
            pixel: Some(pixel),
            rays: &rays,
            options: DrawOptions::default(),
        });
        let shown = drawing.camera.expect("the camera as drawn");
        let marker = drawing
            .markers
            .iter()
            .find(|m| m.color == palette::PRIMARY && m.at == shown.pixel_center(pixel[0], pixel[1]))
            .expect("P_ij is marked");
        let primary = rays
            .iter()
            .find(|r| r.kind == RayKind::Primary)
            .expect("a primary ray");
        assert_eq!(primary.from, world.camera.p0);
        // The window point the ray is drawn through, and P_ij itself.
        let window = primary
            .window_point
            .expect("primary rays know their window point");
        let off_line =
            |p: Vec3| (p - primary.from).cross(primary.dir).length() / (p - primary.from).length();
        assert!(
            off_line(window) < 1e-5,
            "window point off the ray by {}",
            off_line(window)
        );
        let pixel_size = shown.h_d / shown.h as f32;
        let distance = marker.at.distance(world.camera.p0);
        let allowed = if sample.is_some() {
            pixel_size / distance
        } else {
            1e-5
        };
        assert!(
            off_line(marker.at) <= allowed,
            "P_ij off the ray by {}",
            off_line(marker.at)
        );
        // And the drawn segment is that ray.
        let drawn = drawing.segments.iter().any(|s| {
            let a = Vec3::new(s[0], s[1], s[2]);
            let b = Vec3::new(s[3], s[4], s[5]);
            a == primary.from && (b - a).normalize().dot(primary.dir) > 1.0 - 1e-6
        });
        assert!(drawn, "the primary ray is drawn from P0 along v_ij");
    }
}

#[test]
fn a_sparse_fan_draws_one_ray_per_fan_pixel() {
    let (world, objects) = seed();
    let plain = build(&Inputs {
        world: &world,
        objects: &objects,
        selected_object: None,
        pixel: None,
        rays: &[],
        options: DrawOptions::default(),
    });
    let options = DrawOptions {
        fan: Fan::Sparse,
        fan_every: 100,
        ..DrawOptions::default()
    };
    let with_fan = build(&Inputs {
        world: &world,
        objects: &objects,
        selected_object: None,
        pixel: None,
        rays: &[],
        options,
    });
    let (w, h) = (world.camera.w, world.camera.h);
    let expected = (50..w).step_by(100).count() * (50..h).step_by(100).count();
    assert_eq!(with_fan.segments.len() - plain.segments.len(), expected);
}

#[test]
fn an_environment_map_is_drawn_with_its_zenith_azimuth_and_brightest_texel() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/reference/sky.xml");
    let scene = scene::read_file(&path).expect("the sky scene loads");
    let resolved = scene::resolve(&scene).expect("resolves");
    let world = World::new(&resolved).expect("renders");
    let drawing = build(&Inputs {
        world: &world,
        objects: &resolved.objects,
        selected_object: None,
        pixel: None,
        rays: &[],
        options: DrawOptions::default(),
    });
    let at = |name: &str| {
        drawing
            .labels
            .iter()
            .find(|l| l.text == name)
            .unwrap_or_else(|| panic!("no label {name}"))
            .at
    };
    let (centre, radius) = scene_sphere(&resolved.objects, world.camera.p0);
    // The map is turned 30° about y: φ = 0 points at −z turned by 30°.
    let zero = (at("sky φ = 0") - centre).normalize();
    let expected = glam::Mat3::from_rotation_y(30f32.to_radians()) * Vec3::NEG_Z;
    assert!((zero - expected).length() < 1e-4, "{zero} vs {expected}");
    assert!(((at("sky θ = 0") - centre).normalize() - Vec3::Y).length() < 1e-4);
    // The sun of scripts/make_sky_map.py, 40° above the horizon at 60° of
    // azimuth, turned with the map; its plateau is 4° wide.
    let sun = ((at("sky's brightest") - centre) / (1.8 * radius)).normalize();
    let (e, a) = (40f32.to_radians(), 60f32.to_radians());
    let true_sun = glam::Mat3::from_rotation_y(30f32.to_radians())
        * Vec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos());
    let off = sun.dot(true_sun).clamp(-1.0, 1.0).acos().to_degrees();
    assert!(off < 5.0, "{sun} is {off}° from the sun {true_sun}");
}
