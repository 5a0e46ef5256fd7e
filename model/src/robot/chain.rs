//! A kinematic tree with one planning chain: forward kinematics of every link and the
//! geometric Jacobian of any point on any link.
//!
//! Frames: link poses are world-frame isometries (m, rad). Joint axes are unit vectors in
//! the joint frame (URDF convention: child link frame = parent frame * origin * motion).
//! Jacobians are 6 x dof, rows (vx, vy, vz, wx, wy, wz) in the world frame.

use super::super::collision::query::intersects;
use super::super::collision::Geometry;
use crate::random::SplitMix64;
use nalgebra::{DMatrix, DVector, Isometry3, Point3, Translation3, Unit, UnitQuaternion, Vector3};

/// How a joint moves its child link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Turns about its axis (rad).
    Revolute,
    /// Slides along its axis (m).
    Prismatic,
    /// Does not move.
    Fixed,
}

/// A joint: how a link hangs from its parent.
#[derive(Clone, Debug)]
pub struct Joint {
    /// The URDF's joint name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// Index of the parent link.
    pub parent: usize,
    /// Pose of the joint frame in the parent link frame.
    pub origin: Isometry3<f64>,
    /// Unit axis in the joint frame.
    pub axis: Unit<Vector3<f64>>,
    /// Position limits (rad or m).
    pub lower: f64,
    /// Upper position limit (rad or m); `lower` is the lower one.
    pub upper: f64,
    /// Velocity limit (rad/s or m/s).
    pub max_velocity: f64,
    /// Index in the configuration vector, for joints on the planning chain.
    pub dof: Option<usize>,
    /// Value of a movable joint that is not on the planning chain (held still).
    pub held_value: f64,
}

impl Joint {
    /// Child frame relative to the joint frame at joint value `value`.
    #[inline]
    fn motion(&self, value: f64) -> Isometry3<f64> {
        match self.kind {
            JointKind::Revolute => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&self.axis, value),
            ),
            JointKind::Prismatic => Isometry3::from_parts(
                Translation3::from(self.axis.into_inner() * value),
                UnitQuaternion::identity(),
            ),
            JointKind::Fixed => Isometry3::identity(),
        }
    }
}

/// A rigid link of the robot.
#[derive(Clone, Debug)]
pub struct Link {
    /// The URDF's link name.
    pub name: String,
    /// The joint whose child this link is (`None` for the root).
    pub joint: Option<Joint>,
    /// Collision shapes in the link frame.
    pub geometry: Vec<Geometry>,
}

/// Links in topological order (every parent before its children; link 0 is the root).
#[derive(Clone, Debug)]
pub struct KinematicChain {
    /// Every link, parents first.
    pub links: Vec<Link>,
    /// World pose of the root link.
    pub base: Isometry3<f64>,
    /// For each configuration index, the link whose joint it drives.
    pub dof_links: Vec<usize>,
}

impl KinematicChain {
    /// The number of joints the planner moves (the configuration's length).
    pub fn dof(&self) -> usize {
        self.dof_links.len()
    }

    /// The index of the link named `name`, if there is one.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    /// The joint driven by configuration index `i`.
    pub fn dof_joint(&self, i: usize) -> &Joint {
        self.links[self.dof_links[i]]
            .joint
            .as_ref()
            .expect("a dof link has a joint")
    }

    /// Whether `link`'s pose depends on the configuration: some joint of the planning
    /// chain lies between it and the root (a held joint does not move it).
    pub fn moves_with_configuration(&self, link: usize) -> bool {
        let mut current = link;
        while let Some(joint) = &self.links[current].joint {
            if joint.dof.is_some() {
                return true;
            }
            current = joint.parent;
        }
        false
    }

    /// Position limits of the configuration, per index.
    pub fn limits(&self) -> Vec<(f64, f64)> {
        (0..self.dof())
            .map(|i| {
                let j = self.dof_joint(i);
                (j.lower, j.upper)
            })
            .collect()
    }

    /// A configuration drawn uniformly within the position limits, joint by joint in order.
    pub fn random_configuration(&self, rng: &mut SplitMix64) -> DVector<f64> {
        DVector::from_iterator(
            self.dof(),
            (0..self.dof()).map(|i| {
                let j = self.dof_joint(i);
                rng.uniform(j.lower, j.upper)
            }),
        )
    }

    /// Do links `a` and `b`, at their world `poses`, touch (any of their shapes)?
    pub fn links_intersect(&self, poses: &[Isometry3<f64>], a: usize, b: usize) -> bool {
        self.links[a].geometry.iter().any(|ga| {
            self.links[b]
                .geometry
                .iter()
                .any(|gb| intersects(ga, &poses[a], gb, &poses[b]))
        })
    }

    /// World poses of all links at configuration `q`, written to `poses`.
    pub fn forward_kinematics(&self, q: &DVector<f64>, poses: &mut Vec<Isometry3<f64>>) {
        poses.clear();
        for link in &self.links {
            let pose = match &link.joint {
                None => self.base,
                Some(j) => {
                    let value = j.dof.map_or(j.held_value, |i| q[i]);
                    poses[j.parent] * j.origin * j.motion(value)
                }
            };
            poses.push(pose);
        }
    }

    /// The 6 x dof geometric Jacobian of the world point `point`, rigidly attached to
    /// `link`, given the link poses from [`forward_kinematics`](Self::forward_kinematics).
    pub fn point_jacobian(
        &self,
        poses: &[Isometry3<f64>],
        link: usize,
        point: &Point3<f64>,
    ) -> DMatrix<f64> {
        let mut jac = DMatrix::zeros(6, self.dof());
        let mut current = link;
        while let Some(joint) = &self.links[current].joint {
            if let Some(i) = joint.dof {
                // The joint's motion keeps its axis fixed, so the axis and (for revolute
                // joints) the axis point can be read off the child link's pose.
                let pose = &poses[current];
                let axis = pose.rotation * joint.axis.into_inner();
                match joint.kind {
                    JointKind::Revolute => {
                        let lever = point - Point3::from(pose.translation.vector);
                        jac.fixed_view_mut::<3, 1>(0, i)
                            .copy_from(&axis.cross(&lever));
                        jac.fixed_view_mut::<3, 1>(3, i).copy_from(&axis);
                    }
                    JointKind::Prismatic => {
                        jac.fixed_view_mut::<3, 1>(0, i).copy_from(&axis);
                    }
                    JointKind::Fixed => {}
                }
            }
            current = joint.parent;
        }
        jac
    }

    /// Is `q` inside the joint limits?
    pub fn within_limits(&self, q: &DVector<f64>) -> Result<(), usize> {
        for i in 0..self.dof() {
            let j = self.dof_joint(i);
            if !(q[i] >= j.lower && q[i] <= j.upper) {
                return Err(i);
            }
        }
        Ok(())
    }

    /// Is link `b` a descendant of link `a`?
    pub fn is_ancestor(&self, a: usize, b: usize) -> bool {
        let mut current = b;
        while let Some(j) = &self.links[current].joint {
            if j.parent == a {
                return true;
            }
            current = j.parent;
        }
        false
    }
}
