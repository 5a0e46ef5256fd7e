//! [`Darrt`]: DARRT's primitives (Transit, Push, PickPlace) and its check of a path,
//! for the DARRT planner (`cpp/planners/darrt/`).

use super::core::{guarded, Flat, SharedCore};
use super::ffi::{HeldStates, PrimitiveCheck};
use super::Problem;
use crate::planning::darrt;
use crate::scene::Scene;
use crate::state::State;
use std::sync::Arc;

/// DARRT's primitives on one problem's scene.
pub struct Darrt {
    core: SharedCore,
    scene: Arc<Scene>,
}

impl Darrt {
    /// DARRT's primitives for `problem`.
    pub fn new(problem: &Problem) -> Box<Darrt> {
        Box::new(Darrt {
            core: problem.core.clone(),
            scene: problem.scene.clone(),
        })
    }

    /// Transit: is the straight joint-space line from `from` to `to` (same object poses)
    /// valid?
    pub fn transit(&self, from: &[f64], to: &[f64]) -> Result<bool, String> {
        guarded("darrt transit", || {
            let flat = Flat(&self.scene);
            let (from, to) = (flat.state(from)?, flat.state(to)?);
            if from.objects != to.objects {
                return Err("a transit moves no object: the object poses differ".into());
            }
            Ok(crate::planning::transit::check_transit(&self.scene, &from, &to.q).is_ok())
        })
    }

    /// Push, first part: writes the state with the hand caging `object` (ready to carry
    /// it to `target`, `[x, y, yaw]`) and returns true, or false if none is found.
    pub fn approach(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
        result: &mut [f64],
    ) -> Result<bool, String> {
        guarded("darrt approach", || {
            let flat = Flat(&self.scene);
            let state = flat.state(state)?;
            let (object, target) = flat.object_target(object, target)?;
            if result.len() != flat.state_len() {
                return Err("the result state has the wrong length".into());
            }
            match darrt::approach(&self.scene, &state, object, &target) {
                Ok(caged) => {
                    caged.write_flat(result);
                    Ok(true)
                }
                Err(_) => Ok(false),
            }
        })
    }

    /// Push, second part: carries the object caged in `state` to `target` (`[x, y,
    /// yaw]`). Returns the states of the carry (flat, one after another), or none if the
    /// line is blocked.
    pub fn carry(&self, state: &[f64], object: usize, target: &[f64]) -> Result<Vec<f64>, String> {
        guarded("darrt carry", || {
            let flat = Flat(&self.scene);
            let state = flat.state(state)?;
            let (object, target) = flat.object_target(object, target)?;
            let cage = darrt::Cage::of_state(&self.scene, &state, object);
            Ok(darrt::carry(&self.scene, &state, &cage, &target)
                .map(|states| states.iter().flat_map(State::to_flat).collect())
                .unwrap_or_default())
        })
    }

    /// PickPlace: grasps `object` where it rests in `state`, carries it and sets it down
    /// at `target` (`[x, y, yaw]`), drawn from `seed`, within the search's time limit.
    /// Returns the states after `state` and what the hand holds in each, both empty if no
    /// way is found.
    pub fn pick_place(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
        seed: u64,
    ) -> Result<HeldStates, String> {
        guarded("darrt pick_place", || {
            let flat = Flat(&self.scene);
            let state = flat.state(state)?;
            let (object, target) = flat.object_target(object, target)?;
            let settings = darrt::PickPlaceSettings::default();
            let deadline = self.core.lock().deadline;
            let path = darrt::pick_place(
                &self.scene,
                &state,
                object,
                &target,
                &settings,
                seed,
                deadline,
            )
            .unwrap_or_default();
            Ok(HeldStates {
                states: path.iter().flat_map(|p| p.state.to_flat()).collect(),
                held: path.iter().map(|p| held_to_flat(p.held)).collect(),
            })
        })
    }

    /// Checks a DARRT path (flat states one after another, and what the hand holds in
    /// each: an object index or -1) and measures it; an invalid path's check says why.
    pub fn check(&self, states: &[f64], held: &[i64]) -> Result<PrimitiveCheck, String> {
        guarded("darrt check", || {
            let states = Flat(&self.scene).states(states)?;
            if held.len() != states.len() {
                return Err(format!(
                    "{} states but {} entries of what the hand holds",
                    states.len(),
                    held.len()
                ));
            }
            let objects = self.scene.objects.len();
            let path = states
                .into_iter()
                .zip(held)
                .map(|(state, &h)| match h {
                    -1 => Ok(darrt::PathState::resting(state)),
                    h if (0..objects as i64).contains(&h) => Ok(darrt::PathState {
                        state,
                        held: Some(h as usize),
                    }),
                    h => Err(format!(
                        "the hand holds object {h}, not -1 or an object index"
                    )),
                })
                .collect::<Result<Vec<_>, String>>()?;
            Ok(PrimitiveCheck::from(darrt::check_path(&self.scene, &path)))
        })
    }
}

/// What the hand holds, as the bridge passes it: the object's index, or -1.
fn held_to_flat(held: Option<usize>) -> i64 {
    held.map_or(-1, |i| i as i64)
}
