//! The rendered image: one texture, updated in place with every frame and
//! shown pixel-exact (nearest-neighbour) at 100%.

use renderer::progressive::RenderedFrame;

/// The texture the frames go into.
#[derive(Default)]
pub struct ImageView {
    texture: Option<egui::TextureHandle>,
}

impl ImageView {
    /// Uploads `frame` as 8-bit sRGB into the one texture (created on first use).
    pub fn show_frame(&mut self, ctx: &egui::Context, frame: &RenderedFrame) {
        let bytes: Vec<u8> = frame
            .pixels
            .iter()
            .flat_map(|&c| renderer::film::linear_to_srgb8(c))
            .collect();
        let image =
            egui::ColorImage::from_rgb([frame.width as usize, frame.height as usize], &bytes);
        match &mut self.texture {
            Some(texture) => texture.set(image, egui::TextureOptions::NEAREST),
            None => {
                self.texture =
                    Some(ctx.load_texture("render", image, egui::TextureOptions::NEAREST))
            }
        }
    }

    /// Draws the image at 100% (one image pixel per physical pixel), scrollable.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let Some(texture) = &self.texture else {
            ui.centered_and_justified(|ui| ui.spinner());
            return;
        };
        let size = texture.size_vec2() / ui.ctx().pixels_per_point();
        egui::ScrollArea::both().show(ui, |ui| {
            ui.add(egui::Image::new((texture.id(), size)));
        });
    }
}
