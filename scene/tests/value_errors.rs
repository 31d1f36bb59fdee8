//! Errors in attribute values, each at the exact `line:column` of the value
//! (or of the element, for a degenerate triangle) with the key phrase of its
//! message.

mod common;
use common::{assert_error, in_scene};

#[test]
fn bad_numbers_point_at_the_value() {
    assert_error(
        &in_scene(r#"  <sphere radius="abc"/>"#),
        2,
        19,
        r#"radius must be a positive number, got "abc""#,
    );
    for bad in ["nan", "NaN", "inf", "-infinity", "1e39", "-1e39"] {
        let line = format!(r#"  <floor y="{bad}"/>"#);
        assert_error(&in_scene(&line), 2, 13, "must be a finite number");
    }
    assert_error(
        &in_scene(r#"  <sphere center="0 nan 0"/>"#),
        2,
        19,
        "must be a finite number",
    );
    assert_error(
        &in_scene(r#"  <sphere center="0 1"/>"#),
        2,
        19,
        "center must be three finite numbers",
    );
    assert_error(
        &in_scene(r#"  <sphere center="0 1 2 3"/>"#),
        2,
        19,
        "found 4 numbers",
    );
    assert_error(&in_scene(r#"  <sphere center="0,,1 2"/>"#), 2, 19, "comma");
}

#[test]
fn columns_count_characters_not_bytes() {
    assert_error(
        &in_scene("  <!-- é -->  <sphere radius='-1'/>"),
        2,
        31,
        "positive",
    );
}

#[test]
fn non_positive_sizes_point_at_the_value() {
    let text = "<scene>\n  <sphere radius=\"1\"/>\n    <sphere radius=\"-1\"/>\n</scene>";
    assert_error(text, 3, 21, r#"radius must be a positive number, got "-1""#);
    assert_error(
        &in_scene(r#"  <cylinder height="0"/>"#),
        2,
        21,
        "height must be a positive number",
    );
    assert_error(
        &in_scene(r#"  <torus minor="-0.1"/>"#),
        2,
        17,
        "minor must be a positive number",
    );
    assert_error(
        &in_scene(r#"  <box size="1 0 1"/>"#),
        2,
        14,
        "size must be three positive numbers",
    );
}

#[test]
fn degenerate_triangle_points_at_the_element() {
    let text =
        "<scene>\n  <sphere/>\n  <triangle t0=\"0 0 0\" t1=\"1 1 1\" t2=\"2 2 2\"/>\n</scene>";
    assert_error(text, 3, 3, "degenerate triangle");
    assert_error(
        &in_scene(r#"   <triangle t0="1 0 0" t1="1 0 0"/>"#),
        2,
        4,
        "degenerate triangle",
    );
}

#[test]
fn zero_normal_and_direction_are_errors() {
    assert_error(
        &in_scene(r#"  <plane normal="0 0 0"/>"#),
        2,
        18,
        "normal must not be the zero vector",
    );
    assert_error(
        &in_scene(r#"  <light type="directional" direction="0,0,0"/>"#),
        2,
        40,
        "direction must not be the zero vector",
    );
}

#[test]
fn camera_values_are_validated() {
    assert_error(
        &in_scene(r#"  <camera toward="0 0 0"/>"#),
        2,
        19,
        "toward must not be the zero vector",
    );
    assert_error(
        &in_scene(r#"  <camera up="0 0 0"/>"#),
        2,
        15,
        "up must not be the zero vector",
    );
    assert_error(
        &in_scene(r#"  <camera toward="0 0 -1" up="0 0 2"/>"#),
        2,
        31,
        "up must not be parallel to toward",
    );
    assert_error(
        &in_scene(r#"  <camera toward="0 -3 0"/>"#),
        2,
        19,
        "parallel to the default up",
    );
    for theta in ["0", "90", "-5", "120"] {
        let line = format!(r#"  <camera theta="{theta}"/>"#);
        assert_error(
            &in_scene(&line),
            2,
            18,
            "theta must be an angle in degrees strictly between 0 and 90",
        );
    }
    assert_error(
        &in_scene(r#"  <camera d="0"/>"#),
        2,
        14,
        "d must be a positive number",
    );
    for (attr, value, column) in [
        ("width", "0", 18),
        ("width", "16385", 18),
        ("height", "2.5", 19),
        ("height", "-1", 19),
    ] {
        let line = format!(r#"  <camera {attr}="{value}"/>"#);
        assert_error(
            &in_scene(&line),
            2,
            column,
            "must be a whole number of pixels from 1 to 16384",
        );
    }
}

#[test]
fn light_attributes_must_fit_the_light_type() {
    let text = "<scene>\n  <light type=\"directional\" position=\"1 2 3\"/>\n</scene>";
    assert_error(
        text,
        2,
        39,
        "position does not apply to a directional light; a directional light takes direction",
    );
    assert_error(
        &in_scene(r#"  <light direction="1 2 3"/>"#),
        2,
        21,
        "a point light takes position",
    );
    assert_error(
        &in_scene(r#"  <light type="ambient" position="1 2 3"/>"#),
        2,
        35,
        "ambient light takes only color",
    );
    assert_error(
        &in_scene(r#"  <light type="spot"/>"#),
        2,
        16,
        "type must be point, directional or ambient",
    );
    assert_error(
        &in_scene(r#"  <light intensity="-1"/>"#),
        2,
        21,
        "intensity must be a number ≥ 0",
    );
}

#[test]
fn material_parameters_are_range_checked() {
    assert_error(
        &in_scene(r#"  <sphere ior="0"/>"#),
        2,
        16,
        "ior must be an index of refraction from 0.1 to 10",
    );
    assert_error(
        &in_scene(r#"  <sphere shininess="-1"/>"#),
        2,
        22,
        "shininess must be a number ≥ 0",
    );
    assert_error(
        &in_scene(r#"  <sphere specular="1.5"/>"#),
        2,
        21,
        "specular must be a number from 0 to 1",
    );
    assert_error(
        &in_scene(r#"  <material name="m" reflectivity="-0.1"/>"#),
        2,
        36,
        "reflectivity must be a number from 0 to 1",
    );
    assert_error(
        &in_scene(r#"  <sphere material="metal" roughness="2"/>"#),
        2,
        39,
        "roughness must be a number from 0 to 1",
    );
    assert_error(
        &in_scene(r#"  <sphere color="1.5 0 0"/>"#),
        2,
        18,
        "color components must be linear values from 0 to 1",
    );
    assert_error(
        &in_scene(r#"  <sphere emission="-1 0 0"/>"#),
        2,
        21,
        "must not be negative",
    );
    assert_error(
        &in_scene(r#"  <sphere color="redd"/>"#),
        2,
        18,
        "unknown colour name \"redd\"; did you mean \"red\"?",
    );
    assert_error(
        &in_scene(r##"  <sphere color="#12345"/>"##),
        2,
        18,
        "#rrggbb",
    );
    assert_error(
        &in_scene(r#"  <sphere emission="1 inf 1"/>"#),
        2,
        21,
        "must be a finite number",
    );
}

#[test]
fn a_sky_strength_must_be_a_finite_number_not_below_zero() {
    assert_error(
        &in_scene(r#"  <sky color="1 1 1" strength="-1"/>"#),
        2,
        32,
        "a number ≥ 0",
    );
    for bad in ["NaN", "inf"] {
        assert_error(
            &in_scene(&format!(r#"  <sky color="1 1 1" strength="{bad}"/>"#)),
            2,
            32,
            "must be a finite number",
        );
    }
}

#[test]
fn sky_needs_a_color_or_a_map_and_its_color_is_validated() {
    assert_error(&in_scene("  <sky/>"), 2, 3, "<sky> needs a color or a map");
    assert_error(
        &in_scene(r#"  <sky color="-0.1 0 0"/>"#),
        2,
        15,
        "colour components must not be negative",
    );
    assert_error(
        &in_scene(r#"  <sky color="1 NaN 1"/>"#),
        2,
        15,
        "must be a finite number",
    );
    assert_error(
        &in_scene(r#"  <sky color="1 inf 1"/>"#),
        2,
        15,
        "must be a finite number",
    );
    assert_error(
        &in_scene(r#"  <sky color="2 2 2"/>"#),
        2,
        15,
        "color components must be linear values from 0 to 1",
    );
    assert_error(
        &in_scene(r#"  <sky color="skyblu"/>"#),
        2,
        15,
        "did you mean \"skyblue\"?",
    );
    assert_error(
        &in_scene(r#"  <sky colour="1 1 1"/>"#),
        2,
        8,
        "unknown attribute \"colour\" on <sky>; did you mean \"color\"?",
    );
}
