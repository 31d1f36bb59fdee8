//! What the commands share: the error a user can fix, and reading a scene
//! with the command line's size overrides into a world and its options.

use super::args::SceneArgs;
use anyhow::Result;
use renderer::{RenderOptions, World};

/// A failure the user can fix, reported as one line with exit code 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UserError(pub String);

/// Reads the scene with the size overrides applied and prepares it, with
/// the options to trace it by; a scene that cannot be read or rendered is a [`UserError`].
pub fn prepare(args: &SceneArgs) -> Result<(World, RenderOptions, scene::View)> {
    let mut scene = scene::read_any(&args.scene).map_err(|e| UserError(e.to_string()))?;
    crate::io::output::warn_about_models(&scene);
    if let Some(w) = args.width {
        scene.camera.width = w;
    }
    if let Some(h) = args.height {
        scene.camera.height = h;
    }
    let world = World::from_scene(&scene)
        .and_then(|world| renderer::film::image_memory::check_world_fits(&world).map(|()| world))
        .map_err(|e| UserError(format!("{}: {e}", args.scene.display())))?;
    let options = RenderOptions {
        integrator: args.integrator.into(),
        method: args.method.into(),
        max_depth: args.max_depth,
        min_weight: if (0.0..=1.0).contains(&args.min_weight) {
            args.min_weight
        } else {
            return Err(UserError(format!(
                "--min-weight {}: the weight must be a number from 0 to 1",
                args.min_weight
            ))
            .into());
        },
        seed: args.seed,
        sampling: args.sampler.into(),
        adaptive: match args.adaptive {
            Some(threshold) if threshold > 0.0 && threshold.is_finite() => {
                Some(renderer::integrator::adaptive::Adaptive { threshold })
            }
            Some(threshold) => {
                return Err(UserError(format!(
                    "--adaptive {threshold}: the error threshold must be a positive number"
                ))
                .into());
            }
            None => None,
        },
    };
    Ok((world, options, scene.view))
}
