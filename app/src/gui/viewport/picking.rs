//! Picking: the object under a pixel of the image, found by tracing the ray
//! through the pixel's centre in the prepared world.

use super::image_view::ImageView;
use crate::gui::session::Prepared;
use renderer::Method;
use renderer::display::Display;

/// The object under pixel (i, j) of `prepared`'s image, if any.
pub fn object_at(prepared: &Prepared, method: Method, [i, j]: [u32; 2]) -> Option<usize> {
    let world = &prepared.world;
    if i >= world.camera.w || j >= world.camera.h {
        return None;
    }
    let ray = world.camera.center_ray(i, j);
    world.intersect(&ray, method).map(|hit| hit.object as usize)
}

/// The name of the object under the pointer at `pixel`, while `image`
/// shows object ids.
pub fn hover_text(
    image: &ImageView,
    prepared: Option<&Prepared>,
    method: Method,
    pixel: Option<[u32; 2]>,
) -> Option<String> {
    if image.shown_display() != Some(Display::ObjectId) {
        return None;
    }
    let prepared = prepared?;
    let object = object_at(prepared, method, pixel?)?;
    prepared.world.names.get(object).cloned()
}
