//! Prepared maps kept across worlds: the distribution of a 4k map takes a
//! good fraction of a second to build, and every edit builds a new world,
//! so a map is prepared once per (`Arc`-shared) image, as mesh BVHs are.

use super::map::EnvMap;
use scene::EnvImage;
use std::sync::{Arc, Mutex, Weak};

/// Every live image's prepared map; entries die with their image.
static CACHE: Mutex<Vec<(Weak<EnvImage>, Arc<EnvMap>)>> = Mutex::new(Vec::new());

/// The prepared map of `image`, built on first use.
pub fn map_for(image: &Arc<EnvImage>) -> Arc<EnvMap> {
    let find = |cache: &[(Weak<EnvImage>, Arc<EnvMap>)]| {
        cache
            .iter()
            .find(|(weak, _)| std::ptr::eq(weak.as_ptr(), Arc::as_ptr(image)))
            .map(|(_, map)| map.clone())
    };
    {
        let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        cache.retain(|(weak, _)| weak.strong_count() > 0);
        if let Some(map) = find(&cache) {
            return map;
        }
    }
    let map = Arc::new(EnvMap::new(image));
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    match find(&cache) {
        Some(built) => built,
        None => {
            cache.push((Arc::downgrade(image), map.clone()));
            map
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_image_gets_the_same_map() {
        let image = Arc::new(EnvImage {
            path: "a.exr".into(),
            width: 2,
            height: 2,
            texels: vec![[1.0; 3]; 4],
        });
        let other = Arc::new((*image).clone());
        assert!(Arc::ptr_eq(&map_for(&image), &map_for(&image)));
        assert!(!Arc::ptr_eq(&map_for(&image), &map_for(&other)));
    }
}
