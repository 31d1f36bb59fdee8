//! What several test files share: loading the scenes that ship with raylab.

use renderer::World;
use std::path::Path;

/// `assets/FOLDER/NAME` (a shipped or reference scene) at `width` × `height`.
pub fn asset_world(folder: &str, name: &str, width: u32, height: u32) -> World {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(folder)
        .join(name);
    let mut scene = scene::read_file(&path).expect("a shipped scene parses");
    scene.camera.width = width;
    scene.camera.height = height;
    World::from_scene(&scene).expect("a shipped scene is valid")
}
