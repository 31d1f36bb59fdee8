//! Bottom-level BVHs kept across worlds: a mesh's BVH is built once (when
//! first needed) and reused by every later world that draws the same
//! (`Arc`-shared) mesh, so an edit rebuilds only the top level, never a
//! million-triangle mesh.

use crate::accel::{Aabb, MeshBvh};
use rayon::prelude::*;
use scene::TriangleMesh;
use std::sync::{Arc, Mutex, OnceLock, Weak};

/// What is kept of a mesh: the box around its triangles, found when the
/// mesh is first seen, and its BVH, built when first asked for (a world
/// that traces the mesh's only instance in world space, among its grouped
/// triangles, never asks unless the lecture's method traces it).
#[derive(Debug)]
pub struct MeshEntry {
    mesh: Weak<TriangleMesh>,
    bounds: Aabb,
    bvh: OnceLock<Arc<MeshBvh>>,
}

impl MeshEntry {
    /// The box around the mesh's triangles (the BVH's box; empty for none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// True once the BVH is built.
    pub fn is_built(&self) -> bool {
        self.bvh.get().is_some()
    }

    /// The mesh's BVH, built now if it was not yet (`mesh` is the mesh).
    pub fn bvh(&self, mesh: &TriangleMesh) -> &Arc<MeshBvh> {
        self.bvh
            .get_or_init(|| Arc::new(MeshBvh::build(&mesh.positions, &mesh.triangles)))
    }
}

/// Builds, in parallel, the BVH of each of `meshes` (a mesh with its entry)
/// not built yet. Only those go to rayon's workers: a world whose meshes'
/// BVHs are all built (an edit of the camera or of another object) is
/// prepared without waiting for them.
pub fn build_bvhs<'a>(meshes: impl Iterator<Item = (&'a Arc<MeshEntry>, &'a TriangleMesh)>) {
    let mut missing: Vec<_> = meshes.filter(|(e, _)| !e.is_built()).collect();
    missing.sort_by_key(|(e, _)| Arc::as_ptr(e));
    missing.dedup_by_key(|(e, _)| Arc::as_ptr(e));
    missing.par_iter().for_each(|(e, m)| {
        e.bvh(m);
    });
}

/// Every live mesh's entry; entries die with their mesh.
static CACHE: Mutex<Vec<Arc<MeshEntry>>> = Mutex::new(Vec::new());

/// The entry of each mesh, in order: kept ones reused, the others made (their
/// boxes found in parallel, their BVHs not built) and kept.
pub fn entries_for(meshes: &[Arc<TriangleMesh>]) -> Vec<Arc<MeshEntry>> {
    let find = |cache: &[Arc<MeshEntry>], mesh: &Arc<TriangleMesh>| {
        cache
            .iter()
            .find(|e| std::ptr::eq(e.mesh.as_ptr(), Arc::as_ptr(mesh)))
            .cloned()
    };
    let known: Vec<Option<Arc<MeshEntry>>> = {
        let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        cache.retain(|e| e.mesh.strong_count() > 0);
        meshes.iter().map(|m| find(&cache, m)).collect()
    };
    let entries: Vec<Arc<MeshEntry>> = if known.iter().all(Option::is_some) {
        known.into_iter().flatten().collect()
    } else {
        meshes
            .par_iter()
            .zip(known)
            .map(|(mesh, known)| {
                known.unwrap_or_else(|| {
                    Arc::new(MeshEntry {
                        mesh: Arc::downgrade(mesh),
                        bounds: Aabb::around(
                            mesh.triangles
                                .iter()
                                .flatten()
                                .map(|&i| mesh.positions[i as usize]),
                        ),
                        bvh: OnceLock::new(),
                    })
                })
            })
            .collect()
    };
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    for (mesh, entry) in meshes.iter().zip(&entries) {
        if find(&cache, mesh).is_none() {
            cache.push(entry.clone());
        }
    }
    entries
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
    fn the_same_mesh_gets_the_same_entry_its_bvh_built_when_asked_and_a_dropped_mesh_is_forgotten()
    {
        let mesh = triangle_mesh();
        let first = entries_for(std::slice::from_ref(&mesh));
        assert!(first[0].bvh.get().is_none(), "not built until asked for");
        assert_eq!(
            first[0].bounds(),
            Aabb::around([Vec3::ZERO, Vec3::X, Vec3::Y])
        );
        let again = entries_for(&[mesh.clone(), mesh.clone()]);
        build_bvhs(again.iter().map(|e| (e, &*mesh)));
        assert!(Arc::ptr_eq(&first[0], &again[0]) && Arc::ptr_eq(&first[0], &again[1]));
        assert!(first[0].bvh.get().is_some(), "built when asked for");
        assert_eq!(first[0].bvh(&mesh).bounds(), first[0].bounds());
        let other = triangle_mesh();
        let different = entries_for(std::slice::from_ref(&other));
        assert!(!Arc::ptr_eq(&first[0], &different[0]));
        let weak = Arc::downgrade(&mesh);
        drop((mesh, first, again));
        entries_for(&[]);
        let cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        assert!(
            cache
                .iter()
                .all(|e| !std::ptr::eq(e.mesh.as_ptr(), weak.as_ptr()))
        );
    }
}
