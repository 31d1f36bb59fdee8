//! Errors in the document's structure and names, each at its exact
//! `line:column` with the key phrase of its message. Inputs span several
//! lines so that line numbers matter.

mod common;
use common::{assert_error, fail, in_scene};

#[test]
fn error_display_is_file_line_column_message() {
    let e = fail(&in_scene(r#"  <sphere radius="-1"/>"#));
    assert_eq!(
        e.to_string(),
        r#"bad.xml:2:19: radius must be a positive number, got "-1""#
    );
}

#[test]
fn malformed_xml_is_reported_where_the_parser_stopped() {
    // A tag without its `>` swallows the next tag: at the stray `<`.
    let text = "<scene>\n  <sphere radius=\"1\"\n  <box/>\n</scene>";
    assert_error(text, 3, 3, "is this tag missing its \">\"?");
    // An unquoted attribute value: at the value.
    assert_error(&in_scene("  <sphere radius=1/>"), 2, 18, "quotes");
    // A tag that never ends: quick-xml reports the `<` of the unclosed tag.
    assert_error(
        "<scene>\n  <sphere/>\n  <box size=\"1 1 1\"\n",
        3,
        3,
        "malformed XML",
    );
    // A comment that never ends.
    assert_error(
        "<scene>\n  <sphere/>\n  <!-- no end\n</scene>\n",
        3,
        3,
        "malformed XML",
    );
    // A missing `=`.
    assert_error(
        &in_scene(r#"  <sphere radius "1"/>"#),
        2,
        18,
        "expected \"=\"",
    );
    // The same attribute twice: at the second one.
    assert_error(
        &in_scene(r#"  <sphere radius="1" radius="2"/>"#),
        2,
        22,
        "twice",
    );
}

#[test]
fn unknown_element_points_at_its_tag_and_suggests_the_nearest() {
    let text = "<scene>\n  <sphere/>\n  <spere radius=\"1\"/>\n</scene>\n";
    assert_error(
        text,
        3,
        3,
        "unknown element <spere>; did you mean <sphere>?",
    );
    assert_error(
        &in_scene("  <wibble/>"),
        2,
        3,
        "expected one of: camera, light, sky, view, material",
    );
    assert_error(
        &in_scene("  <sphere/></spere>"),
        2,
        12,
        "unexpected end tag </spere>; did you mean </sphere>?",
    );
}

#[test]
fn unknown_attribute_points_at_its_name_and_lists_the_valid_ones() {
    let e = fail(&in_scene(r#"  <sphere center="0 0 0" radus="2"/>"#));
    assert_eq!((e.line, e.column), (2, 26));
    assert_eq!(
        e.message,
        "unknown attribute \"radus\" on <sphere>; did you mean \"radius\"? (expected one of: \
         center, radius, name, material, color, ior, shininess, specular, reflectivity, roughness, \
         emission)"
    );
    assert_error(
        &in_scene(r#"  <camera fov="40"/>"#),
        2,
        11,
        "unknown attribute \"fov\" on <camera>",
    );
}

#[test]
fn a_second_camera_is_an_error_at_its_tag() {
    let text = "<scene>\n  <camera theta=\"30\"/>\n  <sphere/>\n  <camera/>\n</scene>";
    assert_error(
        text,
        4,
        3,
        "at most one <camera>; the first is at line 2, column 3",
    );
}

#[test]
fn a_second_sky_is_an_error_at_its_tag() {
    let text =
        "<scene>\n  <sky color=\"0.5 0.7 1\"/>\n  <sphere/>\n  <sky color=\"black\"/>\n</scene>";
    assert_error(
        text,
        4,
        3,
        "at most one <sky>; the first is at line 2, column 3",
    );
}

#[test]
fn a_misspelt_sky_suggests_sky() {
    assert_error(
        &in_scene(r#"  <skye color="1 1 1"/>"#),
        2,
        3,
        "unknown element <skye>; did you mean <sky>?",
    );
    assert_error(
        &in_scene(r#"  <sky color="1 1 1"></skye>"#),
        2,
        22,
        "unexpected end tag </skye>; did you mean </sky>?",
    );
}

#[test]
fn missing_end_of_scene_is_an_error_at_the_end_of_the_file() {
    assert_error("<scene>\n  <sphere/>\n", 3, 1, "expected </scene>");
    assert_error(
        "<scene>\n  <sphere/>",
        2,
        12,
        "expected </scene> to close the <scene> at line 1, column 1",
    );
    assert_error("", 1, 1, "expected a <scene> element");
    assert_error("  \n<!-- nothing -->\n", 3, 1, "expected a <scene> element");
}

#[test]
fn structure_errors_point_at_the_offending_place() {
    assert_error(
        "<scene>\n  <sphere/> hello\n</scene>",
        2,
        13,
        "unexpected text \"hello\"",
    );
    assert_error(
        "<scene>\n  <sphere> 3 </sphere>\n</scene>",
        2,
        12,
        "unexpected text",
    );
    assert_error("<scene>\n</scene>\n<sphere/>\n", 3, 1, "after </scene>");
    assert_error("<scene>\n</scene>\ntrailing", 3, 1, "after </scene>");
    assert_error(
        "<scene/>\n</scene>",
        2,
        1,
        "unexpected end tag </scene> after </scene>",
    );
    assert_error(
        "\n<world>\n</world>",
        2,
        1,
        "expected the root element <scene>, found <world>",
    );
    assert_error(
        "<scene>\n  <scene/>\n</scene>",
        2,
        3,
        "cannot contain another <scene>",
    );
    assert_error(
        "<scene\n  name=\"x\">\n</scene>",
        2,
        3,
        "<scene> takes no attributes",
    );
    assert_error("<scene>\n  &amp;\n</scene>", 2, 3, "unexpected text");
}

#[test]
fn unknown_material_is_an_error_at_the_value_with_a_suggestion() {
    let text = "<scene>\n  <material name=\"blue-glass\" base=\"glass\"/>\n  <sphere material=\"glas\"/>\n</scene>";
    assert_error(
        text,
        3,
        21,
        "unknown material \"glas\"; did you mean \"glass\"?",
    );
    let text =
        "<scene>\n  <sphere material=\"blue-glas\"/>\n  <material name=\"blue-glass\"/>\n</scene>";
    assert_error(text, 2, 21, "did you mean \"blue-glass\"?");
}

#[test]
fn material_definitions_are_checked() {
    assert_error(
        &in_scene(r#"  <material base="glass"/>"#),
        2,
        3,
        "<material> needs a name",
    );
    assert_error(
        &in_scene(r#"  <material name="glass"/>"#),
        2,
        19,
        "\"glass\" is a built-in material",
    );
    let text =
        "<scene>\n  <material name=\"a\"/>\n  <material name=\"a\" base=\"metal\"/>\n</scene>";
    assert_error(
        text,
        3,
        19,
        "material \"a\" is already defined at line 2, column 19",
    );
    let text = "<scene>\n  <material name=\"a\" base=\"b\"/>\n  <material name=\"b\"/>\n</scene>";
    assert_error(text, 2, 28, "unknown base material \"b\"");
    assert_error(
        &in_scene(r#"  <material name="m" base="glas"/>"#),
        2,
        28,
        "did you mean \"glass\"?",
    );
}

#[test]
fn unreadable_file_is_an_error_at_line_1_column_1() {
    let path = std::path::Path::new("/nonexistent/raylab/scene.xml");
    let e = scene::read_file(path)
        .err()
        .unwrap_or_else(|| panic!("read a missing file"));
    assert_eq!((e.line, e.column), (1, 1));
    assert!(e.message.contains("cannot read the file"), "{e}");
}

#[test]
fn non_utf8_file_is_an_error_at_the_first_bad_byte() {
    let path = std::env::temp_dir().join(format!("raylab-non-utf8-{}.xml", std::process::id()));
    std::fs::write(&path, b"<scene>\n  <sphere name=\"a\xffb\"/>\n</scene>\n")
        .unwrap_or_else(|e| panic!("{e}"));
    let result = scene::read_file(&path);
    let _ = std::fs::remove_file(&path);
    let e = result.err().unwrap_or_else(|| panic!("read invalid UTF-8"));
    assert_eq!((e.line, e.column), (2, 18));
    assert!(e.message.contains("not valid UTF-8"), "{e}");
}

#[test]
fn a_mesh_without_src_or_with_a_missing_file_is_an_error_at_it() {
    assert_error(&in_scene("  <mesh/>"), 2, 3, "needs a src attribute");
    // The message names the file and why it could not be loaded.
    assert_error(
        &in_scene(r#"  <mesh src="no-such-model.glb"/>"#),
        2,
        14,
        "no-such-model.glb",
    );
}
