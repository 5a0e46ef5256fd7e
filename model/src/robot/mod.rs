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
pub use projection::{EeAction, ProjectionFailure, ProjectionSettings, PushingPlane};

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

    /// How far the end effector's collision geometry reaches from the tool point (m): the
    /// bounding spheres of the end-effector link's shapes, about the tool point.
    pub fn tool_reach(&self) -> f64 {
        let tool = self.tool.translation.vector; // in the end-effector link frame
        self.chain.links[self.ee_link]
            .geometry
            .iter()
            .map(|g| {
                let sphere = g.shape.compute_bounding_sphere(&g.local);
                (sphere.center().coords - tool).norm() + sphere.radius()
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
    let path_is_rigid = |from: usize, to: usize| {
        let mut current = to;
        while current != from {
            match &chain.links[current].joint {
                Some(j) if j.dof.is_none() => current = j.parent,
                _ => return false,
            }
        }
        true
    };
    (chain.is_ancestor(a, b) && path_is_rigid(a, b))
        || (chain.is_ancestor(b, a) && path_is_rigid(b, a))
}
