//! The window's root: [`RaylabApp`] owns one part per job (the document,
//! the render session, the image, the inspector, the file workflow, crash
//! recovery, the debug view), lays out each frame in [`RaylabApp::show`]
//! and carries out every [`Command`] in one place, [`RaylabApp::run`].

use super::commands::{self, Command};
use super::crash_recovery::CrashRecovery;
use super::debug_view::{DebugRenderer, DebugView, Inputs, Split, Splitter};
use super::doc::change;
use super::doc::document::{Document, RenderSettings};
use super::doc::edits::{self, Action, Selection};
use super::files::dialogs::DialogKind;
use super::files::{FileWorkflow, Files, Outcome, Pending};
use super::inspector::Inspector;
use super::panels::error_plot::ErrorPlot;
use super::panels::status_bar::{self, FrameTimes, Shown};
use super::panels::{camera_panel, help, render_panel, scene_panel};
use super::session::SessionSync;
use super::settings::Settings;
use super::viewport::camera_drag::CameraDrag;
use super::viewport::image_view::{Gestures, ImageView};
use super::viewport::{picking, screenshot};
use scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The application state: the document, its render session and what is shown.
pub struct RaylabApp {
    /// The open scene, its file and undo history.
    pub(super) doc: Document,
    /// The selected object or light.
    pub(super) selection: Selection,
    /// The render session: what it was given, the prepared world, the newest frame.
    pub(super) session: SessionSync,
    /// The image view (one texture, updated in place).
    pub(super) image: ImageView,
    /// The camera drag in progress on the image.
    pub(super) camera_drag: CameraDrag,
    /// The inspected pixel, its ray tree and the inspector panel.
    pub(super) inspector: Inspector,
    /// The reference image and the live error of each pass against it.
    pub(super) errors: ErrorPlot,
    /// Dialogs, "save changes?", the path prompt and messages.
    pub(super) files: FileWorkflow,
    /// Remembered between runs.
    settings: Settings,
    /// Autosave, and the offer of what crashed runs left.
    recovery: CrashRecovery,
    /// The 3D debug view is shown beside or below the image.
    pub(super) show_debug: bool,
    /// The 3D debug view's state.
    pub(super) debug: DebugView,
    /// The image's share of the centre while the debug view is shown.
    debug_split: Splitter,
    /// The help overlay is shown.
    show_help: bool,
    /// The title last sent to the window.
    title: String,
    /// The UI thread's frame times.
    frame_times: FrameTimes,
    /// The wgpu device and egui's renderer, when the window draws with wgpu.
    gpu: Option<eframe::egui_wgpu::RenderState>,
    /// The image gesture that last moved the camera ("orbit", "pan",
    /// "dolly"), to name its undo step.
    camera_move: Option<&'static str>,
    /// When the wheel last dollied the camera: notches within
    /// [`WHEEL_GESTURE`] of each other are one undo step.
    last_wheel: Option<Instant>,
}

/// Wheel notches closer together than this are one gesture (one undo step);
/// egui also spreads each notch over several frames.
const WHEEL_GESTURE: std::time::Duration = std::time::Duration::from_millis(500);

impl RaylabApp {
    /// An app showing `scene` (loaded from `path`).
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        Self {
            doc: Document::new(scene, path, RenderSettings::default()),
            selection: Selection::None,
            session: SessionSync::default(),
            image: ImageView::default(),
            camera_drag: CameraDrag::default(),
            inspector: Inspector::default(),
            errors: ErrorPlot::default(),
            files: FileWorkflow::default(),
            settings: Settings::default(),
            recovery: CrashRecovery::default(),
            show_debug: false,
            camera_move: None,
            last_wheel: None,
            debug: DebugView::default(),
            debug_split: Splitter::default(),
            show_help: false,
            title: String::new(),
            frame_times: FrameTimes::default(),
            gpu: None,
        }
    }

    /// Autosaves unsaved changes to a recovery file in `dir` and offers to
    /// restore what crashed runs left there (see [`CrashRecovery`]).
    pub fn with_recovery(mut self, dir: &Path) -> Self {
        self.recovery = CrashRecovery::in_dir(dir);
        self
    }

    /// Lets the app draw with wgpu itself (the debug view); without it the
    /// debug view says it cannot draw.
    pub fn with_gpu(mut self, gpu: Option<eframe::egui_wgpu::RenderState>) -> Self {
        self.gpu = gpu;
        self
    }

    /// This app's untitled scene named by the model file it was read from
    /// (a .gltf or .glb opened directly).
    pub fn with_origin(mut self, origin: Option<PathBuf>) -> Self {
        self.doc.origin = origin;
        self
    }

    /// This app with `message` shown in front until it is dismissed (a
    /// scene that could not be opened at start).
    pub fn with_message(mut self, message: String) -> Self {
        self.files.message = Some(message);
        self
    }

    /// An app restoring its settings from eframe's storage.
    pub fn with_storage(
        scene: Scene,
        path: Option<PathBuf>,
        storage: Option<&dyn eframe::Storage>,
    ) -> Self {
        let mut app = Self::new(scene, path.clone());
        if let Some(settings) = storage.and_then(|s| eframe::get_value(s, Settings::KEY)) {
            app.settings = settings;
        }
        if let Some(path) = path {
            app.settings.remember(&path);
        }
        app
    }

    /// Records the edits since the last undo step as one step, named by
    /// what changed, unless `gesture` (one still under way).
    fn record_step(&mut self, gesture: bool) {
        let camera_move = self.camera_move;
        if self
            .doc
            .history
            .settle_named(&self.doc.state, gesture, |before, after| {
                change::describe(before, after, camera_move)
            })
        {
            self.camera_move = None;
        }
    }

    /// Names the object under the pointer (in the object-id mode) and turns
    /// this frame's mouse gestures on the image into a pick (which also
    /// inspects the pixel), a hover inspection or a camera move (remembered
    /// by kind for its undo step's name; a wheel dolly also starts the
    /// wheel's gesture).
    fn on_image(&mut self, gestures: &Gestures, dragging: bool) {
        let method = self.doc.state.render.method;
        let prepared = self.session.prepared.as_ref();
        self.image.hover_text =
            picking::hover_text(&self.image, prepared, method, gestures.hovered_pixel);
        if let Some(pixel) = gestures.clicked_pixel {
            self.selection = match prepared.and_then(|p| picking::object_at(p, method, pixel)) {
                Some(object) => Selection::Object(object),
                None => Selection::None,
            };
            self.inspector.inspect(pixel, false, prepared, method);
        }
        if gestures.inspect_hover
            && let Some(pixel) = gestures.hovered_pixel
        {
            self.inspector.inspect(pixel, true, prepared, method);
        }
        let moved = [
            (gestures.orbit != egui::Vec2::ZERO, "orbit"),
            (gestures.pan != egui::Vec2::ZERO, "pan"),
            (gestures.dolly != 0.0, "dolly"),
        ];
        if let Some(&(_, name)) = moved.iter().find(|(moved, _)| *moved) {
            self.camera_move = Some(name);
            if name == "dolly" && !dragging {
                self.last_wheel = Some(Instant::now());
            }
        }
        let camera = &mut self.doc.state.scene.camera;
        self.camera_drag
            .apply(gestures, dragging, prepared, method, camera);
    }

    /// The 3D debug view of the prepared scene.
    fn debug_view(&mut self, ui: &mut egui::Ui) {
        let Some(prepared) = &self.session.prepared else {
            ui.label("Nothing to show: the scene cannot be rendered.");
            return;
        };
        if let Some(gpu) = &self.gpu {
            DebugRenderer::install(gpu);
        }
        let selected_object = match self.selection {
            Selection::Object(k) => Some(k),
            _ => None,
        };
        let inputs = Inputs {
            world: &prepared.world,
            objects: &prepared.resolved.objects,
            selected_object,
            pixel: self.inspector.pixel(),
            rays: self.inspector.drawn_rays(),
            options: self.debug.options,
        };
        self.debug.show(ui, &inputs, self.gpu.is_some());
    }

    /// Carries out `command`.
    pub(super) fn run(&mut self, ctx: &egui::Context, command: Command) {
        match command {
            Command::New => self.with_files(|files| files.guarded(ctx, Pending::New)),
            Command::Open => self.with_files(|files| files.guarded(ctx, Pending::OpenDialog)),
            Command::OpenPath(path) => {
                self.with_files(|files| files.guarded(ctx, Pending::Open(path)));
            }
            Command::Save => self.files().save(ctx),
            Command::SaveAs => self.files().start_dialog(ctx, DialogKind::SaveScene),
            Command::SaveImage => self.files().start_dialog(ctx, DialogKind::SaveImage),
            Command::LoadReference => self.files().start_dialog(ctx, DialogKind::Reference),
            Command::CopyImage => {
                if let Some(frame) = &self.session.frame {
                    ctx.copy_image(screenshot::color_image(frame));
                }
            }
            Command::Quit => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
            Command::Undo => {
                self.camera_drag.end();
                self.record_step(false);
                self.doc.history.undo(&mut self.doc.state);
            }
            Command::Redo => {
                self.camera_drag.end();
                self.doc.history.redo(&mut self.doc.state);
            }
            Command::Edit(Action::ChooseSkyMap) => {
                self.files().start_dialog(ctx, DialogKind::SkyMap);
            }
            Command::Edit(action) => {
                let resolved = self.session.prepared.as_ref().map(|p| &p.resolved);
                self.selection =
                    edits::apply(action, &mut self.doc.state.scene, resolved, self.selection);
            }
            Command::Display(display) => self.image.display = display,
            Command::NextDisplay => self.image.display = self.image.display.next(),
            Command::Fit => self.image.fit(),
            Command::ActualSize => self.image.actual_size(),
            Command::TogglePause => self.session.toggle_pause(),
            Command::ToggleHelp => self.show_help = !self.show_help,
            Command::ToggleDebugView => self.show_debug = !self.show_debug,
        }
        self.selection = self.selection.valid_in(&self.doc.state.scene);
    }

    /// Puts `doc` in place of the current document (new, opened or
    /// restored), with nothing selected or being dragged, and renders it
    /// even when it compares equal to the scene on screen: meshes compare by
    /// file name, and the file may have changed since it was last read.
    fn replace_document(&mut self, doc: Document) {
        self.doc = doc;
        self.session.forget_submitted();
        self.selection = Selection::None;
        self.camera_drag.end();
    }

    /// The file workflow at work on this app's document, settings and image.
    pub(super) fn files(&mut self) -> Files<'_> {
        Files {
            flow: &mut self.files,
            doc: &mut self.doc,
            settings: &mut self.settings,
            frame: self.session.frame.as_ref(),
            camera: self.session.prepared.as_ref().map(|p| &p.world.camera),
        }
    }

    /// Runs `step` of the file workflow, then does what it leaves for the app.
    fn with_files(&mut self, step: impl FnOnce(&mut Files<'_>) -> Outcome) {
        match step(&mut self.files()) {
            Outcome::Done => {}
            Outcome::Replace(doc) => self.replace_document(*doc),
            Outcome::LoadReference(path) => self.load_reference(&path),
            Outcome::LoadSkyMap(path) => self.load_sky_map(&path),
        }
    }

    /// Makes the map in `path` the sky's (a sky added if there is none,
    /// keeping its tint and rotation), named relative to the scene's folder
    /// when it lies inside it; a bad file is a message and changes nothing.
    pub fn load_sky_map(&mut self, path: &Path) {
        match scene::load_sky_map(path) {
            Ok(image) => {
                let src = self
                    .doc
                    .path
                    .as_deref()
                    .and_then(Path::parent)
                    .and_then(|folder| path.strip_prefix(folder).ok())
                    .unwrap_or(path)
                    .to_string_lossy()
                    .into_owned();
                let map = scene::SkyMap {
                    src,
                    image: std::sync::Arc::new(image),
                };
                let scene = &mut self.doc.state.scene;
                match &mut scene.sky {
                    Some(sky) => {
                        // A constant colour's radiance is not a sensible tint.
                        if sky.map.is_none() {
                            sky.color = glam::Vec3::ONE;
                        }
                        sky.map = Some(map);
                    }
                    None => {
                        scene.sky = Some(scene::Sky {
                            color: glam::Vec3::ONE,
                            map: Some(map),
                            rotate: glam::Vec3::ZERO,
                            strength: 1.0,
                        });
                    }
                }
                self.selection = Selection::Sky;
            }
            Err(error) => {
                self.files.message = Some(format!(
                    "Cannot use {} as the environment map: {error}",
                    path.display()
                ));
            }
        }
    }

    /// Acts on a file chosen in a dialog or typed into the path prompt.
    pub(super) fn chosen(&mut self, ctx: &egui::Context, kind: DialogKind, path: PathBuf) {
        self.with_files(|files| files.chosen(ctx, kind, path));
    }

    /// Loads a reference image for the live error plot; a bad file is a message.
    pub fn load_reference(&mut self, path: &Path) {
        match renderer::diagnostics::reference_image::read_exr_rgb(path) {
            Ok(image) => self.set_reference(path.to_path_buf(), image),
            Err(error) => self.files.message = Some(format!("Cannot load the reference: {error}")),
        }
    }

    /// Plots the live error against `image`, read from `path`.
    pub fn set_reference(
        &mut self,
        path: PathBuf,
        image: renderer::diagnostics::reference_image::LinearImage,
    ) {
        self.errors.set_reference(path, image);
    }

    /// Sends the window title when it changed.
    fn update_title(&mut self, ctx: &egui::Context) {
        let title = self.doc.title();
        if title != self.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
    }

    /// Autosaves the scene when due at `now`; a failed write is a message.
    pub(super) fn autosave_at(&mut self, ctx: &egui::Context, now: Instant) {
        if let Some(error) = self.recovery.autosave_at(ctx, now, &self.doc) {
            self.files.message.get_or_insert(error);
        }
    }

    /// The offer to restore a crashed run's work, if one waits.
    fn recovery_modal(&mut self, ctx: &egui::Context) {
        match self.recovery.offer(ctx, self.doc.state.render) {
            Some(Ok(doc)) => self.replace_document(doc),
            Some(Err(message)) => self.files.message = Some(message),
            None => {}
        }
    }

    /// Draws the whole window into `ui`.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let started = Instant::now();
        let ctx = ui.ctx().clone();
        if let Some(frame) = self.session.receive() {
            self.image.show_frame(&ctx, frame);
            self.errors.add(frame);
        }
        if let Some((kind, path)) = self.files().poll_dialogs() {
            self.chosen(&ctx, kind, path);
        }
        let mut commands = commands::from_keyboard(&ctx);
        commands.extend(commands::from_dropped_files(&ctx));
        self.files.hold_close(&ctx, &self.doc);

        egui::Panel::top("menu").show(ui, |ui| {
            let state = commands::MenuState {
                recent: &self.settings.recent,
                can_undo: self.doc.history.can_undo(&self.doc.state),
                can_redo: self.doc.history.can_redo(&self.doc.state),
                undo_name: self.doc.history.undo_name(&self.doc.state),
                redo_name: self.doc.history.redo_name(&self.doc.state),
                has_image: self.session.frame.is_some(),
                has_selection: self.selection != Selection::None,
                display: self.image.display,
            };
            commands.extend(commands::menu_bar(ui, &state));
        });
        egui::Panel::bottom("status").show(ui, |ui| {
            let shown = self.session.frame.as_ref().map(Shown::of);
            let note = self.files.current_note();
            if let Some((_, left)) = note {
                ui.ctx().request_repaint_after(left);
            }
            let pause = status_bar::show(
                ui,
                shown.as_ref(),
                note.map(|(text, _)| text),
                self.session.error.as_deref(),
                self.doc.state.render.target_spp,
                self.session.paused,
                &self.frame_times,
            );
            commands.extend(pause.then_some(Command::TogglePause));
        });
        egui::Panel::left("camera")
            .resizable(true)
            .default_size(330.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().id_salt("left").show(ui, |ui| {
                    let camera = self.session.prepared.as_ref().map(|p| p.world.camera);
                    camera_panel::show(ui, &mut self.doc.state.scene, camera.as_ref());
                    ui.separator();
                    render_panel::show(ui, &mut self.doc.state.render);
                    ui.separator();
                    let load_reference = self.errors.show(ui);
                    commands.extend(load_reference.then_some(Command::LoadReference));
                });
            });
        egui::Panel::right("scene")
            .resizable(true)
            .default_size(360.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .id_salt("right")
                    .show(ui, |ui| {
                        let resolved = self.session.prepared.as_ref().map(|p| &p.resolved);
                        let (_, action) = scene_panel::show(
                            ui,
                            &mut self.doc.state.scene,
                            resolved,
                            &mut self.selection,
                        );
                        commands.extend(action.map(Command::Edit));
                    });
            });
        self.inspector.panel(ui, &self.session);
        egui::CentralPanel::default().show(ui, |ui| {
            // Carried out at once, so that the view opens in the frame of the click.
            if let Some(command) = commands::toolbar(ui, self.show_debug) {
                self.run(&ctx, command);
            }
            // With the debug view on, beside the image or below it, whichever
            // leaves the image larger; half each until the line is dragged.
            let image_rect = self.show_debug.then(|| {
                let camera = &self.doc.state.scene.camera;
                let split = Split::for_centre(ui.available_size(), camera.width, camera.height);
                let (image, debug) = self.debug_split.layout(ui, split);
                ui.scope_builder(egui::UiBuilder::new().max_rect(debug), |ui| {
                    self.debug_view(ui)
                });
                image
            });
            let mut image_part = |ui: &mut egui::Ui| {
                let gestures = self.image.ui(ui, &mut self.doc.state.scene.view);
                self.inspector.mark(ui, &self.image);
                gestures
            };
            let gestures = match image_rect {
                Some(rect) => {
                    ui.scope_builder(egui::UiBuilder::new().max_rect(rect), image_part)
                        .inner
                }
                None => image_part(ui),
            };
            let dragging = ctx.input(|i| i.pointer.any_down());
            self.on_image(&gestures, dragging);
        });
        self.with_files(|files| files.guard_modal(&ctx));
        self.recovery_modal(&ctx);
        self.files.message_modal(&ctx);
        if let Some((kind, path)) = self.files.path_prompt_modal(&ctx) {
            self.chosen(&ctx, kind, path);
        }
        help::window(&ctx, &mut self.show_help);

        for command in commands {
            self.run(&ctx, command);
        }
        // A drag, a text field being typed in or a turn of the wheel is one
        // undo step, recorded when it ends.
        let wheeling = self.last_wheel.is_some_and(|t| t.elapsed() < WHEEL_GESTURE);
        if wheeling {
            ctx.request_repaint_after(WHEEL_GESTURE);
        }
        let gesture = ctx.input(|i| i.pointer.any_down()) || ctx.text_edit_focused() || wheeling;
        self.record_step(gesture);
        self.update_title(&ctx);
        self.autosave_at(&ctx, Instant::now());
        let display = self.image.display;
        if self
            .session
            .submit_if_changed(&ctx, &self.doc.state, self.doc.path.as_deref(), display)
        {
            // An unpinned inspection follows the camera of a newly prepared world.
            self.inspector.follow(self.session.prepared.as_ref());
        }
        let all_samples = self.show_debug && self.debug.options.all_samples;
        let options = self.doc.state.render.options();
        self.inspector.refresh(&self.session, options, all_samples);
        self.frame_times.record(started.elapsed());
    }
}

impl eframe::App for RaylabApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, Settings::KEY, &self.settings);
    }

    /// A clean exit (nothing unsaved, or the user chose not to save) leaves
    /// nothing to recover; an exit forced past unsaved changes keeps the file.
    fn on_exit(&mut self) {
        let clean = self.files.allow_close || !self.doc.is_modified();
        self.recovery.on_exit(clean);
    }
}
