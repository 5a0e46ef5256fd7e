//! Perturbed worlds carried along the search (robust planning's particles). Each tree
//! state holds, beside its nominal object poses, the poses the same controls reached in
//! each of a few perturbed worlds ([`Noise::default`]: start poses, masses, frictions,
//! pressure distributions). A propagation is valid only if it is in every world and each
//! world's goal object stays within the goal margin of the nominal one (so a nominal
//! state inside the disc less the margin has every world's inside the disc, and a branch
//! whose outcome scatters is cut where it starts to), and the goal is reached only when
//! every world's goal object is inside the disc: the tree
//! grows only by pushes whose outcome does not hinge on what nobody knows exactly, in the
//! manner of King et al.'s unobservable Monte Carlo planning for rearrangement (ICRA 2017).
//!
//! The arm's motion does not depend on the objects, so a world's state is the nominal
//! joints with that world's object poses. Flat layout, world after world:
//! `[x, y, yaw]` of every object (m, m, rad; world frame).

use crate::planning::robustness::{Noise, PerturbedWorld};
use crate::random::SplitMix64;
use crate::robot::EeAction;
use crate::scene::{Goal, Scene};
use crate::state::State;
use crate::validity::Invalid;
use nalgebra::DVector;

/// Why a propagation failed in a perturbed world.
#[derive(Clone, Debug, PartialEq)]
pub enum WorldStop {
    /// A state the world reached is invalid (its reserves off).
    Invalid(Invalid),
    /// The world's goal object is further from the nominal one than the goal margin:
    /// with the nominal goal object inside the disc less the margin, it might be outside.
    GoalObjectDiverges,
}

impl WorldStop {
    /// A short name, as [`Invalid::kind`].
    pub fn kind(&self) -> &'static str {
        match self {
            WorldStop::Invalid(why) => why.kind(),
            WorldStop::GoalObjectDiverges => "goal object diverges",
        }
    }
}

/// The perturbed worlds of one search (none: nominal planning).
#[derive(Default)]
pub struct ParticleWorlds {
    worlds: Vec<PerturbedWorld>,
    /// Objects per world.
    objects: usize,
    /// The scene's goal (none without worlds).
    goal: Option<Goal>,
}

impl ParticleWorlds {
    /// `count` worlds drawn from `seed`, each a possible real version of `scene`.
    pub fn draw(scene: &Scene, count: usize, seed: u64) -> Result<Self, Invalid> {
        let mut rng = SplitMix64::new(seed ^ 0x9A27_1C1E_5EED);
        let worlds = (0..count)
            .map(|_| PerturbedWorld::draw(&Noise::default(), scene, &mut rng))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            worlds,
            objects: scene.objects.len(),
            goal: Some(scene.goal.clone()),
        })
    }

    /// The number of perturbed worlds.
    pub fn len(&self) -> usize {
        self.worlds.len()
    }

    /// Are there no perturbed worlds?
    pub fn is_empty(&self) -> bool {
        self.worlds.is_empty()
    }

    /// The number of values of the flat layout.
    pub fn flat_len(&self) -> usize {
        3 * self.objects * self.worlds.len()
    }

    /// Every world's start poses, flat.
    pub fn start_flat(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.flat_len());
        for world in &self.worlds {
            let start = world.start();
            out.extend(start.objects.iter().flat_map(|p| [p.x, p.y, p.theta]));
        }
        out
    }

    /// The state of world `i` for the nominal joints `q` and the worlds' poses `flat`.
    fn state(&self, q: &DVector<f64>, flat: &[f64], i: usize) -> State {
        let n = 3 * self.objects;
        State::from_flat_parts(q, &flat[i * n..(i + 1) * n])
    }

    /// Holds `action` for `steps` steps in every world from the nominal joints `q` and
    /// the worlds' poses `from`, the nominal state reaching `nominal`; writes the poses
    /// reached into `to`. The first world to fail says why.
    pub fn propagate(
        &mut self,
        q: &DVector<f64>,
        from: &[f64],
        action: &EeAction,
        steps: usize,
        nominal: &State,
        to: &mut [f64],
    ) -> Result<(), WorldStop> {
        let n = 3 * self.objects;
        to.copy_from_slice(from);
        for i in 0..self.worlds.len() {
            let start = self.state(q, from, i);
            let run = self.worlds[i].propagate_steps(&start, action, steps);
            if let Some(why) = run.stopped_by {
                return Err(WorldStop::Invalid(why));
            }
            if let Some(Goal::ObjectInDisc { object, margin, .. }) = &self.goal {
                let apart = run.state.objects[*object].translation()
                    - nominal.objects[*object].translation();
                if apart.norm() > *margin {
                    return Err(WorldStop::GoalObjectDiverges);
                }
            }
            let slots = to[i * n..(i + 1) * n].chunks_exact_mut(3);
            for (pose, slot) in run.state.objects.iter().zip(slots) {
                slot.copy_from_slice(&[pose.x, pose.y, pose.theta]);
            }
        }
        Ok(())
    }

    /// Whether every world's state is valid (its reserves off: only what would happen).
    pub fn all_valid(&self, q: &DVector<f64>, flat: &[f64]) -> bool {
        (0..self.worlds.len()).all(|i| self.worlds[i].is_valid(&self.state(q, flat, i)))
    }

    /// The largest distance of a world's goal object from the goal disc (m; the whole
    /// disc, the planning margin being the nominal state's reserve); `-inf` without worlds.
    pub fn goal_distance(&self, q: &DVector<f64>, flat: &[f64]) -> f64 {
        let Some(goal) = &self.goal else {
            return f64::NEG_INFINITY;
        };
        (0..self.worlds.len())
            .map(|i| goal.task_distance(&self.state(q, flat, i)))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}
