//! Robots: a kinematic chain with collision geometry, an end effector held on a pushing
//! plane, and the pairs of links checked for self-collision.
//!
//! Two kinds share one implementation: an arm loaded from URDF, and the free-flying planar
//! hand of the earlier workshop paper, which is built as a chain of its own
//! (prismatic x, prismatic y, revolute z) so that kinematics, projection and contact
//! code are the same for both.

pub mod chain;
pub mod collision_matrix;
pub mod ik;
pub mod mesh;
pub mod planar_hand;
pub mod projection;
pub mod srdf;
pub mod urdf;
pub mod wgr;

pub use chain::{Joint, JointKind, KinematicChain, Link};
pub use ik::IkSettings;
pub use projection::{
    EeAction, ProjectionFailure, ProjectionSettings, PushingPlane, MAX_JOINT_STEP,
};

use nalgebra::{DVector, Isometry3};

/// What kind of robot pushes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RobotKind {
    /// A serial arm from URDF.
    Arm,
    /// A free-flying SE(2) hand (configuration x, y, yaw).
    PlanarHand,
}

/// The robot that pushes: its links and joints, its tool and the plane the tool is held on.
#[derive(Clone, Debug)]
pub struct Robot {
    /// An arm from URDF, or the planar hand.
    pub kind: RobotKind,
    /// Links and joints, parents first.
    pub chain: KinematicChain,
    /// The end-effector link.
    pub ee_link: usize,
    /// The tool point and frame in the end-effector link frame.
    pub tool: Isometry3<f64>,
    /// The plane and orientation the tool is held on.
    pub plane: PushingPlane,
    /// Link pairs checked for self-collision.
    pub self_collision_pairs: Vec<(usize, usize)>,
    /// Tolerances of the constraint projection.
    pub projection: ProjectionSettings,
}

impl Robot {
    /// A robot whose self-collision pairs are every pair of links that are not adjacent.
    pub fn new(
        kind: RobotKind,
        chain: KinematicChain,
        ee_link: usize,
        tool: Isometry3<f64>,
        plane: PushingPlane,
        projection: ProjectionSettings,
    ) -> Robot {
        let self_collision_pairs = non_adjacent_pairs(&chain);
        Robot {
            kind,
            chain,
            ee_link,
            tool,
            plane,
            self_collision_pairs,
            projection,
        }
    }

    /// Leaves the link pairs `allowed` (either order) out of the self-collision checks.
    pub fn skip_self_collisions(&mut self, allowed: &[(usize, usize)]) {
        let allowed = |a: usize, b: usize| allowed.contains(&(a, b)) || allowed.contains(&(b, a));
        self.self_collision_pairs.retain(|&(a, b)| !allowed(a, b));
    }

    /// The number of joints the planner moves.
    pub fn dof(&self) -> usize {
        self.chain.dof()
    }

    /// World pose of the tool frame, from link poses.
    pub fn tool_pose(&self, poses: &[Isometry3<f64>]) -> Isometry3<f64> {
        poses[self.ee_link] * self.tool
    }

    /// World poses of all links at `q`.
    pub fn link_poses(&self, q: &DVector<f64>) -> Vec<Isometry3<f64>> {
        let mut poses = Vec::with_capacity(self.chain.links.len());
        self.chain.forward_kinematics(q, &mut poses);
        poses
    }

    /// How far the end effector's collision geometry reaches across the tool's axis (m):
    /// the bounding spheres of the shapes of every link rigidly joined to the
    /// end-effector link (a tool frame on a link of its own, below the pusher that
    /// carries the geometry, reaches as far as the pusher), each its centre's distance
    /// from the tool's z axis plus its radius. On the pushing plane the tool's z axis is
    /// vertical: this is how far from the tool point the end effector meets an object.
    #[allow(non_snake_case)] // X_WT: the tool frame in the world frame
    pub fn tool_reach(&self) -> f64 {
        let chain = &self.chain;
        // Any configuration: the links measured move as one body.
        let poses = self.link_poses(&DVector::zeros(self.dof()));
        let X_WT = poses[self.ee_link] * self.tool;
        let body = rigid_body(chain, self.ee_link);
        (0..chain.links.len())
            .filter(|&l| rigid_body(chain, l) == body)
            .flat_map(|l| chain.links[l].geometry.iter().map(move |g| (l, g)))
            .map(|(l, g)| {
                let sphere = g.shape.compute_bounding_sphere(&(poses[l] * g.local));
                let p_TC = X_WT.inverse_transform_point(sphere.center());
                p_TC.xy().coords.norm() + sphere.radius()
            })
            .fold(0.0, f64::max)
    }

    /// Indices of links that have collision geometry.
    pub fn solid_links(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.chain.links.len()).filter(|&l| !self.chain.links[l].geometry.is_empty())
    }
}

/// Pairs of links with geometry that are not adjacent. Two solid links are adjacent when
/// one is the other's nearest solid ancestor: links without geometry between them
/// (the zero-length links of a spherical shoulder, say) do not separate them.
pub(crate) fn non_adjacent_pairs(chain: &KinematicChain) -> Vec<(usize, usize)> {
    let solid = |l: usize| !chain.links[l].geometry.is_empty();
    let nearest_solid_ancestor = |l: usize| {
        let mut current = l;
        while let Some(j) = &chain.links[current].joint {
            if solid(j.parent) {
                return Some(j.parent);
            }
            current = j.parent;
        }
        None
    };
    let solids: Vec<usize> = (0..chain.links.len()).filter(|&l| solid(l)).collect();
    let mut pairs = Vec::new();
    for (i, &a) in solids.iter().enumerate() {
        for &b in &solids[i + 1..] {
            let adjacent =
                nearest_solid_ancestor(b) == Some(a) || nearest_solid_ancestor(a) == Some(b);
            // Links rigidly joined (no movable joint between them) never move apart.
            if !adjacent && !rigidly_joined(chain, a, b) {
                pairs.push((a, b));
            }
        }
    }
    pairs
}

/// Are the two links connected by fixed joints (or held joints) only?
fn rigidly_joined(chain: &KinematicChain, a: usize, b: usize) -> bool {
    rigid_body(chain, a) == rigid_body(chain, b)
}

/// The rigid body `link` belongs to, named by its first link: up from `link` over fixed
/// (and held) joints to the link a moving joint drives, or the root.
fn rigid_body(chain: &KinematicChain, link: usize) -> usize {
    let mut current = link;
    while let Some(j) = &chain.links[current].joint {
        if j.dof.is_some() {
            break;
        }
        current = j.parent;
    }
    current
}
