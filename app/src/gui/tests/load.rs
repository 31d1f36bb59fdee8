//! Under load: a thousand random edits in quick succession while the tracer
//! refines the generated torus-knot scene. Nothing panics or hangs, the
//! image on screen at the end is of the last edit (its job's generation and
//! its pixels, against an independent render), memory stays flat, and
//! moving the mesh never rebuilds its BVH.

use super::own_process::{in_own_process, test_path};
use super::process_probe::Memory;
use super::settle;
use crate::gui::RaylabApp;
use crate::gui::commands::Command;
use crate::gui::doc::edits::{Action, Selection};
use crate::gui::doc::history::History;
use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::Vec3;
use rand_core::Rng;
use rand_pcg::Pcg32;
use renderer::progressive::Step;
use renderer::{Film, World};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Edits in one run.
const EDITS: usize = 1000;
/// The image's size: small enough that debug builds keep up, large enough
/// for every preview stride.
const SIZE: (u32, u32) = (320, 180);
/// How long a preview of an edit may take before the test calls it a hang.
const PREVIEW_LIMIT: Duration = Duration::from_secs(60);
/// RSS may grow over the second half of the run by at most the size of the
/// knot's mesh (positions, normals and triangles: 24 MiB for a million
/// triangles): one leaked copy of the mesh, or of its larger BVH, fails.
/// What should grow is small: the history keeps at most 500 snapshots of a
/// few kilobytes, a frame is 320 × 180 pixels (about 1 MiB), old worlds
/// share the mesh and its BVH, and the scene has at most [`MAX_SPHERES`]
/// spheres.
fn growth_limit_mib(triangles: usize) -> f64 {
    let mesh = scene::generate::torus_knot(2, 3, triangles);
    let bytes = std::mem::size_of_val(mesh.positions.as_slice())
        + std::mem::size_of_val(mesh.normals.as_slice())
        + std::mem::size_of_val(mesh.triangles.as_slice());
    bytes as f64 / (1024.0 * 1024.0)
}

/// The knot scene's camera, which camera edits vary.
const EYE: Vec3 = Vec3::new(0.0, 5.65, 8.5);
const TOWARD: Vec3 = Vec3::new(0.0, -5.1, -8.5);

/// The kinds of random edit.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Edit {
    Eye,
    Toward,
    Theta,
    D,
    Orbit,
    Colour,
    Material,
    Move,
    AddSphere,
    RemoveSphere,
    Undo,
    Redo,
}

const KINDS: [Edit; 12] = [
    Edit::Eye,
    Edit::Toward,
    Edit::Theta,
    Edit::D,
    Edit::Orbit,
    Edit::Colour,
    Edit::Material,
    Edit::Move,
    Edit::AddSphere,
    Edit::RemoveSphere,
    Edit::Undo,
    Edit::Redo,
];

/// Uniform in [lo, hi).
fn uniform(rng: &mut Pcg32, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32
}

/// A vector with each coordinate uniform in [−r, r).
fn jitter(rng: &mut Pcg32, r: f32) -> Vec3 {
    Vec3::new(
        uniform(rng, -r, r),
        uniform(rng, -r, r),
        uniform(rng, -r, r),
    )
}

/// The knot scene at [`SIZE`], refining to `target` spp (`None`: without
/// end), with nothing to undo.
pub(super) fn knot_app(triangles: usize, target: Option<u32>) -> RaylabApp {
    let mut scene = scene::generate::knot_scene(triangles);
    (scene.camera.width, scene.camera.height) = SIZE;
    let mut app = RaylabApp::new(scene, None);
    app.doc.state.render.target_spp = target;
    app.doc.history = History::new(&app.doc.state);
    app
}

/// A test renderer that applies texture updates by forgetting them. (The
/// harness's default renderer keeps every update until a first render, so a
/// long run that never renders would hold every frame ever shown.)
pub(super) struct DiscardTextures;

impl egui_kittest::TestRenderer for DiscardTextures {
    fn handle_delta(&mut self, delta: &mut egui::TexturesDelta) {
        delta.clear();
    }

    fn render(
        &mut self,
        _ctx: &egui::Context,
        _output: &egui::FullOutput,
    ) -> Result<image::RgbaImage, String> {
        Err("this harness does not render".into())
    }
}

/// A harness like [`super::harness`] whose renderer discards texture
/// updates ([`DiscardTextures`]), for runs of many frames.
pub(super) fn harness_discarding_textures(app: RaylabApp) -> Harness<'static, RaylabApp> {
    Harness::builder()
        .with_size(egui::Vec2::new(1200.0, 800.0))
        .renderer(DiscardTextures)
        .build_ui_state(|ui, app: &mut RaylabApp| app.show(ui), app)
}

/// True when the frame on screen belongs to the newest submitted job.
pub(super) fn shows_newest(h: &Harness<'static, RaylabApp>) -> bool {
    h.state()
        .session
        .frame
        .as_ref()
        .is_some_and(|f| f.generation == h.state().session.generation)
}

/// Steps until the newest job's first frame is on screen; panics after
/// [`PREVIEW_LIMIT`]. Returns how long it took.
pub(super) fn wait_for_newest(h: &mut Harness<'static, RaylabApp>) -> Duration {
    let started = Instant::now();
    while !shows_newest(h) {
        assert!(
            started.elapsed() < PREVIEW_LIMIT,
            "no frame of generation {} within {PREVIEW_LIMIT:?}: the renderer hangs",
            h.state().session.generation
        );
        std::thread::sleep(Duration::from_millis(1));
        h.step();
    }
    started.elapsed()
}

/// Checks the frame on screen against an independent render of the
/// document's scene at the same step: the same world built afresh from the
/// scene, the same options, the same preview stride or number of passes.
pub(super) fn assert_shows_the_document(h: &Harness<'static, RaylabApp>) {
    let app = h.state();
    let frame = app.session.frame.as_ref().expect("a frame");
    assert_eq!(frame.generation, app.session.generation, "a stale frame");
    let (scene, options) = app.session.submitted.as_ref().expect("submitted");
    assert_eq!(
        *scene, app.doc.state.scene,
        "the job is not of the document"
    );
    assert_eq!(*options, app.doc.state.render.options());
    let world = World::from_scene(&app.doc.state.scene).expect("the scene renders");
    let expected = match frame.step {
        Step::Preview { stride } => renderer::film::preview::preview(&world, options, stride),
        Step::Passes { spp } => Film::render(&world, options, spp).linear(),
    };
    let camera = &app.doc.state.scene.camera;
    assert_eq!((frame.width, frame.height), (camera.width, camera.height));
    let differing = frame
        .linear_image()
        .iter()
        .zip(&expected)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{differing} pixels of the {:?} on screen differ from an independent render",
        frame.step
    );
}

/// At most this many spheres are added, so that the scene's size does not
/// drift upwards over the run (which would make memory grow for good reason).
const MAX_SPHERES: usize = 8;

/// The indices of the scene's spheres.
fn spheres(h: &Harness<'static, RaylabApp>) -> Vec<usize> {
    (h.state().doc.state.scene.objects.iter().enumerate())
        .filter(|(_, o)| matches!(o.shape, scene::Shape::Sphere { .. }))
        .map(|(k, _)| k)
        .collect()
}

/// Makes one random edit of `kind`; false when it had nothing to act on.
fn edit(h: &mut Harness<'static, RaylabApp>, rng: &mut Pcg32, kind: Edit) -> bool {
    let ctx = h.ctx.clone();
    match kind {
        Edit::Eye => {
            let eye = EYE + jitter(rng, 1.0);
            h.state_mut().doc.state.scene.camera.eye = Some(eye);
        }
        Edit::Toward => {
            let toward = TOWARD + jitter(rng, 1.0);
            h.state_mut().doc.state.scene.camera.toward = Some(toward);
        }
        Edit::Theta => h
            .get_by_role_and_label(Role::Slider, "θ")
            .set_value_accesskit(f64::from(uniform(rng, 12.0, 40.0))),
        Edit::D => h
            .get_by_role_and_label(Role::SpinButton, "d")
            .set_value_accesskit(f64::from(uniform(rng, 0.5, 3.0))),
        Edit::Orbit => {
            // A drag on the image: the mouse gesture, over two frames.
            let [w, hh] = [SIZE.0 / 2, SIZE.1 / 2];
            let Some(start) = h.state().image.pixel_on_screen([w, hh]) else {
                return false;
            };
            let by = egui::vec2(uniform(rng, -40.0, 40.0), uniform(rng, -20.0, 20.0));
            h.hover_at(start);
            h.drag_at(start);
            h.step();
            h.hover_at(start + by);
            h.step();
            h.drop_at(start + by);
        }
        Edit::Colour => {
            let objects = &mut h.state_mut().doc.state.scene.objects;
            let k = rng.next_u32() as usize % objects.len();
            objects[k].params.color = Some(Vec3::new(
                uniform(rng, 0.0, 1.0),
                uniform(rng, 0.0, 1.0),
                uniform(rng, 0.0, 1.0),
            ));
        }
        Edit::Material => {
            let objects = &mut h.state_mut().doc.state.scene.objects;
            let k = rng.next_u32() as usize % objects.len();
            let all = scene::BaseMaterial::ALL;
            let material = all[rng.next_u32() as usize % all.len()];
            objects[k].material = Some(material.name().to_owned());
        }
        Edit::Move => {
            let translate_to = Vec3::new(0.0, 1.15, 0.0) + jitter(rng, 1.5);
            let turn_to = Vec3::new(0.0, uniform(rng, -180.0, 180.0), 0.0);
            let knot = &mut h.state_mut().doc.state.scene.objects[0];
            let scene::Shape::Mesh {
                translate, rotate, ..
            } = &mut knot.shape
            else {
                panic!("object 0 is the knot");
            };
            *translate = Some(translate_to);
            *rotate = turn_to;
        }
        Edit::AddSphere if spheres(h).len() >= MAX_SPHERES => {
            return edit(h, rng, Edit::RemoveSphere);
        }
        Edit::AddSphere => {
            let by_menu = rng.next_u32().is_multiple_of(2);
            if by_menu {
                h.get_by_label("Add").click();
                h.step();
                h.step();
            }
            if let Some(item) = h.query_by_label("sphere").filter(|_| by_menu) {
                item.click();
            } else {
                // (The click on Add closes the menu when a previous frame left it open.)
                h.key_press(Key::Escape);
                h.state_mut()
                    .run(&ctx, Command::Edit(Action::AddObject("sphere")));
            }
        }
        Edit::RemoveSphere => {
            let spheres = spheres(h);
            if spheres.is_empty() {
                return false;
            }
            let k = spheres[rng.next_u32() as usize % spheres.len()];
            h.state_mut().selection = Selection::Object(k);
            h.state_mut().run(&ctx, Command::Edit(Action::Delete));
        }
        Edit::Undo => h.key_press_modifiers(Modifiers::COMMAND, Key::Z),
        Edit::Redo => h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z),
    }
    true
}

/// The figures of one run.
struct Figures {
    triangles: usize,
    start: Memory,
    half: Memory,
    end: Memory,
    last_edit_to_preview: Duration,
    edits_time: Duration,
    total: Duration,
}

/// Runs [`EDITS`] seeded random edits on the knot of `triangles` and checks
/// the properties; returns the figures.
fn random_edits_while_tracing(triangles: usize, seed: u64) -> Figures {
    let started = Instant::now();
    let mut rng = Pcg32::new(seed, 0xda3e_39cb_94b9_5bdb);
    let mut h = harness_discarding_textures(knot_app(triangles, Some(4)));
    wait_for_newest(&mut h);
    let knot_bvh = |h: &Harness<'static, RaylabApp>| {
        let world = &h.state().session.prepared.as_ref().expect("prepared").world;
        Arc::clone(world.meshes[0].bvh())
    };
    let bvh = knot_bvh(&h);
    let start = Memory::now();
    eprintln!(
        "{triangles} triangles ready after {:.1} s; RSS {:.0} MiB",
        started.elapsed().as_secs_f64(),
        start.rss_mib()
    );
    let mut half = start;
    let mut undone = 0;
    let mut kinds = [0usize; KINDS.len()];
    // Frames shown: previews, then full passes.
    let (mut shown, mut last_seen) = ([0usize; 2], None);
    let mut checked = 0;
    let edits_started = Instant::now();
    let mut last_edit = edits_started;
    for n in 1..=EDITS {
        let k = rng.next_u32() as usize % KINDS.len();
        let before = h.state().doc.state.clone();
        last_edit = Instant::now();
        if edit(&mut h, &mut rng, KINDS[k]) {
            kinds[k] += 1;
        }
        for _ in 0..=rng.next_u32() % 3 {
            h.step();
            let app = h.state();
            if let Some(frame) = &app.session.frame {
                assert!(frame.generation <= app.session.generation);
                let seen = Some((frame.generation, frame.step));
                if seen != last_seen {
                    last_seen = seen;
                    shown[usize::from(matches!(frame.step, Step::Passes { .. }))] += 1;
                }
            }
        }
        if rng.next_u32().is_multiple_of(8) {
            // Now and then the edit is left to show, and what shows is checked.
            wait_for_newest(&mut h);
            assert_shows_the_document(&h);
            checked += 1;
        }
        if KINDS[k] == Edit::Undo && h.state().doc.state != before {
            undone += 1;
        }
        assert!(
            Arc::ptr_eq(&knot_bvh(&h), &bvh),
            "edit {n} ({:?}) rebuilt the knot's BVH",
            KINDS[k]
        );
        if n % 100 == 0 {
            let m = Memory::now();
            eprintln!(
                "after {n} edits: RSS {:.0} MiB, peak {:.0} MiB, {} objects, generation {}",
                m.rss_mib(),
                m.peak_mib(),
                h.state().doc.state.scene.objects.len(),
                h.state().session.generation
            );
            if n == EDITS / 2 {
                half = m;
            }
        }
    }
    let edits_time = edits_started.elapsed();
    wait_for_newest(&mut h);
    let last_edit_to_preview = last_edit.elapsed();
    assert_shows_the_document(&h);
    settle(&mut h);
    assert_shows_the_document(&h);
    let end = Memory::now();
    eprintln!(
        "edit counts {:?}; undos that changed something: {undone}; frames shown during the \
         edits: {} previews, {} full passes; {checked} frames checked against independent renders",
        KINDS.iter().zip(kinds).collect::<Vec<_>>(),
        shown[0],
        shown[1]
    );
    assert!(undone > 0, "no undo ever undid anything");
    Figures {
        triangles,
        start,
        half,
        end,
        last_edit_to_preview,
        edits_time,
        total: started.elapsed(),
    }
}

impl Figures {
    /// Prints the figures and checks that memory stayed flat.
    fn report_and_check(&self) {
        let growth = self.end.rss_mib() - self.half.rss_mib();
        eprintln!(
            "{} triangles, {EDITS} edits: RSS {:.0} MiB before, {:.0} after {}, {:.0} at the end \
             (growth over the second half {growth:+.1} MiB), peak {:.0} MiB; \
             last edit to its first frame {:.0} ms; edits {:.1} s ({:.0} edits/s), total {:.1} s",
            self.triangles,
            self.start.rss_mib(),
            self.half.rss_mib(),
            EDITS / 2,
            self.end.rss_mib(),
            self.end.peak_mib(),
            self.last_edit_to_preview.as_secs_f64() * 1e3,
            self.edits_time.as_secs_f64(),
            EDITS as f64 / self.edits_time.as_secs_f64(),
            self.total.as_secs_f64(),
        );
        let limit = growth_limit_mib(self.triangles);
        assert!(
            growth < limit,
            "RSS grew by {growth:.1} MiB (limit {limit:.1}) over the last {} edits",
            EDITS / 2
        );
    }
}

/// The knot's triangles: the benchmark's million, or `RAYLAB_STRESS_TRIANGLES`.
fn scene_spec_knot() -> usize {
    std::env::var("RAYLAB_STRESS_TRIANGLES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(crate::bench::scene_spec::KNOT_TRIANGLES)
}

#[test]
fn a_thousand_random_edits_while_tracing_end_on_the_last_edit() {
    let name = test_path(
        module_path!(),
        "a_thousand_random_edits_while_tracing_end_on_the_last_edit",
    );
    if in_own_process(&name, Duration::from_secs(600)) {
        random_edits_while_tracing(scene_spec_knot(), 0x5eed).report_and_check();
    }
}
