//! The debug view: the lecture's board drawing in 3D, live. A free observer
//! camera (its own orbit, pan and zoom) looks at the scene, the ray-tracing
//! camera at P0 with t, u and r, the view volume, the view window at distance
//! d with its pixel grid and C00, and the selected pixel's P_ij and rays.
//! Drawn with wgpu inside egui through a paint callback; labels are egui text.

pub mod drawing;
mod gpu;
pub mod observer;
pub mod rays;
mod split;
mod tessellate;

pub use drawing::{DrawOptions, Fan, Inputs};
pub use gpu::DebugRenderer;
pub use rays::DrawnRay;
pub use split::{Split, Splitter};

use drawing::{Drawing, palette};
use glam::Vec3;
use gpu::{DebugCallback, GpuScene};
use observer::Observer;
use std::sync::Arc;

/// Orbit speed of the observer, radians per point dragged.
const ORBIT_SPEED: f32 = 0.01;
/// Zoom speed: the distance shrinks by e^(speed · points scrolled).
const ZOOM_SPEED: f32 = 0.003;

/// What the drawing was built from; a change rebuilds it.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    world: usize,
    options: DrawOptions,
    selected_object: Option<usize>,
    pixel: Option<[u32; 2]>,
    rays: Vec<DrawnRay>,
}

impl Key {
    /// True when `inputs` would build this very drawing.
    fn matches(&self, inputs: &Inputs<'_>) -> bool {
        self.world == std::ptr::from_ref(inputs.world) as usize
            && self.options == inputs.options
            && self.selected_object == inputs.selected_object
            && self.pixel == inputs.pixel
            && self.rays == inputs.rays
    }
}

/// The built drawing: its triangles and segments handed to the GPU, its
/// labels and markers painted by egui.
struct Built {
    key: Key,
    scene: Arc<GpuScene>,
    drawing: Drawing,
}

/// The debug view's state: what to draw and from where.
#[derive(Default)]
pub struct DebugView {
    /// What to draw.
    pub options: DrawOptions,
    /// The observer; framed on the scene when first shown.
    observer: Option<Observer>,
    built: Option<Built>,
    versions: u64,
}

impl DebugView {
    /// Turns the observer about its target (as a drag would), once it exists.
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        if let Some(observer) = &mut self.observer {
            observer.view = observer.view.orbit(yaw, pitch);
        }
    }

    /// Rebuilds the drawing when its inputs changed.
    fn update(&mut self, inputs: &Inputs<'_>) {
        if self.built.as_ref().is_some_and(|b| b.key.matches(inputs)) {
            return;
        }
        let key = Key {
            world: std::ptr::from_ref(inputs.world) as usize,
            options: inputs.options,
            selected_object: inputs.selected_object,
            pixel: inputs.pixel,
            rays: inputs.rays.to_vec(),
        };
        let mut drawing = drawing::build(inputs);
        self.versions += 1;
        let scene = Arc::new(GpuScene {
            version: self.versions,
            triangles: std::mem::take(&mut drawing.triangles),
            segments: std::mem::take(&mut drawing.segments),
        });
        self.built = Some(Built {
            key,
            scene,
            drawing,
        });
    }

    /// Frames the observer on the drawing (scene, camera and, when near, the view window).
    fn frame(&mut self, inputs: &Inputs<'_>) {
        if let Some(built) = &self.built {
            let camera = &inputs.world.camera;
            self.observer = Some(Observer::framing(
                &built.drawing.frame_points,
                camera.p0,
                camera.t,
                camera.u,
            ));
        }
    }

    /// The toolbar of drawing options above the view.
    fn toolbar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            let o = &mut self.options;
            ui.selectable_value(&mut o.solid, true, "Solid");
            ui.selectable_value(&mut o.solid, false, "Wireframe");
            ui.separator();
            ui.checkbox(&mut o.grid, "Ground grid");
            ui.checkbox(&mut o.pixel_grid, "Pixel grid");
            ui.separator();
            egui::ComboBox::new("fan", "ray fan")
                .selected_text(match o.fan {
                    Fan::Off => "none",
                    Fan::Sparse => "sparse",
                    Fan::Row => "row j",
                    Fan::Column => "column i",
                })
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut o.fan, Fan::Off, "none");
                    ui.selectable_value(&mut o.fan, Fan::Sparse, "sparse: every n-th pixel");
                    ui.selectable_value(&mut o.fan, Fan::Row, "row j of the inspected pixel");
                    ui.selectable_value(&mut o.fan, Fan::Column, "column i of the inspected pixel");
                });
            if o.fan != Fan::Off {
                ui.label("every");
                ui.add(
                    egui::DragValue::new(&mut o.fan_every)
                        .range(1..=4096)
                        .suffix(" px"),
                );
            }
            ui.checkbox(&mut o.all_samples, "all samples")
                .on_hover_text("Draw the rays of every sample of the inspected pixel so far");
            ui.separator();
            if ui
                .button("Frame")
                .on_hover_text("Look at the scene, the camera and the view window again")
                .clicked()
            {
                self.observer = None;
            }
        });
    }

    /// Shows the view filling `ui`. `gpu` says whether wgpu can paint it
    /// (the pipelines are installed).
    pub fn show(&mut self, ui: &mut egui::Ui, inputs: &Inputs<'_>, gpu: bool) {
        self.toolbar(ui);
        let inputs = Inputs {
            options: self.options,
            ..*inputs
        };
        self.update(&inputs);
        if self.observer.is_none() {
            self.frame(&inputs);
        }
        let (rect, response) =
            ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
        self.navigate(ui, rect, &response);
        let (Some(observer), Some(built)) = (self.observer, &self.built) else {
            return;
        };
        let painter = ui.painter_at(rect);
        let screen = observer.screen(rect);
        let background = egui::Color32::from_rgb(28, 30, 36);
        if gpu {
            let view = observer.view;
            let light = (view.eye - view.target
                + 0.5 * view.distance() * view.up.normalize_or(Vec3::Y))
            .normalize_or(Vec3::Y);
            painter.add(gpu::paint_callback(
                rect,
                DebugCallback {
                    scene: Arc::clone(&built.scene),
                    view_proj: screen.view_proj,
                    light,
                    background,
                },
            ));
        } else {
            painter.rect_filled(rect, 0.0, background);
            painter.text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "The 3D view needs the wgpu renderer.",
                egui::FontId::proportional(14.0),
                egui::Color32::LIGHT_GRAY,
            );
        }
        for marker in &built.drawing.markers {
            if let Some(at) = screen.project(marker.at) {
                painter.circle(
                    at,
                    3.5,
                    marker.color,
                    egui::Stroke::new(1.0, egui::Color32::BLACK),
                );
            }
        }
        let font = egui::FontId::proportional(13.0);
        let shown: Vec<(egui::Pos2, std::sync::Arc<egui::Galley>)> = built
            .drawing
            .labels
            .iter()
            .filter_map(|label| {
                let at = screen.project(label.at)?;
                let galley = painter.layout_no_wrap(label.text.clone(), font.clone(), label.color);
                Some((at, galley))
            })
            .collect();
        let sizes: Vec<(egui::Pos2, egui::Vec2)> =
            shown.iter().map(|(at, g)| (*at, g.size())).collect();
        for ((at, galley), place) in shown.into_iter().zip(place_labels(&sizes, rect)) {
            if !place.expand(4.0).contains(at) {
                // Moved off its point to keep clear of another: a leader line.
                painter.line_segment(
                    [at, place.left_bottom()],
                    egui::Stroke::new(1.0, egui::Color32::from_white_alpha(90)),
                );
            }
            painter.rect_filled(place.expand(2.0), 3.0, egui::Color32::from_black_alpha(170));
            painter.galley(place.min, galley, egui::Color32::WHITE);
        }
        legend(&painter, rect, built.drawing.grid_every);
    }

    /// Drag orbits the observer, Shift-drag or right-drag pans, the wheel zooms.
    fn navigate(&mut self, ui: &egui::Ui, rect: egui::Rect, response: &egui::Response) {
        let Some(observer) = self.observer.as_mut() else {
            return;
        };
        let shift = ui.input(|i| i.modifiers.shift);
        let delta = response.drag_delta();
        if response.dragged_by(egui::PointerButton::Secondary)
            || (shift && response.dragged_by(egui::PointerButton::Primary))
        {
            let scale = observer.units_per_point(rect);
            observer.view = observer.view.pan(-delta.x * scale, delta.y * scale);
        } else if response.dragged_by(egui::PointerButton::Primary)
            || response.dragged_by(egui::PointerButton::Middle)
        {
            observer.view = observer
                .view
                .orbit(-delta.x * ORBIT_SPEED, -delta.y * ORBIT_SPEED);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                observer.view = observer.view.dolly((-scroll * ZOOM_SPEED).exp());
            }
        }
    }
}

/// Text with its bottom-left corner at `at`, on a dark box so it reads over anything.
/// Where to draw labels of the given sizes, each anchored at its point
/// (drawn above and right of it), so that no two overlap and each stays
/// inside `bounds` (as far as its width allows): a label that would cover
/// an earlier one moves up or down by its height, nearest first (up to
/// eight rows either way), and one past an edge moves back in. Labels are
/// placed in order.
pub fn place_labels(labels: &[(egui::Pos2, egui::Vec2)], bounds: egui::Rect) -> Vec<egui::Rect> {
    let mut placed: Vec<egui::Rect> = Vec::with_capacity(labels.len());
    for &(at, size) in labels {
        let home = egui::Rect::from_min_size(at + egui::vec2(5.0, -5.0 - size.y), size);
        let fit = |r: egui::Rect| {
            // Left of the right edge, then right of the left one (a label
            // wider than the view starts at its left edge).
            let r = r.translate(egui::vec2((bounds.right() - 2.0 - r.right()).min(0.0), 0.0));
            let dx = (bounds.left() + 2.0 - r.left()).max(0.0);
            let dy = (bounds.top() + 2.0 - r.top()).max(0.0);
            r.translate(egui::vec2(dx, dy))
        };
        let step = size.y + 4.0;
        let clear = |r: &egui::Rect| !placed.iter().any(|p| p.expand(2.0).intersects(*r));
        let spot = (0..=16)
            .map(|k: i32| {
                let rows = if k % 2 == 1 { -(k + 1) / 2 } else { k / 2 };
                fit(home.translate(egui::vec2(0.0, rows as f32 * step)))
            })
            .find(clear)
            .unwrap_or_else(|| fit(home));
        placed.push(spot);
    }
    placed
}

/// The colour key in the view's corner.
fn legend(painter: &egui::Painter, rect: egui::Rect, grid_every: u32) {
    let grid = if grid_every == 1 {
        "pixel grid: every pixel".to_owned()
    } else {
        format!("pixel grid: every {grid_every}th line")
    };
    let entries = [
        (palette::PRIMARY, "primary ray, P_ij".to_owned()),
        (palette::SHADOW_FREE, "shadow ray, light reached".to_owned()),
        (palette::SHADOW_BLOCKED, "shadow ray, blocked".to_owned()),
        (palette::REFLECTION, "reflection".to_owned()),
        (palette::REFRACTION, "refraction".to_owned()),
        (palette::NORMAL, "normal at a hit".to_owned()),
        (palette::C00, "C00".to_owned()),
        (egui::Color32::GRAY, grid),
    ];
    let font = egui::FontId::proportional(12.0);
    let line = 15.0;
    let top_left = rect.left_bottom() + egui::vec2(8.0, -8.0 - line * entries.len() as f32);
    let key = egui::Rect::from_min_size(top_left, egui::vec2(190.0, line * entries.len() as f32));
    painter.rect_filled(key.expand(4.0), 4.0, egui::Color32::from_black_alpha(170));
    for (k, (color, text)) in entries.iter().enumerate() {
        let y = top_left.y + k as f32 * line + 0.5 * line;
        painter.line_segment(
            [egui::pos2(top_left.x, y), egui::pos2(top_left.x + 16.0, y)],
            egui::Stroke::new(3.0, *color),
        );
        painter.text(
            egui::pos2(top_left.x + 22.0, y),
            egui::Align2::LEFT_CENTER,
            text,
            font.clone(),
            egui::Color32::LIGHT_GRAY,
        );
    }
}

#[cfg(test)]
mod tests;
