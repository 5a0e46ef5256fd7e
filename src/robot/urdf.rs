//! Robots from URDF: the kinematic tree, joint limits and collision geometry.

use super::chain::{Joint, JointKind, KinematicChain, Link};
use super::mesh::{load_convex_mesh, resolve_mesh_path};
use crate::collision::{Geometry, Primitive};
use crate::error::{Error, Result};
use crate::math::isometry_from_xyz_rpy;
use nalgebra::{Isometry3, Unit, Vector3};
use std::path::Path;

/// Loads the URDF at `path` as a kinematic chain whose configuration is the movable
/// joints on the path from the root link to `end_effector`, in order.
///
/// Movable joints off that path (fingers, say) are held at 0 (or the nearest limit).
/// Continuous joints get the limits [-pi, pi]. Floating, planar and spherical joints are
/// rejected. `base` is the world pose of the root link.
pub fn load_urdf(path: &Path, end_effector: &str, base: Isometry3<f64>) -> Result<KinematicChain> {
    let urdf_error = |message: String| Error::Urdf {
        file: path.to_path_buf(),
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        file: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let robot = urdf_rs::read_from_string(&text).map_err(|e| urdf_error(e.to_string()))?;

    // The root is the one link that is no joint's child.
    let is_child = |name: &str| robot.joints.iter().any(|j| j.child.link == name);
    let roots: Vec<&str> = robot
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|n| !is_child(n))
        .collect();
    let root = match roots.as_slice() {
        [root] => *root,
        [] => return Err(urdf_error("no root link (the joints form a cycle)".into())),
        many => {
            return Err(urdf_error(format!(
                "several root links ({}): the links must form one tree",
                many.join(", ")
            )))
        }
    };
    if !robot.links.iter().any(|l| l.name == end_effector) {
        return Err(urdf_error(format!(
            "no link named '{end_effector}' (the end-effector link)"
        )));
    }
    for j in &robot.joints {
        for name in [&j.parent.link, &j.child.link] {
            if !robot.links.iter().any(|l| &l.name == name) {
                return Err(urdf_error(format!(
                    "joint '{}' names the missing link '{name}'",
                    j.name
                )));
            }
        }
    }

    // Breadth-first from the root gives a topological order (parents first).
    let mut order: Vec<(String, Option<usize>)> = vec![(root.to_string(), None)];
    let mut next = 0;
    while next < order.len() {
        let parent_name = order[next].0.clone();
        for (ji, j) in robot.joints.iter().enumerate() {
            if j.parent.link == parent_name {
                if order.iter().any(|(n, _)| *n == j.child.link) {
                    return Err(urdf_error(format!(
                        "link '{}' has more than one parent",
                        j.child.link
                    )));
                }
                order.push((j.child.link.clone(), Some(ji)));
            }
        }
        next += 1;
    }

    // The planning chain: joints from the end effector up to the root.
    let mut chain_joints = Vec::new();
    let mut current = end_effector.to_string();
    while let Some(pos) = order.iter().position(|(n, _)| *n == current) {
        let Some(ji) = order[pos].1 else { break };
        chain_joints.push(ji);
        current = robot.joints[ji].parent.link.clone();
    }
    chain_joints.reverse();

    let mut links: Vec<Link> = Vec::with_capacity(order.len());
    let mut dof_links = Vec::new();
    for (name, joint_index) in &order {
        let urdf_link = robot
            .links
            .iter()
            .find(|l| &l.name == name)
            .expect("ordered links exist");
        let geometry = link_geometry(path, urdf_link)?;
        let joint = match joint_index {
            None => None,
            Some(ji) => {
                let j = &robot.joints[*ji];
                let on_chain = chain_joints.contains(ji);
                let joint = convert_joint(path, j, &links)?;
                let joint = if on_chain && joint.kind != JointKind::Fixed {
                    dof_links.push(links.len());
                    Joint {
                        dof: Some(dof_links.len() - 1),
                        ..joint
                    }
                } else {
                    joint
                };
                Some(joint)
            }
        };
        links.push(Link {
            name: name.clone(),
            joint,
            geometry,
        });
    }
    Ok(KinematicChain {
        links,
        base,
        dof_links,
    })
}

fn convert_joint(path: &Path, j: &urdf_rs::Joint, links: &[Link]) -> Result<Joint> {
    let urdf_error = |message: String| Error::Urdf {
        file: path.to_path_buf(),
        message: format!("joint '{}': {message}", j.name),
    };
    let parent = links
        .iter()
        .position(|l| l.name == j.parent.link)
        .expect("parents come first in breadth-first order");
    let (kind, lower, upper) = match j.joint_type {
        urdf_rs::JointType::Revolute => (JointKind::Revolute, j.limit.lower, j.limit.upper),
        urdf_rs::JointType::Continuous => (
            JointKind::Revolute,
            -std::f64::consts::PI,
            std::f64::consts::PI,
        ),
        urdf_rs::JointType::Prismatic => (JointKind::Prismatic, j.limit.lower, j.limit.upper),
        urdf_rs::JointType::Fixed => (JointKind::Fixed, 0.0, 0.0),
        ref other => return Err(urdf_error(format!("{other:?} joints are not supported"))),
    };
    let numbers = j
        .origin
        .xyz
        .iter()
        .chain(j.origin.rpy.iter())
        .chain(j.axis.xyz.iter());
    if numbers
        .chain([&lower, &upper, &j.limit.velocity])
        .any(|v| !v.is_finite())
    {
        return Err(urdf_error(
            "origin, axis and limits must be finite numbers".into(),
        ));
    }
    if kind != JointKind::Fixed && lower >= upper {
        return Err(urdf_error(format!(
            "limit lower ({lower}) must be below upper ({upper})"
        )));
    }
    let axis = Unit::try_new(Vector3::from(*j.axis.xyz), 1e-9)
        .ok_or_else(|| urdf_error("axis must not be zero".into()))?;
    let max_velocity = if j.limit.velocity > 0.0 {
        j.limit.velocity
    } else {
        f64::INFINITY
    };
    Ok(Joint {
        name: j.name.clone(),
        kind,
        parent,
        origin: isometry_from_xyz_rpy(*j.origin.xyz, *j.origin.rpy),
        axis,
        lower,
        upper,
        max_velocity,
        dof: None,
        held_value: 0.0_f64.clamp(lower.min(upper), upper.max(lower)),
    })
}

fn link_geometry(path: &Path, link: &urdf_rs::Link) -> Result<Vec<Geometry>> {
    let urdf_error = |message: String| Error::Urdf {
        file: path.to_path_buf(),
        message: format!("link '{}': {message}", link.name),
    };
    let mut out = Vec::new();
    for c in &link.collision {
        let primitive = match &c.geometry {
            urdf_rs::Geometry::Box { size } => Primitive::Box {
                size: Vector3::from(**size),
            },
            urdf_rs::Geometry::Cylinder { radius, length } => Primitive::Cylinder {
                radius: *radius,
                length: *length,
            },
            urdf_rs::Geometry::Sphere { radius } => Primitive::Sphere { radius: *radius },
            urdf_rs::Geometry::Capsule { radius, length } => Primitive::Capsule {
                radius: *radius,
                length: *length,
            },
            urdf_rs::Geometry::Mesh { filename, scale } => {
                let mesh_path = resolve_mesh_path(filename, path).ok_or_else(|| Error::Mesh {
                    file: path.to_path_buf(),
                    message: format!("link '{}': mesh '{filename}' not found", link.name),
                })?;
                load_convex_mesh(&mesh_path, scale.as_ref().map_or([1.0; 3], |s| **s))?
            }
        };
        check_dimensions(&primitive).map_err(urdf_error)?;
        let local = isometry_from_xyz_rpy(*c.origin.xyz, *c.origin.rpy);
        let geometry = Geometry::new(&primitive, local)
            .ok_or_else(|| urdf_error("collision mesh is flat (no convex hull)".into()))?;
        out.push(geometry);
    }
    Ok(out)
}

/// Positive, finite dimensions for primitive solids.
pub fn check_dimensions(primitive: &Primitive) -> std::result::Result<(), String> {
    let dims: Vec<f64> = match primitive {
        Primitive::Box { size } => size.iter().copied().collect(),
        Primitive::Cylinder { radius, length } | Primitive::Capsule { radius, length } => {
            vec![*radius, *length]
        }
        Primitive::Sphere { radius } => vec![*radius],
        Primitive::ConvexHull { .. } => vec![],
    };
    if dims.iter().all(|d| d.is_finite() && *d > 0.0) {
        Ok(())
    } else {
        Err(format!(
            "dimensions must be positive and finite, got {dims:?}"
        ))
    }
}
