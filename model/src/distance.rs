//! The distance metric of Sec. III-D:
//! `Dist(x, x') = w_q ||q - q'|| + sum_i w_i ||o_i - o'_i||`.
//!
//! The SE(2) part is `sqrt(dx^2 + dy^2 + (l dtheta)^2)` with `dtheta` wrapped to
//! (-pi, pi] and `l` (m/rad) the length one radian counts as. The goal object gets the
//! higher weight, which steers the search towards moving it.

use crate::math::{wrap_angle, Pose2};
use crate::scene::{Goal, Scene};
use crate::state::State;
use std::f64::consts::PI;

/// The distance the planners measure between states (the paper's weighted metric): the
/// joint-space distance times `robot_weight` plus, per object, its planar distance (yaw
/// counted as `rotation_length` m per rad) times `object_weight`, the goal object's times
/// `goal_object_weight`.
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
        // A grasp goal is the arm's: its object weighs as clutter does.
        let goal_object = match scene.goal {
            Goal::ObjectInDisc { object, .. } => Some(object),
            Goal::Configuration { .. } | Goal::Grasp { .. } => None,
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
        self.squared_object_distance(a, b).sqrt()
    }

    fn squared_object_distance(&self, a: &Pose2, b: &Pose2) -> f64 {
        let dtheta = wrap_angle(a.theta - b.theta) * self.rotation_length;
        (a.x - b.x).powi(2) + (a.y - b.y).powi(2) + dtheta * dtheta
    }

    /// The distance from `a` to `b` (a weighted sum of rad and m); symmetric, zero for
    /// equal states.
    pub fn distance(&self, a: &State, b: &State) -> f64 {
        self.combine((&a.q - &b.q).norm(), |i| {
            self.squared_object_distance(&a.objects[i], &b.objects[i])
        })
    }

    /// The same distance for states in the flat layout `[q, x_1, y_1, theta_1, ...]`
    /// (no allocation: the planner's nearest-neighbour queries call this a lot).
    pub fn distance_flat(&self, a: &[f64], b: &[f64]) -> f64 {
        let dof = a.len() - State::flat_len(0, self.object_weights.len());
        let robot = a[..dof]
            .iter()
            .zip(&b[..dof])
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt();
        let pose = |s: &[f64], i: usize| {
            let k = State::flat_object(dof, i);
            Pose2::new(s[k], s[k + 1], s[k + 2])
        };
        self.combine(robot, |i| {
            self.squared_object_distance(&pose(a, i), &pose(b, i))
        })
    }

    /// A lower bound of [`Self::distance_flat`] from `a` to every flat state whose numbers
    /// lie within `[lo, hi]` (per number; yaws as raw angles in (-pi, pi]): each block of
    /// the sum (joints, each object's pose) takes its own smallest value over the box.
    /// Nearest-neighbour search skips a box whose bound already exceeds the best distance.
    pub fn lower_bound_flat(&self, a: &[f64], lo: &[f64], hi: &[f64]) -> f64 {
        // Finite numbers (the tree checks them), `lo <= hi`: at most one of the two
        // differences is positive, so the larger of them and 0 is the gap, with no branch
        // to mispredict (a query's boxes fall either side at random).
        let gap = |x: f64, lo: f64, hi: f64| (lo - x).max(x - hi).max(0.0);
        let dof = a.len() - State::flat_len(0, self.object_weights.len());
        let robot = (0..dof)
            .map(|j| gap(a[j], lo[j], hi[j]).powi(2))
            .sum::<f64>()
            .sqrt();
        self.combine(robot, |i| {
            let k = State::flat_object(dof, i);
            let dx = gap(a[k], lo[k], hi[k]);
            let dy = gap(a[k + 1], lo[k + 1], hi[k + 1]);
            let dtheta = arc_gap(a[k + 2], lo[k + 2], hi[k + 2]) * self.rotation_length;
            dx * dx + dy * dy + dtheta * dtheta
        })
    }

    /// How much one unit of each flat number counts in the metric (1/rad for joints, 1/m
    /// for positions, 1/rad for yaws): the nearest-neighbour tree splits its boxes along
    /// the number whose spread counts most.
    pub fn flat_weights(&self, dof: usize) -> Vec<f64> {
        let mut weights = vec![self.robot_weight; dof];
        for w in &self.object_weights {
            weights.extend([*w, *w, w * self.rotation_length]);
        }
        weights
    }

    /// `w_q robot + sum_i w_i sqrt(squared(i))`, summed in object order. The roots are
    /// taken a chunk at a time so that they run side by side (SIMD; a root's latency
    /// dominated the nearest-neighbour search); each is correctly rounded and the sum keeps
    /// its order, so the result is bit for bit that of one root after another.
    fn combine(&self, robot: f64, squared: impl Fn(usize) -> f64) -> f64 {
        const CHUNK: usize = 4;
        let mut objects = 0.0;
        for (c, weights) in self.object_weights.chunks(CHUNK).enumerate() {
            let mut roots = [0.0; CHUNK];
            for (j, root) in roots.iter_mut().enumerate().take(weights.len()) {
                *root = squared(c * CHUNK + j);
            }
            let roots = roots.map(f64::sqrt);
            for (w, root) in weights.iter().zip(roots) {
                objects += w * root;
            }
        }
        self.robot_weight * robot + objects
    }
}

/// The angle (rad) from `theta` to the nearest angle of the arc swept counterclockwise
/// from `lo` to `hi` (raw angles, `lo <= hi`; a span of a turn or more is the whole
/// circle).
fn arc_gap(theta: f64, lo: f64, hi: f64) -> f64 {
    if (lo..=hi).contains(&theta) {
        return 0.0;
    }
    if [theta, lo, hi].iter().all(|a| (-PI..=PI).contains(a)) {
        // Within one turn (the tree's yaws and its queries): up to the arc's start, or
        // round the other way back to its end; no wrapping needed.
        return if theta < lo {
            (lo - theta).min(theta - hi + 2.0 * PI)
        } else {
            (theta - hi).min(lo - theta + 2.0 * PI)
        };
    }
    let span = hi - lo;
    let mut from_lo = wrap_angle(theta - lo - PI) + PI; // in (0, 2 pi]
    if from_lo >= 2.0 * PI {
        from_lo -= 2.0 * PI;
    }
    if span >= 2.0 * PI || from_lo <= span {
        0.0
    } else {
        // Outside the arc: back to its end, or on to its start.
        (from_lo - span).min(2.0 * PI - from_lo)
    }
}
