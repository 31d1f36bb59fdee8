//! Reading accessors: every byte range checked before it is read (so a bad
//! offset, stride or count is an error, never a panic), any component type
//! converted to `f32` (normalised integers by the glTF rules), sparse
//! substitution applied. One allocation per accessor, none per element.

use super::buffers::Buffers;
use ::gltf::Accessor;
use ::gltf::accessor::{DataType, Dimensions, sparse::IndexType};
use glam::{Vec2, Vec3};

/// The `count` elements of `accessor` as 3-vectors.
pub(super) fn read_vec3(accessor: &Accessor, buffers: &Buffers) -> Result<Vec<Vec3>, String> {
    expect_dimensions(accessor, Dimensions::Vec3)?;
    let normalized = accessor.normalized();
    macro_rules! vec3 {
        ($read:expr, $size:expr) => {
            read_with(accessor, buffers, 3 * $size, |b: &[u8]| {
                Vec3::new(
                    $read(&b[0..], normalized),
                    $read(&b[$size..], normalized),
                    $read(&b[2 * $size..], normalized),
                )
            })
        };
    }
    match accessor.data_type() {
        DataType::F32 => vec3!(f32_at, 4),
        DataType::U8 => vec3!(u8_at, 1),
        DataType::I8 => vec3!(i8_at, 1),
        DataType::U16 => vec3!(u16_at, 2),
        DataType::I16 => vec3!(i16_at, 2),
        DataType::U32 => Err(unsigned_int_attribute(accessor)),
    }
}

/// The `count` elements of `accessor` as 2-vectors.
pub(super) fn read_vec2(accessor: &Accessor, buffers: &Buffers) -> Result<Vec<Vec2>, String> {
    expect_dimensions(accessor, Dimensions::Vec2)?;
    let normalized = accessor.normalized();
    macro_rules! vec2 {
        ($read:expr, $size:expr) => {
            read_with(accessor, buffers, 2 * $size, |b: &[u8]| {
                Vec2::new($read(&b[0..], normalized), $read(&b[$size..], normalized))
            })
        };
    }
    match accessor.data_type() {
        DataType::F32 => vec2!(f32_at, 4),
        DataType::U8 => vec2!(u8_at, 1),
        DataType::I8 => vec2!(i8_at, 1),
        DataType::U16 => vec2!(u16_at, 2),
        DataType::I16 => vec2!(i16_at, 2),
        DataType::U32 => Err(unsigned_int_attribute(accessor)),
    }
}

/// The `count` vertex indices of an index accessor (unsigned byte, short or
/// int scalars).
pub(super) fn read_indices(accessor: &Accessor, buffers: &Buffers) -> Result<Vec<u32>, String> {
    expect_dimensions(accessor, Dimensions::Scalar)?;
    match accessor.data_type() {
        DataType::U8 => read_with(accessor, buffers, 1, |b: &[u8]| u32::from(b[0])),
        DataType::U16 => read_with(accessor, buffers, 2, |b: &[u8]| {
            u32::from(u16::from_le_bytes([b[0], b[1]]))
        }),
        DataType::U32 => read_with(accessor, buffers, 4, |b: &[u8]| {
            u32::from_le_bytes([b[0], b[1], b[2], b[3]])
        }),
        other => Err(format!(
            "accessor {}: indices must be unsigned bytes, shorts or ints, not {other:?}",
            accessor.index()
        )),
    }
}

fn expect_dimensions(accessor: &Accessor, expected: Dimensions) -> Result<(), String> {
    let found = accessor.dimensions();
    if found == expected {
        Ok(())
    } else {
        Err(format!(
            "accessor {} has type {found:?}; {expected:?} was expected",
            accessor.index()
        ))
    }
}

fn unsigned_int_attribute(accessor: &Accessor) -> String {
    format!(
        "accessor {}: vertex attributes cannot use UNSIGNED_INT components (glTF allows them only for indices)",
        accessor.index()
    )
}

fn f32_at(b: &[u8], _normalized: bool) -> f32 {
    f32::from_le_bytes([b[0], b[1], b[2], b[3]])
}

fn u8_at(b: &[u8], normalized: bool) -> f32 {
    let v = f32::from(b[0]);
    if normalized { v / 255.0 } else { v }
}

fn i8_at(b: &[u8], normalized: bool) -> f32 {
    let v = f32::from(b[0] as i8);
    if normalized { (v / 127.0).max(-1.0) } else { v }
}

fn u16_at(b: &[u8], normalized: bool) -> f32 {
    let v = f32::from(u16::from_le_bytes([b[0], b[1]]));
    if normalized { v / 65535.0 } else { v }
}

fn i16_at(b: &[u8], normalized: bool) -> f32 {
    let v = f32::from(i16::from_le_bytes([b[0], b[1]]));
    if normalized {
        (v / 32767.0).max(-1.0)
    } else {
        v
    }
}

/// The byte range of `count` elements of `size` bytes, `stride` apart,
/// starting at `offset` in `data`; an error if any of it lies outside.
fn elements(data: &[u8], offset: usize, stride: usize, count: usize, size: usize) -> Option<&[u8]> {
    if count == 0 {
        return Some(&[]);
    }
    let end = stride
        .checked_mul(count - 1)?
        .checked_add(size)?
        .checked_add(offset)?;
    data.get(offset..end)
}

/// Reads `accessor` element by element with `decode` (which gets exactly
/// `size` bytes; zeros when it has no buffer view, as glTF specifies), then
/// applies its sparse substitutions.
fn read_with<T: Copy + Default>(
    accessor: &Accessor,
    buffers: &Buffers,
    size: usize,
    decode: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, String> {
    let index = accessor.index();
    let count = accessor.count();
    let take = || {
        buffers
            .take_elements(count)
            .map_err(|e| format!("accessor {index}: {e}"))
    };
    let mut out = match accessor.view() {
        Some(view) => {
            let stride = view.stride().unwrap_or(size);
            if stride < size {
                return Err(format!(
                    "accessor {index}: bufferView {} has byteStride {stride}, less than the {size}-byte element",
                    view.index()
                ));
            }
            let data = buffers
                .view(&view)
                .map_err(|e| format!("accessor {index}: {e}"))?;
            let bytes = elements(data, accessor.offset(), stride, count, size).ok_or_else(|| {
                format!(
                    "accessor {index}: {count} elements of {size} bytes, {stride} apart from byteOffset {}, do not fit in bufferView {} ({} bytes)",
                    accessor.offset(),
                    view.index(),
                    data.len()
                )
            })?;
            take()?;
            // `stride >= size`, so every chunk but possibly the last is a
            // whole stride; the range ends with a whole element.
            let mut out = Vec::with_capacity(count);
            out.extend((0..count).map(|i| decode(&bytes[i * stride..i * stride + size])));
            out
        }
        None => {
            take()?;
            vec![T::default(); count]
        }
    };
    if let Some(sparse) = accessor.sparse() {
        let n = sparse.count();
        let indices = sparse.indices();
        let index_size = indices.index_type().size();
        let view = indices.view();
        let data = buffers
            .view(&view)
            .map_err(|e| format!("accessor {index}, sparse indices: {e}"))?;
        let index_bytes =
            elements(data, indices.offset(), index_size, n, index_size).ok_or_else(|| {
                format!(
                    "accessor {index}: its {n} sparse indices do not fit in bufferView {}",
                    view.index()
                )
            })?;
        let values = sparse.values();
        let view = values.view();
        let data = buffers
            .view(&view)
            .map_err(|e| format!("accessor {index}, sparse values: {e}"))?;
        let value_bytes = elements(data, values.offset(), size, n, size).ok_or_else(|| {
            format!(
                "accessor {index}: its {n} sparse values do not fit in bufferView {}",
                view.index()
            )
        })?;
        for k in 0..n {
            let b = &index_bytes[k * index_size..(k + 1) * index_size];
            let target = match indices.index_type() {
                IndexType::U8 => usize::from(b[0]),
                IndexType::U16 => usize::from(u16::from_le_bytes([b[0], b[1]])),
                IndexType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
            };
            let slot = out.get_mut(target).ok_or_else(|| {
                format!("accessor {index}: sparse index {target} is out of range (count {count})")
            })?;
            *slot = decode(&value_bytes[k * size..(k + 1) * size]);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalised_integers_follow_the_gltf_formulas() {
        assert_eq!(u8_at(&[255], true), 1.0);
        assert_eq!(u8_at(&[51], true), 0.2);
        assert_eq!(u8_at(&[7], false), 7.0);
        assert_eq!(i8_at(&[0x80], true), -1.0, "-128 clamps to -1");
        assert_eq!(i8_at(&[127], true), 1.0);
        assert_eq!(u16_at(&65535u16.to_le_bytes(), true), 1.0);
        assert_eq!(i16_at(&(-32768i16).to_le_bytes(), true), -1.0);
        assert_eq!(i16_at(&(-5i16).to_le_bytes(), false), -5.0);
        assert_eq!(f32_at(&1.5f32.to_le_bytes(), true), 1.5);
    }

    #[test]
    fn element_ranges_are_checked_without_overflow() {
        let data = [0u8; 40];
        // 3 elements of 12 bytes, 12 apart = 36 bytes from 0.
        assert_eq!(elements(&data, 0, 12, 3, 12).map(<[u8]>::len), Some(36));
        // Interleaved: the last element only needs its own 12 bytes.
        assert_eq!(elements(&data, 4, 24, 2, 12).map(<[u8]>::len), Some(36));
        assert_eq!(elements(&data, 8, 12, 3, 12), None, "ends at 44 > 40");
        assert_eq!(elements(&data, 0, usize::MAX, 3, 12), None, "overflow");
        assert_eq!(elements(&data, 100, 4, 0, 4).map(<[u8]>::len), Some(0));
    }
}
