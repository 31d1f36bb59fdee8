//! Tests of the whole acceleration structure, and the meshes the unit tests
//! of its parts share.

pub(crate) mod meshes;
mod no_lost_hits;
