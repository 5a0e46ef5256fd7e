//! The Static RRT baseline inside the full state space: every movable object except the
//! goal object is a static obstacle where it starts. States keep all objects (so Static
//! RRT shares the problem, and OMPL's benchmark, with PC RRT); the clutter objects must
//! stay at their start poses, and the physics runs on `Scene::with_static_clutter`.

use crate::propagate::Propagator;
use crate::scene::Scene;
use crate::state::State;

/// Static RRT's physics inside the full problem: the goal object is propagated in the scene
/// whose clutter is static obstacles, and every other object stays at its start pose.
pub struct StaticClutter {
    /// Propagates in the scene whose clutter is static obstacles.
    pub propagator: Propagator,
    /// The goal object's index in the full state, if the goal is an object goal.
    goal: Option<usize>,
    /// The full start state (where the clutter stays).
    start: State,
}

impl StaticClutter {
    /// Static RRT's physics for `scene`.
    pub fn new(scene: &Scene) -> Self {
        Self {
            propagator: Propagator::new(scene.with_static_clutter()),
            goal: scene.goal.object(),
            start: scene.start.clone(),
        }
    }

    /// The state of the static-clutter scene: the robot and the goal object only.
    pub fn reduce(&self, full: &State) -> State {
        State {
            q: full.q.clone(),
            objects: self.goal.map(|g| vec![full.objects[g]]).unwrap_or_default(),
        }
    }

    /// A full state from a reduced one; the clutter is where it starts.
    pub fn expand(&self, reduced: &State) -> State {
        let mut full = self.start.clone();
        full.q = reduced.q.clone();
        if let Some(g) = self.goal {
            full.objects[g] = reduced.objects[0];
        }
        full
    }

    /// Is every clutter object exactly at its start pose?
    pub fn clutter_in_place(&self, full: &State) -> bool {
        full.objects
            .iter()
            .zip(&self.start.objects)
            .enumerate()
            .all(|(i, (a, b))| Some(i) == self.goal || a == b)
    }

    /// The full-state index of object `i` of the static-clutter scene.
    pub fn full_object(&self, i: usize) -> usize {
        debug_assert_eq!(i, 0);
        self.goal.unwrap_or(i)
    }
}
