//! raylab's scene: the data model, the XML format (read and write), defaults
//! and validation. No rendering and no GUI here.
//!
//! ```
//! let scene = scene::read_str(r#"<scene> <sphere color="red"> </scene>"#, "inline.xml").unwrap();
//! assert_eq!(scene.objects.len(), 1);
//! ```

mod bounded_read;
pub mod color;
mod error;
pub mod generate;
mod gltf;
pub mod layout;
pub mod materials;
pub mod mesh;
pub mod model;
mod model_scene;
mod numbers;
mod read;
mod resolve;
mod resolved;
mod sky_map;
mod suggest;
mod write;

pub use error::{InvalidScene, SceneError};
pub use gltf::{load_model, load_model_bytes};
pub use mesh::TriangleMesh;
pub use model::model_file::{
    MeshInstance, ModelCamera, ModelError, ModelFile, ModelMaterial, Texture, Wrap,
};
pub use model::*;
pub use model_scene::{is_model_path, read_any, read_model_scene};
pub use numbers::MAX_MAGNITUDE;
pub use read::{read_file, read_str};
pub use resolve::resolve;
pub use resolved::*;
pub use sky_map::{MAX_TEXELS as MAX_SKY_MAP_TEXELS, load_sky_map};
pub use write::write_string;
