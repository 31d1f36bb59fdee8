//! The rays the debug view draws, and the inspector's ray tree turned into
//! them.

use glam::Vec3;
use renderer::Inspection;
use renderer::integrator::RayKind as Traced;

/// Which kind of ray a drawn segment is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayKind {
    /// From P0 through the view window.
    Primary,
    /// Toward a light; `blocked` when something lies in between.
    Shadow {
        /// Stopped at a blocker.
        blocked: bool,
    },
    /// Mirror reflection.
    Reflection,
    /// Refraction into or out of glass.
    Refraction,
}

/// One ray of the selected pixel, ready to draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawnRay {
    /// Which kind.
    pub kind: RayKind,
    /// Where it starts.
    pub from: Vec3,
    /// Its unit direction.
    pub dir: Vec3,
    /// How far it goes: to its hit, its light or its blocker; `None` when it
    /// goes on without end (a miss, or toward a directional light).
    pub length: Option<f32>,
    /// The unit normal at its end when the ray hit a surface there.
    pub normal: Option<Vec3>,
    /// For primary rays: the point on the view window it passes through.
    pub window_point: Option<Vec3>,
}

/// Every ray of `inspection`, from its origin to what it hit, to its light,
/// or to its blocker; misses and rays toward directional lights go on.
pub fn drawn_rays(inspection: &Inspection) -> impl Iterator<Item = DrawnRay> + '_ {
    inspection.rays.iter().map(|node| {
        let blocked = node.shadow.as_ref().is_some_and(|s| s.blocked);
        let kind = match node.kind {
            Traced::Primary => RayKind::Primary,
            Traced::Shadow => RayKind::Shadow { blocked },
            Traced::Reflection => RayKind::Reflection,
            Traced::Refraction => RayKind::Refraction,
        };
        let length = match (&node.hit, &node.shadow) {
            (Some(hit), _) => Some(hit.alpha),
            (None, Some(shadow)) => match &shadow.blocker {
                Some(blocker) => Some(blocker.alpha),
                None => Some(node.t_max).filter(|t| t.is_finite()),
            },
            (None, None) => None,
        };
        DrawnRay {
            kind,
            from: node.origin,
            dir: node.direction,
            length,
            normal: node.hit.as_ref().map(|hit| hit.normal),
            window_point: (node.kind == Traced::Primary).then_some(inspection.window_point),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderer::integrator::Integrator;

    /// The Cornell box of the references (open toward the camera) at 16 × 16.
    fn cornell() -> renderer::World {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../assets/reference/cornell.xml");
        let mut scene = scene::read_file(&path).expect("the Cornell box loads");
        scene.camera.width = 16;
        scene.camera.height = 16;
        renderer::World::from_scene(&scene).expect("the Cornell box renders")
    }

    #[test]
    fn a_path_traced_sample_draws_its_bounces_and_its_light_samples() {
        let world = cornell();
        let options = renderer::RenderOptions {
            integrator: Integrator::Path,
            ..Default::default()
        };
        // A pixel on the back wall: diffuse bounces, with light samples.
        let inspection = renderer::inspect_pixel(&world, &options, 8, 6, Some(0)).expect("inside");
        let rays: Vec<DrawnRay> = drawn_rays(&inspection).collect();
        assert_eq!(rays.len(), inspection.rays.len(), "one segment per ray");
        let bounces = rays
            .iter()
            .filter(|r| r.kind == RayKind::Reflection)
            .count();
        let shadows = rays
            .iter()
            .filter(|r| matches!(r.kind, RayKind::Shadow { .. }))
            .count();
        assert!(bounces >= 1 && shadows >= 1, "{rays:?}");
        // A ray that hit ends at its hit point, a shadow ray at its light
        // point or its blocker; only a ray out of the open front goes on.
        for (ray, node) in rays.iter().zip(&inspection.rays) {
            match (&node.hit, ray.length) {
                (Some(hit), Some(length)) => {
                    let end = ray.from + ray.dir * length;
                    assert!((end - hit.point).length() < 1e-3, "{ray:?} ends at its hit");
                }
                (None, length) if node.shadow.is_some() => {
                    assert!(length.is_some_and(|l| l > 0.0 && l < 4.0), "{ray:?}");
                }
                (None, None) => assert!(ray.dir.z > 0.0, "{ray:?} leaves by the open front"),
                _ => panic!("{ray:?}: a hit without a length"),
            }
        }
    }
}
