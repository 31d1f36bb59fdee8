//! One glTF primitive → one [`TriangleMesh`]: indices (8/16/32-bit or none),
//! triangle lists, strips and fans, POSITION, NORMAL and TEXCOORD_0, with
//! every index and position checked.

use super::accessors::{read_indices, read_vec2, read_vec3};
use super::buffers::Buffers;
use super::warnings::{DRACO, MESHOPT, Warnings};
use crate::mesh::TriangleMesh;
use ::gltf::mesh::{Mode, Semantic};
use ::gltf::{Accessor, Primitive};
use glam::Vec3;

/// Extensions in use that decide whether a primitive's data can be read.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Compression {
    /// KHR_draco_mesh_compression is used: accessors without data are Draco's.
    pub draco: bool,
    /// EXT_meshopt_compression is used: some buffers may have no data.
    pub meshopt: bool,
}

impl Compression {
    /// Which compression extensions the document uses.
    pub(super) fn of(doc: &::gltf::Document) -> Self {
        Self {
            draco: doc.extensions_used().any(|e| e == DRACO),
            meshopt: doc.extensions_used().any(|e| e == MESHOPT),
        }
    }
}

/// The mesh of `primitive`, or `None` when it draws nothing raylab can show
/// (points or lines, compressed data, no positions, no triangles); those
/// cases are reported in `warnings`. `place` names the primitive in errors.
pub(super) fn load(
    primitive: &Primitive,
    place: &str,
    buffers: &Buffers,
    compression: Compression,
    warnings: &mut Warnings,
) -> Result<Option<TriangleMesh>, String> {
    let mode = primitive.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        warnings.once("points and lines", || {
            "point and line primitives (modes POINTS, LINES, LINE_LOOP, LINE_STRIP) are not supported: raylab draws surfaces only, so they are skipped".into()
        });
        return Ok(None);
    }
    let Some(position) = primitive.get(&Semantic::Positions) else {
        warnings.once("no POSITION", || {
            "primitives without a POSITION attribute are skipped (there is nothing to draw)".into()
        });
        return Ok(None);
    };
    if compression.draco && position.view().is_none() && position.sparse().is_none() {
        warnings.once(DRACO, || {
            format!("extension {DRACO} is not supported: its Draco-compressed primitives are skipped (primitives with uncompressed data still load)")
        });
        return Ok(None);
    }
    if compression.meshopt && reads_missing_buffer(primitive, buffers) {
        warnings.once(MESHOPT, || {
            format!("extension {MESHOPT} is not supported: primitives whose data is meshopt-compressed are skipped")
        });
        return Ok(None);
    }
    if primitive.morph_targets().next().is_some() {
        warnings.once("morph targets", || {
            "morph targets are not supported: meshes are drawn in their base shape".into()
        });
    }
    if primitive.get(&Semantic::Colors(0)).is_some() {
        warnings.once("vertex colours", || {
            "vertex colours (COLOR_0) are not supported: the material's colour is used alone".into()
        });
    }

    let at = |what: &str, e: String| format!("{place}, {what}: {e}");
    let positions = read_vec3(&position, buffers).map_err(|e| at("POSITION", e))?;
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(at(
            "POSITION",
            format!(
                "accessor {}: vertex {i} is not finite ({})",
                position.index(),
                positions[i]
            ),
        ));
    }
    let vertices = positions.len();
    if u32::try_from(vertices).is_err() {
        return Err(at("POSITION", format!("{vertices} vertices are too many")));
    }

    let triangles = match primitive.indices() {
        Some(accessor) => {
            let indices = read_indices(&accessor, buffers).map_err(|e| at("indices", e))?;
            check_range(&indices, vertices, &accessor).map_err(|e| at("indices", e))?;
            assemble(mode, &indices).map_err(|e| at("indices", e))?
        }
        None if mode == Mode::Triangles => {
            if !vertices.is_multiple_of(3) {
                return Err(at(
                    "POSITION",
                    format!(
                        "a non-indexed triangle list needs a multiple of 3 vertices, not {vertices}"
                    ),
                ));
            }
            (0..vertices as u32 / 3)
                .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
                .collect()
        }
        None => {
            let sequence: Vec<u32> = (0..vertices as u32).collect();
            assemble(mode, &sequence).map_err(|e| at("POSITION", e))?
        }
    };
    if triangles.is_empty() {
        return Ok(None);
    }

    let normals = match primitive.get(&Semantic::Normals) {
        Some(accessor) => {
            let mut normals = read_vec3(&accessor, buffers).map_err(|e| at("NORMAL", e))?;
            same_count(&normals, vertices, &accessor).map_err(|e| at("NORMAL", e))?;
            if !normalise(&mut normals, &positions, &triangles) {
                warnings.once("bad normals", || {
                    format!("{place} (and maybe others) has zero or non-finite normals: raylab uses area-weighted face normals for those vertices")
                });
            }
            normals
        }
        None => TriangleMesh::face_normals_per_vertex(&positions, &triangles),
    };

    let uvs = match primitive.get(&Semantic::TexCoords(0)) {
        Some(accessor) => {
            let uvs = read_vec2(&accessor, buffers).map_err(|e| at("TEXCOORD_0", e))?;
            same_count(&uvs, vertices, &accessor).map_err(|e| at("TEXCOORD_0", e))?;
            if let Some(i) = uvs.iter().position(|uv| !uv.is_finite()) {
                return Err(at(
                    "TEXCOORD_0",
                    format!("accessor {}: element {i} is not finite", accessor.index()),
                ));
            }
            uvs
        }
        None => Vec::new(),
    };

    Ok(Some(TriangleMesh {
        positions,
        triangles,
        normals,
        uvs,
    }))
}

/// Whether any accessor of `primitive` reads a buffer that has no data.
fn reads_missing_buffer(primitive: &Primitive, buffers: &Buffers) -> bool {
    let missing = |accessor: Accessor| {
        let views = accessor.view().into_iter().chain(
            accessor
                .sparse()
                .into_iter()
                .flat_map(|s| [s.indices().view(), s.values().view()]),
        );
        views
            .into_iter()
            .any(|v| !buffers.has_data(v.buffer().index()))
    };
    primitive.indices().is_some_and(missing) || primitive.attributes().any(|(_, a)| missing(a))
}

fn same_count<T>(values: &[T], vertices: usize, accessor: &Accessor) -> Result<(), String> {
    if values.len() == vertices {
        Ok(())
    } else {
        Err(format!(
            "accessor {} has {} elements but POSITION has {vertices}",
            accessor.index(),
            values.len()
        ))
    }
}

/// Every index must name a vertex.
fn check_range(indices: &[u32], vertices: usize, accessor: &Accessor) -> Result<(), String> {
    let max = indices.iter().copied().max().unwrap_or(0);
    if indices.is_empty() || (max as usize) < vertices {
        return Ok(());
    }
    let at = indices
        .iter()
        .position(|&i| i as usize >= vertices)
        .unwrap_or(0);
    Err(format!(
        "accessor {}: index {} at position {at} is out of range (the primitive has {vertices} vertices)",
        accessor.index(),
        indices[at]
    ))
}

/// Triangles from indices in a triangle-list, -strip or -fan order. Strips
/// alternate their winding as glTF specifies; degenerate triangles of strips
/// and fans (their usual stitching) are dropped. Lists are kept as they are.
fn assemble(mode: Mode, indices: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    let distinct = |t: &[u32; 3]| t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    let n = indices.len();
    Ok(match mode {
        Mode::Triangles => {
            if !n.is_multiple_of(3) {
                return Err(format!(
                    "a triangle list needs a multiple of 3 indices, not {n}"
                ));
            }
            indices
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect()
        }
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                let (a, b, c) = (indices[i], indices[i + 1], indices[i + 2]);
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .filter(distinct)
            .collect(),
        Mode::TriangleFan => (0..n.saturating_sub(2))
            .map(|i| [indices[i + 1], indices[i + 2], indices[0]])
            .filter(distinct)
            .collect(),
        _ => Vec::new(),
    })
}

/// Normalises `normals` in place; any that cannot be (zero, non-finite)
/// become the area-weighted face normal. Returns whether all were usable.
fn normalise(normals: &mut [Vec3], positions: &[Vec3], triangles: &[[u32; 3]]) -> bool {
    let mut all_good = true;
    for n in normals.iter_mut() {
        match n.try_normalize() {
            Some(unit) => *n = unit,
            None => {
                *n = Vec3::ZERO;
                all_good = false;
            }
        }
    }
    if !all_good {
        let faces = TriangleMesh::face_normals_per_vertex(positions, triangles);
        for (n, face) in normals.iter_mut().zip(faces) {
            if *n == Vec3::ZERO {
                *n = face;
            }
        }
    }
    all_good
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_alternate_winding_and_drop_degenerates() {
        // 0-1-2-3 strip: (0,1,2), then (2,1,3) keeps the same facing.
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 2, 3]).expect("strip"),
            vec![[0, 1, 2], [2, 1, 3]]
        );
        // Repeated indices stitch two strips; the zero-area triangles vanish.
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 2, 2, 3, 3, 4, 5]).expect("stitched"),
            vec![[0, 1, 2], [4, 3, 5]]
        );
        assert!(
            assemble(Mode::TriangleStrip, &[0, 1])
                .expect("short")
                .is_empty()
        );
    }

    #[test]
    fn fans_pivot_on_the_first_vertex() {
        assert_eq!(
            assemble(Mode::TriangleFan, &[0, 1, 2, 3]).expect("fan"),
            vec![[1, 2, 0], [2, 3, 0]]
        );
    }

    #[test]
    fn lists_need_whole_triangles() {
        assert_eq!(
            assemble(Mode::Triangles, &[0, 1, 2, 2, 1, 0]).expect("two"),
            vec![[0, 1, 2], [2, 1, 0]]
        );
        let e = assemble(Mode::Triangles, &[0, 1, 2, 3]).expect_err("4 indices");
        assert!(e.contains("multiple of 3"), "{e}");
    }

    #[test]
    fn unusable_normals_fall_back_to_face_normals() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let triangles = [[0, 1, 2]];
        let mut normals = [Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, Vec3::NAN];
        assert!(!normalise(&mut normals, &positions, &triangles));
        assert_eq!(normals, [Vec3::Z; 3]);
        let mut good = [Vec3::new(3.0, 0.0, 4.0)];
        assert!(normalise(&mut good, &[Vec3::ZERO], &[]));
        assert_eq!(good[0], Vec3::new(0.6, 0.0, 0.8));
    }
}
