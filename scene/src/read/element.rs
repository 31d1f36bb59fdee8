//! One start tag: its name, its attributes (checked against the names the
//! element takes) and typed access to their values, with errors at the value.

use super::position::Locator;
use super::values::{self, Range};
use crate::SceneError;
use crate::color::parse_color;
use crate::model::MaterialParams;
use crate::suggest::did_you_mean;
use glam::Vec3;
use quick_xml::XmlVersion;
use quick_xml::events::BytesStart;
use quick_xml::events::attributes::AttrError;
use std::borrow::Cow;

/// One attribute: its name, its value (entities replaced) and where both are.
struct Attr {
    name: String,
    value: String,
    /// Byte offset of the value's first character.
    at: usize,
}

/// A start (or empty-element) tag with validated attribute names.
pub(crate) struct Element<'a> {
    loc: &'a Locator<'a>,
    /// The element name.
    pub tag: String,
    /// Byte offset of the tag's `<`.
    pub at: usize,
    attrs: Vec<Attr>,
}

impl<'a> Element<'a> {
    /// Reads the tag's attributes; an attribute not in `allowed` is an error
    /// that suggests the closest allowed name.
    pub fn parse(
        start: &BytesStart<'_>,
        loc: &'a Locator<'a>,
        allowed: &[&str],
    ) -> Result<Self, SceneError> {
        let name = start.name().0;
        let name_at = loc.offset_of(name).unwrap_or(0);
        let tag = name.to_owned();
        let mut attrs = Vec::new();
        for attr in start.attributes() {
            let attr = attr.map_err(|e| attr_error(loc, name, name_at, &e))?;
            let key = attr.key.0;
            let key_at = loc.offset_of(key).unwrap_or(name_at);
            if !allowed.contains(&key) {
                let message = if allowed.is_empty() {
                    format!("<{tag}> takes no attributes, got {key:?}")
                } else if key.starts_with('<') {
                    format!("unexpected \"<\" inside <{tag}>; is this tag missing its \">\"?")
                } else {
                    format!(
                        "unknown attribute {key:?} on <{tag}>{} (expected one of: {})",
                        did_you_mean(key, allowed.iter().copied()),
                        allowed.join(", ")
                    )
                };
                return Err(loc.error(key_at, message));
            }
            let at = match &attr.value {
                Cow::Borrowed(raw) => loc.offset_of(raw),
                Cow::Owned(_) => None,
            }
            .unwrap_or(key_at);
            let value = attr
                .normalized_value(XmlVersion::Implicit1_0)
                .map_err(|e| loc.error(at, format!("bad entity or character reference: {e}")))?;
            attrs.push(Attr {
                name: key.to_owned(),
                value: value.into_owned(),
                at,
            });
        }
        Ok(Element {
            loc,
            tag,
            at: name_at.saturating_sub(1),
            attrs,
        })
    }

    /// The attribute's value and the offset of its first character.
    pub fn raw(&self, name: &str) -> Option<(&str, usize)> {
        self.attrs
            .iter()
            .find(|a| a.name == name)
            .map(|a| (a.value.as_str(), a.at))
    }

    /// The attribute's value as a string.
    pub fn string(&self, name: &str) -> Option<String> {
        self.raw(name).map(|(v, _)| v.to_owned())
    }

    /// The attribute's value passed through `parse`, whose message becomes an
    /// error at the value.
    pub fn parsed<T>(
        &self,
        name: &str,
        parse: impl FnOnce(&str, &str) -> Result<T, String>,
    ) -> Result<Option<T>, SceneError> {
        match self.raw(name) {
            None => Ok(None),
            Some((text, at)) => parse(name, text)
                .map(Some)
                .map_err(|message| self.loc.error(at, message)),
        }
    }

    /// A number in `range`.
    pub fn number(&self, name: &str, range: Range) -> Result<Option<f32>, SceneError> {
        self.parsed(name, |n, t| values::number(n, t, range))
    }

    /// Three finite numbers.
    pub fn vector(&self, name: &str) -> Result<Option<Vec3>, SceneError> {
        self.parsed(name, values::vector)
    }

    /// An error at the value of attribute `name` (or at the tag without one).
    pub fn error_at(&self, name: &str, message: impl Into<String>) -> SceneError {
        let at = self.raw(name).map_or(self.at, |(_, at)| at);
        self.loc.error(at, message)
    }

    /// The line and column of a byte offset in the same text.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        self.loc.line_column(offset)
    }

    /// An error at the tag's `<`.
    pub fn error(&self, message: impl Into<String>) -> SceneError {
        self.loc.error(self.at, message)
    }

    /// A colour; `emission` may exceed 1, `color` may not.
    pub fn color(&self, name: &str) -> Result<Option<Vec3>, SceneError> {
        self.parsed(name, |n, t| {
            let c = parse_color(t).map_err(|why| format!("{n}: {why}"))?;
            if n == "color" && c.max_element() > 1.0 {
                let hint = if self.tag == "sky" {
                    "a <sky> is at most white, 1 1 1; for more light, add a <light>"
                } else {
                    "for more light, raise intensity or emission"
                };
                return Err(format!(
                    "color components must be linear values from 0 to 1, got {t:?} ({hint})"
                ));
            }
            Ok(c)
        })
    }

    /// The material parameters (`color`, `ior`, …) given on this element.
    pub fn params(&self) -> Result<MaterialParams, SceneError> {
        Ok(MaterialParams {
            color: self.color("color")?,
            ior: self.number("ior", Range::Ior)?,
            shininess: self.number("shininess", Range::NonNegative)?,
            specular: self.number("specular", Range::Unit)?,
            reflectivity: self.number("reflectivity", Range::Unit)?,
            roughness: self.number("roughness", Range::Unit)?,
            emission: self.color("emission")?,
        })
    }
}

/// A malformed attribute as an error at its position in the tag.
/// A `<` before the problem usually means the tag lacks its `>`: say so there.
fn attr_error(loc: &Locator<'_>, tag: &str, name_at: usize, e: &AttrError) -> SceneError {
    let (pos, message) = match *e {
        AttrError::ExpectedEq(p) => (p, "expected \"=\" after the attribute name"),
        AttrError::ExpectedValue(p) => (p, "expected a quoted value after \"=\""),
        AttrError::UnquotedValue(p) => (p, "attribute values must be in quotes"),
        AttrError::ExpectedQuote(p, _) => (p, "the attribute value has no closing quote"),
        AttrError::Duplicated(p, _) => (p, "this attribute is given twice"),
    };
    let at = name_at + pos;
    let stray = loc.text.get(name_at..at).and_then(|t| t.find('<'));
    match stray {
        Some(i) => loc.error(
            name_at + i,
            format!("unexpected \"<\" inside <{tag}>; is this tag missing its \">\"?"),
        ),
        None => loc.error(at, message),
    }
}
