//! PLACEHOLDER (being written): the XML scene writer.
use crate::Scene;
/// Writes a scene as XML, only non-default values, in a stable order.
pub fn write_string(_scene: &Scene) -> String { String::from("<scene>\n</scene>\n") }
