//! [`Metric`]: the state space's distance (`ob::StateSpace::distance`), and the
//! nearest-neighbour structure of the planners' trees in it ([`NearestTree`]).

use super::core::{guarded, Flat};
use super::Problem;
use crate::distance::DistanceMetric;
use crate::planner::NearestTree;

/// The model's metric between flat states ([`DistanceMetric`]).
pub struct Metric {
    metric: DistanceMetric,
    state_len: usize,
    max_extent: f64,
    dof: usize,
    nearest_checks: usize,
}

impl Metric {
    /// The metric of `problem`'s states.
    pub fn new(problem: &Problem) -> Box<Metric> {
        let scene = &problem.scene;
        let metric = DistanceMetric::from_scene(scene);
        Box::new(Metric {
            max_extent: metric.max_extent(scene),
            state_len: Flat(scene).state_len(),
            dof: scene.robot.dof(),
            nearest_checks: scene.planner.nearest_checks as usize,
            metric,
        })
    }

    /// The distance between two flat states.
    pub fn distance(&self, a: &[f64], b: &[f64]) -> Result<f64, String> {
        guarded("distance", || {
            let n = self.state_len;
            if a.len() != n || b.len() != n {
                return Err(format!(
                    "states of {} and {} values, this scene needs {n}",
                    a.len(),
                    b.len()
                ));
            }
            Ok(self.metric.distance_flat(a, b))
        })
    }

    /// The largest distance between two states within the bounds.
    pub fn max_extent(&self) -> f64 {
        self.max_extent
    }

    /// An empty nearest-neighbour tree in this metric.
    pub fn nearest_tree(&self) -> Box<NearestTree> {
        Box::new(NearestTree::new(
            self.metric.clone(),
            self.dof,
            self.nearest_checks,
        ))
    }
}

// The tree's calls from C++, each with the state's length checked.

pub(super) fn tree_add(tree: &mut NearestTree, state: &[f64]) -> Result<usize, String> {
    tree.checked(state)?;
    Ok(tree.add(state))
}

/// The nearest state's index, or -1 for an empty tree.
pub(super) fn tree_nearest(tree: &NearestTree, state: &[f64]) -> Result<i64, String> {
    let nearest = tree.nearest(tree.checked(state)?);
    Ok(nearest.map_or(-1, |(id, _)| id as i64))
}

pub(super) fn tree_nearest_k(
    tree: &NearestTree,
    state: &[f64],
    k: usize,
) -> Result<Vec<usize>, String> {
    Ok(indices(tree.nearest_k(tree.checked(state)?, k)))
}

pub(super) fn tree_nearest_r(
    tree: &NearestTree,
    state: &[f64],
    radius: f64,
) -> Result<Vec<usize>, String> {
    Ok(indices(tree.nearest_r(tree.checked(state)?, radius)))
}

fn indices(found: Vec<(usize, f64)>) -> Vec<usize> {
    found.into_iter().map(|(id, _)| id).collect()
}
