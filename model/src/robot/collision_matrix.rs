//! Which pairs of a robot's links need no self-collision check, found as MoveIt's Setup
//! Assistant finds them: links adjacent in the tree are never checked (the robot's own
//! rule, [`Robot::new`]); of the other pairs, those in collision at the zero configuration,
//! those in collision in nearly every random configuration, and those in collision in none,
//! may be skipped. A pair that always touches is part of the robot's design (a cover over
//! a joint), one that never does cannot reach the other; either way checking it only costs
//! time, or stops every search.
//!
//! "Never" is a sampled verdict, as in MoveIt: two links that meet in a rare configuration
//! the samples missed would go unchecked. More samples make it rarer.

use super::{non_adjacent_pairs, Robot};
use crate::random::SplitMix64;
use nalgebra::DVector;

/// Share of the random configurations in which a pair must collide to count as always
/// in collision (MoveIt's Setup Assistant's default, 95 %).
pub const ALWAYS_SHARE: f64 = 0.95;

/// Why a pair of links may be left out of the self-collision checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkipReason {
    /// They collide at the zero configuration (each joint at 0, or its nearest limit).
    AtZero,
    /// They collide in at least [`ALWAYS_SHARE`] of the random configurations.
    Always,
    /// They collide in none of the random configurations.
    Never,
}

impl SkipReason {
    /// The reason in words, as MoveIt's SRDF writes it (`Default`, `Always`, `Never`).
    pub fn name(self) -> &'static str {
        match self {
            SkipReason::AtZero => "Default",
            SkipReason::Always => "Always",
            SkipReason::Never => "Never",
        }
    }
}

/// A pair of links (indices into the chain's links) that may go unchecked.
#[derive(Clone, Debug, PartialEq)]
pub struct SkippedPair {
    /// One link.
    pub a: usize,
    /// The other.
    pub b: usize,
    /// Why.
    pub reason: SkipReason,
    /// In how many of the random configurations they collided.
    pub collisions: usize,
}

/// The self-collision pairs of a robot, sorted.
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionMatrix {
    /// Random configurations tried.
    pub samples: usize,
    /// Pairs of solid links that are not adjacent (those the robot would check).
    pub candidates: usize,
    /// Pairs that may go unchecked, in the candidates' order.
    pub skipped: Vec<SkippedPair>,
}

/// The [`CollisionMatrix`] of `robot` from `samples` configurations drawn uniformly within
/// the joint limits with `seed` (the same robot, samples and seed: the same matrix).
pub fn collision_matrix(robot: &Robot, samples: usize, seed: u64) -> CollisionMatrix {
    let chain = &robot.chain;
    let candidates = non_adjacent_pairs(chain);
    let limits = chain.limits();
    let zero = DVector::from_iterator(
        limits.len(),
        limits.iter().map(|&(lo, hi)| 0.0f64.clamp(lo, hi)),
    );
    let at_zero = robot.link_poses(&zero);
    let mut counts = vec![0usize; candidates.len()];
    let mut rng = SplitMix64::new(seed);
    for _ in 0..samples {
        let poses = robot.link_poses(&chain.random_configuration(&mut rng));
        for (count, &(a, b)) in counts.iter_mut().zip(&candidates) {
            *count += usize::from(chain.links_intersect(&poses, a, b));
        }
    }
    let skipped = candidates
        .iter()
        .zip(&counts)
        .filter_map(|(&(a, b), &collisions)| {
            let reason = if chain.links_intersect(&at_zero, a, b) {
                SkipReason::AtZero
            } else if samples > 0 && collisions as f64 >= ALWAYS_SHARE * samples as f64 {
                SkipReason::Always
            } else if samples > 0 && collisions == 0 {
                SkipReason::Never
            } else {
                return None;
            };
            Some(SkippedPair {
                a,
                b,
                reason,
                collisions,
            })
        })
        .collect();
    CollisionMatrix {
        samples,
        candidates: candidates.len(),
        skipped,
    }
}
