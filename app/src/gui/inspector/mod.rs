//! The pixel inspector: which pixel is inspected, its ray tree re-traced
//! whenever what it was traced from changes, the rays the debug view draws
//! of it, and the inspector panel.

mod panel;
pub mod pixel;

use super::debug_view::{self, DrawnRay};
use super::session::{Prepared, SessionSync};
use super::viewport::image_view::ImageView;
use pixel::InspectedPixel;
use renderer::{Method, RenderOptions};
use std::sync::Arc;

/// What an inspection was traced from: the world, the options, the pixel and
/// the sample (or, for all samples, their count).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InspectionKey {
    world: usize,
    options: RenderOptions,
    pixel: [u32; 2],
    sample: Option<u32>,
}

/// At most this many samples' rays are drawn at once.
const MAX_DRAWN_SAMPLES: u32 = 64;

/// The inspected pixel and what is cached of it.
#[derive(Default)]
pub struct Inspector {
    /// The pixel under inspection.
    pub inspected: Option<InspectedPixel>,
    /// Its ray tree, with what it was traced from.
    pub inspection: Option<(InspectionKey, renderer::Inspection)>,
    /// The rays the debug view draws: the inspection's, or those of all the
    /// pixel's samples so far (then the key's sample is their count).
    drawn_rays: Option<(InspectionKey, bool, Vec<DrawnRay>)>,
}

impl Inspector {
    /// Inspects pixel (i, j) of `prepared`'s image; a pinned pixel moves only
    /// on a click, not on hover.
    pub fn inspect(
        &mut self,
        pixel: [u32; 2],
        hover: bool,
        prepared: Option<&Prepared>,
        method: Method,
    ) {
        let inspected = match self.inspected {
            Some(current) if current.pixel == pixel => current,
            Some(current) if current.pinned && hover => current,
            Some(current) => InspectedPixel {
                pixel,
                point: None,
                ..current
            },
            None => InspectedPixel::new(pixel),
        };
        self.inspected = Some(inspected);
        self.remember_point(prepared, method);
    }

    /// Records the point the inspected pixel's centre ray hits, which an
    /// unpinned inspection follows when the camera moves.
    fn remember_point(&mut self, prepared: Option<&Prepared>, method: Method) {
        let (Some(inspected), Some(prepared)) = (&mut self.inspected, prepared) else {
            return;
        };
        let [i, j] = inspected.pixel;
        let ray = prepared.world.camera.center_ray(i, j);
        inspected.point = prepared
            .world
            .intersect(&ray, method)
            .map(|hit| ray.at(hit.alpha));
    }

    /// Moves the inspected pixel with the camera of a newly prepared world
    /// (see [`InspectedPixel::follow`]).
    pub fn follow(&mut self, prepared: Option<&Prepared>) {
        if let (Some(inspected), Some(prepared)) = (&mut self.inspected, prepared) {
            *inspected = inspected.follow(&prepared.world.camera);
        }
    }

    /// The inspected pixel (i, j), if any.
    pub fn pixel(&self) -> Option<[u32; 2]> {
        self.inspected.map(|p| p.pixel)
    }

    /// The rays the debug view draws.
    pub fn drawn_rays(&self) -> &[DrawnRay] {
        self.drawn_rays
            .as_ref()
            .map_or(&[][..], |(_, _, rays)| rays.as_slice())
    }

    /// Re-traces the inspected pixel when it, its sample, the scene or the
    /// `options` changed (one path: microseconds), and, with `all`, every
    /// sample the image on screen has (for the debug view to draw).
    pub fn refresh(&mut self, session: &SessionSync, options: RenderOptions, all: bool) {
        let (Some(inspected), Some(prepared)) = (self.inspected, &session.prepared) else {
            self.inspection = None;
            self.drawn_rays = None;
            return;
        };
        let world = &prepared.world;
        let key = InspectionKey {
            world: Arc::as_ptr(world) as usize,
            options,
            pixel: inspected.pixel,
            sample: inspected.sample,
        };
        let [i, j] = inspected.pixel;
        if self.inspection.as_ref().is_none_or(|(k, _)| *k != key) {
            self.inspection = renderer::inspect_pixel(world, &options, i, j, inspected.sample)
                .ok()
                .map(|inspection| (key, inspection));
        }
        let drawn = InspectionKey {
            sample: if all {
                Some(session.shown_spp().clamp(1, MAX_DRAWN_SAMPLES))
            } else {
                key.sample
            },
            ..key
        };
        if self
            .drawn_rays
            .as_ref()
            .is_some_and(|(k, a, _)| (*k, *a) == (drawn, all))
        {
            return;
        }
        let rays = match (all, &self.inspection) {
            (true, _) => (0..drawn.sample.unwrap_or(1))
                .filter_map(|k| renderer::inspect_pixel(world, &options, i, j, Some(k)).ok())
                .flat_map(|inspection| {
                    debug_view::rays::drawn_rays(&inspection).collect::<Vec<_>>()
                })
                .collect(),
            (false, Some((_, inspection))) => debug_view::rays::drawn_rays(inspection).collect(),
            (false, None) => Vec::new(),
        };
        self.drawn_rays = Some((drawn, all, rays));
    }

    /// The pixel inspector, while a pixel is inspected: docked under the
    /// image in a panel the user can resize (egui remembers its height), so
    /// that the image, the inspector and the object editor are all in view.
    /// Call it after the side panels and before the image's central panel.
    pub fn panel(&mut self, ui: &mut egui::Ui, session: &SessionSync) {
        let spp = session.shown_spp();
        let (Some(inspected), Some((_, inspection)), Some(prepared)) =
            (&mut self.inspected, &self.inspection, &session.prepared)
        else {
            return;
        };
        let camera = &prepared.world.camera;
        let [i, j] = inspected.pixel;
        let accumulated = session
            .frame
            .as_ref()
            .filter(|f| spp > 0 && f.width == camera.w && f.height == camera.h)
            .and_then(|f| f.linear_at(i, j))
            .map(|c| (c, spp));
        let cx = panel::Context {
            camera,
            accumulated,
            lights: &prepared.world.lights,
        };
        let mut open = true;
        let most = (0.7 * ui.available_height()).max(120.0);
        egui::Panel::bottom("inspector")
            .resizable(true)
            .default_size(260.0_f32.min(most))
            .size_range(100.0..=most)
            .show(ui, |ui| {
                ui.add_space(2.0);
                ui.strong("Pixel inspector");
                // Both ways: a row wider than the centre (a table of a
                // sample's vertices) scrolls instead of widening the panel
                // under the object editor.
                egui::ScrollArea::both()
                    .id_salt("inspector")
                    .auto_shrink([false, false])
                    .show(ui, |ui| {
                        open = panel::show(ui, inspected, inspection, &cx);
                    });
            });
        if !open {
            self.inspected = None;
        }
    }

    /// Outlines the inspected pixel on the image.
    pub fn mark(&self, ui: &egui::Ui, image: &ImageView) {
        if let Some(rect) = self.pixel().and_then(|p| image.pixel_rect(p)) {
            let rect = rect.expand(2.0);
            let painter = ui.painter();
            painter.rect_stroke(
                rect,
                0.0,
                egui::Stroke::new(3.0, egui::Color32::BLACK),
                egui::StrokeKind::Outside,
            );
            painter.rect_stroke(
                rect,
                0.0,
                egui::Stroke::new(1.5, debug_view::drawing::palette::PRIMARY),
                egui::StrokeKind::Outside,
            );
        }
    }
}
