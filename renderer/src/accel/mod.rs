//! Ray-tracing acceleration: a two-level bounding-volume hierarchy traversed
//! by our own conservative code, which never loses a hit that a brute-force
//! watertight test over every triangle would find.
//!
//! - [`MeshBvh`]: the bottom level, one per triangle mesh (8-wide nodes built
//!   top down by a binned SAH, triangles copied into packs of four in leaf
//!   order; obvhs's PLOC tree collapsed to the same nodes for comparison:
//!   it builds slower and traces slower). One ray at a time ([`MeshBvh::closest_hit`]), or
//!   a batch ([`MeshBvh::closest_hits`]): coherent rays in packets of
//!   sixteen in SIMD lanes (`mesh/lanes.rs`) that share each node's loads
//!   and each triangle's test, incoherent ones several at a time,
//!   interleaved, to hide memory latency, when the tree is larger than
//!   half the last-level cache (`cache_size.rs`; else one after another).
//! - [`SceneBvh`]: the top level over items known only by their boxes (mesh
//!   instances, analytic shapes), the same 8-wide nodes by the same binned
//!   SAH, leaves of up to eight items; the caller intersects each item.
//! - [`Instance`]: an affine placement of a mesh, mapping rays into the mesh's
//!   space so that α is unchanged.
//! - [`reference`](mod@reference): brute force over every triangle, the oracle of the tests.
//!
//! Why obvhs's own traversal is not used: its node test has no conservative
//! t_far correction (Ize, "Robust BVH Ray Traversal", JCGT 2013), its CWBVH
//! node test replaces the ray's t_min by a fixed 1e-4, and its rays clamp
//! near-zero direction components; each loses hits (measured by
//! `cargo bench -p raylab-renderer --bench bvh -- --lost`). Our node tests are in [`slab`] and [`wide`]; [`simd`] compiles
//! them for the widest SIMD the CPU has.

pub(crate) mod binned_sah;
mod cache_size;
mod huge_pages;
pub mod instance;
pub mod mesh;
mod ploc;
pub mod reference;
pub mod scene;
mod simd;
pub mod slab;
pub mod sphere_pack;
mod stack;
pub mod triangle_pack;
pub mod wide;
mod wide_build;

#[cfg(test)]
mod tests;

pub use self::scene::{Aabb, SceneBvh};
pub use instance::Instance;
pub use mesh::{MeshBvh, MeshHit};
