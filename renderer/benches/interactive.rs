//! Latency of an edit on the seed scene at 1280×720: the first coarse preview
//! (every 8th pixel) and the first full-resolution pass, the two steps the
//! interactive app shows after every edit (targets: 16 ms and 150 ms), and
//! the whole sequence the progressive session traces after an edit (previews
//! 8, 4, 2, then the first pass, each taking the samples of the one before).

use criterion::{Criterion, criterion_group, criterion_main};
use renderer::film::preview::{PreviewSamples, preview};
use renderer::{Film, RenderOptions, World};
use std::path::Path;

fn seed_world() -> World {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
    let mut scene = scene::read_file(&path).expect("the seed scene loads");
    scene.camera.width = 1280;
    scene.camera.height = 720;
    World::from_scene(&scene).expect("valid")
}

fn edit_latency(c: &mut Criterion) {
    let world = seed_world();
    let options = RenderOptions::default();
    let mut group = c.benchmark_group("edit-latency/seed-1280x720");
    group.sample_size(20);
    for stride in [8, 4, 2] {
        group.bench_function(format!("preview-stride-{stride}"), |b| {
            b.iter(|| preview(&world, &options, stride))
        });
    }
    group.bench_function("first-full-pass", |b| {
        b.iter(|| {
            let mut film = Film::new(world.camera.w, world.camera.h);
            film.add_pass(&world, &options);
            film
        })
    });
    group.bench_function("previews-8-4-2-then-first-pass", |b| {
        b.iter(|| {
            let mut samples: Option<PreviewSamples> = None;
            for stride in [8, 4, 2] {
                let next = PreviewSamples::trace(&world, &options, stride, samples.as_ref());
                std::hint::black_box(next.image());
                samples = Some(next);
            }
            let mut film = Film::new(world.camera.w, world.camera.h);
            let known = samples.expect("three previews");
            film.add_pass_reusing(&world, &options, &known, &|| false);
            film
        })
    });
    group.finish();
}

criterion_group!(benches, edit_latency);
criterion_main!(benches);
