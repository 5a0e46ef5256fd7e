//! [`Propagator`]: OMPL's state propagator (`oc::StatePropagator`), with the counts the
//! search reports and the time limit it keeps.

use super::core::{guarded, Flat, SharedCore};
use super::Problem;
use crate::planner::{SearchCounter, SearchStats};
use crate::propagate;
use std::time::{Duration, Instant};

/// Holds a control for some steps from a state, in the problem's mode (pushing, or
/// Static RRT's pinned clutter) and in every perturbed world.
pub struct Propagator {
    core: SharedCore,
    /// The pushing problem's physics (Static RRT's is the core's view).
    propagator: propagate::Propagator,
    search: SearchCounter,
    steps_taken: u64,
    /// Wall time spent propagating (progress reports: the rest is the planner's).
    propagating: Duration,
}

impl Propagator {
    /// The propagator of `problem`.
    pub fn new(problem: &Problem) -> Box<Propagator> {
        Box::new(Propagator {
            core: problem.core.clone(),
            propagator: propagate::Propagator::new((*problem.scene).clone()),
            search: SearchCounter::new(&problem.scene),
            steps_taken: 0,
            propagating: Duration::ZERO,
        })
    }

    /// Holds `control` for `steps` steps from `state` (and its perturbed worlds' poses
    /// `particles`, see [`Problem::set_particles`]); writes the state reached (or, if a
    /// step was invalid, the invalid state it tried to reach) and the worlds' poses, and
    /// says whether it is valid: in every world.
    pub fn propagate(
        &mut self,
        state: &[f64],
        particles: &[f64],
        control: &[f64],
        steps: usize,
        result: &mut [f64],
        result_particles: &mut [f64],
    ) -> Result<bool, String> {
        let started = Instant::now();
        let outcome = guarded("propagate", || {
            let mut core = self.core.lock();
            let flat = Flat(self.propagator.scene());
            // OMPL propagates one step at a time: a step from the last valid result
            // continues the same propagation.
            let continues = core.last_result_validity(state) == Some(true);
            let start = flat.state(state)?;
            let action = flat.action(control)?;
            if result.len() != state.len() {
                return Err("the result state has the wrong length".into());
            }
            core.check_particles(particles)?;
            core.check_particles(result_particles)?;
            // Count the propagation, then write the state reached: the valid part's end,
            // or the invalid state the last step tried to reach. Past the deadline: the
            // start, invalid, nothing counted.
            // `reached`: the state the propagation ended in, valid or not.
            let (valid, taken, reached) = if core.past_deadline(started) {
                result.copy_from_slice(state);
                (false, None, None)
            } else if let Some(view) = &mut core.static_clutter {
                let run = view
                    .propagator
                    .propagate_steps(&view.reduce(&start), &action, steps);
                let end = view.expand(&run.state);
                let stopped = run.stopped_by.as_ref();
                self.search.record(&start, &end, stopped, continues);
                match stopped {
                    None => end.write_flat(result),
                    Some(_) => view
                        .expand(&view.propagator.attempted_state())
                        .write_flat(result),
                }
                (stopped.is_none(), Some(run.steps), Some(end))
            } else {
                let run = self.propagator.propagate_steps(&start, &action, steps);
                let stopped = run.stopped_by.as_ref();
                self.search.record(&start, &run.state, stopped, continues);
                match stopped {
                    None => run.state.write_flat(result),
                    Some(_) => self.propagator.attempted_state().write_flat(result),
                }
                (stopped.is_none(), Some(run.steps), Some(run.state))
            };
            if let Some(taken) = taken {
                self.steps_taken += taken as u64 + u64::from(!valid);
            }
            // The perturbed worlds follow the same controls from the same joints.
            result_particles.copy_from_slice(particles);
            let valid = valid && {
                // Valid: `result` holds `reached`.
                let nominal = reached
                    .as_ref()
                    .expect("a propagation that ran ended somewhere");
                let stopped = core.particles.propagate(
                    &start.q,
                    particles,
                    &action,
                    steps,
                    nominal,
                    result_particles,
                );
                if let Err(why) = &stopped {
                    self.search.record_perturbed_world_stop(why.kind());
                }
                stopped.is_ok()
            };
            if valid {
                let tool = match &core.static_clutter {
                    Some(view) => view.propagator.tool_xy(),
                    None => self.propagator.tool_xy(),
                };
                if let Some(tool) = tool {
                    core.recent_tools.push(result, tool);
                }
            }
            // Kept in the same buffer: OMPL propagates one step at a time.
            match &mut core.last_result {
                Some((last, last_valid)) => {
                    last.clear();
                    last.extend_from_slice(result);
                    *last_valid = valid;
                }
                None => core.last_result = Some((result.to_vec(), valid)),
            }
            Ok(valid)
        });
        self.propagating += started.elapsed();
        outcome
    }

    /// From `seconds` from now on, every propagation is refused (invalid, no step taken),
    /// and so is DARRT's PickPlace: the search's time limit. Infinite: no limit.
    pub fn set_time_limit(&mut self, seconds: f64) {
        self.core.lock().deadline = crate::planning::deadline(Instant::now(), seconds);
    }

    /// Whether the time limit has passed: from then on every propagation is refused, so
    /// a search that waits for steps must stop on this instead.
    pub fn past_time_limit(&self) -> bool {
        self.core.lock().past_deadline(Instant::now())
    }

    /// Propagation steps taken so far.
    pub fn steps(&self) -> u64 {
        self.steps_taken
    }

    /// Wall time (s) spent propagating so far.
    pub fn seconds(&self) -> f64 {
        self.propagating.as_secs_f64()
    }

    /// What the propagations so far did.
    pub fn search_stats(&self) -> &SearchStats {
        self.search.stats()
    }
}
