//! The hostile-file corpus (tests/hostile, written by make_corpus.py): every
//! file is refused with a one-line error that names the file and the place
//! (or, where `expected.tsv` says `loads`, is accepted), none panics, none
//! allocates more than [`HEAP_PER_FILE`], and each returns in well under a
//! second.
//!
//! One test in its own binary: the heap cap is process-wide, so no other test
//! may allocate beside it.

#![allow(unsafe_code)] // only the #[global_allocator] static below

use cap::Cap;
use std::alloc::System;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

#[global_allocator]
static HEAP: Cap<System> = Cap::new(System, usize::MAX);

/// The most a hostile file may make the reader allocate beyond what the test
/// holds already; past it the allocation fails and the test aborts loudly.
const HEAP_PER_FILE: usize = 64 << 20;

/// "Well under a second" for every file, even in a debug build.
const TIME_PER_FILE: Duration = Duration::from_millis(500);

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/hostile")
}

/// (file relative to the corpus, what its error must contain — or `loads`);
/// several parts that must all appear are joined by ` && `.
fn expectations() -> Vec<(String, String)> {
    let text = std::fs::read_to_string(corpus().join("expected.tsv")).expect("expected.tsv");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let (file, expected) = l.split_once('\t').expect("FILE<TAB>EXPECTED");
            (file.to_owned(), expected.to_owned())
        })
        .collect()
}

/// Reads one corpus file the way the program would: scenes with the XML
/// reader, models with the glTF importer. Ok holds a one-line summary.
fn read(path: &Path) -> Result<String, String> {
    if scene::is_model_path(path) {
        scene::load_model(path)
            .map(|m| format!("{} triangles", m.drawn_triangles()))
            .map_err(|e| e.to_string())
    } else {
        scene::read_file(path)
            .map(|s| format!("{} objects", s.objects.len()))
            .map_err(|e| e.to_string())
    }
}

#[test]
fn every_hostile_file_is_a_one_line_error_naming_file_and_place_quickly_and_in_bounded_memory() {
    let expected = expectations();
    let mut listed: Vec<String> = expected.iter().map(|(f, _)| f.clone()).collect();
    listed.sort();
    let mut on_disk = Vec::new();
    for dir in ["xml", "gltf"] {
        for entry in std::fs::read_dir(corpus().join(dir)).expect("corpus folder") {
            let name = entry
                .expect("entry")
                .file_name()
                .to_string_lossy()
                .into_owned();
            if !name.ends_with(".bin") {
                on_disk.push(format!("{dir}/{name}"));
            }
        }
    }
    on_disk.sort();
    assert_eq!(
        listed, on_disk,
        "expected.tsv must list every corpus file once"
    );

    let mut failures = Vec::new();
    for (file, want) in &expected {
        let path = corpus().join(file);
        HEAP.set_limit(HEAP.allocated() + HEAP_PER_FILE)
            .expect("limit above what is allocated");
        let start = Instant::now();
        let outcome = read(&path);
        let took = start.elapsed();
        HEAP.set_limit(usize::MAX).expect("lift the limit");
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        let problem = match (&outcome, want.as_str()) {
            (Ok(_), "loads") => None,
            (Ok(summary), _) => Some(format!(
                "was accepted ({summary}); expected an error with {want:?}"
            )),
            (Err(e), "loads") => Some(format!("was refused, expected to load: {e}")),
            (Err(e), _) if e.contains('\n') => Some(format!("error is not one line: {e:?}")),
            (Err(e), _) if !e.contains(name) => Some(format!("error does not name the file: {e}")),
            (Err(e), _) if !want.split(" && ").all(|part| e.contains(part)) => {
                Some(format!("error does not say {want:?}: {e}"))
            }
            (Err(_), _) => None,
        };
        if took > TIME_PER_FILE {
            failures.push(format!("{file}: took {took:?}"));
        }
        eprintln!(
            "{file} ({took:.1?}): {}",
            match &outcome {
                Ok(s) => format!("loads: {s}"),
                Err(e) => e.clone(),
            }
        );
        if let Some(problem) = problem {
            failures.push(format!("{file}: {problem}"));
        }
    }
    assert!(
        failures.is_empty(),
        "hostile files mishandled:\n{}",
        failures.join("\n")
    );
}
