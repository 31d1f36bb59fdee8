//! The reader never panics: random text, random XML-ish token soup and random
//! mutations of the full example all give `Ok` or an `Err` whose position lies
//! inside the input.

use proptest::prelude::*;
use scene::read_str;

const EXAMPLE: &str = r##"<?xml version="1.0"?>
<scene>
  <!-- the format's full example -->
  <camera eye="0 1.5 6" toward="0 -0.2 -1" up="0 1 0" theta="25" d="3" width="800" height="600"/>
  <light type="point" position="-4 6 4" color="white" intensity="60"/>
  <light type="directional" direction="-1 -2 -1" color="white" intensity="0.5"/>
  <material name="blue-glass" base="glass" color="0.6 0.8 1"/>
  <sphere center="0 1 0" radius="1" color="red"/>
  <box center="2.5 0.75 0" size="1.5 1.5 1.5" rotate="0 30 0" color="purple"/>
  <cylinder base="-2.5 0 0" radius="0.6" height="1.8" color="#3080ff"/>
  <cone base="0 0 -2" radius="0.8" height="2" material="blue-glass">
  <torus center="0 0.3 2" major="1" minor="0.3" material="metal" color="gold"></torus>
  <triangle t0="-1 0 0" t1="1 0 0" t2="0 1 0"/>
  <plane point="0 -1 0" normal="0 1 0"/>
  <floor material="marble" name="é &amp; ü"/>
</scene>
"##;

/// Reads `text` and checks that an error's line and column lie inside it
/// (a column may point just past the last character of its line).
fn check(text: &str) -> Result<(), TestCaseError> {
    if let Err(e) = read_str(text, "fuzz.xml") {
        let lines: Vec<&str> = text.split('\n').collect();
        prop_assert!(
            e.line >= 1 && e.line <= lines.len(),
            "line of {} in {:?}",
            e,
            text
        );
        let width = lines.get(e.line - 1).map_or(0, |l| l.chars().count());
        prop_assert!(
            e.column >= 1 && e.column <= width + 1,
            "column of {} in {:?}",
            e,
            text
        );
        prop_assert!(!e.message.is_empty());
    }
    Ok(())
}

/// One edit of a byte string.
#[derive(Clone, Debug)]
enum Edit {
    Delete(prop::sample::Index),
    Insert(prop::sample::Index, u8),
    Truncate(prop::sample::Index),
}

fn edit() -> impl Strategy<Value = Edit> {
    let interesting = prop_oneof![
        prop::sample::select(b"<>/=\"' #&;!?-.,0123456789eaz\n\t".to_vec()),
        any::<u8>(),
    ];
    prop_oneof![
        4 => any::<prop::sample::Index>().prop_map(Edit::Delete),
        4 => (any::<prop::sample::Index>(), interesting).prop_map(|(i, b)| Edit::Insert(i, b)),
        1 => any::<prop::sample::Index>().prop_map(Edit::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, edit: &Edit) {
    match edit {
        Edit::Delete(i) if !bytes.is_empty() => {
            bytes.remove(i.index(bytes.len()));
        }
        Edit::Insert(i, b) => bytes.insert(i.index(bytes.len() + 1), *b),
        Edit::Truncate(i) => bytes.truncate(i.index(bytes.len() + 1)),
        Edit::Delete(_) => {}
    }
}

/// XML-ish fragments that reach deeper into the reader than random characters.
fn token_soup() -> impl Strategy<Value = String> {
    let token = prop::sample::select(vec![
        "<scene>",
        "</scene>",
        "<scene/>",
        "<sphere",
        "<box",
        "<camera",
        "<light",
        "<material",
        "<triangle",
        "<floor",
        "<torus",
        "/>",
        ">",
        "</sphere>",
        " radius=\"",
        " center=\"",
        " color=\"",
        " name=\"",
        " base=\"",
        " material=\"",
        " type=\"",
        " theta=\"",
        " up=\"",
        " toward=\"",
        "\"",
        "'",
        "1",
        "-1",
        "0 0 0",
        "1e39",
        "nan",
        "red",
        "#fff",
        "glass",
        "directional",
        "ambient",
        " ",
        "\n",
        "é",
        "&amp;",
        "&bogus;",
        "&#xFFFFFF;",
        "<!--",
        "-->",
        "<?xml version=\"1.0\"?>",
        "<![CDATA[x]]>",
        "<!DOCTYPE scene>",
        "\u{feff}",
    ]);
    prop::collection::vec(token, 0..40).prop_map(|t| t.concat())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn random_text_never_panics_and_errors_lie_inside_it(text in "\\PC{0,200}") {
        check(&text)?;
    }

    #[test]
    fn xml_token_soup_never_panics_and_errors_lie_inside_it(text in token_soup()) {
        check(&text)?;
    }

    #[test]
    fn mutated_example_never_panics_and_errors_lie_inside_it(
        edits in prop::collection::vec(edit(), 1..6)
    ) {
        let mut bytes = EXAMPLE.as_bytes().to_vec();
        for e in &edits {
            apply(&mut bytes, e);
        }
        check(&String::from_utf8_lossy(&bytes))?;
    }
}

#[test]
fn every_truncation_of_the_example_is_handled() {
    for (end, _) in EXAMPLE.char_indices() {
        let text = &EXAMPLE[..end];
        if let Err(e) = check(text) {
            panic!("{e}");
        }
        // A file cut off before `</scene>` never loads.
        if !text.contains("</scene>") {
            assert!(read_str(text, "t.xml").is_err(), "{text:?} loaded");
        }
    }
    assert!(read_str(EXAMPLE, "t.xml").is_ok());
}
