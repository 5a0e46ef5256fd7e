//! The problem a planner kind searches in a scene. Every planner's states hold the whole
//! scene (the robot and every object, as `ompl::tools::Benchmark` needs when planners
//! share a problem); Static RRT's problem pins every object but the goal object where it
//! starts: in its physics they are static obstacles ([`StaticClutter`]).

use super::PlannerKind;
use super::{finish, FinishSettings, FinishedPath};
use crate::planning::mend::{mend, MendSettings, Mended};
use crate::planning::path::{simulate, PathControl, SimulatedPath};
use crate::planning::robustness::{robustness, Noise, RobustnessReport};
use crate::planning::static_clutter::StaticClutter;
use crate::planning::trajectory::{executable, Trajectory};
use crate::propagate::Propagator;
use crate::scene::Scene;
use crate::state::State;
use std::sync::Arc;

/// The problem a planner kind searches in a scene: the scene, with every object in its
/// states; for Static RRT the clutter is pinned where it starts. Simulating, finishing,
/// robustness and trajectories of its plans go through it.
pub struct Problem {
    scene: Arc<Scene>,
    /// Static RRT's physics, where the clutter is pinned.
    pinned: Option<StaticClutter>,
}

impl Problem {
    /// The problem `planner` searches in `scene`.
    pub fn new(scene: Scene, planner: PlannerKind) -> Problem {
        Problem {
            pinned: planner.pins_clutter().then(|| StaticClutter::new(&scene)),
            scene: Arc::new(scene),
        }
    }

    /// The whole scene, whose states the plan holds.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene whose physics the planner searches: for Static RRT, the robot and the goal
    /// object among obstacles (its states hold only those).
    pub fn searched_scene(&self) -> &Scene {
        match &self.pinned {
            Some(view) => view.propagator.scene(),
            None => &self.scene,
        }
    }

    fn searched_propagator(&self) -> Propagator {
        match &self.pinned {
            Some(view) => Propagator::new(view.propagator.shared_scene()),
            None => Propagator::new(self.scene.clone()),
        }
    }

    /// The searched scene's state of a whole-scene state.
    fn searched(&self, state: &State) -> State {
        match &self.pinned {
            Some(view) => view.reduce(state),
            None => state.clone(),
        }
    }

    /// The whole-scene state of a searched scene's state (the clutter at rest).
    fn whole_state(&self, state: &State) -> State {
        match &self.pinned {
            Some(view) => view.expand(state),
            None => state.clone(),
        }
    }

    /// A path of the searched scene in whole-scene states (the clutter at rest).
    fn whole(&self, mut path: SimulatedPath) -> SimulatedPath {
        if let Some(view) = &self.pinned {
            for states in [&mut path.states, &mut path.step_states] {
                for state in states.iter_mut() {
                    *state = view.expand(state);
                }
            }
            for push in path.contacts.iter_mut().flatten().flatten() {
                push.object = view.full_object(push.object);
            }
        }
        path
    }

    /// Simulates `controls` from the scene's start (`record_steps`: every step's state).
    pub fn simulate(&self, controls: &[PathControl], record_steps: bool) -> SimulatedPath {
        let searched = self.searched_scene();
        let path = simulate(
            &mut self.searched_propagator(),
            &searched.start,
            controls,
            record_steps,
        );
        self.whole(path)
    }

    /// The rest `controls` from the scene's start (an observed state) mended where it
    /// fails ([`mend`]): the first edit valid to its end whose final state (of the whole
    /// scene) `reaches` accepts, within `settings`' budget.
    pub fn mend(
        &self,
        controls: &[PathControl],
        reaches: impl Fn(&State) -> bool,
        settings: &MendSettings,
    ) -> Option<Mended> {
        mend(
            &mut self.searched_propagator(),
            &self.searched_scene().start,
            controls,
            |s| reaches(&self.whole_state(s)),
            settings,
        )
    }

    /// Finishes a found path ([`finish`]); `states` are the planner's, of the whole scene.
    pub fn finish(
        &self,
        controls: &[PathControl],
        states: &[State],
        solved: bool,
        settings: &FinishSettings,
    ) -> Result<FinishedPath, String> {
        let searched: Vec<State> = states.iter().map(|s| self.searched(s)).collect();
        let mut finished = finish(self.searched_scene(), controls, &searched, solved, settings)?;
        finished.simulation = self.whole(finished.simulation);
        Ok(finished)
    }

    /// Perturbed re-simulations of `controls` ([`crate::planning::robustness`]).
    pub fn robustness(
        &self,
        controls: &[PathControl],
        noise: &Noise,
        trials: usize,
        seed: u64,
    ) -> RobustnessReport {
        robustness(self.searched_scene(), controls, noise, trials, seed)
    }

    /// The executable trajectory of `controls` (every object of the scene).
    pub fn trajectory(&self, controls: &[PathControl]) -> Result<Trajectory, String> {
        self.timed(controls).map(|(_, trajectory)| trajectory)
    }

    /// `controls` simulated (every step's state recorded) and timed into their executable
    /// trajectory; an error if they do not simulate.
    pub fn timed(&self, controls: &[PathControl]) -> Result<(SimulatedPath, Trajectory), String> {
        let path = self.simulate(controls, true);
        if let Some((i, reason)) = &path.stopped_by {
            return Err(format!("the plan does not simulate: control {i}: {reason}"));
        }
        let trajectory = executable(&self.scene, controls, &path.step_states)?;
        Ok((path, trajectory))
    }
}
