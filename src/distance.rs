//! The distance metric of Sec. III-D:
//! `Dist(x, x') = w_q ||q - q'|| + sum_i w_i ||o_i - o'_i||`.
//!
//! The SE(2) part is `sqrt(dx^2 + dy^2 + (l dtheta)^2)` with `dtheta` wrapped to
//! (-pi, pi] and `l` (m/rad) the length one radian counts as. The goal object gets the
//! higher weight, which steers the search towards moving it.

use crate::math::{wrap_angle, Pose2};
use crate::scene::{Goal, Scene};
use crate::state::State;

#[derive(Clone, Debug, PartialEq)]
pub struct DistanceMetric {
    /// Weight of the joint-space distance (1/rad).
    pub robot_weight: f64,
    /// Weight of each object's SE(2) distance (1/m).
    pub object_weights: Vec<f64>,
    /// Length (m) one radian of yaw counts as.
    pub rotation_length: f64,
}

impl DistanceMetric {
    /// The metric with the scene's weights; the goal object gets `goal_object_weight`.
    pub fn from_scene(scene: &Scene) -> Self {
        let p = &scene.planner;
        let goal_object = match scene.goal {
            Goal::ObjectInDisc { object, .. } => Some(object),
            Goal::Configuration { .. } => None,
        };
        Self {
            robot_weight: p.robot_weight,
            object_weights: (0..scene.objects.len())
                .map(|i| {
                    if Some(i) == goal_object {
                        p.goal_object_weight
                    } else {
                        p.object_weight
                    }
                })
                .collect(),
            rotation_length: p.rotation_length,
        }
    }

    /// The largest distance between two states within the bounds: joints at opposite
    /// limits, every object at opposite corners of the table and turned half a turn
    /// (OMPL's `getMaximumExtent`).
    pub fn max_extent(&self, scene: &Scene) -> f64 {
        let joints = scene
            .robot
            .chain
            .limits()
            .iter()
            .map(|(lo, hi)| (hi - lo) * (hi - lo))
            .sum::<f64>()
            .sqrt();
        let table = &scene.table;
        let object = ((table.x.1 - table.x.0).powi(2)
            + (table.y.1 - table.y.0).powi(2)
            + (std::f64::consts::PI * self.rotation_length).powi(2))
        .sqrt();
        self.robot_weight * joints + self.object_weights.iter().sum::<f64>() * object
    }

    /// Distance between two object poses (m).
    pub fn object_distance(&self, a: &Pose2, b: &Pose2) -> f64 {
        let dtheta = wrap_angle(a.theta - b.theta) * self.rotation_length;
        ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + dtheta * dtheta).sqrt()
    }

    pub fn distance(&self, a: &State, b: &State) -> f64 {
        self.combine(
            (&a.q - &b.q).norm(),
            a.objects.iter().copied().zip(b.objects.iter().copied()),
        )
    }

    /// The same distance for states in the flat layout `[q, x_1, y_1, theta_1, ...]`
    /// (no allocation: the planner's nearest-neighbour queries call this a lot).
    pub fn distance_flat(&self, a: &[f64], b: &[f64]) -> f64 {
        let dof = a.len() - 3 * self.object_weights.len();
        let robot = a[..dof]
            .iter()
            .zip(&b[..dof])
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt();
        let pose = |s: &[f64], i: usize| {
            Pose2::new(s[dof + 3 * i], s[dof + 3 * i + 1], s[dof + 3 * i + 2])
        };
        let objects = (0..self.object_weights.len()).map(|i| (pose(a, i), pose(b, i)));
        self.combine(robot, objects)
    }

    fn combine(&self, robot: f64, objects: impl Iterator<Item = (Pose2, Pose2)>) -> f64 {
        let objects: f64 = self
            .object_weights
            .iter()
            .zip(objects)
            .map(|(w, (pa, pb))| w * self.object_distance(&pa, &pb))
            .sum();
        self.robot_weight * robot + objects
    }
}
