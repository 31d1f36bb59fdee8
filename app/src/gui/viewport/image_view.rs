//! The rendered image: one texture updated in place with every frame, shown
//! pixel-exact at 100 %, zoomable (nearest-neighbour when magnified) and
//! pannable; mouse gestures on it become camera moves and picks.

use renderer::display::{Display, Legend};
use renderer::progressive::RenderedFrame;
use scene::{Tonemap, View};

/// Sampling of the image texture: single pixels stay crisp when magnified.
const TEXTURE_OPTIONS: egui::TextureOptions = egui::TextureOptions {
    magnification: egui::TextureFilter::Nearest,
    minification: egui::TextureFilter::Linear,
    wrap_mode: egui::TextureWrapMode::ClampToEdge,
    mipmap_mode: None,
};

/// How the image is scaled into the view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Zoom {
    /// As large as fits, but never magnified.
    Fit,
    /// Image pixels per physical screen pixel (1 = 100 %).
    Scale(f32),
}

/// What the user did on the image this frame, in screen points.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Gestures {
    /// The pixel (i, j) clicked with the primary button.
    pub clicked_pixel: Option<[u32; 2]>,
    /// Alt is held: the hovered pixel is to be inspected.
    pub inspect_hover: bool,
    /// Orbit drag (left or middle button, no modifier).
    pub orbit: egui::Vec2,
    /// Pan drag (Shift).
    pub pan: egui::Vec2,
    /// Dolly drag (Ctrl, vertical) plus wheel, in points.
    pub dolly: f32,
    /// A camera drag began this frame.
    pub drag_started: bool,
    /// Image pixels per screen point, to turn point deltas into pixels.
    pub pixels_per_point: f32,
    /// The pixel (i, j) under the pointer.
    pub hovered_pixel: Option<[u32; 2]>,
}

/// The texture and the zoom/pan state.
pub struct ImageView {
    texture: Option<egui::TextureHandle>,
    size: [usize; 2],
    /// How the image is scaled.
    pub zoom: Zoom,
    /// Offset of the image centre from the view centre, in points.
    offset: egui::Vec2,
    /// Where the image was drawn last, in points.
    last_rect: Option<egui::Rect>,
    /// The display mode chosen in the view's toolbar (the frame on screen
    /// may still show the previous one for a step).
    pub display: Display,
    /// The legend of the frame on screen.
    legend: Option<Legend>,
    /// Shown as a tooltip while the pointer is over the image (the name of
    /// the object under it, in the object-id mode).
    pub hover_text: Option<String>,
}

impl Default for ImageView {
    fn default() -> Self {
        Self {
            texture: None,
            size: [0, 0],
            zoom: Zoom::Fit,
            offset: egui::Vec2::ZERO,
            last_rect: None,
            display: Display::Color,
            legend: None,
            hover_text: None,
        }
    }
}

impl ImageView {
    /// Writes `frame`'s 8-bit sRGB pixels into the one texture: in place when the
    /// size is unchanged, re-created only when the image size changes.
    pub fn show_frame(&mut self, ctx: &egui::Context, frame: &RenderedFrame) {
        let image = super::screenshot::color_image(frame);
        let size = image.size;
        match &mut self.texture {
            Some(texture) if self.size == size => {
                texture.set_partial([0, 0], image, TEXTURE_OPTIONS)
            }
            Some(texture) => texture.set(image, TEXTURE_OPTIONS),
            None => self.texture = Some(ctx.load_texture("render", image, TEXTURE_OPTIONS)),
        }
        self.size = size;
        self.legend = Some(frame.legend.clone());
    }

    /// The display mode of the frame on screen.
    pub fn shown_display(&self) -> Option<Display> {
        self.legend.as_ref().map(|l| l.display)
    }

    /// The square pixel (i, j) covered when the image was drawn last, in screen points.
    pub fn pixel_rect(&self, [i, j]: [u32; 2]) -> Option<egui::Rect> {
        let rect = self.last_rect?;
        let [w, h] = self.size.map(|s| s as f32);
        let size = egui::vec2(rect.width() / w, rect.height() / h);
        ((i as f32) < w && (j as f32) < h).then(|| {
            egui::Rect::from_min_size(rect.min + egui::vec2(i as f32, j as f32) * size, size)
        })
    }

    /// The pixel (i, j) under screen point `pos`, if the image covers it.
    fn pixel_at(
        &self,
        rect: egui::Rect,
        pos: egui::Pos2,
        ppp: f32,
        scale: f32,
    ) -> Option<[u32; 2]> {
        if !rect.contains(pos) {
            return None;
        }
        let p = (pos - rect.min) * ppp / scale;
        Some([p.x as u32, p.y as u32])
            .filter(|[i, j]| (*i as usize) < self.size[0] && (*j as usize) < self.size[1])
    }

    /// Where the centre of pixel (i, j) was drawn last, in screen points.
    #[cfg(test)]
    pub fn pixel_on_screen(&self, [i, j]: [u32; 2]) -> Option<egui::Pos2> {
        let rect = self.last_rect?;
        let [w, h] = self.size.map(|s| s as f32);
        Some(
            rect.min
                + egui::vec2(
                    (i as f32 + 0.5) / w * rect.width(),
                    (j as f32 + 0.5) / h * rect.height(),
                ),
        )
    }

    /// Image pixels per physical pixel for the current zoom inside `view`.
    fn scale(&self, view: egui::Rect, ppp: f32) -> f32 {
        match self.zoom {
            Zoom::Scale(s) => s,
            Zoom::Fit => {
                let [w, h] = self.size.map(|s| s.max(1) as f32);
                (view.width() * ppp / w)
                    .min(view.height() * ppp / h)
                    .min(1.0)
            }
        }
    }

    /// Where the image lies in `view`, its corner on a physical pixel so that
    /// 100 % is pixel-exact.
    fn image_rect(&self, view: egui::Rect, ppp: f32) -> egui::Rect {
        let scale = self.scale(view, ppp);
        let size = egui::vec2(self.size[0] as f32, self.size[1] as f32) * scale / ppp;
        let centre = view.center() + self.offset;
        let min = ((centre - size / 2.0) * ppp).round() / ppp;
        egui::Rect::from_min_size(min, size)
    }

    /// Sets the zoom so that `scale` image pixels map to a physical pixel,
    /// keeping the image point under `anchor` fixed.
    fn zoom_about(&mut self, view: egui::Rect, ppp: f32, factor: f32, anchor: egui::Pos2) {
        let old = self.scale(view, ppp);
        let new = (old * factor).clamp(1.0 / 16.0, 64.0);
        let centre = view.center() + self.offset;
        let from_centre = (centre - anchor) * (new / old);
        self.offset = anchor + from_centre - view.center();
        self.zoom = Zoom::Scale(new);
    }

    /// Draws the image into the remaining space, with the controls of how
    /// it is shown (`shown`, the scene's exposure and tone curve, edited in
    /// place), and reports the user's gestures.
    pub fn ui(&mut self, ui: &mut egui::Ui, shown: &mut View) -> Gestures {
        let view = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(view, egui::Sense::click_and_drag());
        let ppp = ui.ctx().pixels_per_point();
        let Some(texture) = &self.texture else {
            ui.put(view, egui::Spinner::new());
            return Gestures::default();
        };
        let rect = self.image_rect(view, ppp);
        self.last_rect = Some(rect);
        let painter = ui.painter_at(view);
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        painter.image(texture.id(), rect, uv, egui::Color32::WHITE);

        let scale = self.scale(view, ppp);
        let mut gestures = Gestures {
            pixels_per_point: ppp / scale,
            ..Gestures::default()
        };
        let (modifiers, scroll, zoom) =
            ui.input(|i| (i.modifiers, i.smooth_scroll_delta, i.zoom_delta()));
        if let Some(pos) = response.hover_pos() {
            gestures.hovered_pixel = self.pixel_at(rect, pos, ppp, scale);
        }
        let response = match &self.hover_text {
            Some(text) if gestures.hovered_pixel.is_some() => {
                response.on_hover_text_at_pointer(text.as_str())
            }
            _ => response,
        };
        if response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
        {
            gestures.clicked_pixel = self.pixel_at(rect, pos, ppp, scale);
        }
        gestures.inspect_hover = modifiers.alt;
        let camera_drag = response.dragged_by(egui::PointerButton::Primary)
            || response.dragged_by(egui::PointerButton::Middle);
        if camera_drag {
            let delta = response.drag_delta();
            if modifiers.shift {
                gestures.pan = delta;
            } else if modifiers.command || modifiers.ctrl {
                gestures.dolly = delta.y;
            } else {
                gestures.orbit = delta;
            }
            gestures.drag_started = response.drag_started();
        }
        if response.dragged_by(egui::PointerButton::Secondary) {
            self.offset += response.drag_delta();
        }
        if response.hovered() {
            if zoom != 1.0 {
                let anchor = response.hover_pos().unwrap_or(view.center());
                self.zoom_about(view, ppp, zoom, anchor);
            } else if scroll.y != 0.0 {
                gestures.dolly -= scroll.y;
            }
        }
        self.overlay(ui, view, scale, shown);
        if let Some(legend) = &self.legend {
            super::legend::show(ui, view, legend);
        }
        gestures
    }

    /// The zoom read-out, the Fit / 100 % buttons, the display mode and the
    /// colour's exposure and tone curve in the view's corner.
    fn overlay(&mut self, ui: &mut egui::Ui, view: egui::Rect, scale: f32, shown: &mut View) {
        let corner =
            egui::Rect::from_min_size(view.min + egui::vec2(6.0, 6.0), egui::vec2(820.0, 52.0))
                .intersect(view.shrink(6.0));
        // Within the view only: beside it may lie the debug view's own toolbar.
        ui.scope_builder(egui::UiBuilder::new().max_rect(corner), |ui| {
            ui.set_clip_rect(view);
            ui.horizontal_wrapped(|ui| {
                ui.label(
                    egui::RichText::new(format!("{:.0} %", scale * 100.0))
                        .background_color(ui.visuals().extreme_bg_color),
                );
                if ui.small_button("Fit").clicked() {
                    self.fit();
                }
                if ui.small_button("100 %").clicked() {
                    self.actual_size();
                }
                ui.separator();
                egui::ComboBox::from_id_salt("display-mode")
                    .selected_text(self.display.label())
                    .width(170.0)
                    .show_ui(ui, |ui| {
                        for d in Display::ALL {
                            ui.selectable_value(&mut self.display, d, d.label());
                        }
                    })
                    .response
                    .on_hover_text("What the image shows (M cycles)");
                ui.separator();
                view_controls(ui, shown);
            });
        });
    }

    /// Fits the image into the view (never magnifying), centred.
    pub fn fit(&mut self) {
        self.zoom = Zoom::Fit;
        self.offset = egui::Vec2::ZERO;
    }

    /// Shows the image at 100 %, centred.
    pub fn actual_size(&mut self) {
        self.zoom = Zoom::Scale(1.0);
        self.offset = egui::Vec2::ZERO;
    }
}

/// The exposure (stops) and tone curve of the colour, edited in place: a
/// display setting saved with the scene, undoable, and never a restart.
fn view_controls(ui: &mut egui::Ui, shown: &mut View) {
    ui.add(
        egui::DragValue::new(&mut shown.exposure)
            .range(-View::MAX_EXPOSURE..=View::MAX_EXPOSURE)
            .speed(0.02)
            .max_decimals(2)
            .prefix("exposure ")
            .suffix(" EV"),
    )
    .on_hover_text(
        "Exposure in stops: the colour × 2^EV before the tone curve \
         (shown and saved as PNG; EXR stays linear; double-click to type)",
    );
    egui::ComboBox::from_id_salt("tone-curve")
        .selected_text(shown.tonemap.label())
        .width(150.0)
        .show_ui(ui, |ui| {
            for t in Tonemap::ALL {
                ui.selectable_value(&mut shown.tonemap, t, t.label());
            }
        })
        .response
        .on_hover_text(
            "How radiance above white is shown: clamped per channel, or rolled off \
             toward white keeping hues (Khronos PBR Neutral)",
        );
}
