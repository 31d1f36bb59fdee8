//! The inspector's ray tree as segments for the debug view.

use super::drawing::{DrawnRay, RayKind};
use renderer::Inspection;
use renderer::integrator::RayKind as Traced;

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
