//! The group of a large world's triangles ([`LoneTriangles`]: its mesh
//! instances placed in world space) kept across worlds: an edit that leaves
//! every triangle where it was (the camera, a material, a light, a sphere)
//! reuses it, where building it again would cost as much as building the
//! meshes' own BVHs. Only the last world's group is kept, and only while
//! its meshes live. A mesh moved builds its group again, as Embree's and
//! Mitsuba's scenes do (a million triangles: ~0.1 s on two threads).

use super::placed_mesh::PlacedMesh;
use super::top_level::LoneTriangles;
use crate::shapes::Shape;
use scene::{ResolvedObject, TriangleMesh};
use std::sync::{Arc, Mutex, Weak};

/// The process's cache.
static CACHE: Mutex<GroupCache> = Mutex::new(GroupCache { kept: None });

/// The last group built, with what it was built from. (A group is the same
/// whether built again or kept: the image never depends on which.)
#[derive(Debug)]
pub(super) struct GroupCache {
    kept: Option<(Key, Arc<LoneTriangles>)>,
}

impl GroupCache {
    /// The kept group when it was built from `key`.
    pub(super) fn kept(&mut self, key: &Key) -> Option<Arc<LoneTriangles>> {
        if let Some((k, _)) = &self.kept
            && k.meshes.iter().any(|m| m.strong_count() == 0)
        {
            self.kept = None;
        }
        self.kept
            .as_ref()
            .filter(|(k, _)| k == key)
            .map(|(_, group)| group.clone())
    }

    /// Keeps `group`, built from `key`, in place of the one kept before.
    pub(super) fn keep(&mut self, key: Key, group: Arc<LoneTriangles>) {
        self.kept = Some((key, group));
    }
}

/// [`GroupCache::kept`] with the process's cache.
pub(super) fn kept(key: &Key) -> Option<Arc<LoneTriangles>> {
    CACHE.lock().unwrap_or_else(|e| e.into_inner()).kept(key)
}

/// [`GroupCache::keep`] with the process's cache.
pub(super) fn keep(key: Key, group: Arc<LoneTriangles>) {
    CACHE
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .keep(key, group);
}

/// What a group is built from, in object order: the `<triangle>` objects'
/// corners and each instance's mesh and placement, all to the bit.
#[derive(Clone, Debug)]
pub(super) struct Key {
    parts: Vec<Part>,
    /// The instances' meshes: held (weakly) so that a mesh's address is not
    /// reused by another while the key names it.
    meshes: Vec<Weak<TriangleMesh>>,
}

#[derive(Clone, Debug, PartialEq)]
enum Part {
    Triangle {
        object: u32,
        corners: [[u32; 3]; 3],
    },
    Instance {
        object: u32,
        mesh: usize,
        world_from_mesh: [u32; 12],
    },
}

impl PartialEq for Key {
    fn eq(&self, other: &Self) -> bool {
        self.parts == other.parts
    }
}

impl Key {
    /// The key of a world of `objects` whose instances are `meshes`.
    pub(super) fn of(objects: &[ResolvedObject], meshes: &[PlacedMesh]) -> Key {
        let mut parts = Vec::new();
        let mut placed = meshes.iter().peekable();
        for (id, object) in objects.iter().enumerate() {
            let object_id = id as u32;
            match Shape::from_geometry(&object.geometry) {
                Some(Shape::Triangle(t)) => parts.push(Part::Triangle {
                    object: object_id,
                    corners: [t.t0, t.t1, t.t2].map(|p| p.to_array().map(f32::to_bits)),
                }),
                Some(_) => {}
                None => {
                    while let Some(m) = placed.next_if(|m| m.object == object_id) {
                        parts.push(Part::Instance {
                            object: object_id,
                            mesh: Arc::as_ptr(&m.mesh) as usize,
                            world_from_mesh: m
                                .instance
                                .world_from_object
                                .to_cols_array()
                                .map(f32::to_bits),
                        });
                    }
                }
            }
        }
        Key {
            parts,
            meshes: meshes.iter().map(|m| Arc::downgrade(&m.mesh)).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    /// The key of `scene` with its knot at `y`, and its world.
    fn knot_at(scene: &scene::Scene, y: f32) -> (Key, World) {
        let mut scene = scene.clone();
        if let scene::Shape::Mesh { translate, .. } = &mut scene.objects[0].shape {
            *translate = Some(glam::Vec3::new(0.0, y, 0.0));
        }
        let resolved = scene::resolve(&scene).expect("valid");
        let world = World::new(&resolved).expect("valid");
        (Key::of(&resolved.objects, &world.meshes), world)
    }

    #[test]
    fn a_kept_group_is_reused_for_the_same_placement_only() {
        let scene = scene::generate::knot_scene(9000);
        let (key, world) = knot_at(&scene, 1.15);
        let group = world.top.lone_triangles.clone().expect("grouped");
        let mut cache = GroupCache { kept: None };
        assert!(cache.kept(&key).is_none(), "nothing kept");
        cache.keep(key.clone(), group.clone());
        assert!(Arc::ptr_eq(&cache.kept(&key).expect("kept"), &group));
        let (moved, _) = knot_at(&scene, 1.5);
        assert!(cache.kept(&moved).is_none(), "the knot moved");
        let (other, _) = knot_at(&scene::generate::knot_scene(9000), 1.15);
        assert!(cache.kept(&other).is_none(), "another mesh");
        // Its meshes gone, the group is forgotten.
        drop((scene, world, group, other));
        assert!(cache.kept(&key).is_none() && cache.kept.is_none());
    }
}
