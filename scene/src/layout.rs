//! Geometry the defaults need: rotations, bounding boxes, the row in which
//! unplaced objects rest on the floor, and a camera that frames the scene.

use crate::model::Shape;
use crate::resolved::{Geometry, ModelRef};
use glam::{Mat3, Mat4, Vec3};

/// The rotation of `rotate_deg` degrees about x, then y, then z (world_from_object).
pub fn rotation_from_euler_degrees(rotate_deg: Vec3) -> Mat3 {
    let r = rotate_deg * (std::f32::consts::PI / 180.0);
    Mat3::from_rotation_z(r.z) * Mat3::from_rotation_y(r.y) * Mat3::from_rotation_x(r.x)
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box around a set of points.
    pub fn around(points: impl IntoIterator<Item = Vec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| Aabb {
            min: b.min.min(p),
            max: b.max.max(p),
        })
    }

    /// The empty box (union identity).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// The smallest box containing both.
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x
    }

    /// The centre.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the diagonal: the radius of a sphere around the centre that holds the box.
    pub fn radius(&self) -> f32 {
        0.5 * (self.max - self.min).length()
    }
}

/// The eight corners of the box [lo, hi].
fn box_corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|k| {
        Vec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// The box around a local box [lo, hi] after rotation and translation.
fn rotated_box(origin: Vec3, rotate_deg: Vec3, lo: Vec3, hi: Vec3) -> Aabb {
    let rot = rotation_from_euler_degrees(rotate_deg);
    Aabb::around(box_corners(lo, hi).map(|corner| origin + rot * corner))
}

/// world_from_model of a placed model: translate · rotate (x, then y, then z) · scale.
pub fn model_transform(translate: Vec3, rotate_deg: Vec3, scale: Vec3) -> Mat4 {
    Mat4::from_translation(translate)
        * Mat4::from_mat3(rotation_from_euler_degrees(rotate_deg))
        * Mat4::from_scale(scale)
}

/// The world-space bounding box of a geometry; `None` for an infinite plane.
pub fn bounds(geometry: &Geometry) -> Option<Aabb> {
    Some(match *geometry {
        Geometry::Sphere { center, radius } => Aabb {
            min: center - Vec3::splat(radius),
            max: center + Vec3::splat(radius),
        },
        Geometry::Box {
            center,
            size,
            rotate,
        } => rotated_box(center, rotate, -0.5 * size, 0.5 * size),
        Geometry::Cylinder {
            base,
            radius,
            height,
            rotate,
        }
        | Geometry::Cone {
            base,
            radius,
            height,
            rotate,
        } => rotated_box(
            base,
            rotate,
            Vec3::new(-radius, 0.0, -radius),
            Vec3::new(radius, height, radius),
        ),
        Geometry::Torus {
            center,
            major,
            minor,
            rotate,
        } => {
            let e = Vec3::new(major + minor, minor, major + minor);
            rotated_box(center, rotate, -e, e)
        }
        Geometry::Triangle { t0, t1, t2 } => Aabb::around([t0, t1, t2]),
        Geometry::Plane { .. } => return None,
        Geometry::Mesh {
            ref model,
            world_from_model,
            ..
        } => {
            let (lo, hi) = model.bounds()?;
            Aabb::around(box_corners(lo, hi).map(|c| world_from_model.transform_point3(c)))
        }
    })
}

/// The geometry of `shape` with its anchor at `anchor` when the shape has none.
pub fn geometry_at(shape: &Shape, anchor: Vec3) -> Geometry {
    match *shape {
        Shape::Mesh {
            ref source,
            translate,
            rotate,
            scale,
        } => Geometry::Mesh {
            model: ModelRef(source.model.clone()),
            world_from_model: model_transform(translate.unwrap_or(anchor), rotate, scale),
            file_materials: true,
        },
        Shape::Sphere { center, radius } => Geometry::Sphere {
            center: center.unwrap_or(anchor),
            radius,
        },
        Shape::Box {
            center,
            size,
            rotate,
        } => Geometry::Box {
            center: center.unwrap_or(anchor),
            size,
            rotate,
        },
        Shape::Cylinder {
            base,
            radius,
            height,
            rotate,
        } => Geometry::Cylinder {
            base: base.unwrap_or(anchor),
            radius,
            height,
            rotate,
        },
        Shape::Cone {
            base,
            radius,
            height,
            rotate,
        } => Geometry::Cone {
            base: base.unwrap_or(anchor),
            radius,
            height,
            rotate,
        },
        Shape::Torus {
            center,
            major,
            minor,
            rotate,
        } => Geometry::Torus {
            center: center.unwrap_or(anchor),
            major,
            minor,
            rotate,
        },
        Shape::Triangle { t0, t1, t2 } => Geometry::Triangle { t0, t1, t2 },
        Shape::Plane { point, normal } => Geometry::Plane { point, normal },
        Shape::Floor { y } => Geometry::Plane {
            point: Vec3::new(0.0, y, 0.0),
            normal: Vec3::Y,
        },
    }
}

/// True when the shape has an anchor left to the layout.
pub fn is_unplaced(shape: &Shape) -> bool {
    matches!(
        shape,
        Shape::Sphere { center: None, .. }
            | Shape::Box { center: None, .. }
            | Shape::Cylinder { base: None, .. }
            | Shape::Cone { base: None, .. }
            | Shape::Torus { center: None, .. }
            | Shape::Mesh {
                translate: None,
                ..
            }
    )
}

/// Gap between neighbouring unplaced objects in the row.
const ROW_GAP: f32 = 0.5;

/// Geometries for `shapes`: given anchors are kept; unplaced shapes rest on
/// the floor at height `floor_y`, side by side along x in document order,
/// the row centred on x = 0 and z = 0.
pub fn place(shapes: &[&Shape], floor_y: f32) -> Vec<Geometry> {
    // Each unplaced shape's box when anchored at the origin.
    let footprints: Vec<Option<Aabb>> = shapes
        .iter()
        .map(|s| {
            if is_unplaced(s) {
                bounds(&geometry_at(s, Vec3::ZERO))
            } else {
                None
            }
        })
        .collect();
    let widths: Vec<f32> = footprints
        .iter()
        .flatten()
        .map(|b| b.max.x - b.min.x)
        .collect();
    let total = widths.iter().sum::<f32>() + ROW_GAP * widths.len().saturating_sub(1) as f32;
    let mut cursor = -0.5 * total;
    shapes
        .iter()
        .zip(&footprints)
        .map(|(shape, footprint)| match footprint {
            Some(b) => {
                let anchor = Vec3::new(cursor - b.min.x, floor_y - b.min.y, -b.center().z);
                cursor += b.max.x - b.min.x + ROW_GAP;
                geometry_at(shape, anchor)
            }
            None => geometry_at(shape, Vec3::ZERO),
        })
        .collect()
}

/// The default viewing direction: from the front (+z) and slightly above.
pub const DEFAULT_TOWARD: Vec3 = Vec3::new(0.0, -0.3, -1.0);

/// Extra room around the framed box, as a factor on the eye's distance.
const FRAMING_MARGIN: f32 = 1.12;

/// How far back from `focus`'s centre, along the unit toward vector `t`, the
/// eye must stand for every corner of `focus` to fall inside the view volume
/// of half-height angle θ and aspect ρ (up vector `up`), with a small margin.
pub fn framing_distance(focus: &Aabb, t: Vec3, up: Vec3, theta_deg: f32, aspect: f32) -> f32 {
    let u = (up - up.dot(t) * t).normalize_or(Vec3::Y);
    let r = t.cross(u);
    let tan_v = theta_deg.to_radians().tan().max(1e-4);
    let tan_h = aspect * tan_v;
    let center = focus.center();
    let mut distance = 0.0f32;
    for k in 0..8 {
        let corner = Vec3::new(
            if k & 1 == 0 { focus.min.x } else { focus.max.x },
            if k & 2 == 0 { focus.min.y } else { focus.max.y },
            if k & 4 == 0 { focus.min.z } else { focus.max.z },
        ) - center;
        // With the eye at centre − D t, this corner lies at depth D + corner·t.
        let depth_offset = corner.dot(t);
        distance = distance
            .max(corner.dot(r).abs() / tan_h - depth_offset)
            .max(corner.dot(u).abs() / tan_v - depth_offset);
    }
    FRAMING_MARGIN * distance.max(1e-3)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unplaced_objects_rest_on_the_floor_side_by_side() {
        let shapes = [
            Shape::default_for_tag("cone").expect("cone"),
            Shape::default_for_tag("sphere").expect("sphere"),
            Shape::default_for_tag("box").expect("box"),
        ];
        let placed = place(&shapes.each_ref(), 0.0);
        let boxes: Vec<Aabb> = placed.iter().map(|g| bounds(g).expect("finite")).collect();
        for b in &boxes {
            assert!(b.min.y.abs() < 1e-6, "rests on the floor: {b:?}");
        }
        for pair in boxes.windows(2) {
            assert!(
                (pair[1].min.x - pair[0].max.x - ROW_GAP).abs() < 1e-5,
                "side by side"
            );
        }
        let row = boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(*b));
        assert!(row.center().x.abs() < 1e-5, "centred: {row:?}");
    }

    #[test]
    fn rotated_box_bounds_grow_by_the_rotation() {
        let g = Geometry::Box {
            center: Vec3::ZERO,
            size: Vec3::ONE,
            rotate: Vec3::new(0.0, 45.0, 0.0),
        };
        let b = bounds(&g).expect("finite");
        assert!((b.max.x - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-6);
        assert!((b.max.y - 0.5).abs() < 1e-6);
    }
}
