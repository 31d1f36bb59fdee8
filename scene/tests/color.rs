//! Colour parsing and formatting (`scene::color`).

use glam::Vec3;
use scene::color::{format_color, linear_to_srgb, parse_color, srgb_to_linear};

fn parse(text: &str) -> Vec3 {
    parse_color(text).unwrap_or_else(|e| panic!("{text:?}: {e}"))
}

#[test]
fn names_and_hex_are_srgb_converted_to_linear() {
    assert_eq!(parse("red"), Vec3::X);
    assert_eq!(parse("RED"), Vec3::X);
    assert_eq!(parse(" White "), Vec3::ONE);
    let purple = srgb_to_linear(128.0 / 255.0);
    assert_eq!(parse("purple"), Vec3::new(purple, 0.0, purple));
    assert_eq!(parse("#800080"), parse("purple"));
    assert_eq!(parse("#FFD700"), parse("gold"));
    assert_eq!(parse("#f0f"), parse("#ff00ff"));
    assert_eq!(parse("rebeccapurple"), parse("#663399"));
}

#[test]
fn numbers_are_linear_and_may_be_comma_separated() {
    assert_eq!(parse("0.6 0.8 1"), Vec3::new(0.6, 0.8, 1.0));
    assert_eq!(parse("0.6, 0.8,1"), Vec3::new(0.6, 0.8, 1.0));
    assert_eq!(parse("2 3 4"), Vec3::new(2.0, 3.0, 4.0));
}

#[test]
fn bad_colours_are_errors_that_say_what_was_expected() {
    for (text, phrase) in [
        ("redd", "did you mean \"red\"?"),
        ("#12345", "#rrggbb"),
        ("#ggg", "#rrggbb"),
        ("#ff000080", "#rrggbb"),
        ("1 2", "found 2 numbers"),
        ("1 nan 2", "finite"),
        ("-1 0 0", "negative"),
        ("", "three linear numbers"),
        ("rgb(1,2,3)", "colour name"),
    ] {
        match parse_color(text) {
            Ok(c) => panic!("{text:?} parsed as {c}"),
            Err(e) => assert!(e.contains(phrase), "{text:?}: {e:?} lacks {phrase:?}"),
        }
    }
}

#[test]
fn srgb_conversions_are_inverse() {
    for b in 0..=255u8 {
        let s = f32::from(b) / 255.0;
        assert!((linear_to_srgb(srgb_to_linear(s)) - s).abs() < 1e-6, "{b}");
    }
    assert_eq!(srgb_to_linear(0.04045), 0.04045 / 12.92);
    assert_eq!(srgb_to_linear(1.0), 1.0);
}

#[test]
fn format_writes_hex_exactly_when_every_channel_is_a_byte_and_parses_back_exactly() {
    for b in 0..=255u8 {
        let c = Vec3::new(
            srgb_to_linear(f32::from(b) / 255.0),
            srgb_to_linear(f32::from(255 - b) / 255.0),
            srgb_to_linear(f32::from(b / 2) / 255.0),
        );
        let text = format_color(c);
        assert_eq!(text, format!("#{b:02x}{:02x}{:02x}", 255 - b, b / 2));
        assert_eq!(parse(&text), c);
    }
    assert_eq!(format_color(Vec3::new(0.5, 0.25, 1.0)), "0.5 0.25 1");
    assert_eq!(format_color(Vec3::new(2.0, 0.0, 0.0)), "2 0 0");
    assert_eq!(format_color(Vec3::new(1.0, 0.0, 0.3)), "1 0 0.3");
    assert_eq!(
        parse(&format_color(Vec3::new(0.1, 0.2, 0.3))),
        Vec3::new(0.1, 0.2, 0.3)
    );
}
