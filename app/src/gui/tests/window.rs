//! Headless UI tests (egui_kittest): the window's behaviour without a display.

use super::{harness, seed_app, seed_path, settle, step_shown};
use crate::gui::RaylabApp;
use crate::gui::commands::Command;
use crate::gui::doc::edits::{self, Selection};
use egui::{Key, Modifiers, PointerButton};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::Vec3;
use renderer::integrator::adaptive::Adaptive;
use renderer::progressive::Step;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The linear pixels on screen.
fn pixels(h: &Harness<'static, RaylabApp>) -> Vec<Vec3> {
    h.state()
        .session
        .frame
        .as_ref()
        .expect("a frame")
        .linear_image()
        .into_owned()
}

/// Clicks the primary button at `pos` without moving.
fn click_at(h: &mut Harness<'static, RaylabApp>, pos: egui::Pos2) {
    h.hover_at(pos);
    h.step();
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
}

/// The panel's d field.
fn d_field<'h>(h: &'h Harness<'static, RaylabApp>) -> egui_kittest::Node<'h> {
    h.get_by_role_and_label(egui::accesskit::Role::SpinButton, "d")
}

#[test]
fn window_refines_the_seed_scene_and_shows_the_lecture_values() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    assert!(h.state().session.generation >= 1);
    h.get_by_label("C00");
    h.get_by_label("2 / 2 spp");
}

#[test]
fn editing_theta_in_the_panel_starts_a_new_render_and_changes_the_image() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let (before, image) = (h.state().session.generation, pixels(&h));
    h.get_by_role_and_label(egui::accesskit::Role::Slider, "θ")
        .set_value_accesskit(40.0);
    h.step();
    assert_eq!(h.state().doc.state.scene.camera.theta_deg, 40.0);
    assert!(
        h.state().session.generation > before,
        "an edit submits a new job"
    );
    settle(&mut h);
    assert_ne!(pixels(&h), image, "a wider view shows a different picture");
}

#[test]
fn editing_d_changes_nothing_in_the_image() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let image = pixels(&h);
    let d = h
        .state()
        .session
        .prepared
        .as_ref()
        .expect("prepared")
        .world
        .camera
        .d;
    d_field(&h).set_value_accesskit(f64::from(d) * 7.5);
    h.step();
    let camera_d = h.state().doc.state.scene.camera.d.expect("d was set");
    assert!((camera_d - d * 7.5).abs() < 1e-3 * d, "d is now {camera_d}");
    settle(&mut h);
    assert_eq!(
        pixels(&h),
        image,
        "moving the view window along t leaves the image alone"
    );
}

#[test]
fn a_degenerate_camera_keeps_the_last_image_and_says_why() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let before = h.state().session.generation;
    h.state_mut().doc.state.scene.camera.up = Vec3::ZERO;
    h.step();
    assert_eq!(
        h.state().session.generation,
        before,
        "no job for an invalid scene"
    );
    h.step(); // the status bar shows the error from the next frame on
    h.get_by_label("camera: the up vector u is zero or not finite");
    assert!(h.state().session.frame.is_some(), "the last image stays");
}

#[test]
fn raising_the_target_spp_refines_the_same_image_further() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let generation = h.state().session.generation;
    h.get_by_label_contains("target spp")
        .set_value_accesskit(4.0);
    h.step();
    assert_eq!(h.state().doc.state.render.target_spp, Some(4));
    settle(&mut h);
    assert_eq!(h.state().session.generation, generation, "no restart");
}

#[test]
fn adding_a_sphere_lists_it_and_shows_it_in_the_image() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let image = pixels(&h);
    h.get_by_label("Add").click();
    step_shown(&mut h);
    h.get_by_label("sphere").click();
    h.step();
    assert_eq!(h.state().doc.state.scene.objects.len(), 5);
    assert_eq!(h.state().selection, Selection::Object(4));
    settle(&mut h);
    h.get_by_label("sphere 5");
    // The new sphere covers pixels that showed something else before.
    let world = &h.state().session.prepared.as_ref().expect("prepared").world;
    let covered = (0..48u32)
        .flat_map(|j| (0..64u32).map(move |i| (i, j)))
        .filter(|&(i, j)| {
            world
                .intersect(&world.camera.center_ray(i, j), renderer::Method::Robust)
                .is_some_and(|hit| hit.object == 4)
        })
        .count();
    assert!(covered > 20, "the new sphere covers only {covered} pixels");
    assert_ne!(pixels(&h), image);
}

#[test]
fn undo_and_redo_round_trip_a_camera_edit_and_a_colour_edit() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let original = h.state().doc.state.clone();
    h.get_by_role_and_label(egui::accesskit::Role::Slider, "θ")
        .set_value_accesskit(35.0);
    h.step();
    h.state_mut().doc.state.scene.objects[1].params.color = Some(Vec3::new(0.1, 0.2, 0.9));
    h.step();
    let edited = h.state().doc.state.clone();

    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(h.state().doc.state, original, "two undos restore the start");
    assert!(!h.state().doc.is_modified());
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.step();
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.step();
    assert_eq!(h.state().doc.state, edited, "two redos restore the edits");
    settle(&mut h);
}

#[test]
fn an_orbit_drag_is_one_undo_step_and_keeps_the_distance_to_the_target() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let original = h.state().doc.state.clone();
    let start = h.state().image.pixel_on_screen([32, 24]).expect("drawn");
    h.hover_at(start);
    h.drag_at(start);
    h.step();
    for k in 1..=10 {
        h.hover_at(start + egui::vec2(6.0 * k as f32, 2.0 * k as f32));
        h.step();
    }
    let during = h.state().camera_drag.view.expect("orbiting");
    h.drop_at(start + egui::vec2(60.0, 20.0));
    h.step();
    let camera = &h.state().doc.state.scene.camera;
    let eye = camera.eye.expect("the eye was written back");
    assert_ne!(Some(eye), original.scene.camera.eye);
    assert!((eye.distance(during.target) - during.distance()).abs() < 1e-3 * during.distance());
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(h.state().doc.state, original, "the whole drag is one step");
    settle(&mut h);
}

#[test]
fn three_wheel_notches_are_one_undo_step_named_dolly_and_theta_is_named_too() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let original = h.state().doc.state.clone();
    let centre = h.state().image.pixel_on_screen([32, 24]).expect("drawn");
    h.hover_at(centre);
    h.step();
    for _ in 0..3 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Line,
            delta: egui::vec2(0.0, 1.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Wheel,
            modifiers: Modifiers::NONE,
        });
        // egui spreads a notch over several frames.
        for _ in 0..6 {
            h.step();
            std::thread::sleep(std::time::Duration::from_millis(15));
        }
    }
    let dollied = h.state().doc.state.scene.camera.eye;
    assert_ne!(dollied, original.scene.camera.eye, "the wheel dollied");
    // Half a second after the last notch the turn of the wheel is one step.
    std::thread::sleep(std::time::Duration::from_millis(600));
    h.step();
    h.step();
    assert_eq!(
        h.state().doc.history.undo_name(&h.state().doc.state),
        Some("dolly")
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(
        h.state().doc.state,
        original,
        "one undo takes the whole turn back"
    );

    h.get_by_role_and_label(egui::accesskit::Role::Slider, "θ")
        .set_value_accesskit(35.0);
    h.step();
    h.step();
    assert_eq!(
        h.state().doc.history.undo_name(&h.state().doc.state),
        Some("θ"),
        "{:?}",
        h.state().doc.state.scene.camera
    );
    h.get_by_label("Edit").click();
    step_shown(&mut h);
    // The button reads "Undo θ" and its shortcut.
    assert!(
        h.query_by_label_contains("Undo θ").is_some(),
        "the menu names the step"
    );
    assert_eq!(
        h.state().doc.history.redo_name(&h.state().doc.state),
        None,
        "the new edit ended the redo branch"
    );
    settle(&mut h);
}

#[test]
fn clicking_the_image_selects_the_object_under_the_pointer() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let world = h
        .state()
        .session
        .prepared
        .as_ref()
        .expect("prepared")
        .world
        .clone();
    for object in 0..world.objects.len() as u32 {
        // A pixel inside the object's silhouette, away from its edge.
        let pixel = (2..46u32)
            .flat_map(|j| (2..62u32).map(move |i| [i, j]))
            .find(|&[i, j]| {
                [[0i32, 0], [-1, 0], [1, 0], [0, -1], [0, 1]]
                    .iter()
                    .all(|[di, dj]| {
                        let ray = world
                            .camera
                            .center_ray((i as i32 + di) as u32, (j as i32 + dj) as u32);
                        world
                            .intersect(&ray, renderer::Method::Robust)
                            .is_some_and(|hit| hit.object == object)
                    })
            });
        let Some(pixel) = pixel else { continue };
        // Let the panels settle after the previous selection changed them.
        // The previous click opened the pixel inspector; close it so that it
        // covers nothing (the image is tiny here).
        h.state_mut().inspector.inspected = None;
        h.run_steps(3);
        let pos = h.state().image.pixel_on_screen(pixel).expect("drawn");
        click_at(&mut h, pos);
        assert_eq!(
            h.state().selection,
            Selection::Object(object as usize),
            "clicking pixel {pixel:?} of {}",
            world.names[object as usize]
        );
    }
    assert_eq!(
        h.state().doc.state.scene.camera.eye,
        None,
        "a click does not move the camera"
    );
}

#[test]
fn opening_a_file_with_unsaved_changes_asks_first() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    h.state_mut().doc.state.scene.camera.theta_deg = 30.0;
    h.step();
    let other = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/primitives.xml");
    let ctx = h.ctx.clone();
    h.state_mut().run(&ctx, Command::OpenPath(other.clone()));
    step_shown(&mut h);
    h.get_by_label("Unsaved changes");
    h.get_by_label("Cancel").click();
    h.step();
    assert_eq!(h.state().doc.path.as_deref(), Some(seed_path().as_path()));
    assert_eq!(
        h.state().doc.state.scene.camera.theta_deg,
        30.0,
        "nothing lost"
    );

    h.state_mut().run(&ctx, Command::OpenPath(other.clone()));
    step_shown(&mut h);
    h.get_by_label("Don't save").click();
    h.step();
    assert_eq!(h.state().doc.path.as_deref(), Some(other.as_path()));
    assert!(!h.state().doc.is_modified());
    assert!(h.state().doc.title().starts_with("primitives.xml"));
}

#[test]
fn closing_with_unsaved_changes_is_held_until_the_user_answers() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    h.state_mut().doc.state.scene.objects.pop();
    h.step();
    h.state_mut().files.guard = Some(crate::gui::files::Pending::Close);
    step_shown(&mut h);
    h.get_by_label("Save the changes to seed.xml before closing?");
    h.get_by_label("Cancel").click();
    h.step();
    assert!(!h.state().files.allow_close);
    assert_eq!(h.state().files.guard, None);
}

#[test]
fn saving_the_image_writes_the_tonemapped_accumulation_buffer_and_the_camera() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("shot.png");
    h.state_mut().files().save_image(&path);
    assert_eq!(h.state().files.message, None);
    let frame = h.state().session.frame.as_ref().expect("a frame");
    let expected: Vec<u8> = frame
        .linear_image()
        .iter()
        .flat_map(|&c| renderer::display::srgb::linear_to_srgb8(c))
        .collect();
    let written = image::open(&path).expect("a PNG").to_rgb8();
    assert_eq!(written.dimensions(), (48, 32));
    assert_eq!(
        written.into_raw(),
        expected,
        "PNG pixels = tonemapped buffer"
    );
    let text = crate::io::output::read_png_provenance(&path).expect("text chunks");
    assert!(text.get("raylab:camera").is_some_and(|c| c.contains("P0=")));
    assert!(
        text.get("raylab:scene")
            .is_some_and(|s| s.ends_with("seed.xml"))
    );
    assert_eq!(text.get("raylab:spp"), Some("2"));
}

#[test]
fn saving_the_scene_and_reopening_it_gives_the_same_picture() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    h.get_by_role_and_label(egui::accesskit::Role::Slider, "θ")
        .set_value_accesskit(31.0);
    h.step();
    settle(&mut h);
    let image = pixels(&h);
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("edited.xml");
    let ctx = h.ctx.clone();
    h.state_mut().chosen(
        &ctx,
        crate::gui::files::dialogs::DialogKind::SaveScene,
        path.clone(),
    );
    assert!(!h.state().doc.is_modified());
    h.state_mut().run(&ctx, Command::OpenPath(path.clone()));
    h.step();
    assert_eq!(h.state().doc.path.as_deref(), Some(path.as_path()));
    h.state_mut().doc.state.render.target_spp = Some(2);
    settle(&mut h);
    assert_eq!(pixels(&h), image);
}

/// A pixel of the image whose centre ray hits the object named `name`, with
/// its four neighbours on the same object (so a click cannot miss it).
fn pixel_on(h: &Harness<'static, RaylabApp>, name: &str) -> ([u32; 2], u32) {
    let world = &h.state().session.prepared.as_ref().expect("prepared").world;
    let object = world
        .names
        .iter()
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no object {name} in {:?}", world.names)) as u32;
    let (w, h) = (world.camera.w, world.camera.h);
    let hits = |i: u32, j: u32| {
        world
            .intersect(&world.camera.center_ray(i, j), renderer::Method::Robust)
            .is_some_and(|hit| hit.object == object)
    };
    let pixel = (1..h - 1)
        .flat_map(|j| (1..w - 1).map(move |i| [i, j]))
        .find(|&[i, j]| {
            hits(i, j) && hits(i - 1, j) && hits(i + 1, j) && hits(i, j - 1) && hits(i, j + 1)
        })
        .unwrap_or_else(|| panic!("{name} covers no pixel"));
    (pixel, object)
}

#[test]
fn clicking_a_pixel_on_the_red_sphere_inspects_its_rays() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let sphere = h
        .state()
        .session
        .prepared
        .as_ref()
        .expect("prepared")
        .world
        .names[1]
        .clone();
    let (pixel, object) = pixel_on(&h, &sphere);
    let pos = h.state().image.pixel_on_screen(pixel).expect("drawn");
    click_at(&mut h, pos);
    step_shown(&mut h);
    let (_, inspection) = h
        .state()
        .inspector
        .inspection
        .as_ref()
        .expect("the click inspects the pixel");
    assert_eq!([inspection.i, inspection.j], pixel);
    let hit = inspection
        .primary()
        .hit
        .as_ref()
        .expect("the primary ray hits");
    assert_eq!(hit.object.index, object);
    assert_eq!(hit.shape, "sphere");
    // The ray through P_ij is the depth AOV's ray: the same α.
    let world = &h.state().session.prepared.as_ref().expect("prepared").world;
    let alpha = renderer::film::aov::aov_at(
        world,
        renderer::film::aov::Aov::Depth,
        renderer::Method::Robust,
        pixel[0],
        pixel[1],
    )[0];
    assert_eq!(hit.alpha, alpha);
    // The window shows the pixel, its shadow ray and α.
    h.get_by_label(&format!("Pixel ({}, {})", pixel[0], pixel[1]));
    assert!(
        inspection
            .rays
            .iter()
            .any(|r| r.kind == renderer::integrator::RayKind::Shadow),
        "a shadow ray toward the light"
    );
    assert!(h.query_all_by_label_contains("shadow").next().is_some());
    let alpha = format!("α = {:.3}", hit.alpha);
    assert!(
        h.query_all_by_label_contains(&alpha).next().is_some(),
        "{alpha} shown"
    );
}

#[test]
fn stepping_to_a_sample_re_traces_the_sample_that_went_into_the_image() {
    let mut app = seed_app(32, 24);
    app.doc.state.render.target_spp = Some(1);
    let mut h = harness(app);
    settle(&mut h);
    let (pixel, _) = pixel_on(
        &h,
        &h.state()
            .session
            .prepared
            .as_ref()
            .expect("prepared")
            .world
            .names[1]
            .clone(),
    );
    let pos = h.state().image.pixel_on_screen(pixel).expect("drawn");
    click_at(&mut h, pos);
    step_shown(&mut h);
    h.get_by_label("sample").click();
    step_shown(&mut h);
    let (_, inspection) = h.state().inspector.inspection.as_ref().expect("inspected");
    assert_eq!(inspection.sample, Some(0));
    // With one pass on screen, the image's pixel is exactly sample 0.
    let frame = h.state().session.frame.as_ref().expect("a frame");
    let shown = frame.linear_at(pixel[0], pixel[1]).expect("on the image");
    assert_eq!(
        shown.to_array().map(f32::to_bits),
        inspection.color.to_array().map(f32::to_bits)
    );
}

#[test]
fn an_unpinned_inspection_follows_its_point_and_a_pinned_one_keeps_its_pixel() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let sphere = h
        .state()
        .session
        .prepared
        .as_ref()
        .expect("prepared")
        .world
        .names[1]
        .clone();
    let (pixel, _) = pixel_on(&h, &sphere);
    let pos = h.state().image.pixel_on_screen(pixel).expect("drawn");
    click_at(&mut h, pos);
    step_shown(&mut h);
    // Doubling d moves the view window, not the image: the pixel stays.
    let d = h
        .state()
        .session
        .prepared
        .as_ref()
        .expect("prepared")
        .world
        .camera
        .d;
    h.state_mut().doc.state.scene.camera.d = Some(2.0 * d);
    h.run_steps(2);
    assert_eq!(
        h.state().inspector.inspected.expect("inspected").pixel,
        pixel
    );
    // Moving the camera sideways moves the point across the image; the
    // unpinned pixel follows it.
    let camera = h
        .state()
        .session
        .prepared
        .as_ref()
        .expect("prepared")
        .world
        .camera;
    h.state_mut().doc.state.scene.camera.eye = Some(camera.p0 + 0.4 * camera.r);
    h.state_mut().doc.state.scene.camera.toward = Some(camera.t);
    h.run_steps(2);
    let followed = h.state().inspector.inspected.expect("inspected").pixel;
    assert!(
        followed[0] < pixel[0],
        "{followed:?}: the point moves left as the camera moves right"
    );
    let (_, inspection) = h.state().inspector.inspection.as_ref().expect("inspected");
    assert_eq!(
        inspection.primary().hit.as_ref().map(|hit| hit.shape),
        Some("sphere"),
        "still on the sphere"
    );
    // Pinned, it keeps (i, j) whatever the camera does.
    h.get_by_label("Pin").click();
    h.step();
    h.state_mut().doc.state.scene.camera.eye = Some(camera.p0);
    h.run_steps(2);
    assert_eq!(
        h.state().inspector.inspected.expect("inspected").pixel,
        followed
    );
}

#[test]
fn the_g_key_shows_the_debug_view_beside_the_image() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    assert!(h.query_by_label("ray fan").is_none());
    h.key_press(Key::G);
    step_shown(&mut h);
    assert!(h.state().show_debug);
    h.get_by_label("ray fan");
    h.get_by_label("Wireframe").click();
    h.step();

    assert!(!h.state().debug.options.solid);
}

/// The whole window drawn with wgpu (lavapipe): the image with the inspected
/// pixel, the debug view with its rays and the inspector, saved for a look.
/// A `width` × `height` harness of the app `make` builds on a wgpu render
/// state (Vulkan: lavapipe here), drawn by wgpu.
fn wgpu_harness(
    width: f32,
    height: f32,
    make: impl FnOnce(eframe::egui_wgpu::RenderState) -> RaylabApp,
) -> Harness<'static, RaylabApp> {
    use eframe::egui_wgpu::{RendererOptions, WgpuSetup};
    use egui_kittest::wgpu::{WgpuTestRenderer, create_render_state, default_wgpu_setup};
    let mut setup = default_wgpu_setup();
    if let WgpuSetup::CreateNew(new) = &mut setup {
        new.instance_descriptor.backends = eframe::wgpu::Backends::VULKAN;
    }
    let render_state = create_render_state(setup, RendererOptions::PREDICTABLE);
    let app = make(render_state.clone());
    Harness::builder()
        .with_size(egui::Vec2::new(width, height))
        .renderer(WgpuTestRenderer::from_render_state(render_state))
        .build_ui_state(|ui, app: &mut RaylabApp| app.show(ui), app)
}

/// Clicks the seed scene's sphere (object 1) in the image: it is selected
/// and its pixel inspected.
fn click_the_sphere(h: &mut Harness<'static, RaylabApp>) {
    let world = &h.state().session.prepared.as_ref().expect("prepared").world;
    let sphere = world.names[1].clone();
    let (pixel, _) = pixel_on(h, &sphere);
    let pos = h.state().image.pixel_on_screen(pixel).expect("drawn");
    click_at(h, pos);
    step_shown(h);
}

/// The window drawn by wgpu, also saved as target/tmp/`name` for a person
/// to look at.
fn keep_rendered(h: &mut Harness<'static, RaylabApp>, name: &str) -> image::RgbaImage {
    let image = h.render().expect("the window renders");
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/tmp");
    std::fs::create_dir_all(&out).expect("target/tmp");
    image.save(out.join(name)).expect("saved");
    image
}

#[test]
fn the_window_with_debug_view_and_inspector_renders_with_wgpu() {
    let mut h = wgpu_harness(1400.0, 860.0, |render_state| {
        let mut app = seed_app(160, 120).with_gpu(Some(render_state));
        app.show_debug = true;
        app
    });
    settle(&mut h);
    click_the_sphere(&mut h);
    let image = keep_rendered(&mut h, "window_debug_view.png");
    let distinct: std::collections::HashSet<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 500, "only {} colours", distinct.len());
}

/// At the window sizes people use, with an object selected and a pixel
/// inspected: the image, the inspector (docked under it) and the object
/// editor are all in view and do not cover each other. Saved for a look
/// (target/tmp/layout_W×H.png).
#[test]
fn at_1280x800_and_1920x1080_the_image_the_docked_inspector_and_the_editor_are_all_in_view() {
    for (width, height) in [(1280.0, 800.0), (1920.0, 1080.0)] {
        let mut h = wgpu_harness(width, height, |render_state| {
            seed_app(320, 180).with_gpu(Some(render_state))
        });
        settle(&mut h);
        click_the_sphere(&mut h);
        step_shown(&mut h);
        let window = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(width, height));
        let inspector = h.get_by_label("Pixel inspector").rect();
        // The editor's "material" (the inspector names the hit's material too).
        let material = h
            .query_all_by_label("material")
            .map(|n| n.rect())
            .max_by(|a, b| a.left().total_cmp(&b.left()))
            .expect("the object editor's material row");
        let image_bottom = h.state().image.pixel_on_screen([0, 179]).expect("drawn").y;
        let image_top = h.state().image.pixel_on_screen([0, 0]).expect("drawn").y;
        assert!(
            inspector.top() > image_bottom,
            "{width}×{height}: the inspector ({inspector:?}) starts below the image (bottom row at {image_bottom})"
        );
        assert!(image_top > 0.0, "the image is in view");
        assert!(
            window.contains_rect(material) && window.contains_rect(inspector),
            "{width}×{height}: the editor ({material:?}) and the inspector are in the window"
        );
        assert!(
            !inspector.intersects(material),
            "the inspector does not cover the editor"
        );
        keep_rendered(&mut h, &format!("layout_{width}x{height}.png"));
    }
}

/// With the debug view on in a 1280×800 window, a 16:9 image keeps more than
/// half the centre's width (the debug view opens below it, where beside it
/// the image was a strip of a quarter of the window), and the debug view's
/// toolbar is in view above the inspector.
#[test]
fn at_1280x800_the_debug_view_opens_below_a_wide_image_and_leaves_it_large() {
    let (width, height) = (1280.0, 800.0);
    let mut h = wgpu_harness(width, height, |render_state| {
        let mut app = seed_app(640, 360).with_gpu(Some(render_state));
        app.show_debug = true;
        app
    });
    settle(&mut h);
    click_the_sphere(&mut h);
    step_shown(&mut h);
    let left = h.state().image.pixel_on_screen([0, 0]).expect("drawn");
    let right = h.state().image.pixel_on_screen([639, 359]).expect("drawn");
    let fan = h.get_by_label("ray fan").rect();
    let inspector = h.get_by_label("Pixel inspector").rect();
    let shown_width = right.x - left.x;
    assert!(
        shown_width > 0.25 * width,
        "the image is {shown_width} points wide in a {width}-point window"
    );
    assert!(
        fan.top() > right.y,
        "the debug view ({fan:?}) is below the image"
    );
    assert!(fan.bottom() < inspector.top(), "and above the inspector");
    keep_rendered(&mut h, "layout_1280x800_debug_view.png");
}

/// Steps the UI until the frame on screen is shown in `display`.
fn settle_display(h: &mut Harness<'static, RaylabApp>, display: renderer::display::Display) {
    let deadline = Instant::now() + Duration::from_secs(60);
    while Instant::now() < deadline {
        h.step();
        if h.state().image.shown_display() == Some(display) {
            return;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    panic!("the image never showed {display:?}");
}

/// Steps the UI until the frame on screen was shown through `view`.
fn settle_view(h: &mut Harness<'static, RaylabApp>, view: scene::View) {
    let deadline = Instant::now() + Duration::from_secs(60);
    while Instant::now() < deadline {
        h.step();
        if h.state()
            .session
            .frame
            .as_ref()
            .is_some_and(|f| f.view == view)
        {
            return;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    panic!("the image was never shown through {view:?}");
}

/// The exposure and the tone curve in the image view's toolbar show the
/// finished render again through the new view, without a new render: a
/// stop brighter is each pixel's radiance doubled before sRGB. Each is an
/// undo step.
#[test]
fn exposure_and_tone_curve_show_the_render_again_without_restarting() {
    use scene::{Tonemap, View};
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let generation = h.state().session.generation;
    let before = h.state().session.frame.clone().expect("a frame");

    h.get_by_label_contains("exposure").set_value_accesskit(1.0);
    h.step();
    let brighter = View {
        exposure: 1.0,
        tonemap: Tonemap::Clamp,
    };
    assert_eq!(h.state().doc.state.scene.view, brighter);
    settle_view(&mut h, brighter);
    let frame = h.state().session.frame.clone().expect("a frame");
    assert_eq!(h.state().session.generation, generation, "no new render");
    assert_eq!(frame.step, before.step, "the finished film, shown again");
    assert_eq!(frame.pixels, before.pixels, "the radiance is the film's");
    for (rgba, &c) in frame.srgba8.iter().zip(&before.pixels) {
        let [r, g, b] = renderer::display::srgb::linear_to_srgb8(2.0 * c);
        assert_eq!(*rgba, [r, g, b, 255], "{c}");
    }

    h.get_by_value("Clamp").click();
    step_shown(&mut h);
    h.get_by_label("Khronos PBR Neutral").click();
    h.step();
    let neutral = View {
        tonemap: Tonemap::Neutral,
        ..brighter
    };
    assert_eq!(h.state().doc.state.scene.view, neutral);
    settle_view(&mut h, neutral);
    assert_eq!(h.state().session.generation, generation, "no new render");

    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(h.state().doc.state.scene.view, brighter, "undo: the curve");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(
        h.state().doc.state.scene.view,
        View::default(),
        "undo: the exposure"
    );
    settle_view(&mut h, View::default());
    assert_eq!(
        h.state().session.generation,
        generation,
        "still no new render"
    );
}

#[test]
fn choosing_a_display_mode_shows_it_with_its_legend_and_keeps_the_render() {
    use renderer::display::Display;
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let generation = h.state().session.generation;
    let colour = pixels(&h);

    // The combo in the image view's toolbar.
    h.get_by_value("Colour").click();
    step_shown(&mut h);
    h.get_by_label("Cost (shape tests)").click();
    h.step();
    assert_eq!(h.state().image.display, Display::Cost);
    settle_display(&mut h, Display::Cost);
    step_shown(&mut h);
    h.get_by_label("shape tests / sample");
    let frame = h.state().session.frame.as_ref().expect("a frame");
    assert_eq!(
        frame.step,
        Step::Passes { spp: 2 },
        "the finished film, shown again"
    );
    assert_eq!(
        frame.pixels, colour,
        "the colour is kept beside the picture"
    );
    assert_eq!(h.state().session.generation, generation, "no new render");

    // M steps to the next mode, wrapping around to the colour.
    h.key_press(Key::M);
    h.step();
    assert_eq!(h.state().image.display, Display::Color);
    settle_display(&mut h, Display::Color);
    h.key_press(Key::M);
    h.step();
    assert_eq!(h.state().image.display, Display::Depth);
    settle_display(&mut h, Display::Depth);
    step_shown(&mut h);
    h.get_by_label_contains("α (scene units)");
}

#[test]
fn a_loaded_reference_plots_each_pass_error_and_it_falls_as_the_image_refines() {
    // The reference: the same scene at 64 spp with another seed.
    let app = seed_app(48, 32);
    let world = renderer::World::from_scene(&app.doc.state.scene).expect("the seed scene renders");
    let options = renderer::RenderOptions {
        seed: 99,
        ..app.doc.state.render.options()
    };
    let mut film = renderer::Film::new(48, 32);
    for _ in 0..64 {
        film.add_pass(&world, &options);
    }
    let values: Vec<f32> = film.linear().iter().flat_map(|c| c.to_array()).collect();
    let dir = std::env::temp_dir().join(format!("raylab-error-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let reference = dir.join("reference.exr");
    crate::io::output::write_exr(
        &reference,
        48,
        32,
        &["R", "G", "B"],
        &values,
        &crate::io::output::Provenance::default(),
    )
    .expect("the reference is written");

    let mut app = app;
    app.doc.state.render.target_spp = Some(16);
    app.load_reference(&reference);
    assert!(app.files.message.is_none(), "{:?}", app.files.message);
    let mut h = harness(app);
    settle(&mut h);
    h.step();
    let points = h.state().errors.points().to_vec();
    assert!(points.len() >= 2, "{points:?}");
    let (first, last) = (points[0], points[points.len() - 1]);
    assert_eq!(last.1, 16, "{points:?}");
    assert!(
        points.iter().all(|p| p.2.is_finite() && p.0 >= 0.0),
        "{points:?}"
    );
    // Independent samples: the error against a 64-spp reference is the
    // render's variance / n plus the reference's own / 64, so from the first
    // plotted pass (its spp depends on how passes were scheduled) to 16 spp it
    // falls by (1/16 + 1/64) / (1/n₁ + 1/64): 0.08 from 1 spp, 0.49 from 7.
    let expected = (1.0 / 16.0 + 1.0 / 64.0) / (1.0 / f64::from(first.1) + 1.0 / 64.0);
    let ratio = last.2 / first.2;
    assert!(
        ratio < 1.5 * expected && ratio > expected / 1.5,
        "the error went from {:.3e} at {} spp to {:.3e} at 16 spp: × {ratio:.3}, not about × {expected:.3}",
        first.2,
        first.1,
        last.2
    );
    assert!(
        h.query_all_by_label_contains("relative MSE")
            .next()
            .is_some(),
        "the panel shows the newest error"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_broken_reference_file_is_a_message_not_a_crash() {
    let mut app = seed_app(48, 32);
    app.load_reference(Path::new("/no/such/reference.exr"));
    let message = app.files.message.clone().expect("a message");
    assert!(message.contains("reference.exr"), "{message}");
}

#[test]
fn adaptive_sampling_from_the_panel_re_renders_and_the_samples_view_shows_where_they_went() {
    use renderer::display::Display;
    let mut app = seed_app(64, 48);
    app.doc.state.render.target_spp = Some(Adaptive::MIN_SAMPLES + 8);
    let mut h = harness(app);
    settle(&mut h);
    let generation = h.state().session.generation;

    h.get_by_label("stop converged pixels").click();
    h.step();
    assert_eq!(
        h.state().doc.state.render.adaptive,
        Some(Adaptive::default())
    );
    settle(&mut h);
    assert!(h.state().session.generation > generation, "a new render");

    h.get_by_value("Colour").click();
    step_shown(&mut h);
    // The combo's entry (the render panel has a row of the same name).
    h.query_all_by_label("Samples per pixel")
        .last()
        .expect("the display mode's entry")
        .click();
    h.step();
    settle_display(&mut h, Display::SamplesPerPixel);
    step_shown(&mut h);
    // The seed scene's flat, evenly lit areas stop at the minimum while
    // edges and shadows go on: the view is a heatmap with its average.
    h.get_by_label_contains("adaptive:");
}

#[test]
fn ticking_roughness_on_the_glass_cone_sets_it_and_re_renders() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    h.state_mut().selection = Selection::Object(0);
    step_shown(&mut h);
    let generation = h.state().session.generation;
    // The cone's glass is smooth: ticking the row sets its own value, 0.
    h.get_by_label("roughness").click();
    h.step();
    assert_eq!(
        h.state().doc.state.scene.objects[0].params.roughness,
        Some(0.0)
    );
    settle(&mut h);
    assert!(h.state().session.generation > generation, "a new render");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(
        h.state().doc.state.scene.objects[0].params.roughness,
        None,
        "undone"
    );
}

/// The reference scenes' environment map.
fn reference_sky_map() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/reference/sky_map.exr")
}

#[test]
fn a_sky_added_from_the_menu_is_listed_edited_given_a_map_and_undone() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let before = pixels(&h);
    h.get_by_label("Add").click();
    step_shown(&mut h);
    h.get_by_label("Sky").click();
    h.step();
    assert!(h.state().doc.state.scene.sky.is_some());
    assert_eq!(h.state().selection, Selection::Sky);
    settle(&mut h);
    // Listed with the lights, its editor open; the image changed.
    h.get_by_label("sky");
    h.get_by_label("Choose map…");
    assert_ne!(pixels(&h), before);
    // Its strength scales it: a brighter image.
    let dim = pixels(&h);
    h.get_by_role_and_label(egui::accesskit::Role::SpinButton, "×")
        .set_value_accesskit(2.0);
    h.step();
    assert_eq!(
        h.state().doc.state.scene.sky.as_ref().map(|s| s.strength),
        Some(2.0)
    );
    settle(&mut h);
    assert_ne!(pixels(&h), dim);
    // A map chosen (as the file dialog hands it over) replaces the colour,
    // named by its path; the rotation appears in the editor.
    h.state_mut().load_sky_map(&reference_sky_map());
    h.step();
    let sky = h.state().doc.state.scene.sky.clone().expect("a sky");
    assert_eq!(sky.color, Vec3::ONE);
    assert!(
        sky.map
            .as_ref()
            .is_some_and(|m| m.src.ends_with("sky_map.exr"))
    );
    settle(&mut h);
    h.get_by_label("sky: sky_map.exr");
    h.get_by_label("Rotate (°)");
    let lit = pixels(&h);
    // Undo takes the map back off; the sky stays.
    let ctx = h.ctx.clone();
    h.state_mut().run(&ctx, Command::Undo);
    settle(&mut h);
    assert!(
        h.state()
            .doc
            .state
            .scene
            .sky
            .as_ref()
            .is_some_and(|s| s.map.is_none())
    );
    assert_ne!(pixels(&h), lit);
    // Delete removes the selected sky.
    h.state_mut().selection = Selection::Sky;
    h.state_mut()
        .run(&ctx, Command::Edit(edits::Action::Delete));
    h.step();
    assert_eq!(h.state().doc.state.scene.sky, None);
}

#[test]
fn a_file_that_is_not_an_environment_map_is_a_message_and_changes_nothing() {
    let mut app = seed_app(48, 32);
    let before = app.doc.state.scene.clone();
    let png = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
    app.load_sky_map(&png);
    let message = app.files.message.clone().expect("a message");
    assert!(
        message.contains("seed.xml") && message.contains("environment map"),
        "{message}"
    );
    assert_eq!(app.doc.state.scene, before);
}

#[test]
fn the_sky_editor_renders_with_wgpu_beside_a_path_traced_map() {
    let mut h = wgpu_harness(1280.0, 800.0, |render_state| {
        let mut app = seed_app(160, 120).with_gpu(Some(render_state));
        app.load_sky_map(&reference_sky_map());
        app.doc.state.render.integrator = renderer::integrator::Integrator::Path;
        app
    });
    settle(&mut h);
    h.get_by_label("sky: sky_map.exr");
    h.get_by_label("Rotate (°)");
    let image = keep_rendered(&mut h, "window_sky.png");
    let distinct: std::collections::HashSet<[u8; 4]> = image.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 500, "only {} colours", distinct.len());
}
