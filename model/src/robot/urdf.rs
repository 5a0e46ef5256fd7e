//! Robots from URDF: the kinematic tree, joint limits and collision geometry.

use super::chain::{Joint, JointKind, KinematicChain, Link};
use super::mesh::{load_collision_mesh, resolve_mesh_path};
use crate::collision::{Geometry, Primitive};
use crate::error::{Error, Result};
use crate::input::name_list;
use crate::math::isometry_from_xyz_rpy;
use nalgebra::{Isometry3, Unit, Vector3};
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// Most links in a URDF (every link's shapes are checked at every propagation step).
pub const MAX_LINKS: usize = 1000;

/// Loads the URDF at `path` as a kinematic chain whose configuration is the movable
/// joints on the path from the root link to `end_effector`, in order.
///
/// Movable joints off that path (fingers, say) are held at 0 (or the nearest limit), and
/// floating, planar and spherical joints off it at their origin. Continuous joints get the
/// limits [-pi, pi]. Floating, planar and spherical joints on the path are rejected.
/// `base` is the world pose of the root link.
pub fn load_urdf(path: &Path, end_effector: &str, base: Isometry3<f64>) -> Result<KinematicChain> {
    load_urdf_chain(path, None, end_effector, base)
}

/// [`load_urdf`] with the configuration the movable joints from `chain_base` (a link
/// between the root and `end_effector`, as an SRDF group's `<chain base_link>` names it;
/// `None`: the root) to `end_effector`: the joints above it are held like those off the
/// chain (a torso, a mobile base's lift).
pub fn load_urdf_chain(
    path: &Path,
    chain_base: Option<&str>,
    end_effector: &str,
    base: Isometry3<f64>,
) -> Result<KinematicChain> {
    let urdf_error = |message: String| Error::Urdf {
        file: path.to_path_buf(),
        message,
    };
    let text = crate::input::read_text(path, crate::input::MAX_URDF_BYTES)
        .map_err(|message| Error::io(path, message))?;
    let robot = urdf_rs::read_from_string(&text).map_err(|e| urdf_error(e.to_string()))?;

    let order = tree_order(&robot).map_err(urdf_error)?;
    if !order.iter().any(|(name, _)| name == end_effector) {
        return Err(Error::NoEndEffector {
            file: path.to_path_buf(),
            message: format!(
                "no link named '{end_effector}' (the end-effector link); the links are {}",
                name_list(robot.links.iter().map(|l| l.name.as_str()))
            ),
        });
    }

    // The planning chain: joints from the end effector up to the root.
    let position: HashMap<&str, usize> = order
        .iter()
        .enumerate()
        .map(|(i, (name, _))| (name.as_str(), i))
        .collect();
    let mut chain_joints = Vec::new();
    let mut current = end_effector;
    while Some(current) != chain_base {
        let Some(ji) = order[position[current]].1 else {
            if chain_base.is_none() {
                break;
            }
            return Err(Error::NoEndEffector {
                file: path.to_path_buf(),
                message: format!(
                    "link '{}' (the chain's base) is not on the way from the root link to '{end_effector}'",
                    chain_base.unwrap_or_default()
                ),
            });
        };
        chain_joints.push(ji);
        current = robot.joints[ji].parent.link.as_str();
    }
    let chain_joints: HashSet<usize> = chain_joints.into_iter().collect();

    let link_index: HashMap<&str, usize> = robot
        .links
        .iter()
        .enumerate()
        .map(|(i, l)| (l.name.as_str(), i))
        .collect();
    let mut links: Vec<Link> = Vec::with_capacity(order.len());
    let mut dof_links = Vec::new();
    for (name, joint_index) in &order {
        let urdf_link = &robot.links[link_index[name.as_str()]];
        let geometry = link_geometry(path, urdf_link)?;
        let joint = match joint_index {
            None => None,
            Some(ji) => {
                let j = &robot.joints[*ji];
                let on_chain = chain_joints.contains(ji);
                let parent = position[j.parent.link.as_str()];
                let joint = convert_joint(path, j, parent, on_chain)?;
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

/// The URDF's links in breadth-first order from the root (parents first), each with the
/// index of the joint that attaches it to its parent (`None` for the root). Refuses
/// anything but one tree: duplicate names, joints naming missing links, links with two
/// parents, cycles, several roots and links cut off from the root. Linear in the number
/// of links and joints.
fn tree_order(robot: &urdf_rs::Robot) -> std::result::Result<Vec<(String, Option<usize>)>, String> {
    if robot.links.len() > MAX_LINKS {
        return Err(format!(
            "{} links; a robot has at most {MAX_LINKS}",
            robot.links.len()
        ));
    }
    let mut links = HashSet::new();
    for l in &robot.links {
        if l.name.is_empty() {
            return Err("a link has an empty name".into());
        }
        if !links.insert(l.name.as_str()) {
            return Err(format!("two links are named '{}'", l.name));
        }
    }
    let mut joints = HashSet::new();
    let mut parent_joint: HashMap<&str, usize> = HashMap::new();
    let mut children: HashMap<&str, Vec<usize>> = HashMap::new();
    for (ji, j) in robot.joints.iter().enumerate() {
        if !joints.insert(j.name.as_str()) {
            return Err(format!("two joints are named '{}'", j.name));
        }
        for name in [&j.parent.link, &j.child.link] {
            if !links.contains(name.as_str()) {
                return Err(format!(
                    "joint '{}' names the missing link '{name}'",
                    j.name
                ));
            }
        }
        if parent_joint.insert(j.child.link.as_str(), ji).is_some() {
            return Err(format!("link '{}' has more than one parent", j.child.link));
        }
        children.entry(j.parent.link.as_str()).or_default().push(ji);
    }
    let roots: Vec<&str> = robot
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|n| !parent_joint.contains_key(n))
        .collect();
    let root = match roots.as_slice() {
        [root] => *root,
        [] => return Err("no root link (the joints form a cycle)".into()),
        many => {
            return Err(format!(
                "several root links ({}): the links must form one tree",
                name_list(many.iter().copied())
            ))
        }
    };
    let mut order: Vec<(String, Option<usize>)> = vec![(root.to_string(), None)];
    let mut next = 0;
    while next < order.len() {
        if let Some(joints) = children.get(order[next].0.as_str()) {
            order.extend(
                joints
                    .iter()
                    .map(|&ji| (robot.joints[ji].child.link.clone(), Some(ji))),
            );
        }
        next += 1;
    }
    if order.len() < robot.links.len() {
        let reached: HashSet<&str> = order.iter().map(|(n, _)| n.as_str()).collect();
        return Err(format!(
            "links {} are not connected to the root link '{root}' (their joints form a cycle)",
            name_list(
                robot
                    .links
                    .iter()
                    .map(|l| l.name.as_str())
                    .filter(|n| !reached.contains(n))
            )
        ));
    }
    Ok(order)
}

/// `j` as a joint of the chain; `on_chain`: between the root and the end effector (off
/// it, a floating, planar or spherical joint is held like the others, as a fixed one).
fn convert_joint(path: &Path, j: &urdf_rs::Joint, parent: usize, on_chain: bool) -> Result<Joint> {
    let urdf_error = |message: String| Error::Urdf {
        file: path.to_path_buf(),
        message: format!("joint '{}': {message}", j.name),
    };
    // As URDF writes it: `revolute`, `floating`, ...
    let type_name = format!("{:?}", j.joint_type).to_lowercase();
    let (kind, lower, upper) = match j.joint_type {
        urdf_rs::JointType::Revolute => (JointKind::Revolute, j.limit.lower, j.limit.upper),
        urdf_rs::JointType::Continuous => (
            JointKind::Revolute,
            -std::f64::consts::PI,
            std::f64::consts::PI,
        ),
        urdf_rs::JointType::Prismatic => (JointKind::Prismatic, j.limit.lower, j.limit.upper),
        urdf_rs::JointType::Fixed => (JointKind::Fixed, 0.0, 0.0),
        _ if !on_chain => (JointKind::Fixed, 0.0, 0.0),
        _ => {
            return Err(urdf_error(format!(
                "{} joints are not supported between the root link and the end effector (off that chain they are held fixed)",
                type_name
            )))
        }
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
    // Off the chain a joint is held (at 0, or the nearest limit): its range need not be
    // one, as ROS's urdfdom does not ask (grippers' URDFs hold fingers at 0..0).
    if on_chain && kind != JointKind::Fixed && lower >= upper {
        return Err(urdf_error(format!(
            "limit lower ({lower}) must be below upper ({upper})"
        )));
    }
    // A fixed joint has no axis to turn about: ROS's urdfdom does not read it, and public
    // URDFs (Franka's panda_joint8) write `0 0 0` there.
    let axis = match kind {
        JointKind::Fixed => Vector3::z_axis(),
        _ => Unit::try_new(Vector3::from(*j.axis.xyz), 1e-9).ok_or_else(|| {
            urdf_error(format!(
                "axis must not be zero on a {type_name} joint (it is the direction the joint moves about)"
            ))
        })?,
    };
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
        let primitives = match &c.geometry {
            urdf_rs::Geometry::Box { size } => vec![Primitive::Box {
                size: Vector3::from(**size),
            }],
            urdf_rs::Geometry::Cylinder { radius, length } => vec![Primitive::Cylinder {
                radius: *radius,
                length: *length,
            }],
            urdf_rs::Geometry::Sphere { radius } => vec![Primitive::Sphere { radius: *radius }],
            urdf_rs::Geometry::Capsule { radius, length } => vec![Primitive::Capsule {
                radius: *radius,
                length: *length,
            }],
            urdf_rs::Geometry::Mesh { filename, scale } => {
                let mesh_path = resolve_mesh_path(filename, path).map_err(|why| Error::Mesh {
                    file: path.to_path_buf(),
                    message: format!("link '{}': mesh '{filename}' not found: {why}", link.name),
                })?;
                // A concave mesh collides as several convex parts, each a geometry of
                // the link as a URDF's several <collision> elements are.
                load_collision_mesh(&mesh_path, scale.as_ref().map_or([1.0; 3], |s| **s))?
            }
        };
        let local = isometry_from_xyz_rpy(*c.origin.xyz, *c.origin.rpy);
        for primitive in &primitives {
            check_dimensions(primitive).map_err(urdf_error)?;
            let geometry = Geometry::new(primitive, local)
                .ok_or_else(|| urdf_error("collision mesh is flat (no convex hull)".into()))?;
            out.push(geometry);
        }
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
    let most = crate::limits::MAX_EXTENT;
    if dims.iter().all(|d| d.is_finite() && *d > 0.0 && *d <= most) {
        Ok(())
    } else {
        Err(format!(
            "dimensions must be positive and at most {most} m, got {dims:?}"
        ))
    }
}
