//! The pixel inspector: pixel (i, j), P_ij and v_ij, the pixel's accumulated
//! colour, the lecture's equations with the current numbers, and the ray
//! tree of one sample — every ray's kind, origin, direction, what it hit, α,
//! the hit point, the normal, β and γ or the sphere's roots, the material and
//! the colour it contributes.

use super::pixel::InspectedPixel;
use glam::Vec3;
use renderer::inspect::{RayNode, ShadowTarget, SurfaceHit};
use renderer::integrator::{Integrator, RayKind};
use renderer::{Camera, Inspection};

/// What the panel needs besides the inspection.
pub struct Context<'a> {
    /// The camera the inspection was traced with.
    pub camera: &'a Camera,
    /// The pixel's mean colour in the image on screen, and its samples per pixel.
    pub accumulated: Option<(Vec3, u32)>,
    /// The world's lights, by index (shadow rays name theirs).
    pub lights: &'a [renderer::world::light::Light],
}

/// A vector with three decimals.
fn v3(v: Vec3) -> String {
    format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z)
}

/// A number with three decimals.
fn n(x: f32) -> String {
    format!("{x:.3}")
}

/// Shows the inspector for `inspected`; returns false when the user closed it.
pub fn show(
    ui: &mut egui::Ui,
    inspected: &mut InspectedPixel,
    inspection: &Inspection,
    cx: &Context<'_>,
) -> bool {
    let mut open = true;
    let [i, j] = inspected.pixel;
    ui.horizontal(|ui| {
        ui.strong(format!("Pixel ({i}, {j})"));
        ui.checkbox(&mut inspected.pinned, "Pin")
            .on_hover_text("Keep (i, j) when the camera changes; unpinned, the inspector follows the surface point");
        if ui.small_button("Close").clicked() {
            open = false;
        }
    });
    if let Some((color, spp)) = cx.accumulated {
        ui.horizontal(|ui| {
            swatch(ui, color);
            ui.label(format!("accumulated colour {} over {spp} spp", v3(color)));
        });
    }
    sample_picker(ui, inspected, cx.accumulated.map_or(0, |(_, spp)| spp));
    ui.separator();
    equations(ui, inspection, cx.camera);
    ui.separator();
    ui.horizontal(|ui| {
        swatch(ui, inspection.color);
        ui.label(format!(
            "sample colour {} ({})",
            v3(inspection.color),
            integrator_name(inspection.integrator)
        ));
    });
    ui.label(format!(
        "Σ contributions {} (the rays below add up to the sample)",
        v3(inspection.contribution_sum())
    ));
    ray_tree(ui, inspection, cx);
    open
}

/// How the sample was traced, as the inspector says it.
fn integrator_name(integrator: Integrator) -> &'static str {
    match integrator {
        Integrator::Whitted => "Whitted",
        Integrator::Path => "path traced",
    }
}

/// A small square of a linear colour.
fn swatch(ui: &mut egui::Ui, linear: Vec3) {
    let c = egui::Color32::from(egui::Rgba::from_rgb(linear.x, linear.y, linear.z));
    let (rect, _) = ui.allocate_exact_size(egui::vec2(14.0, 14.0), egui::Sense::hover());
    ui.painter().rect_filled(rect, 2.0, c);
}

/// Centre ray or sample k, with buttons to step between samples.
fn sample_picker(ui: &mut egui::Ui, inspected: &mut InspectedPixel, spp: u32) {
    ui.horizontal(|ui| {
        let mut centre = inspected.sample.is_none();
        if ui
            .radio_value(&mut centre, true, "ray through P_ij")
            .on_hover_text(
                "The ray through the pixel centre, the ray of the depth, normal and albedo modes",
            )
            .changed()
        {
            inspected.sample = None;
        }
        if ui.radio_value(&mut centre, false, "sample").changed() {
            inspected.sample = Some(0);
        }
        if let Some(k) = &mut inspected.sample {
            let last = spp.max(1) - 1;
            if ui
                .small_button("<")
                .on_hover_text("previous sample")
                .clicked()
            {
                *k = k.saturating_sub(1);
            }
            ui.add(egui::DragValue::new(k).range(0..=last).prefix("k = "));
            if ui.small_button(">").on_hover_text("next sample").clicked() {
                *k = (*k + 1).min(last);
            }
            ui.weak(format!("of {}", last + 1));
        }
    });
}

/// The lecture's camera equations, then the primary hit's, with the numbers filled in.
fn equations(ui: &mut egui::Ui, inspection: &Inspection, c: &Camera) {
    let (i, j) = (inspection.i, inspection.j);
    let mono = |ui: &mut egui::Ui, text: String| {
        ui.label(egui::RichText::new(text).monospace());
    };
    mono(
        ui,
        format!(
            "C00 = P0 + d t + (H_d/2) u − (W_d/2) r\n    = {} + {} {} + {} {} − {} {}\n    = {}",
            v3(c.p0),
            n(c.d),
            v3(c.t),
            n(c.h_d / 2.0),
            v3(c.u),
            n(c.w_d / 2.0),
            v3(c.r),
            v3(c.c00)
        ),
    );
    mono(
        ui,
        format!(
            "P_ij = C00 + (i + ½)(W_d/w) r − (j + ½)(H_d/h) u\n     = {} + {} · {} {} − {} · {} {}\n     = {}",
            v3(c.c00),
            i as f32 + 0.5,
            n(c.w_d / c.w as f32),
            v3(c.r),
            j as f32 + 0.5,
            n(c.h_d / c.h as f32),
            v3(c.u),
            v3(inspection.p_ij)
        ),
    );
    if inspection.sample.is_some() {
        mono(
            ui,
            format!(
                "jittered: ½ -> ({:.3}, {:.3}), window point {}",
                inspection.offset.x,
                inspection.offset.y,
                v3(inspection.window_point)
            ),
        );
    }
    mono(
        ui,
        format!("v_ij = (P − P0) / |P − P0| = {}", v3(inspection.v_ij)),
    );
    if let Some(hit) = &inspection.primary().hit {
        mono(ui, hit_equation(hit));
    } else {
        mono(
            ui,
            "R_ij misses every object: it sees the background".to_owned(),
        );
    }
}

/// The intersection equation of a hit with its solution.
fn hit_equation(hit: &SurfaceHit) -> String {
    let solved = format!(
        "α = {}, P = P0 + α v = {}, n = {}{}",
        n(hit.alpha),
        v3(hit.point),
        v3(hit.normal),
        if hit.front { "" } else { " (back side)" }
    );
    if let Some(q) = &hit.sphere {
        let roots = q.roots.map_or("none".to_owned(), |r| {
            format!("{} and {}", n(r.near), n(r.far))
        });
        format!(
            "sphere: |v|² α² − 2 (u·v) α + |u|² − r² = 0, u = C − P0\n  a = {}, b = {}, c = {}, b² − 4ac = {}\n  roots α = {roots}\n  {solved}",
            n(q.a),
            n(q.b),
            n(q.c),
            n(q.discriminant),
        )
    } else if let Some(b) = &hit.barycentrics {
        format!(
            "triangle: P0 + α v = t0 + β v1 + γ v2\n  β = {}, γ = {}, 1 − β − γ = {}\n  {solved}",
            n(b.beta),
            n(b.gamma),
            n(1.0 - b.beta - b.gamma)
        )
    } else {
        format!("{}: {solved}", hit.shape)
    }
}

/// One collapsible entry per ray, children indented under their parent.
fn ray_tree(ui: &mut egui::Ui, inspection: &Inspection, cx: &Context<'_>) {
    for (index, ray) in inspection.rays.iter().enumerate() {
        let indent = 14.0 * depth_in_tree(inspection, index) as f32;
        ui.horizontal(|ui| {
            ui.add_space(indent);
            ui.vertical(|ui| {
                egui::CollapsingHeader::new(title(index, ray, cx))
                    .id_salt(("ray", index))
                    .default_open(index == 0)
                    .show(ui, |ui| details(ui, ray));
            });
        });
    }
}

/// How many ancestors a ray has.
fn depth_in_tree(inspection: &Inspection, mut index: usize) -> usize {
    let mut depth = 0;
    while let Some(parent) = inspection.rays[index].parent {
        depth += 1;
        index = parent;
    }
    depth
}

fn kind_name(kind: RayKind) -> &'static str {
    match kind {
        RayKind::Primary => "primary",
        RayKind::Shadow => "shadow",
        RayKind::Reflection => "reflection",
        RayKind::Refraction => "refraction",
    }
}

fn title(index: usize, ray: &RayNode, cx: &Context<'_>) -> String {
    let kind = kind_name(ray.kind);
    match (&ray.hit, &ray.shadow) {
        (Some(hit), _) => format!(
            "#{index} {kind} -> {} ({}), α = {}",
            hit.object.name,
            hit.shape,
            n(hit.alpha)
        ),
        (None, Some(shadow)) => {
            let light = target_label(shadow.target, cx);
            match &shadow.blocker {
                Some(b) => format!(
                    "#{index} {kind} -> {light}: blocked by {} at α = {}",
                    b.object.name,
                    n(b.alpha)
                ),
                None if shadow.blocked => format!("#{index} {kind} -> {light}: blocked"),
                None => format!("#{index} {kind} -> {light}: reaches it"),
            }
        }
        (None, None) => format!("#{index} {kind} -> misses (background)"),
    }
}

/// What a shadow ray goes toward, as the ray tree names it.
fn target_label(target: ShadowTarget, cx: &Context<'_>) -> String {
    match target {
        ShadowTarget::Light(k) => cx
            .lights
            .get(k)
            .map(|light| light_label(k, light))
            .unwrap_or_else(|| format!("light {k}")),
        ShadowTarget::Emitter(sample) => format!("emitter {}", sample.index),
        ShadowTarget::Environment(_) => "sky".to_string(),
    }
}

/// Light `k`'s name in the ray tree: its kind, and where a point light is.
fn light_label(k: usize, light: &renderer::world::light::Light) -> String {
    match light {
        renderer::world::light::Light::Point { position, .. } => {
            format!("point light {k} at {}", v3(*position))
        }
        renderer::world::light::Light::Directional { .. } => format!("directional light {k}"),
        renderer::world::light::Light::Ambient { .. } => format!("ambient light {k}"),
    }
}

fn details(ui: &mut egui::Ui, ray: &RayNode) {
    egui::Grid::new(("ray details", std::ptr::from_ref(ray) as usize))
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            let mut row = |name: &str, value: String| {
                ui.label(name);
                ui.label(egui::RichText::new(value).monospace());
                ui.end_row();
            };
            row("origin", v3(ray.origin));
            row("direction v", v3(ray.direction));
            if ray.t_max.is_finite() {
                row("t_max", n(ray.t_max));
            }
            if let Some(hit) = &ray.hit {
                row(
                    "object",
                    format!("{} (#{}), {}", hit.object.name, hit.object.index, hit.shape),
                );
                row("α", n(hit.alpha));
                row("hit point", v3(hit.point));
                row(
                    "normal",
                    format!(
                        "{}{}",
                        v3(hit.normal),
                        if hit.front { "" } else { " (hit from behind)" }
                    ),
                );
                if let Some(b) = &hit.barycentrics {
                    row("β, γ", format!("{}, {}", n(b.beta), n(b.gamma)));
                }
                if let Some(q) = &hit.sphere {
                    row(
                        "roots",
                        q.roots.map_or("none".to_owned(), |r| {
                            format!("{}, {}", n(r.near), n(r.far))
                        }),
                    );
                }
                let m = &hit.material;
                row(
                    "material",
                    format!(
                        "{} {}, reflectivity {}, ior {}, roughness {}",
                        m.base,
                        v3(m.color),
                        n(m.reflectivity),
                        n(m.ior),
                        n(m.roughness)
                    ),
                );
                if hit.depth_limited {
                    row("note", "max depth reached: no further bounce".to_owned());
                }
                if hit.total_internal_reflection {
                    row("note", "total internal reflection".to_owned());
                }
                if hit.negligible {
                    row(
                        "note",
                        "a bounce left untraced: its weight in the pixel is negligible".to_owned(),
                    );
                }
                if let Some(weight) = hit.emission_weight {
                    row("emission MIS weight", n(weight));
                }
                if let Some(r) = hit.roulette {
                    let verdict = if r.survived { "went on" } else { "ended" };
                    row(
                        "Russian roulette",
                        format!("kept with p = {}: {verdict}", n(r.keep)),
                    );
                }
                if hit.absorbed {
                    row(
                        "note",
                        "the BSDF sample carried no light: path ended".to_owned(),
                    );
                }
            }
            if let Some(s) = &ray.scatter {
                row(
                    "BSDF sample",
                    format!(
                        "{:?} lobe, pdf {}, f·cos/pdf {}",
                        s.lobe,
                        n(s.pdf),
                        v3(s.bsdf_weight)
                    ),
                );
            }
            if let Some(shadow) = &ray.shadow {
                match shadow.target {
                    ShadowTarget::Light(k) => row("light", format!("#{k}")),
                    ShadowTarget::Emitter(e) => {
                        row("emitter", format!("#{}", e.index));
                        row("pdf (solid angle)", n(e.pdf));
                        row("MIS weight", n(e.mis_weight));
                    }
                    ShadowTarget::Environment(e) => {
                        row("toward", "the sky".to_string());
                        row("pdf (solid angle)", n(e.pdf));
                        row("MIS weight", n(e.mis_weight));
                    }
                }
                row("blocked", shadow.blocked.to_string());
            }
            row("weight", v3(ray.weight));
            row("contribution", v3(ray.contribution));
        });
}
