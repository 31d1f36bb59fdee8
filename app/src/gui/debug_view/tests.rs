//! The debug view drawn for real, headless, with wgpu on Mesa's software
//! Vulkan (lavapipe), and compared with a committed snapshot.

use super::*;
use eframe::egui_wgpu::{RendererOptions, WgpuSetup};
use eframe::wgpu;
use egui_kittest::Harness;
use egui_kittest::wgpu::{WgpuTestRenderer, create_render_state, default_wgpu_setup};
use renderer::World;
use scene::ResolvedObject;

/// A render state on Vulkan only: GL rasterises lines slightly differently,
/// and the snapshot must not depend on which adapter wgpu picks first.
fn vulkan_render_state() -> eframe::egui_wgpu::RenderState {
    let mut setup = default_wgpu_setup();
    if let WgpuSetup::CreateNew(new) = &mut setup {
        new.instance_descriptor.backends = wgpu::Backends::VULKAN;
    }
    create_render_state(setup, RendererOptions::PREDICTABLE)
}

/// The lecture's scene with a small image (so the pixel grid shows every
/// pixel) and the view window one unit in front of P0.
fn small_seed() -> (World, Vec<ResolvedObject>) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
    let mut scene = scene::read_file(&path).expect("the seed scene loads");
    scene.camera.width = 32;
    scene.camera.height = 18;
    scene.camera.d = Some(1.0);
    let resolved = scene::resolve(&scene).expect("the seed scene resolves");
    let world = World::new(&resolved).expect("the seed scene renders");
    (world, resolved.objects)
}

struct State {
    view: DebugView,
    world: World,
    objects: Vec<ResolvedObject>,
    pixel: Option<[u32; 2]>,
    rays: Vec<DrawnRay>,
}

/// A 720 × 480 harness drawing the debug view of `state` with wgpu, run two
/// frames, its picture saved as `target/tmp/NAME.png`; the harness and the
/// number of distinct colours in the picture.
fn draw(state: State, name: &str) -> (Harness<'static, State>, usize) {
    let render_state = vulkan_render_state();
    DebugRenderer::install(&render_state);
    let mut harness = Harness::builder()
        .with_size(egui::vec2(720.0, 480.0))
        .renderer(WgpuTestRenderer::from_render_state(render_state))
        .build_ui_state(
            |ui, s: &mut State| {
                let inputs = Inputs {
                    world: &s.world,
                    objects: &s.objects,
                    selected_object: None,
                    pixel: s.pixel,
                    rays: &s.rays,
                    options: s.view.options,
                };
                s.view.show(ui, &inputs, true);
            },
            state,
        );
    harness.run_steps(2);
    let image = harness.render().expect("the view renders");
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/tmp");
    std::fs::create_dir_all(&out).expect("target/tmp");
    image.save(out.join(format!("{name}.png"))).expect("saved");
    let distinct: std::collections::HashSet<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    (harness, distinct.len())
}

#[test]
fn debug_view_snapshot_shows_camera_window_c00_and_a_ray() {
    let (world, objects) = small_seed();
    // A pixel on the red sphere: its primary ray, the shadow ray to the
    // light and the reflection (the sphere is reflective plastic).
    let pixel = [17, 8];
    let options = renderer::RenderOptions::default();
    let inspection =
        renderer::inspect_pixel(&world, &options, pixel[0], pixel[1], None).expect("in the image");
    let sphere = inspection.primary().hit.as_ref().expect("a hit");
    assert_eq!(sphere.shape, "sphere");
    let rays: Vec<DrawnRay> = rays::drawn_rays(&inspection).collect();
    assert!(
        rays.iter()
            .any(|r| matches!(r.kind, rays::RayKind::Shadow { .. }))
    );
    let state = State {
        view: DebugView::default(),
        world,
        objects,
        pixel: Some(pixel),
        rays,
    };
    // The 3D drawing is there, not a blank: the background and many other colours.
    let (mut harness, distinct) = draw(state, "debug_view");
    assert!(distinct > 200, "only {distinct} colours");
    harness.snapshot("debug_view_seed");
}

/// The debug view of a scene under an environment map shows the map's
/// frame (saved for a look, not compared with a snapshot).
#[test]
fn debug_view_of_a_sky_map_draws_its_frame() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/reference/sky.xml");
    let scene = scene::read_file(&path).expect("the sky scene loads");
    let resolved = scene::resolve(&scene).expect("resolves");
    let world = World::new(&resolved).expect("renders");
    assert!(world.environment.map_orientation().is_some());
    let state = State {
        view: DebugView::default(),
        world,
        objects: resolved.objects,
        pixel: None,
        rays: Vec::new(),
    };
    let (_, distinct) = draw(state, "debug_view_sky");
    assert!(distinct > 200, "only {distinct} colours");
}

/// Labels whose points coincide or nearly do (C00 and P_ij of a small
/// view window, seen from afar) are drawn apart, each inside the view.
#[test]
fn labels_at_nearby_points_are_placed_apart_and_inside_the_view() {
    let bounds = egui::Rect::from_min_size(egui::pos2(0.0, 0.0), egui::vec2(300.0, 200.0));
    let size = egui::vec2(90.0, 14.0);
    let labels: Vec<(egui::Pos2, egui::Vec2)> = [
        (100.0, 100.0),
        (101.0, 100.0),
        (100.0, 102.0),
        (104.0, 99.0),
        (290.0, 5.0), // by the right and top edges
    ]
    .iter()
    .map(|&(x, y)| (egui::pos2(x, y), size))
    .collect();
    let placed = super::place_labels(&labels, bounds);
    assert_eq!(placed.len(), labels.len());
    for (a, ra) in placed.iter().enumerate() {
        assert!(
            bounds.contains_rect(*ra),
            "label {a} at {ra:?} is inside the view"
        );
        for (b, rb) in placed.iter().enumerate().skip(a + 1) {
            assert!(
                !ra.intersects(*rb),
                "labels {a} and {b} overlap: {ra:?} {rb:?}"
            );
        }
    }
    // One wider than the view starts at its left edge.
    let wide = super::place_labels(
        &[(egui::pos2(100.0, 100.0), egui::vec2(400.0, 14.0))],
        bounds,
    );
    assert_eq!(wide[0].left(), 2.0);
    // A label alone keeps its place beside its point.
    let alone = super::place_labels(&labels[..1], bounds);
    assert_eq!(alone[0].left_bottom(), egui::pos2(105.0, 95.0));
}
