//! Workspace Goal Regions (Berenson, Srinivasa, Ferguson, Collet, Kuffner, ICRA 2009; the
//! manipulation-planning lecture's definition): a frame `w` in the world, the end
//! effector's pose `T_e^w` relative to `w` at the nominal grasp, and bounds `B^w` on the six
//! displacement coordinates (x, y, z in m; roll, pitch, yaw in rad) of the grasp within
//! `w`. Issue 15: the region, its sampling and its distance.
//!
//! Frames, Drake style: `X_0W` is `w` in the world (`T_w^0`), `X_WS` a displacement
//! sample in `w` (`T_sample^w`), `X_SE` the end effector in the displaced grasp frame
//! (`T_e^w`). Rotations of a displacement are `R = Rz(yaw) Ry(pitch) Rx(roll)`, which the
//! lecture's `d^w` inverts: `roll = atan2(R32, R33)`, `pitch = -asin(R31)`,
//! `yaw = atan2(R21, R11)` (1-based indices).

use super::{IkSettings, Robot};
use crate::math::Pose2;
use crate::random::SplitMix64;
use nalgebra::{DVector, Isometry3, Translation3, UnitQuaternion};

/// A displacement of the grasp within `w`: x, y, z (m), roll, pitch, yaw (rad).
pub type Displacement = [f64; 6];

/// A configuration is inside a grasp region within this distance (the lecture's
/// `d(q, WGR)`, m and rad together).
pub const GRASP_TOLERANCE: f64 = 1e-3;

/// A Workspace Goal Region attached to an object: the region with its frame `w` given in
/// the object frame (`X_OW` in place of `X_0W`).
#[derive(Clone, Debug, PartialEq)]
pub struct Grasp(pub Wgr);

impl Grasp {
    /// The region in the world for the object at `pose` on a table whose top is at
    /// `table_top`: `X_0W = X_0O X_OW`.
    pub fn region(&self, pose: &Pose2, table_top: f64) -> Wgr {
        Wgr {
            x_0w: pose.to_isometry(table_top) * self.0.x_0w,
            ..self.0.clone()
        }
    }
}

/// The lecture's distance from configuration `q` of `robot` to the nearest of `grasps`
/// of an object at `pose` on a table at `table_top` (forward kinematics once).
pub fn distance_to_grasps(
    robot: &Robot,
    table_top: f64,
    grasps: &[Grasp],
    pose: &Pose2,
    q: &DVector<f64>,
) -> f64 {
    let x_0e = robot.tool_pose(&robot.link_poses(q));
    grasps
        .iter()
        .map(|g| g.region(pose, table_top).distance_from_pose(&x_0e))
        .fold(f64::INFINITY, f64::min)
}

/// A Workspace Goal Region.
#[derive(Clone, Debug, PartialEq)]
pub struct Wgr {
    /// `w` in the world (`T_w^0`).
    pub x_0w: Isometry3<f64>,
    /// The end effector in the grasp frame (`T_e^w`).
    pub x_se: Isometry3<f64>,
    /// `B^w`: (min, max) of each displacement coordinate.
    pub bounds: [(f64, f64); 6],
}

/// The transform of a displacement (`T_sample^w` of `d^w_sample`).
pub fn displacement_transform(d: &Displacement) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(d[0], d[1], d[2]),
        UnitQuaternion::from_euler_angles(d[3], d[4], d[5]),
    )
}

/// The displacement of a transform (the lecture's `d^w`): its translation and the roll,
/// pitch and yaw of its rotation.
pub fn displacement(x: &Isometry3<f64>) -> Displacement {
    let r = x.rotation.to_rotation_matrix();
    let r = r.matrix();
    let t = x.translation.vector;
    [
        t.x,
        t.y,
        t.z,
        r[(2, 1)].atan2(r[(2, 2)]),
        -r[(2, 0)].clamp(-1.0, 1.0).asin(),
        r[(1, 0)].atan2(r[(0, 0)]),
    ]
}

impl Wgr {
    /// A uniform sample of the displacement bounds.
    pub fn sample_displacement(&self, rng: &mut SplitMix64) -> Displacement {
        let mut d = [0.0; 6];
        for (value, (lo, hi)) in d.iter_mut().zip(&self.bounds) {
            *value = if hi > lo { rng.uniform(*lo, *hi) } else { *lo };
        }
        d
    }

    /// The end effector's world pose at displacement `d`: `T_w^0 T_sample^w T_e^w`.
    pub fn end_effector_pose(&self, d: &Displacement) -> Isometry3<f64> {
        self.x_0w * displacement_transform(d) * self.x_se
    }

    /// How far an end-effector world pose `x_0e` is from the region: the grasp frame it
    /// implies (`T_s^0 (T_e^w)^-1`), in `w`, as a displacement, less the bounds; the norm
    /// of what lies outside them (m and rad together, as the lecture does).
    pub fn distance_from_pose(&self, x_0e: &Isometry3<f64>) -> f64 {
        let x_ws = self.x_0w.inverse() * x_0e * self.x_se.inverse();
        displacement(&x_ws)
            .iter()
            .zip(&self.bounds)
            .map(|(d, (lo, hi))| {
                if d < lo {
                    d - lo
                } else if d > hi {
                    d - hi
                } else {
                    0.0
                }
            })
            .map(|outside| outside * outside)
            .sum::<f64>()
            .sqrt()
    }

    /// The distance from configuration `q` of `robot` (its tool frame is the end effector).
    pub fn distance(&self, robot: &Robot, q: &DVector<f64>) -> f64 {
        let poses = robot.link_poses(q);
        self.distance_from_pose(&robot.tool_pose(&poses))
    }

    /// Configurations reaching a sample of the region: up to `tries` displacements drawn
    /// uniformly, each solved by inverse kinematics from `seed`, kept when `valid` says so.
    /// The first kept one, or `None`.
    pub fn sample_configuration(
        &self,
        robot: &Robot,
        seed: &DVector<f64>,
        rng: &mut SplitMix64,
        tries: usize,
        valid: impl Fn(&DVector<f64>) -> bool,
    ) -> Option<DVector<f64>> {
        let settings = IkSettings::default();
        (0..tries).find_map(|_| {
            let target = self.end_effector_pose(&self.sample_displacement(rng));
            robot
                .reach_tool_pose(&target, seed, &settings)
                .filter(|q| valid(q))
        })
    }
}
