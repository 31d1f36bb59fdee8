//! What the progressive session's test files share: a small world and a
//! poll for frames.

use renderer::World;
use renderer::progressive::{ProgressiveRenderer, RenderedFrame};
use scene::{Object, Scene, Shape};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// A glass sphere on a marble floor seen at `width` × `height`.
pub fn world(width: u32, height: u32, radius: f32) -> Arc<World> {
    let scene = Scene {
        camera: scene::Camera {
            width,
            height,
            ..Default::default()
        },
        objects: vec![
            Object {
                name: None,
                shape: Shape::Sphere {
                    center: None,
                    radius,
                },
                material: Some("glass".into()),
                params: Default::default(),
            },
            Object {
                name: None,
                shape: Shape::Floor { y: 0.0 },
                material: Some("marble".into()),
                params: Default::default(),
            },
        ],
        ..Default::default()
    };
    Arc::new(World::from_scene(&scene).expect("valid"))
}

/// Polls until `until` accepts a frame or 60 s pass; returns every frame seen.
pub fn frames_until(
    session: &ProgressiveRenderer,
    until: impl Fn(&RenderedFrame) -> bool,
) -> Vec<RenderedFrame> {
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut seen = Vec::new();
    while Instant::now() < deadline {
        if let Some(frame) = session.take_frame() {
            let stop = until(&frame);
            seen.push(frame);
            if stop {
                return seen;
            }
        } else {
            std::thread::sleep(Duration::from_millis(1));
        }
    }
    panic!(
        "no accepted frame within 60 s; saw {:?}",
        seen.iter().map(|f| f.step).collect::<Vec<_>>()
    );
}
