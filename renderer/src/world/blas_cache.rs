//! Bottom-level BVHs kept across worlds: a mesh's BVH is built once and
//! reused by every later world that draws the same (`Arc`-shared) mesh, so
//! an edit rebuilds only the top level, never a million-triangle mesh.

use crate::accel::MeshBvh;
use rayon::prelude::*;
use scene::TriangleMesh;
use std::sync::{Arc, Mutex, Weak};

/// Every live mesh's BVH; entries die with their mesh.
static CACHE: Mutex<Vec<(Weak<TriangleMesh>, Arc<MeshBvh>)>> = Mutex::new(Vec::new());

/// The BVH of each mesh, in order: cached ones reused, the rest built in
/// parallel and remembered.
pub fn bvhs_for(meshes: &[Arc<TriangleMesh>]) -> Vec<Arc<MeshBvh>> {
    let cached = |cache: &[(Weak<TriangleMesh>, Arc<MeshBvh>)], mesh: &Arc<TriangleMesh>| {
        cache
            .iter()
            .find(|(weak, _)| std::ptr::eq(weak.as_ptr(), Arc::as_ptr(mesh)))
            .map(|(_, bvh)| bvh.clone())
    };
    let known: Vec<Option<Arc<MeshBvh>>> = {
        let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        cache.retain(|(weak, _)| weak.strong_count() > 0);
        meshes.iter().map(|m| cached(&cache, m)).collect()
    };
    // Only BVHs to build go to rayon's workers: a world whose meshes are
    // all cached (an edit of the camera or of another object) is prepared
    // without waiting for them.
    let built: Vec<Arc<MeshBvh>> = if known.iter().all(Option::is_some) {
        known.into_iter().flatten().collect()
    } else {
        meshes
            .par_iter()
            .zip(known)
            .map(|(mesh, known)| {
                known.unwrap_or_else(|| Arc::new(MeshBvh::build(&mesh.positions, &mesh.triangles)))
            })
            .collect()
    };
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    for (mesh, bvh) in meshes.iter().zip(&built) {
        if cached(&cache, mesh).is_none() {
            cache.push((Arc::downgrade(mesh), bvh.clone()));
        }
    }
    built
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn triangle_mesh() -> Arc<TriangleMesh> {
        Arc::new(TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
            ..Default::default()
        })
    }

    #[test]
    fn the_same_mesh_gets_the_same_bvh_and_a_dropped_mesh_is_forgotten() {
        let mesh = triangle_mesh();
        let first = bvhs_for(std::slice::from_ref(&mesh));
        let again = bvhs_for(&[mesh.clone(), mesh.clone()]);
        assert!(Arc::ptr_eq(&first[0], &again[0]) && Arc::ptr_eq(&first[0], &again[1]));
        let other = triangle_mesh();
        let different = bvhs_for(std::slice::from_ref(&other));
        assert!(!Arc::ptr_eq(&first[0], &different[0]));
        let weak = Arc::downgrade(&mesh);
        drop((mesh, first, again));
        bvhs_for(&[]);
        let cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        assert!(
            cache
                .iter()
                .all(|(w, _)| !std::ptr::eq(w.as_ptr(), weak.as_ptr()))
        );
    }
}
