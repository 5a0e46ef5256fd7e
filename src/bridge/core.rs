//! What the parts of one problem share, and the checks every call from C++ makes: flat
//! arrays of the right lengths, no panic crossing the bridge.

use crate::math::Pose2;
use crate::planner::{ParticleWorlds, RecentTools};
use crate::planning::path::PathControl;
use crate::planning::static_clutter::StaticClutter;
use crate::robot::EeAction;
use crate::scene::Scene;
use crate::state::State;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Instant;

/// The state one problem's parts share: what the search is (pushing, or Static RRT's
/// pinned clutter; perturbed worlds), what the propagator has just done (which validity
/// and the projection reuse), and when propagation stops.
pub(crate) struct Core {
    /// Static RRT's mode: clutter objects are static obstacles at their start poses,
    /// propagated and checked in this view of the problem.
    pub static_clutter: Option<StaticClutter>,
    /// Robust planning's perturbed worlds, carried along every state (none by default).
    pub particles: ParticleWorlds,
    /// The last state a propagation produced and whether it was valid: OMPL asks
    /// `isValid` of exactly that state next, and the propagation already knows.
    pub last_result: Option<(Vec<f64>, bool)>,
    /// The tool point at the last valid propagation results: the projection's first
    /// coordinates without forward kinematics.
    pub recent_tools: RecentTools,
    /// After this instant propagation (and DARRT's PickPlace) refuses to start: the
    /// search's time limit.
    pub deadline: Option<Instant>,
}

/// One problem's [`Core`], shared by its parts (which C++ may hold on any thread, one
/// thread at a time).
#[derive(Clone)]
pub(crate) struct SharedCore(Arc<Mutex<Core>>);

impl SharedCore {
    pub fn new(scene: &Scene) -> SharedCore {
        // One motion's states: OMPL propagates a control step by step, then projects each.
        let motion_states = (scene.planner.max_duration / scene.planner.step)
            .ceil()
            .clamp(1.0, 1000.0) as usize
            + 1;
        let state_len = State::flat_len(scene.robot.dof(), scene.objects.len());
        SharedCore(Arc::new(Mutex::new(Core {
            static_clutter: None,
            particles: ParticleWorlds::default(),
            last_result: None,
            recent_tools: RecentTools::new(motion_states, state_len),
            deadline: None,
        })))
    }

    /// The core; a part that panicked while holding it left it as it was (every write
    /// to it is one assignment).
    pub fn lock(&self) -> MutexGuard<'_, Core> {
        self.0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

impl Core {
    /// Whether the search's time limit had passed at `at`.
    pub fn past_deadline(&self, at: Instant) -> bool {
        self.deadline.is_some_and(|d| at >= d)
    }

    /// Whether `state` is, bit for bit, the last propagation's result, and if so, its
    /// validity (OMPL asks right after propagating).
    pub fn last_result_validity(&self, state: &[f64]) -> Option<bool> {
        let (last, valid) = self.last_result.as_ref()?;
        let same = last.len() == state.len()
            && last
                .iter()
                .zip(state)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        same.then_some(*valid)
    }

    /// Checks the length of a state's perturbed worlds' poses.
    pub fn check_particles(&self, particles: &[f64]) -> Result<(), String> {
        if particles.len() != self.particles.flat_len() {
            return Err(format!(
                "a state's perturbed worlds have {} values, this search needs {}",
                particles.len(),
                self.particles.flat_len()
            ));
        }
        Ok(())
    }
}

/// Runs `f`, turning a panic into an error message: the caller is C++, and nothing may
/// unwind across the bridge.
pub(crate) fn guarded<T>(what: &str, f: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(panic) => {
            let detail = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("internal error in {what}: {detail}"))
        }
    }
}

/// The flat arrays C++ passes for `scene`, read with their lengths checked.
pub(crate) struct Flat<'a>(pub &'a Scene);

impl Flat<'_> {
    /// A state's number of values.
    pub fn state_len(&self) -> usize {
        State::flat_len(self.0.robot.dof(), self.0.objects.len())
    }

    pub fn check_state_len(&self, flat: &[f64]) -> Result<(), String> {
        if flat.len() != self.state_len() {
            return Err(format!(
                "a state has {} values, this scene needs {}",
                flat.len(),
                self.state_len()
            ));
        }
        Ok(())
    }

    /// The state of a flat array ([`State::to_flat`]).
    pub fn state(&self, flat: &[f64]) -> Result<State, String> {
        self.check_state_len(flat)?;
        Ok(State::from_flat(flat, self.0.robot.dof()))
    }

    /// States one after another in a flat array.
    pub fn states(&self, flat: &[f64]) -> Result<Vec<State>, String> {
        State::many_from_flat(flat, self.0.robot.dof(), self.0.objects.len())
    }

    /// A control ([`EeAction::from_flat`]).
    pub fn action(&self, control: &[f64]) -> Result<EeAction, String> {
        let dof = self.0.robot.dof();
        if control.len() != 3 + dof {
            return Err(format!(
                "a control has {} values, this scene needs {}",
                control.len(),
                3 + dof
            ));
        }
        Ok(EeAction::from_flat(control))
    }

    /// A control path: the controls one after another and their step counts.
    pub fn path_controls(
        &self,
        controls: &[f64],
        steps: &[usize],
    ) -> Result<Vec<PathControl>, String> {
        PathControl::from_flat(controls, steps, self.0.robot.dof())
    }

    /// An object index and a target pose `[x, y, yaw]`, checked.
    pub fn object_target(&self, object: usize, target: &[f64]) -> Result<(usize, Pose2), String> {
        if object >= self.0.objects.len() {
            return Err(format!(
                "object {object} does not exist ({} objects)",
                self.0.objects.len()
            ));
        }
        match target {
            [x, y, yaw] if target.iter().all(|v| v.is_finite()) => {
                Ok((object, Pose2::new(*x, *y, *yaw)))
            }
            _ => Err(format!(
                "a target pose is [x, y, yaw], finite; got {target:?}"
            )),
        }
    }
}
