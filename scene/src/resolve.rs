//! PLACEHOLDER (being written): default filling.
use crate::{InvalidScene, ResolvedScene, Scene};
/// Fills in every default.
pub fn resolve(_scene: &Scene) -> Result<ResolvedScene, InvalidScene> { Err(InvalidScene("not written".into())) }
