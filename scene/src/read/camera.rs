//! `<camera>`, `<light>` and `<sky>`.

use super::element::Element;
use super::values::{self, Range, parallel};
use crate::SceneError;
use crate::model::{
    Camera, Light, LightKind, STUDIO_MAP, Sky, SkyMap, Tonemap, View, defaults, studio_image,
};
use crate::sky_map::load_sky_map;
use crate::suggest::did_you_mean;
use glam::Vec3;
use std::path::Path;
use std::sync::Arc;

/// The attributes `<camera>` takes, in writing order.
pub(crate) const CAMERA_ATTRS: [&str; 7] = ["eye", "toward", "up", "theta", "d", "width", "height"];

/// The attributes `<light>` takes, in writing order.
pub(crate) const LIGHT_ATTRS: [&str; 6] = [
    "type",
    "position",
    "direction",
    "color",
    "intensity",
    "name",
];

/// The attributes `<sky>` takes, in writing order.
pub(crate) const SKY_ATTRS: [&str; 4] = ["color", "map", "rotate", "strength"];

/// The attributes of `<view>`.
pub(crate) const VIEW_ATTRS: [&str; 2] = ["exposure", "tonemap"];

/// The light types, by their scene-file names.
const LIGHT_TYPES: [&str; 3] = ["point", "directional", "ambient"];

/// A `<camera>`: unset attributes keep [`Camera::default`].
pub(crate) fn camera(el: &Element<'_>) -> Result<Camera, SceneError> {
    let pixels = |name: &str, default: u32| -> Result<u32, SceneError> {
        let side = el.parsed(name, |n, t| values::pixels(n, t, Camera::MAX_SIZE))?;
        Ok(side.unwrap_or(default))
    };
    let eye = el.vector("eye")?;
    let toward = el.parsed("toward", values::nonzero_vector)?;
    let up = el
        .parsed("up", values::nonzero_vector)?
        .unwrap_or(Camera::DEFAULT_UP);
    if let Some(toward) = toward
        && parallel(toward, up)
    {
        return Err(if el.raw("up").is_some() {
            el.error_at("up", "up must not be parallel to toward")
        } else {
            el.error_at(
                "toward",
                "toward must not be parallel to the default up vector (0 1 0); give an up vector",
            )
        });
    }
    Ok(Camera {
        eye,
        toward,
        up,
        theta_deg: el
            .number("theta", Range::OpenQuarterTurn)?
            .unwrap_or(Camera::DEFAULT_THETA_DEG),
        d: el.number("d", Range::Positive)?,
        width: pixels("width", Camera::DEFAULT_WIDTH)?,
        height: pixels("height", Camera::DEFAULT_HEIGHT)?,
    })
}

/// A `<light>`: a point light unless `type` says otherwise; unset attributes
/// take the type's defaults.
pub(crate) fn light(el: &Element<'_>) -> Result<Light, SceneError> {
    let kind_name = el.string("type").unwrap_or_else(|| "point".into());
    let (takes, refuses) = match kind_name.as_str() {
        "point" => ("position", ["direction", ""]),
        "directional" => ("direction", ["position", ""]),
        "ambient" => ("", ["position", "direction"]),
        other => {
            return Err(el.error_at(
                "type",
                format!(
                    "type must be point, directional or ambient, got {other:?}{}",
                    did_you_mean(other, LIGHT_TYPES)
                ),
            ));
        }
    };
    if let Some(bad) = refuses
        .into_iter()
        .find(|a| !a.is_empty() && el.raw(a).is_some())
    {
        let hint = if takes.is_empty() {
            "an ambient light takes only color, intensity and name".to_owned()
        } else {
            format!("a {kind_name} light takes {takes}")
        };
        return Err(el.error_at(
            bad,
            format!("{bad} does not apply to a {kind_name} light; {hint}"),
        ));
    }
    let kind = match kind_name.as_str() {
        "point" => LightKind::Point {
            position: el.vector("position")?.unwrap_or(defaults::LIGHT_POSITION),
        },
        "directional" => LightKind::Directional {
            direction: el
                .parsed("direction", values::nonzero_vector)?
                .unwrap_or(defaults::LIGHT_DIRECTION),
        },
        _ => LightKind::Ambient,
    };
    Ok(Light {
        name: el.string("name"),
        color: el.color("color")?.unwrap_or(defaults::LIGHT_COLOR),
        intensity: el
            .number("intensity", Range::NonNegative)?
            .unwrap_or_else(|| defaults::light_intensity(&kind)),
        kind,
    })
}

/// A `<sky>`: a constant `color`, or an environment `map` (a file relative
/// to `dir`, the scene file's folder, loaded here so that a bad one is an
/// error at its attribute) tinted by `color` (white by default) and turned
/// by `rotate`.
pub(crate) fn sky(el: &Element<'_>, dir: &Path) -> Result<Sky, SceneError> {
    let color = el.color("color")?;
    let rotate = el.vector("rotate")?.unwrap_or(Vec3::ZERO);
    let strength = el.number("strength", Range::NonNegative)?.unwrap_or(1.0);
    let map = match el.string("map") {
        None => None,
        Some(src) => {
            if let Some((scheme, _)) = src.split_once("://")
                && scheme != "file"
            {
                return Err(el.error_at(
                    "map",
                    format!(
                        "\"{scheme}://…\" is a network address; raylab never fetches files \
                         from the network (download the map and name the file)"
                    ),
                ));
            }
            let image =
                if src == STUDIO_MAP {
                    studio_image()
                } else {
                    Arc::new(load_sky_map(&dir.join(&src)).map_err(|why| {
                        el.error_at("map", format!("environment map {src:?}: {why}"))
                    })?)
                };
            Some(SkyMap { src, image })
        }
    };
    let color = match (color, &map) {
        (Some(color), _) => color,
        (None, Some(_)) => Vec3::ONE,
        (None, None) => {
            return Err(el.error(
                "<sky> needs a color or a map: the radiance arriving from every direction no \
                 object blocks, such as color=\"0.5 0.7 1\" or map=\"studio.exr\"",
            ));
        }
    };
    Ok(Sky {
        color,
        map,
        rotate,
        strength,
    })
}

/// A `<view>`: unset attributes keep [`View::default`] (as rendered, clamped).
pub(crate) fn view(el: &Element<'_>) -> Result<View, SceneError> {
    let exposure = el.number("exposure", Range::Exposure)?;
    let tonemap = match el.string("tonemap") {
        None => Tonemap::default(),
        Some(name) => Tonemap::from_name(&name).ok_or_else(|| {
            el.error_at(
                "tonemap",
                format!(
                    "tonemap must be {}, got {name:?}{}",
                    Tonemap::ALL.map(Tonemap::name).join(" or "),
                    did_you_mean(&name, Tonemap::ALL.map(Tonemap::name))
                ),
            )
        })?,
    };
    Ok(View {
        exposure: exposure.unwrap_or(0.0),
        tonemap,
    })
}
