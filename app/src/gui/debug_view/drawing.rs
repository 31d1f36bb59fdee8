//! What the debug view draws, built on the CPU from the prepared world: the
//! scene's shapes, a ground grid and world axes, the ray-tracing camera at P0
//! with t, u, r, the view volume, the view window at distance d with its
//! pixel grid, C00 and P_ij, rays, and an environment map's orientation. Everything comes from the tracer's own
//! [`Camera`], so the picture is the lecture's geometry, not a copy of it.

use super::gpu::{GpuSegment, GpuVertex};
use super::rays::{DrawnRay, RayKind};
use super::tessellate::{MeshVertex, OBJECTS_DRAWN_IN_FULL, tessellate, tessellate_bounds};
use egui::Color32;
use glam::Vec3;
use renderer::{Camera, World};
use scene::{Geometry, ResolvedObject};

/// Grid lines per side of the view window at most; coarser grids show every n-th line.
const MAX_GRID_LINES: u32 = 64;

/// Colours of the drawing.
pub mod palette {
    use egui::Color32;
    /// r, x: red.
    pub const R: Color32 = Color32::from_rgb(230, 70, 60);
    /// u, y: green.
    pub const U: Color32 = Color32::from_rgb(90, 200, 80);
    /// t, z: blue.
    pub const T: Color32 = Color32::from_rgb(70, 130, 240);
    /// The view window and its corners.
    pub const WINDOW: Color32 = Color32::from_rgb(235, 235, 235);
    /// C00.
    pub const C00: Color32 = Color32::from_rgb(255, 150, 40);
    /// The selected pixel's P_ij and primary ray.
    pub const PRIMARY: Color32 = Color32::from_rgb(255, 220, 60);
    /// A shadow ray that reaches its light.
    pub const SHADOW_FREE: Color32 = Color32::from_rgb(120, 240, 140);
    /// A shadow ray stopped by a blocker.
    pub const SHADOW_BLOCKED: Color32 = Color32::from_rgb(255, 70, 90);
    /// Mirror reflections.
    pub const REFLECTION: Color32 = Color32::from_rgb(80, 220, 255);
    /// Refractions.
    pub const REFRACTION: Color32 = Color32::from_rgb(230, 110, 255);
    /// Surface normals at hits.
    pub const NORMAL: Color32 = Color32::from_rgb(250, 250, 250);
    /// The selected object.
    pub const SELECTED: Color32 = Color32::from_rgb(255, 160, 30);
    /// An environment map's frame.
    pub const SKY: Color32 = Color32::from_rgb(150, 190, 255);
}

/// Which primary rays to draw besides the selected pixel's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Fan {
    /// None.
    #[default]
    Off,
    /// Every n-th pixel of every n-th row.
    Sparse,
    /// Every pixel (or every n-th) of the selected pixel's row j.
    Row,
    /// Every pixel (or every n-th) of the selected pixel's column i.
    Column,
}

/// The user's choices of what to draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawOptions {
    /// Shaded solids (else wireframes).
    pub solid: bool,
    /// The ground grid and world axes.
    pub grid: bool,
    /// The view window's pixel grid.
    pub pixel_grid: bool,
    /// The fan of primary rays.
    pub fan: Fan,
    /// Pixels between fan rays.
    pub fan_every: u32,
    /// Draw the rays of every sample of the inspected pixel, not just one.
    pub all_samples: bool,
}

impl Default for DrawOptions {
    fn default() -> Self {
        Self {
            solid: true,
            grid: true,
            pixel_grid: true,
            fan: Fan::Off,
            fan_every: 64,
            all_samples: false,
        }
    }
}

/// Text placed at a point in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// Where.
    pub at: Vec3,
    /// What it says.
    pub text: String,
    /// Its colour.
    pub color: Color32,
}

/// A dot at a point in the world, drawn on top of everything.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Marker {
    /// Where.
    pub at: Vec3,
    /// Its colour.
    pub color: Color32,
}

/// What to draw from.
pub struct Inputs<'a> {
    /// The prepared scene (camera, shapes, materials).
    pub world: &'a World,
    /// The resolved objects, in object-id order.
    pub objects: &'a [ResolvedObject],
    /// The selected object, drawn highlighted.
    pub selected_object: Option<usize>,
    /// The selected pixel (i, j).
    pub pixel: Option<[u32; 2]>,
    /// The selected pixel's rays.
    pub rays: &'a [DrawnRay],
    /// What to draw.
    pub options: DrawOptions,
}

/// The finished drawing.
#[derive(Debug, Default)]
pub struct Drawing {
    /// Shaded triangles.
    pub triangles: Vec<GpuVertex>,
    /// Wide line segments.
    pub segments: Vec<GpuSegment>,
    /// Text labels.
    pub labels: Vec<Label>,
    /// Dots.
    pub markers: Vec<Marker>,
    /// The points the observer should see when it frames the drawing.
    pub frame_points: Vec<Vec3>,
    /// The view window's grid shows every n-th pixel line.
    pub grid_every: u32,
    /// The camera as drawn: the tracer's, or — when its view window lies far
    /// beyond the scene (the default d is hundreds of units) — the same
    /// camera with the window moved nearer and scaled with its distance
    /// ([`shown_camera`]): every P_ij keeps its direction from P0.
    pub camera: Option<Camera>,
}

impl Drawing {
    fn line(&mut self, a: Vec3, b: Vec3, color: Color32, width: f32) {
        // The shader writes these values as they are: premultiplied sRGB.
        let c = color.to_array().map(|v| f32::from(v) / 255.0);
        self.segments
            .push([a.x, a.y, a.z, b.x, b.y, b.z, c[0], c[1], c[2], c[3], width]);
    }

    fn label(&mut self, at: Vec3, text: impl Into<String>, color: Color32) {
        self.labels.push(Label {
            at,
            text: text.into(),
            color,
        });
    }

    fn marker(&mut self, at: Vec3, color: Color32) {
        self.markers.push(Marker { at, color });
    }
}

/// The centre and radius of a sphere around the scene's bounded objects and
/// the eye P0 (infinite planes do not count).
fn scene_sphere(objects: &[ResolvedObject], eye: Vec3) -> (Vec3, f32) {
    let (mut lo, mut hi) = (eye, eye);
    for object in objects {
        if let Some(b) = scene::layout::bounds(&object.geometry) {
            lo = lo.min(b.min);
            hi = hi.max(b.max);
        }
    }
    (0.5 * (lo + hi), (0.5 * (hi - lo).length()).max(1e-2))
}

/// The smallest of 1, 2, 5, 10, 20, 50, … pixels between grid lines that
/// keeps at most [`MAX_GRID_LINES`] lines along the longer side.
pub fn grid_every(w: u32, h: u32) -> u32 {
    let longest = w.max(h);
    let mut step = 1u32;
    for k in 0.. {
        let candidate = [1, 2, 5][k % 3] * 10u32.saturating_pow((k / 3) as u32);
        step = candidate;
        if longest / candidate <= MAX_GRID_LINES {
            break;
        }
    }
    step
}

/// The four corners of the view window: C00, then clockwise as seen from P0
/// (top right, bottom right, bottom left).
pub fn window_corners(camera: &Camera) -> [Vec3; 4] {
    let right = camera.w_d * camera.r;
    let down = -camera.h_d * camera.u;
    [
        camera.c00,
        camera.c00 + right,
        camera.c00 + right + down,
        camera.c00 + down,
    ]
}

/// `camera` as the debug view draws it, and whether its window was moved:
/// a view window whose corners all lie within 4 radii of the scene's
/// centre is drawn where it is; one farther away (the lecture's default
/// d = h / (2 tan θ) puts it hundreds of units off for a scene of a few)
/// is drawn halfway from P0 to the scene's near side, its H_d, W_d and C00
/// scaled about P0 by the same factor, so that every P_ij, and so every
/// primary ray, keeps its direction: the picture is the same for any d.
pub fn shown_camera(camera: &Camera, centre: Vec3, radius: f32) -> (Camera, bool) {
    let near = window_corners(camera)
        .iter()
        .all(|c| c.distance(centre) < 4.0 * radius);
    if near {
        return (*camera, false);
    }
    let shown_d = (0.5 * (camera.p0.distance(centre) - radius)).max(0.3 * radius);
    (camera.with_window_at(shown_d), true)
}

/// Builds the drawing.
pub fn build(inputs: &Inputs<'_>) -> Drawing {
    let options = inputs.options;
    let traced = &inputs.world.camera;
    let (centre, radius) = scene_sphere(inputs.objects, traced.p0);
    let (shown, moved) = shown_camera(traced, centre, radius);
    let camera = &shown;
    let mut drawing = Drawing::default();
    objects(&mut drawing, inputs, centre, radius);
    if options.grid {
        ground(&mut drawing, centre, radius);
    }
    camera_and_window(&mut drawing, camera, traced.d, moved, options, radius);
    for (k, light) in inputs.world.lights.iter().enumerate() {
        if let renderer::world::light::Light::Point { position, .. } = light {
            drawing.marker(*position, palette::SHADOW_FREE);
            drawing.label(*position, format!("light {k}"), palette::SHADOW_FREE);
        }
    }
    sky(&mut drawing, &inputs.world.environment, centre, radius);
    fan(&mut drawing, inputs, radius);
    if let Some([i, j]) = inputs.pixel {
        let p_ij = camera.pixel_center(i, j);
        drawing.marker(p_ij, palette::PRIMARY);
        drawing.label(p_ij, format!("P_ij ({i}, {j})"), palette::PRIMARY);
    }
    rays(&mut drawing, inputs.rays, radius, camera.d / traced.d);
    drawing.camera = Some(shown);

    drawing.frame_points = vec![centre - Vec3::splat(radius), centre + Vec3::splat(radius)];
    drawing.frame_points.push(camera.p0);
    // The window as drawn is framed too (it is near the scene, or moved there).
    drawing.frame_points.extend(window_corners(camera));
    drawing
}

fn objects(drawing: &mut Drawing, inputs: &Inputs<'_>, centre: Vec3, radius: f32) {
    let mut mesh: Vec<MeshVertex> = Vec::new();
    let as_boxes = inputs.objects.len() > OBJECTS_DRAWN_IN_FULL;
    for (index, geometry) in inputs.objects.iter().map(|o| &o.geometry).enumerate() {
        mesh.clear();
        if as_boxes {
            tessellate_bounds(geometry, centre, 2.0 * radius, &mut mesh);
        } else {
            tessellate(geometry, centre, 2.0 * radius, &mut mesh);
        }
        let selected = inputs.selected_object == Some(index);
        let base = inputs.world.object_color(index as u32);
        // An infinite plane is only a backdrop here: dimmed so it does not outshine the rest.
        let color = if matches!(geometry, Geometry::Plane { .. }) {
            0.3 * base
        } else {
            base
        };
        if inputs.options.solid {
            drawing.triangles.extend(mesh.iter().map(|v| {
                [
                    v.position.x,
                    v.position.y,
                    v.position.z,
                    v.normal.x,
                    v.normal.y,
                    v.normal.z,
                    color.x,
                    color.y,
                    color.z,
                ]
            }));
        }
        if selected && let Some(b) = scene::layout::bounds(geometry) {
            box_edges(drawing, b.min, b.max, palette::SELECTED);
        }
        if !inputs.options.solid {
            let [r, g, b] = scene_srgb(base);
            let wire = Color32::from_rgb(r, g, b);
            for tri in mesh.chunks_exact(3) {
                for k in 0..3 {
                    drawing.line(tri[k].position, tri[(k + 1) % 3].position, wire, 1.0);
                }
            }
        }
    }
}

/// The twelve edges of the axis-aligned box from `min` to `max`.
fn box_edges(drawing: &mut Drawing, min: Vec3, max: Vec3, color: Color32) {
    let corner = |k: usize| {
        Vec3::new(
            if k & 1 == 0 { min.x } else { max.x },
            if k & 2 == 0 { min.y } else { max.y },
            if k & 4 == 0 { min.z } else { max.z },
        )
    };
    for a in 0..8 {
        for bit in [1, 2, 4] {
            if a & bit == 0 {
                drawing.line(corner(a), corner(a | bit), color, 2.0);
            }
        }
    }
}

/// A linear colour as 8-bit sRGB, lifted so dark materials stay visible as lines.
fn scene_srgb(linear: Vec3) -> [u8; 3] {
    let c = Color32::from(egui::Rgba::from_rgb(linear.x, linear.y, linear.z));
    let lift = |v: u8| v.max(60);
    [lift(c.r()), lift(c.g()), lift(c.b())]
}

/// A ground grid in the plane y = 0 around the scene and the world axes at the origin.
fn ground(drawing: &mut Drawing, centre: Vec3, radius: f32) {
    let step = 10f32.powf((radius / 4.0).log10().floor());
    let half = (2.0 * radius / step).ceil() * step;
    let (cx, cz) = (
        (centre.x / step).round() * step,
        (centre.z / step).round() * step,
    );
    let lines = (2.0 * half / step).round() as i32;
    let grey = Color32::from_rgba_premultiplied(90, 90, 90, 160);
    for k in 0..=lines {
        let offset = -half + k as f32 * step;
        drawing.line(
            Vec3::new(cx + offset, 0.0, cz - half),
            Vec3::new(cx + offset, 0.0, cz + half),
            grey,
            1.0,
        );
        drawing.line(
            Vec3::new(cx - half, 0.0, cz + offset),
            Vec3::new(cx + half, 0.0, cz + offset),
            grey,
            1.0,
        );
    }
    let length = 0.3 * radius;
    for (axis, color, name) in [
        (Vec3::X, palette::R, "x"),
        (Vec3::Y, palette::U, "y"),
        (Vec3::Z, palette::T, "z"),
    ] {
        drawing.line(Vec3::ZERO, axis * length, color, 2.0);
        drawing.label(axis * length, name, color);
    }
}

/// An environment map's orientation around the scene's centre: its
/// horizon (the map's middle row) as a circle, arrows to its zenith (the
/// top row), its azimuth origin (column 0's edge, φ = 0) and φ = 90°, and a
/// line toward its brightest texel (a sun).
fn sky(drawing: &mut Drawing, environment: &renderer::Environment, centre: Vec3, radius: f32) {
    let Some(o) = environment.map_orientation() else {
        return;
    };
    let reach = 1.4 * radius;
    let color = palette::SKY;
    let (a, b) = (o.azimuth_zero, o.azimuth_quarter);
    let segments = 64;
    for k in 0..segments {
        let angle = |k: i32| std::f32::consts::TAU * k as f32 / segments as f32;
        let at = |t: f32| centre + reach * (t.cos() * a + t.sin() * b);
        drawing.line(at(angle(k)), at(angle(k + 1)), color, 1.0);
    }
    for (dir, name) in [
        (o.zenith, "sky θ = 0"),
        (o.azimuth_zero, "sky φ = 0"),
        (o.azimuth_quarter, "sky φ = 90°"),
    ] {
        drawing.line(centre, centre + reach * dir, color, 2.0);
        drawing.label(centre + reach * dir, name, color);
    }
    let sun = centre + 1.8 * radius * o.brightest;
    drawing.line(centre, sun, palette::PRIMARY, 1.0);
    drawing.marker(sun, palette::PRIMARY);
    drawing.label(sun, "sky's brightest", palette::PRIMARY);
}

/// The camera at P0 with t, u, r, the view volume and the view window.
fn camera_and_window(
    drawing: &mut Drawing,
    camera: &Camera,
    traced_d: f32,
    moved: bool,
    options: DrawOptions,
    radius: f32,
) {
    let p0 = camera.p0;
    let length = 0.25 * radius;
    drawing.marker(p0, palette::WINDOW);
    drawing.label(p0, "P0", palette::WINDOW);
    for (axis, color, name) in [
        (camera.t, palette::T, "t"),
        (camera.u, palette::U, "u"),
        (camera.r, palette::R, "r"),
    ] {
        drawing.line(p0, p0 + axis * length, color, 3.0);
        drawing.label(p0 + axis * length, name, color);
    }

    let corners = window_corners(camera);
    // The view volume: from P0 through the window's corners, on to the far
    // side of the scene when the window is nearer than that.
    let reach = p0.distance(corners[0]).max(2.5 * radius);
    let faint = Color32::from_rgba_premultiplied(140, 140, 160, 150);
    for &corner in &corners {
        let dir = (corner - p0).normalize_or_zero();
        drawing.line(p0, corner, palette::WINDOW, 1.0);
        if reach > p0.distance(corner) {
            drawing.line(corner, p0 + dir * reach, faint, 1.0);
        }
    }
    for k in 0..4 {
        drawing.line(corners[k], corners[(k + 1) % 4], palette::WINDOW, 2.0);
    }
    drawing.grid_every = grid_every(camera.w, camera.h);
    if options.pixel_grid {
        let every = drawing.grid_every;
        let grid = Color32::from_rgba_premultiplied(150, 150, 150, 170);
        let right = camera.r * (camera.w_d / camera.w as f32);
        let down = -camera.u * (camera.h_d / camera.h as f32);
        for i in (every..camera.w).step_by(every as usize) {
            let top = camera.c00 + right * i as f32;
            drawing.line(top, top + down * camera.h as f32, grid, 1.0);
        }
        for j in (every..camera.h).step_by(every as usize) {
            let left = camera.c00 + down * j as f32;
            drawing.line(left, left + right * camera.w as f32, grid, 1.0);
        }
    }
    drawing.marker(camera.c00, palette::C00);
    drawing.label(camera.c00, "C00", palette::C00);
    let mid_top = 0.5 * (corners[0] + corners[1]);
    let text = if moved {
        format!(
            "view window drawn at d = {} (d = {})",
            short(camera.d),
            short(traced_d)
        )
    } else {
        format!("view window, d = {}", short(camera.d))
    };
    drawing.label(mid_top, text, palette::WINDOW);
}

/// A number short enough for a label.
fn short(x: f32) -> String {
    if x.abs() >= 100.0 {
        format!("{x:.0}")
    } else {
        format!("{x:.3}")
    }
}

/// A fan of primary rays through P_ij of many pixels, to their first hits.
fn fan(drawing: &mut Drawing, inputs: &Inputs<'_>, radius: f32) {
    let camera = &inputs.world.camera;
    let every = inputs.options.fan_every.max(1);
    let pixels: Vec<[u32; 2]> = match (inputs.options.fan, inputs.pixel) {
        (Fan::Off, _) => Vec::new(),
        (Fan::Sparse, _) => (every / 2..camera.h)
            .step_by(every as usize)
            .flat_map(|j| {
                (every / 2..camera.w)
                    .step_by(every as usize)
                    .map(move |i| [i, j])
            })
            .collect(),
        (Fan::Row, Some([_, j])) => (0..camera.w)
            .step_by(every as usize)
            .map(|i| [i, j])
            .collect(),
        (Fan::Column, Some([i, _])) => (0..camera.h)
            .step_by(every as usize)
            .map(|j| [i, j])
            .collect(),
        (Fan::Row | Fan::Column, None) => Vec::new(),
    };
    let color = Color32::from_rgba_premultiplied(200, 175, 50, 170);
    for [i, j] in pixels {
        let ray = camera.center_ray(i, j);
        let end = match inputs.world.intersect(&ray, renderer::Method::Robust) {
            Some(hit) => ray.at(hit.alpha),
            None => ray.at(3.0 * radius),
        };
        drawing.line(ray.origin, end, color, 1.0);
    }
}

/// The selected pixel's rays, each coloured by kind, with the normal at each hit.
fn rays(drawing: &mut Drawing, rays: &[DrawnRay], radius: f32, window_scale: f32) {
    for ray in rays {
        let (color, width) = match ray.kind {
            RayKind::Primary => (palette::PRIMARY, 3.0),
            RayKind::Shadow { blocked: false } => (palette::SHADOW_FREE, 2.0),
            RayKind::Shadow { blocked: true } => (palette::SHADOW_BLOCKED, 2.0),
            RayKind::Reflection => (palette::REFLECTION, 2.5),
            RayKind::Refraction => (palette::REFRACTION, 2.5),
        };
        let to = ray.from + ray.dir * ray.length.unwrap_or(3.0 * radius);
        drawing.line(ray.from, to, color, width);
        // The window point on the window as drawn (scaled about P0, the
        // primary ray's origin, with the window).
        let window_point = ray
            .window_point
            .map(|w| ray.from + (w - ray.from) * window_scale);
        if let Some(window) = window_point
            && window.distance(ray.from) > to.distance(ray.from)
        {
            // The ray's way on from its hit to the view window it passed through.
            drawing.line(to, window, color.gamma_multiply(0.35), 1.0);
        }
        if let Some(normal) = ray.normal {
            drawing.line(to, to + normal * 0.2 * radius, palette::NORMAL, 2.0);
            drawing.marker(to, color);
        }
    }
}

#[cfg(test)]
mod tests;
