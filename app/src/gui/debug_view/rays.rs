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
