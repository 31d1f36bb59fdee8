//! `raylab inspect`: one sample of one pixel re-traced as a ray tree, printed
//! as pretty JSON (the renderer's [`renderer::Inspection`]).

use crate::cli::InspectArgs;
use crate::render_cmd::UserError;
use anyhow::Result;
use renderer::{RenderOptions, World, inspect_pixel};

/// Inspects the pixel `args` names and returns the inspection as pretty JSON.
pub fn run(args: &InspectArgs) -> Result<String> {
    let &[i, j] = args.pixel.as_slice() else {
        return Err(UserError(format!(
            "--pixel takes two numbers, I and J; got {:?}",
            args.pixel
        ))
        .into());
    };
    let mut scene = scene::read_file(&args.scene).map_err(|e| UserError(e.to_string()))?;
    if let Some(w) = args.width {
        scene.camera.width = w;
    }
    if let Some(h) = args.height {
        scene.camera.height = h;
    }
    let world = World::from_scene(&scene)
        .map_err(|e| UserError(format!("{}: {e}", args.scene.display())))?;
    let options = RenderOptions {
        method: args.method.into(),
        max_depth: args.max_depth,
        seed: args.seed,
    };
    let inspection = inspect_pixel(&world, &options, i, j, args.sample)
        .map_err(|e| UserError(format!("{}: {e}", args.scene.display())))?;
    Ok(serde_json::to_string_pretty(&inspection)?)
}
