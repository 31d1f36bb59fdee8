//! The node hierarchy: which nodes are drawn, and each node's world
//! transform (its own TRS or `matrix` after all its parents').

use super::warnings::Warnings;
use ::gltf::scene::Transform;
use ::gltf::{Document, Node};
use glam::{Mat4, Quat, Vec3};

/// The name raylab gives a node: its own, or `node <index>`.
pub(super) fn node_name(node: &Node) -> String {
    match node.name() {
        Some(name) => name.to_owned(),
        None => format!("node {}", node.index()),
    }
}

/// The node's transform relative to its parent.
pub(super) fn local_transform(node: &Node) -> Result<Mat4, String> {
    let m = match node.transform() {
        Transform::Matrix { matrix } => Mat4::from_cols_array_2d(&matrix),
        Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            // glTF stores (x, y, z, w); a rotation must be a unit quaternion,
            // which exporters round: normalise it.
            let rotation = Quat::from_array(rotation);
            if !(rotation.length_squared() > 0.0) {
                return Err(format!(
                    "node {}: rotation quaternion {rotation:?} is zero",
                    node.index()
                ));
            }
            Mat4::from_scale_rotation_translation(
                Vec3::from_array(scale),
                rotation.normalize(),
                Vec3::from_array(translation),
            )
        }
    };
    Ok(m)
}

/// Visits the nodes of the scene the file shows (its `scene`, else its first
/// scene, else every node that is no node's child), each parent before its
/// children, with the node's world transform.
pub(super) fn walk<'a>(
    doc: &'a Document,
    warnings: &mut Warnings,
    mut visit: impl FnMut(&Node<'a>, &Mat4, &mut Warnings) -> Result<(), String>,
) -> Result<(), String> {
    let roots: Vec<Node<'a>> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => {
            let scenes = doc.scenes().len();
            if scenes > 1 {
                let index = scene.index();
                warnings.once("scenes", || {
                    format!("the file has {scenes} scenes: raylab loads only scene {index} (the file's default)")
                });
            }
            scene.nodes().collect()
        }
        None => {
            let mut is_child = vec![false; doc.nodes().len()];
            for node in doc.nodes() {
                for child in node.children() {
                    is_child[child.index()] = true;
                }
            }
            doc.nodes().filter(|n| !is_child[n.index()]).collect()
        }
    };

    let mut visited = vec![false; doc.nodes().len()];
    let mut stack: Vec<(Node<'a>, Mat4)> = roots
        .into_iter()
        .rev()
        .map(|node| (node, Mat4::IDENTITY))
        .collect();
    while let Some((node, parent)) = stack.pop() {
        let index = node.index();
        if std::mem::replace(&mut visited[index], true) {
            return Err(format!(
                "node {index} is reached twice (two parents, a cycle, or listed as a scene root and as a child): glTF gives every node at most one parent"
            ));
        }
        let world = parent * local_transform(&node)?;
        if !world.is_finite() {
            return Err(format!(
                "node {index}: its world transform is not finite (a transform overflows)"
            ));
        }
        if node.skin().is_some() {
            warnings.once("skins", || {
                "skins are not supported: skinned meshes are drawn in their bind pose at their node's transform (joints and weights are ignored)".into()
            });
        }
        visit(&node, &world, warnings)?;
        let children: Vec<Node<'a>> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|child| (child, world)));
    }
    Ok(())
}
