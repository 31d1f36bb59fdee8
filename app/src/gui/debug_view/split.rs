//! How the centre of the window is shared between the image and the debug
//! view: beside or below it, whichever leaves the image larger, and in a
//! proportion the user drags, kept as the window or the panels around the
//! centre change size.

/// The side of the image the debug view takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split {
    /// Left and right: the debug view on the right.
    Beside,
    /// Top and bottom: the debug view below.
    Below,
}

impl Split {
    /// The split for a centre of `centre` points and an image of
    /// `image_w` × `image_h` pixels: the one where the image, fitted into
    /// half the centre, is the larger (beside on a tie). A wide centre and a
    /// tall image go beside; a 16:9 image in the centre left between the side
    /// panels of a 1280×800 window goes below (half the width would shrink it
    /// to a strip).
    pub fn for_centre(centre: egui::Vec2, image_w: u32, image_h: u32) -> Self {
        let aspect = image_w.max(1) as f32 / image_h.max(1) as f32;
        let fitted_width = |w: f32, h: f32| w.min(h * aspect);
        let beside = fitted_width(0.5 * centre.x, centre.y);
        let below = fitted_width(centre.x, 0.5 * centre.y);
        if below > beside {
            Self::Below
        } else {
            Self::Beside
        }
    }
}

/// The image's share of the centre, dragged by the line between the image
/// and the debug view; a fraction, so that opening the inspector or resizing
/// the window keeps the proportion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Splitter {
    /// The image's fraction of the centre's width (beside) or height (below).
    pub image_share: f32,
}

impl Default for Splitter {
    fn default() -> Self {
        Self { image_share: 0.5 }
    }
}

/// Neither part is made smaller than this many points by a drag.
const MIN_PART: f32 = 120.0;
/// Width of the draggable line between the parts, in points.
const LINE: f32 = 6.0;

impl Splitter {
    /// Divides `ui`'s remaining space by `split` into the image's rectangle
    /// and the debug view's, draws the line between them and moves it with
    /// a drag.
    pub fn layout(&mut self, ui: &mut egui::Ui, split: Split) -> (egui::Rect, egui::Rect) {
        let centre = ui.available_rect_before_wrap();
        ui.allocate_rect(centre, egui::Sense::hover());
        let (length, start) = match split {
            Split::Beside => (centre.width(), centre.left()),
            Split::Below => (centre.height(), centre.top()),
        };
        let at = start + self.clamped(length) * length;
        let line = match split {
            Split::Beside => {
                egui::Rect::from_x_y_ranges(at - 0.5 * LINE..=at + 0.5 * LINE, centre.y_range())
            }
            Split::Below => {
                egui::Rect::from_x_y_ranges(centre.x_range(), at - 0.5 * LINE..=at + 0.5 * LINE)
            }
        };
        let response = ui.interact(
            line,
            egui::Id::unique("image-debug-split"),
            egui::Sense::drag(),
        );
        if let Some(pointer) = response
            .interact_pointer_pos()
            .filter(|_| response.dragged())
        {
            let along = match split {
                Split::Beside => pointer.x,
                Split::Below => pointer.y,
            };
            self.image_share = (along - start) / length.max(1.0);
        }
        let at = start + self.clamped(length) * length;
        let stroke = if response.hovered() || response.dragged() {
            ui.visuals().widgets.active.bg_stroke
        } else {
            ui.visuals().widgets.noninteractive.bg_stroke
        };
        let (image, debug) = match split {
            Split::Beside => {
                ui.painter().vline(at, centre.y_range(), stroke);
                let (image, debug) = centre.split_left_right_at_x(at);
                (
                    image.shrink2(egui::vec2(0.5 * LINE, 0.0)),
                    debug.shrink2(egui::vec2(0.5 * LINE, 0.0)),
                )
            }
            Split::Below => {
                ui.painter().hline(centre.x_range(), at, stroke);
                let (image, debug) = centre.split_top_bottom_at_y(at);
                (
                    image.shrink2(egui::vec2(0.0, 0.5 * LINE)),
                    debug.shrink2(egui::vec2(0.0, 0.5 * LINE)),
                )
            }
        };
        let cursor = match split {
            Split::Beside => egui::CursorIcon::ResizeHorizontal,
            Split::Below => egui::CursorIcon::ResizeVertical,
        };
        if response.hovered() || response.dragged() {
            ui.ctx().set_cursor_icon(cursor);
        }
        (image, debug)
    }

    /// The image's share of `length` points, kept so that neither part is
    /// under `MIN_PART` (half each when there is not room for both).
    fn clamped(&self, length: f32) -> f32 {
        let min = (MIN_PART / length.max(1.0)).min(0.5);
        self.image_share.clamp(min, 1.0 - min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::vec2;

    #[test]
    fn the_image_keeps_the_larger_half() {
        // 500 × 520 points between the panels of a 1280×800 window, 16:9:
        // beside fits 250 wide, below 462 wide.
        assert_eq!(
            Split::for_centre(vec2(500.0, 520.0), 1280, 720),
            Split::Below
        );
        // A wide window: beside fits 800 wide (900 tall allows 1600), below 800.
        assert_eq!(
            Split::for_centre(vec2(1600.0, 900.0), 1280, 720),
            Split::Beside
        );
        // A tall (portrait) image goes beside even in a narrow centre.
        assert_eq!(
            Split::for_centre(vec2(500.0, 520.0), 400, 800),
            Split::Beside
        );
    }

    #[test]
    fn a_dragged_share_keeps_each_part_at_least_its_minimum() {
        let mut s = Splitter { image_share: 0.02 };
        assert_eq!(s.clamped(1000.0), 0.12);
        s.image_share = 0.99;
        assert_eq!(s.clamped(1000.0), 0.88);
        // Too short for two minimums: half each.
        assert_eq!(s.clamped(200.0), 0.5);
        s.image_share = 0.3;
        assert_eq!(s.clamped(1000.0), 0.3, "a share within bounds is kept");
    }

    /// Dragging the line between the parts moves it with the pointer, and
    /// the share it leaves is kept when the centre grows.
    #[test]
    fn dragging_the_line_sets_the_share_and_a_larger_centre_keeps_it() {
        use egui_kittest::Harness;
        let mut h = Harness::builder()
            .with_size(vec2(400.0, 600.0))
            .build_ui_state(
                |ui, (splitter, parts): &mut (Splitter, Option<(egui::Rect, egui::Rect)>)| {
                    *parts = Some(splitter.layout(ui, Split::Below));
                },
                (Splitter::default(), None),
            );
        h.run();
        let (image, debug) = h.state().1.expect("laid out");
        let line = egui::pos2(image.center().x, 0.5 * (image.bottom() + debug.top()));
        h.hover_at(line);
        h.drag_at(line);
        h.step();
        h.hover_at(line + vec2(0.0, 100.0));
        h.step();
        h.drop_at(line + vec2(0.0, 100.0));
        h.step();
        let (image, _) = h.state().1.expect("laid out");
        let share = h.state().0.image_share;
        assert!(
            (image.bottom() - (line.y + 100.0 - 3.0)).abs() < 1.0,
            "the image ends at the dropped line: {image:?}"
        );
        assert!(share > 0.6, "share {share}");
        h.set_size(vec2(400.0, 900.0));
        h.run();
        let (bigger, _) = h.state().1.expect("laid out");
        assert_eq!(h.state().0.image_share, share, "the share is kept");
        assert!(
            bigger.height() > image.height() * 1.4,
            "the image grew with the centre"
        );
    }
}
