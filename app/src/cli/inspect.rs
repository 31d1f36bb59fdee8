//! `raylab inspect`: one sample of one pixel re-traced as a ray tree, printed
//! as pretty JSON (the renderer's [`renderer::Inspection`]).

use super::args::InspectArgs;
use super::prepare::{UserError, prepare};
use anyhow::Result;
use renderer::inspect_pixel;

/// Inspects the pixel `args` names and returns the inspection as pretty JSON.
pub fn run(args: &InspectArgs) -> Result<String> {
    let &[i, j] = args.pixel.as_slice() else {
        return Err(UserError(format!(
            "--pixel takes two numbers, I and J; got {:?}",
            args.pixel
        ))
        .into());
    };
    let (world, options, _) = prepare(&args.scene)?;
    let inspection = inspect_pixel(&world, &options, i, j, args.sample)
        .map_err(|e| UserError(format!("{}: {e}", args.scene.scene.display())))?;
    Ok(serde_json::to_string_pretty(&inspection)?)
}
